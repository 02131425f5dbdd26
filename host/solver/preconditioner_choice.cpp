// Names of the CG preconditioners and the measured default.
#include "snh/error.h"
#include "snh/simulation.h"
#include "solver/lattice_hierarchy.h"

namespace snh {

const char* to_string(Preconditioner p) {
  switch (p) {
    case Preconditioner::automatic:
      return "automatic";
    case Preconditioner::none:
      return "none";
    case Preconditioner::block_jacobi:
      return "block-jacobi";
    case Preconditioner::multigrid:
      return "multigrid";
  }
  return "?";
}

Preconditioner parse_preconditioner(const std::string& text) {
  for (Preconditioner p :
       {Preconditioner::automatic, Preconditioner::none, Preconditioner::block_jacobi, Preconditioner::multigrid})
    if (text == to_string(p)) return p;
  throw Error("preconditioner: expected automatic, none, block-jacobi or multigrid, got '" + text + "'");
}

const char* to_string(MultigridFineLevel f) {
  switch (f) {
    case MultigridFineLevel::automatic:
      return "automatic";
    case MultigridFineLevel::built:
      return "built";
    case MultigridFineLevel::current:
      return "current";
  }
  return "?";
}

MultigridFineLevel parse_multigrid_fine_level(const std::string& text) {
  for (MultigridFineLevel f : {MultigridFineLevel::automatic, MultigridFineLevel::built, MultigridFineLevel::current})
    if (text == to_string(f)) return f;
  throw Error("multigrid fine level: expected automatic, built or current, got '" + text + "'");
}

const char* to_string(ChebyshevKind k) {
  switch (k) {
    case ChebyshevKind::first:
      return "first";
    case ChebyshevKind::fourth:
      return "fourth";
    case ChebyshevKind::optimized_fourth:
      return "optimized-fourth";
  }
  return "?";
}

ChebyshevKind parse_chebyshev_kind(const std::string& text) {
  for (ChebyshevKind k : {ChebyshevKind::first, ChebyshevKind::fourth, ChebyshevKind::optimized_fourth})
    if (text == to_string(k)) return k;
  throw Error("chebyshev kind: expected first, fourth or optimized-fourth, got '" + text + "'");
}

// Measured with `snh-gpu-bench scale --scenes stretch,twist --res
// 8,10,12,16 --preconditioner block-jacobi,multigrid` (pocl, 2 CPU cores,
// double, nu = 0.49; README "Multigrid on hex8 lattices"), session 10, with
// the built fine level and a build per 2 linearizations (MultigridOptions),
// seconds per load step block-Jacobi / multigrid: stretch 3,519 DOFs 0.158 /
// 0.147, 6,363 0.268 / 0.265, 10,275 0.502 / 0.415, 23,859 1.24 / 1.04;
// twist 2,187 0.177 / 0.142, 3,993 0.322 / 0.195, 6,591 0.497 / 0.280,
// 14,739 1.11 / 0.603; twist 107,811 14.5 / 6.58. Multigrid's CG count per
// Newton stays flat while block-Jacobi's grows with the mesh; at about
// 3,500-6,500 DOFs stretch is within 10% either way in this run (an earlier
// one: 3,519 DOFs 0.175 / 0.214, multigrid 22% slower), twist gains 20-45%
// throughout. So:
// multigrid on hex8 lattices from 5,000 DOFs (10,000 in sessions 6-9, 50,000
// before), block-Jacobi otherwise.
Preconditioner default_preconditioner(const Mesh& mesh) {
  constexpr size_t kMultigridFromDofs = 5000;
  return 3 * mesh.vertex_count() >= kMultigridFromDofs && solver::is_hex8_lattice(mesh) ? Preconditioner::multigrid
                                                                                        : Preconditioner::block_jacobi;
}

}  // namespace snh
