// `snh-gpu-bench voxelize-compare SURFACE... --cell H`: the voxelizer's two
// inside rules on each surface, timed, and their cells compared: crossing
// counts (VoxelizeOptions::strict) against generalized winding numbers (the
// default); then the surface opened (a seam: the triangles above its middle
// get their own copies of the vertices they share with the rest; a hole: the
// triangles within four cells of its highest-x vertex removed) against the
// closed original, counting the cells that differ and how far from the
// surface they lie; and, on both, the winding pass alone evaluated at every
// cell centre against the default (filled off the surface where it cannot
// change: fem::winding_at_cell_centres), timed, with the cells whose
// inside test or rounded value differ. CPU only.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "commands.h"
#include "fem/fast_winding_number.h"
#include "snh/error.h"
#include "snh/surface.h"

namespace snh::bench {
namespace {

struct CompareOptions {
  std::vector<std::string> surfaces;
  double cell = 0.0;
  int repeat = 3;
};

TriangleSurface opened(const TriangleSurface& s, double cell) {
  double zlo = s.positions(0, 2), zhi = zlo;
  size_t tip = 0;
  for (size_t v = 0; v < s.vertex_count(); ++v) {
    zlo = std::min(zlo, s.positions(v, 2));
    zhi = std::max(zhi, s.positions(v, 2));
    if (s.positions(v, 0) > s.positions(tip, 0)) tip = v;
  }
  const double middle = 0.5 * (zlo + zhi);
  const auto centroid = [&](size_t t, int d) {
    double x = 0.0;
    for (int k = 0; k < 3; ++k) x += s.positions(size_t(s.triangles[3 * t + k]), d) / 3.0;
    return x;
  };
  std::vector<char> below(s.vertex_count(), 0);
  for (size_t t = 0; t < s.triangle_count(); ++t)
    if (centroid(t, 2) <= middle)
      for (int k = 0; k < 3; ++k) below[s.triangles[3 * t + k]] = 1;
  TriangleSurface out;
  out.positions = s.positions;
  std::vector<int32_t> copy(s.vertex_count(), -1);
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) d2 += std::pow(centroid(t, d) - s.positions(tip, d), 2);
    if (d2 < 16.0 * cell * cell) continue;
    for (int k = 0; k < 3; ++k) {
      int32_t v = s.triangles[3 * t + k];
      if (centroid(t, 2) > middle && below[v]) {
        if (copy[v] < 0) {
          copy[v] = static_cast<int32_t>(out.vertex_count());
          out.positions.push_back({s.positions(size_t(v), 0), s.positions(size_t(v), 1), s.positions(size_t(v), 2)});
        }
        v = copy[v];
      }
      out.triangles.push_back(v);
    }
  }
  return out;
}

double best_seconds(int repeat, const TriangleSurface& s, double cell, const VoxelizeOptions& o, Voxelization& v) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    v = voxelize(s, cell, o);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

// The winding pass on v's grid, every centre against the default: prints
// both times and the cells whose inside test (>= 1/2) or rounded value differ.
void compare_winding_pass(const TriangleSurface& s, const Voxelization& v, int repeat) {
  const TriangleSurface welded = weld_vertices(s, VoxelizeOptions{}.weld_tolerance).surface;
  std::vector<double> full, fast;
  double t_full = 1e300, t_fast = 1e300;
  for (int r = 0; r < repeat; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    full = fem::winding_at_cell_centres(welded, v.origin, v.cell, v.dims, VoxelizeOptions{}.winding_beta, true);
    t_full = std::min(t_full, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    t0 = std::chrono::steady_clock::now();
    fast = fem::winding_at_cell_centres(welded, v.origin, v.cell, v.dims, VoxelizeOptions{}.winding_beta);
    t_fast = std::min(t_fast, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  size_t differ = 0;
  for (size_t i = 0; i < full.size(); ++i)
    differ += (full[i] >= 0.5) != (fast[i] >= 0.5) || std::round(full[i]) != std::round(fast[i]);
  std::cout << "  winding pass: every centre " << t_full << " s, filled off the surface " << t_fast << " s ("
            << t_full / t_fast << "x faster); cells differing: " << differ << "\n";
}

std::set<std::array<int, 3>> cells_of(const Voxelization& v) { return {v.element_cell.begin(), v.element_cell.end()}; }

int run_compare(const CompareOptions& o) {
  std::cout << std::setprecision(4);
  for (const std::string& path : o.surfaces) {
    const TriangleSurface s = read_surface(path);
    VoxelizeOptions strict, winding;
    strict.strict = true;
    strict.name = winding.name = path;
    Voxelization a, b;
    const double ta = best_seconds(o.repeat, s, o.cell, strict, a);
    const double tb = best_seconds(o.repeat, s, o.cell, winding, b);
    const auto ca = cells_of(a), cb = cells_of(b);
    size_t differ = 0;
    for (const auto& c : ca) differ += cb.count(c) ? 0 : 1;
    for (const auto& c : cb) differ += ca.count(c) ? 0 : 1;
    std::cout << path << ": " << s.triangle_count() << " triangles, grid " << a.dims[0] << " x " << a.dims[1] << " x "
              << a.dims[2] << ", " << ca.size() << " cells\n"
              << "  crossing counts (strict): " << ta << " s; winding numbers: " << tb << " s (" << tb / ta
              << "x); cells differing: " << differ << "\n";
    compare_winding_pass(s, b, o.repeat);

    const TriangleSurface open = opened(s, o.cell);
    Voxelization c;
    const double tc = best_seconds(o.repeat, open, o.cell, winding, c);
    const auto cc = cells_of(c);
    std::vector<std::array<int, 3>> changed;
    for (const auto& x : cb)
      if (!cc.count(x)) changed.push_back(x);
    for (const auto& x : cc)
      if (!cb.count(x)) changed.push_back(x);
    // How far each changed centre is from the closed surface, bounded from
    // above by its distance to the nearest surface vertex, in cells.
    double farthest = 0.0;
    for (const auto& x : changed) {
      double nearest = 1e300;
      const double p[3] = {c.origin[0] + (x[0] + 0.5) * o.cell, c.origin[1] + (x[1] + 0.5) * o.cell,
                           c.origin[2] + (x[2] + 0.5) * o.cell};
      for (size_t v = 0; v < s.vertex_count(); ++v)
        nearest =
            std::min(nearest, std::hypot(s.positions(v, 0) - p[0], s.positions(v, 1) - p[1], s.positions(v, 2) - p[2]));
      farthest = std::max(farthest, nearest / o.cell);
    }
    std::cout << "  opened (" << open.vertex_count() - s.vertex_count() << " seam vertices, "
              << s.triangle_count() - open.triangle_count() << " triangles removed): " << tc << " s, " << cc.size()
              << " cells, " << changed.size() << " differ from the closed surface's (farthest centre " << farthest
              << " cells from a surface vertex)\n";
    compare_winding_pass(open, c, o.repeat);
    for (const std::string& w : c.warnings) std::cout << "  warning: " << w << "\n";
  }
  return 0;
}

}  // namespace

void add_voxelize_compare_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "voxelize-compare",
      "Times voxelize with crossing counts (strict) and winding numbers on each surface, compares their cells, and "
      "compares the surface opened along a seam and punctured with its closed original");
  cmd->add_option("surfaces", o->surfaces, "closed surfaces: .obj, .ply or .stl")->required();
  cmd->add_option("--cell", o->cell, "the lattice's cube side")->required()->check(CLI::PositiveNumber);
  cmd->add_option("--repeat", o->repeat, "runs per rule; the best time is reported")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = run_compare(*o); });
}

}  // namespace snh::bench
