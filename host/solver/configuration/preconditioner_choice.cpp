// Names of the CG preconditioners and the measured default.
#include <algorithm>
#include <vector>

#include "fem/name_table.h"
#include "snh/error.h"
#include "snh/simulation.h"
#include "solver/multigrid/lattice_hierarchy.h"

namespace snh {

namespace {

constexpr NameTable<Preconditioner, 4> kPreconditionerNames{{
    {Preconditioner::automatic, "automatic"},
    {Preconditioner::none, "none"},
    {Preconditioner::block_jacobi, "block-jacobi"},
    {Preconditioner::multigrid, "multigrid"},
}};

constexpr NameTable<MultigridFineLevel, 3> kFineLevelNames{{
    {MultigridFineLevel::automatic, "automatic"},
    {MultigridFineLevel::built, "built"},
    {MultigridFineLevel::current, "current"},
}};

constexpr NameTable<ChebyshevKind, 4> kChebyshevKindNames{{
    {ChebyshevKind::automatic, "automatic"},
    {ChebyshevKind::first, "first"},
    {ChebyshevKind::fourth, "fourth"},
    {ChebyshevKind::optimized_fourth, "optimized-fourth"},
}};

}  // namespace

const char* to_string(Preconditioner p) { return name_of(kPreconditionerNames, p); }

Preconditioner parse_preconditioner(const std::string& text) {
  return value_named(kPreconditionerNames, text, "preconditioner");
}

const char* to_string(MultigridFineLevel f) { return name_of(kFineLevelNames, f); }

MultigridFineLevel parse_multigrid_fine_level(const std::string& text) {
  return value_named(kFineLevelNames, text, "multigrid fine level");
}

const char* to_string(ChebyshevKind k) { return name_of(kChebyshevKindNames, k); }

ChebyshevKind parse_chebyshev_kind(const std::string& text) {
  return value_named(kChebyshevKindNames, text, "chebyshev kind");
}

// Measured with `snh-gpu-bench scene twist|stretch --res R [--nu N]
// --preconditioner multigrid [--multigrid-smoother-degree 1
// --multigrid-chebyshev optimized-fourth]` (pocl, 2 CPU cores, double;
// docs/performance.md), total seconds,
// degree 2 of the first kind / degree 1 of the optimized fourth kind: twist
// res 32 (107,811 DOFs) nu 0.49 13.0-13.5 / 9.1-11.2, nu 0.495 14.3 / 14.2,
// nu 0.499 22.9 / 25.3; twist res 40 (206,763 DOFs) 23.1 / 20.5; stretch
// res 32 (171,015 DOFs) 66.1 / 61.8; stretch res 40 (326,835 DOFs) 144 /
// 120; stretch res 48 (553,191 DOFs) 292 / 248; twist res 48 (352,947
// DOFs) 16.3 / 15.7; the stretch cylinder at 969,111 DOFs 28.9
// / 36.3 s per load step (74 more Newton iterations); between
// them stretch res 52 (703,395 DOFs) 339 / 324, a tie: degree 2
// from 6 * 10^5, the default before.
MultigridOptions resolved_smoothing(MultigridOptions options, size_t dofs, double poisson_ratio) {
  constexpr size_t kDegreeOneBelowDofs = 600000;
  constexpr double kDegreeOneBelowPoisson = 0.495;
  const bool degree_set = options.smoother_degree != 0, kind_set = options.chebyshev_kind != ChebyshevKind::automatic;
  if (!degree_set && !kind_set) {
    const bool light = dofs < kDegreeOneBelowDofs && poisson_ratio < kDegreeOneBelowPoisson;
    options.smoother_degree = light ? 1 : 2;
    options.chebyshev_kind = light ? ChebyshevKind::optimized_fourth : ChebyshevKind::first;
  }
  if (!degree_set && kind_set) options.smoother_degree = 2;
  if (degree_set && !kind_set) options.chebyshev_kind = ChebyshevKind::first;
  return options;
}

double max_poisson_ratio(const MaterialMap& materials) {
  std::vector<char> used(materials.materials.size(), materials.element_material.empty() ? 1 : 0);
  for (int32_t m : materials.element_material)
    if (m >= 0 && static_cast<size_t>(m) < used.size()) used[static_cast<size_t>(m)] = 1;
  double nu = 0.0;
  for (size_t m = 0; m < used.size(); ++m) {
    if (!used[m]) continue;
    const LameParameters lame = materials.materials[m].lame();
    nu = std::max(nu, lame.lambda / (2.0 * (lame.lambda + lame.mu)));
  }
  return nu;
}

// Measured with `snh-gpu-bench scale --scenes stretch,twist --res
// 8,10,12,16 --preconditioner block-jacobi,multigrid` (pocl, 2 CPU cores,
// double, nu = 0.49; docs/performance.md), with
// the built fine level and a build per 2 linearizations (MultigridOptions),
// seconds per load step block-Jacobi / multigrid: stretch 3,519 DOFs 0.158 /
// 0.147, 6,363 0.268 / 0.265, 10,275 0.502 / 0.415, 23,859 1.24 / 1.04;
// twist 2,187 0.177 / 0.142, 3,993 0.322 / 0.195, 6,591 0.497 / 0.280,
// 14,739 1.11 / 0.603; twist 107,811 14.5 / 6.58. Multigrid's CG count per
// Newton stays flat while block-Jacobi's grows with the mesh; at about
// 3,500-6,500 DOFs stretch is within 10% either way in this run (an earlier
// one: 3,519 DOFs 0.175 / 0.214, multigrid 22% slower), twist gains 20-45%
// throughout. So:
// multigrid on hex8 lattices from 5,000 DOFs (earlier 10,000, and 50,000
// before that), block-Jacobi otherwise.
Preconditioner default_preconditioner(const Mesh& mesh) {
  constexpr size_t kMultigridFromDofs = 5000;
  return 3 * mesh.vertex_count() >= kMultigridFromDofs && solver::is_hex8_lattice(mesh) ? Preconditioner::multigrid
                                                                                        : Preconditioner::block_jacobi;
}

}  // namespace snh
