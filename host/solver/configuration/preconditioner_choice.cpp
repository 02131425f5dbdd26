// Names of the CG preconditioners and the measured default.
#include <algorithm>
#include <vector>

#include "fem/name_table.h"
#include "snh/error.h"
#include "snh/simulation.h"
#include "solver/configuration/measured_thresholds.h"
#include "solver/multigrid/lattice_hierarchy.h"

namespace snh {

namespace {

constexpr NameTable<Preconditioner, 3> kPreconditionerNames{{
    {Preconditioner::none, "none"},
    {Preconditioner::block_jacobi, "block-jacobi"},
    {Preconditioner::multigrid, "multigrid"},
}};

constexpr NameTable<MultigridFineLevel, 2> kFineLevelNames{{
    {MultigridFineLevel::built, "built"},
    {MultigridFineLevel::current, "current"},
}};

constexpr NameTable<ChebyshevKind, 3> kChebyshevKindNames{{
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

// Neither set: degree 1 of the optimized fourth kind below 600,000 DOFs and
// Poisson's ratio 0.495, degree 2 of the first kind otherwise, each measured
// the faster on its side of those bounds (docs/performance.md, "Multigrid
// smoothing (degree and kind)"). One set: the other takes its fixed default
// (degree 2, the first kind).
MultigridOptions resolved_smoothing(MultigridOptions options, size_t dofs, double poisson_ratio) {
  const bool degree_set = options.smoother_degree.has_value(), kind_set = options.chebyshev_kind.has_value();
  if (!degree_set && !kind_set) {
    const bool light = dofs < solver::kDegreeOneBelowDofs && poisson_ratio < solver::kDegreeOneBelowPoisson;
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

// Multigrid on hex8 lattices from 5,000 DOFs, block-Jacobi otherwise.
// Multigrid's CG count per Newton stays flat while block-Jacobi's grows with
// the mesh; from about that size multigrid measured faster (docs/performance.md,
// "Default preconditioner: multigrid from 5,000 DOFs").
Preconditioner default_preconditioner(const Mesh& mesh) {
  return 3 * mesh.vertex_count() >= solver::kMultigridFromDofs && solver::is_hex8_lattice(mesh)
             ? Preconditioner::multigrid
             : Preconditioner::block_jacobi;
}

}  // namespace snh
