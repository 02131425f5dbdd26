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

// Measured with `snh-gpu-bench scene NAME --preconditioner P` (pocl, 2 CPU
// cores, double, nu = 0.49; README "Multigrid on hex8 lattices"): on twist
// at 12,288 DOFs multigrid takes 26 Newton / 69 CG against block-Jacobi's
// 43 / 1,380 and less wall time, and its CG count per Newton iteration
// stays nearly flat up to 107,811 DOFs; on the 3,519-DOF stretch its set-up
// per Newton iteration costs more than block-Jacobi's extra CG iterations.
// So: multigrid on hex8 lattices from 10,000 DOFs, block-Jacobi otherwise.
Preconditioner default_preconditioner(const Mesh& mesh) {
  constexpr size_t kMultigridFromDofs = 10000;
  return 3 * mesh.vertex_count() >= kMultigridFromDofs && solver::is_hex8_lattice(mesh) ? Preconditioner::multigrid
                                                                                        : Preconditioner::block_jacobi;
}

}  // namespace snh
