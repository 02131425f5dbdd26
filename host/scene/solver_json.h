// What a solve ran, as the scene reports write it: the product variant and
// precision, the preconditioner with the multigrid's smoothing, and the
// Hessian mode. Shared by the scene JSON (from a SolveResult) and the rigged
// scene's (from a FrameRecord, whose fields of the same names are the frame
// solve's).
#pragma once

#include <nlohmann/json.hpp>

#include "snh/simulation.h"

namespace snh::scene_io {

template <class Ran>  // SolveResult or FrameRecord
void add_solver_json(nlohmann::ordered_json& j, const SolveOptions& options, const Ran& r) {
  j["product"] = to_string(r.product);
  j["product_precision"] = to_string(r.product_precision);
  j["preconditioner"] = to_string(r.preconditioner);
  if (r.preconditioner == Preconditioner::multigrid) {
    // As requested ("automatic": unset, docs/design.md).
    j["multigrid_fine_level"] = name_or_automatic(options.multigrid.fine_level);
    j["multigrid_fine_float"] = options.multigrid.fine_level_float;
    j["multigrid_float_cycle"] = r.multigrid_float_cycle;                      // as used
    j["multigrid_smoother_degree"] = r.multigrid_smoother_degree.value_or(0);  // as used (resolved)
    j["multigrid_chebyshev"] = name_or_automatic(r.multigrid_chebyshev);
  }
  j["hessian"] = to_string(options.hessian);
  j["fail_on_inverted"] = options.fail_on_inverted;
}

}  // namespace snh::scene_io
