// Names of the CG preconditioners and the measured default.
#include "snh/error.h"
#include "snh/simulation.h"

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

Preconditioner default_preconditioner(const Mesh&) { return Preconditioner::block_jacobi; }

}  // namespace snh
