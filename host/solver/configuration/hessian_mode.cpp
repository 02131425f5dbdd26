// Names of the Newton Hessian modes (snh::HessianMode).
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh {

const char* to_string(HessianMode m) { return m == HessianMode::projected ? "projected" : "adaptive"; }

HessianMode parse_hessian_mode(const std::string& text) {
  for (HessianMode m : {HessianMode::projected, HessianMode::adaptive})
    if (text == to_string(m)) return m;
  throw Error("hessian: expected projected or adaptive, got '" + text + "'");
}

}  // namespace snh
