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

// Measured with `snh-gpu-bench scale` (pocl, 2 CPU cores, double, nu = 0.49;
// README "Multigrid on hex8 lattices"), with the hierarchy reused between
// linearizations (MultigridOptions::rebuild_every), seconds per load step
// block-Jacobi / multigrid: twist 3,993 DOFs 0.452 / 0.363, 6,591 0.757 /
// 0.618, 12,288 1.43 / 1.05, 107,811 23.7 / 10.3; stretch 3,519 0.21 / 0.244,
// 6,363 0.418 / 0.447, 10,275 0.693 / 0.718, 23,859 1.73 / 1.68. Multigrid's
// CG count per Newton stays flat while block-Jacobi's grows with the mesh;
// below about 10,000 DOFs its set-up and V-cycle cost about what
// block-Jacobi's extra CG iterations do (stretch loses up to 15% there,
// twist gains 25%). So: multigrid on hex8 lattices from 10,000 DOFs,
// block-Jacobi otherwise.
Preconditioner default_preconditioner(const Mesh& mesh) {
  constexpr size_t kMultigridFromDofs = 10000;
  return 3 * mesh.vertex_count() >= kMultigridFromDofs && solver::is_hex8_lattice(mesh) ? Preconditioner::multigrid
                                                                                        : Preconditioner::block_jacobi;
}

}  // namespace snh
