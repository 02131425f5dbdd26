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

// Measured with `snh-gpu-bench scale` (pocl, 2 CPU cores, double, nu = 0.49;
// README "Multigrid on hex8 lattices"), seconds per load step block-Jacobi /
// multigrid: twist 12,288 DOFs 1.87 / 1.50, twist 107,811 DOFs 34.4 / 17.4,
// stretch 3,519 DOFs 0.27 / 0.42, stretch 23,859 DOFs 2.43 / 2.96, stretch
// 73,059 DOFs 14.6 / 14.6. Multigrid's
// CG count per Newton stays flat while block-Jacobi's grows with the mesh,
// but its set-up per Newton iteration costs more than block-Jacobi's extra
// CG iterations on the smaller and easier meshes. So: multigrid on hex8
// lattices from 50,000 DOFs, block-Jacobi otherwise.
Preconditioner default_preconditioner(const Mesh& mesh) {
  constexpr size_t kMultigridFromDofs = 50000;
  return 3 * mesh.vertex_count() >= kMultigridFromDofs && solver::is_hex8_lattice(mesh) ? Preconditioner::multigrid
                                                                                        : Preconditioner::block_jacobi;
}

}  // namespace snh
