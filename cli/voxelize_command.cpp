// `snh voxelize SURFACE --cell H --out LATTICE` (also `snh-gpu-bench voxelize`): a closed surface
// (.obj, .ply, .stl) to a hex8 lattice (voxelize in surface.h), written by
// write_mesh in the format --out's extension names (.msh, .vtk, .vtu, .mesh;
// .vtk and .vtu with each element's grid cell as a cell array), and what
// the lattice is: cells, vertices, pieces, its volume against the
// surface's enclosed volume.
#include <array>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "cli_commands.h"
#include "snh/error.h"
#include "snh/mesh_io.h"
#include "snh/surface.h"

namespace snh::cli {
namespace {

struct VoxelizeCommand {
  std::string surface;
  double cell = 0.0;
  std::string out;
  int64_t max_cells = VoxelizeOptions{}.max_grid_cells;
  bool cover_surface = false;
  bool strict = false;
  double weld_tolerance = VoxelizeOptions{}.weld_tolerance;
};

int run_voxelize(const VoxelizeCommand& o) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const TriangleSurface surface = read_surface(o.surface);
  const auto t1 = Clock::now();
  VoxelizeOptions options;
  options.max_grid_cells = o.max_cells;
  options.cover_surface = o.cover_surface;
  options.strict = o.strict;
  options.weld_tolerance = o.weld_tolerance;
  options.name = o.surface;
  Voxelization v = voxelize(surface, o.cell, options);
  for (const std::string& warning : v.warnings) std::cerr << "warning: " << warning << "\n";
  const auto t2 = Clock::now();
  MeshArray grid_cell{"grid_cell", 3, {}};
  grid_cell.values.reserve(3 * v.element_cell.size());
  for (const auto& c : v.element_cell) grid_cell.values.insert(grid_cell.values.end(), c.begin(), c.end());
  v.lattice.cell_arrays.push_back(std::move(grid_cell));
  write_mesh(o.out, v.lattice);
  const auto t3 = Clock::now();

  const double enclosed = v.report.enclosed_volume;
  const double lattice = double(v.lattice.element_count()) * o.cell * o.cell * o.cell;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  std::cout << std::setprecision(6);
  std::cout << "surface: " << o.surface << ", " << surface.vertex_count() << " vertices, " << surface.triangle_count()
            << " triangles, area " << surface_area(surface) << "\n";
  std::cout << "grid: " << v.dims[0] << " x " << v.dims[1] << " x " << v.dims[2] << " cells of " << v.cell << " from ("
            << v.origin[0] << ", " << v.origin[1] << ", " << v.origin[2] << ")\n";
  const SurfaceReport& r = v.report;
  std::cout << "surface defects: " << r.welded_vertices << " welded vertices, " << r.open_edges << " open edges, "
            << r.non_manifold_edges << " non-manifold edges, " << r.inconsistent_edges << " inconsistent edges, "
            << r.degenerate_triangles << " degenerate triangles, " << r.shells << " shells\n";
  std::cout << "cells: " << v.lattice.element_count() << "\n";
  std::cout << "vertices: " << v.lattice.vertex_count() << "\n";
  std::cout << "components: " << v.components << "\n";
  // Vertices kept apart across a thin gap sit at the same position; readers
  // refuse such files unless told (mesh_io.h).
  std::map<std::array<double, 3>, int> at;
  for (size_t i = 0; i < v.lattice.vertex_count(); ++i) ++at[v.lattice.vertex(i)];
  size_t coincident = 0;
  for (const auto& [position, count] : at) coincident += count > 1 ? count : 0;
  std::cout << "coincident vertices: " << coincident;
  if (coincident > 0)
    std::cout << " (read the lattice back with MeshReadOptions::allow_coincident_vertices, or the scene key "
                 "mesh.allow_coincident_vertices)";
  std::cout << "\n";
  std::cout << "lattice volume: " << lattice << "\n";
  std::cout << "enclosed volume: " << enclosed << "\n";
  std::cout << "relative volume difference: " << (lattice - enclosed) / enclosed << "\n";
  std::cout << "seconds: read " << seconds(t0, t1) << ", voxelize " << seconds(t1, t2) << ", write " << seconds(t2, t3)
            << "\n";
  std::cout << "wrote: " << o.out << "\n";
  return 0;
}

}  // namespace

void add_voxelize_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<VoxelizeCommand>();
  CLI::App* cmd = app.add_subcommand(
      "voxelize",
      "A triangle surface (.obj, .ply, .stl) to a hex8 lattice: cells whose centres are inside (winding number >= "
      "1/2; seams, holes and flipped triangles are welded or tolerated and reported on stderr), not glued "
      "across gaps thinner than a cell (written as .msh, .vtk, .vtu or .mesh)");
  cmd->add_option("surface", o->surface, "the surface: .obj, .ply (ASCII or binary) or .stl (ASCII or binary)")
      ->required();
  cmd->add_option("--cell", o->cell, "cube side of the lattice, in the surface's units")
      ->required()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", o->out,
                  "the lattice: .msh (Gmsh 2.2), .vtk (VTK legacy), .vtu (VTK XML) or .mesh (Medit), by its extension; "
                  ".vtk and .vtu carry a cell array grid_cell (each element's i j k)")
      ->required();
  cmd->add_flag("--cover-surface", o->cover_surface,
                "also keep the cells the surface passes through (every surface point in a kept cell; a gap "
                "holding a cell centre is glued)");
  cmd->add_flag("--strict", o->strict,
                "refuse a surface that is not closed and consistently oriented, and decide inside by crossing counts "
                "(default: weld, warn about defects and decide inside by winding numbers)");
  cmd->add_option("--weld-tolerance", o->weld_tolerance,
                  "vertices closer than this times the bounding box's diagonal are welded into one")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--max-cells", o->max_cells, "refuse grids of more cells than this")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = run_voxelize(*o); });
}

}  // namespace snh::cli
