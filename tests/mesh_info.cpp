// snh-mesh-info PATH: reads a mesh with read_mesh and prints its vertex and
// element counts, element type, total rest volume, groups (name, tag,
// dimension, vertex and element counts) and arrays (name, components, sum of
// values) as JSON (used by tests/meshio_crosscheck.py). A bad file prints the reader's message to
// stderr and exits with status 1. `--write OUT ...` also writes the mesh to
// each OUT with write_mesh (the format by OUT's extension).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "snh/error.h"
#include "snh/mesh.h"
#include "snh/mesh_io.h"

int main(int argc, char** argv) {
  if (argc < 2 || argc == 3 || (argc > 3 && std::string(argv[2]) != "--write")) {
    std::cerr << "usage: snh-mesh-info MESH [--write OUT ...] (.msh, .vtk, .vtu, .mesh, .node/.ele)\n";
    return 2;
  }
  try {
    const snh::Mesh mesh = snh::read_mesh(argv[1]);
    for (int i = 3; i < argc; ++i) snh::write_mesh(argv[i], mesh);
    nlohmann::json out;
    out["path"] = argv[1];
    out["vertices"] = mesh.vertex_count();
    out["elements"] = mesh.element_count();
    out["type"] = snh::to_string(mesh.type);
    out["volume"] = snh::mesh_volume(mesh, mesh.positions);
    out["groups"] = nlohmann::json::array();
    for (const snh::MeshGroup& g : mesh.groups)
      out["groups"].push_back({{"name", g.name},
                               {"tag", g.tag},
                               {"dimension", g.dimension},
                               {"vertices", g.vertices.size()},
                               {"elements", g.elements.size()}});
    for (const char* kind : {"point_arrays", "cell_arrays"}) {
      out[kind] = nlohmann::json::array();
      for (const snh::MeshArray& a : kind[0] == 'p' ? mesh.point_arrays : mesh.cell_arrays) {
        double sum = 0.0;
        for (double v : a.values) sum += v;
        out[kind].push_back({{"name", a.name}, {"components", a.components}, {"sum", sum}});
      }
    }
    std::cout << out.dump(2) << "\n";
  } catch (const snh::Error& e) {
    std::cerr << "snh-mesh-info: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
