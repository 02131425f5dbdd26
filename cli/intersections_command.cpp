// `snh intersections FILE`: whether a surface passes through itself, by the
// exact count of surface_intersections.h. FILE is a triangle surface (.obj,
// .ply, .stl; vertices that repeat a position exactly, as at the seams of
// an OBJ, are welded into one first) or a volume mesh (.msh, .vtk, .vtu, .mesh,
// .node/.ele), whose boundary surface is checked.
#include <cctype>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_commands.h"
#include "snh/error.h"
#include "snh/mesh_io.h"
#include "snh/surface.h"
#include "snh/surface_intersections.h"

namespace snh::cli {
namespace {

struct IntersectionsCommand {
  std::string file;
  std::string json_path;
  size_t pairs = 10;
  bool no_weld = false;
};

bool is_surface_file(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj" || ext == ".ply" || ext == ".stl";
}

int run_intersections(const IntersectionsCommand& o) {
  TriangleSurface surface;
  std::string kind;
  if (is_surface_file(o.file)) {
    surface = read_surface(o.file);
    kind = "surface";
    if (!o.no_weld) {
      const WeldedSurface welded = weld_vertices(surface, 0.0);
      if (welded.merged() > 0) kind += ", " + std::to_string(welded.merged()) + " repeated positions welded";
      surface = welded.surface;
    }
  } else {
    MeshReadOptions read_options;
    read_options.allow_coincident_vertices = true;  // the two sides of a slit touch: they are reported
    const Mesh mesh = read_mesh(o.file, read_options);
    surface = boundary_surface(mesh).surface;
    kind = std::string("boundary of a ") + (mesh.type == ElementType::hex8 ? "hex8" : "tet4") + " mesh of " +
           std::to_string(mesh.element_count()) + " elements";
  }
  SelfIntersectionOptions options;
  options.max_pairs = o.pairs;
  options.name = o.file;
  const auto t0 = std::chrono::steady_clock::now();
  const SelfIntersections r = count_self_intersections(surface, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const auto corners = [&](int32_t t) {
    return std::to_string(surface.triangles[3 * size_t(t)]) + " " +
           std::to_string(surface.triangles[3 * size_t(t) + 1]) + " " +
           std::to_string(surface.triangles[3 * size_t(t) + 2]);
  };
  std::cout << "file: " << o.file << " (" << kind << "), " << surface.vertex_count() << " vertices, " << r.triangles
            << " triangles\n";
  std::cout << "intersecting triangle pairs: " << r.intersecting_pairs << "\n";
  std::cout << "degenerate triangles: " << r.degenerate_triangles << "\n";
  for (const auto& p : r.first_pairs)
    std::cout << "  triangle " << p[0] << " (vertices " << corners(p[0]) << ") x triangle " << p[1] << " (vertices "
              << corners(p[1]) << ")\n";
  for (int32_t t : r.first_degenerate)
    std::cout << "  degenerate triangle " << t << " (vertices " << corners(t) << ")\n";
  std::cout << std::setprecision(3) << "seconds: " << seconds << "\n";
  std::cout << (r.clean() ? "clean: yes" : "clean: no") << "\n";

  if (!o.json_path.empty()) {
    nlohmann::ordered_json doc;
    doc["file"] = o.file;
    doc["vertices"] = surface.vertex_count();
    doc["triangles"] = r.triangles;
    doc["surface_intersections"] = r.intersecting_pairs;
    doc["degenerate_triangles"] = r.degenerate_triangles;
    doc["first_pairs"] = nlohmann::ordered_json::array();
    for (const auto& p : r.first_pairs) doc["first_pairs"].push_back({p[0], p[1]});
    doc["first_degenerate"] = r.first_degenerate;
    doc["clean"] = r.clean();
    std::ofstream out(o.json_path);
    out << doc.dump(2) << "\n";
    if (!out) throw Error(o.json_path + ": cannot be written");
  }
  return r.clean() ? 0 : 2;
}

}  // namespace

void add_intersections_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<IntersectionsCommand>();
  CLI::App* cmd = app.add_subcommand(
      "intersections",
      "Counts exactly the pairs of triangles of a surface that intersect (touching counts; neighbours meet only "
      "where they share a vertex or an edge): a triangle surface, or the boundary of a volume mesh. Exit status 2 "
      "when any pair intersects or any triangle is degenerate");
  cmd->add_option("file", o->file,
                  "a surface (.obj, .ply, .stl) or a volume mesh (.msh, .vtk, .vtu, .mesh, .node, .ele)")
      ->required();
  cmd->add_option("--json", o->json_path, "also write the count and the first pairs as JSON to this file");
  cmd->add_option("--pairs", o->pairs, "list at most this many pairs")->capture_default_str();
  cmd->add_flag("--no-weld", o->no_weld,
                "surfaces: keep vertices that repeat a position apart (they then touch; default: welded)");
  cmd->callback([o, &exit_code] { exit_code = run_intersections(*o); });
}

}  // namespace snh::cli
