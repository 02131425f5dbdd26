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

// Measured with `snh-gpu-bench scale --scenes stretch,twist --res
// 8,10,12,16 --preconditioner block-jacobi,multigrid` (pocl, 2 CPU cores,
// double, nu = 0.49; README "Multigrid on hex8 lattices"), session 10, with
// the built fine level and a build per 2 linearizations (MultigridOptions),
// seconds per load step block-Jacobi / multigrid: stretch 3,519 DOFs 0.175 /
// 0.214, 6,363 0.356 / 0.327, 10,275 0.563 / 0.487, 23,859 1.43 / 1.34;
// twist 2,187 0.189 / 0.137, 3,993 0.369 / 0.259, 6,591 0.594 / 0.347,
// 14,739 1.25 / 0.747; twist 107,811 16.3 / 8.2. Multigrid's CG count per
// Newton stays flat while block-Jacobi's grows with the mesh; below about
// 5,000 DOFs its set-up and V-cycle cost what block-Jacobi's extra CG
// iterations do (stretch loses 20% at 3,519, twist still gains). So:
// multigrid on hex8 lattices from 5,000 DOFs (10,000 in sessions 6-9, 50,000
// before), block-Jacobi otherwise.
Preconditioner default_preconditioner(const Mesh& mesh) {
  constexpr size_t kMultigridFromDofs = 5000;
  return 3 * mesh.vertex_count() >= kMultigridFromDofs && solver::is_hex8_lattice(mesh) ? Preconditioner::multigrid
                                                                                        : Preconditioner::block_jacobi;
}

}  // namespace snh
