// The per-phase profile (snh::SolveProfile) as the reports write it: a JSON
// object with one key per phase, and the phases in a fixed order for tables,
// then `kernels`: seconds per OpenCL kernel by name, then the device traffic
// (launches, blocking read-backs, bytes each way) in all and by phase. And the Newton history
// (snh::NewtonIteration) as the scene reports write it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "snh/simulation.h"

namespace snh::scene_io {

// (key, seconds) in the order the reports show them; `total` last.
inline std::vector<std::pair<std::string, double>> profile_parts(const SolveProfile& p) {
  return {{"linearization", p.linearization},
          {"products", p.products},
          {"preconditioner_setup", p.preconditioner_setup},
          {"preconditioner_apply", p.preconditioner_apply},
          {"cg_vector_work", p.cg_vector_work},
          {"line_search_energies", p.line_search_energies},
          {"transfers", p.transfers},
          {"other", p.other},
          {"total", p.total}};
}

inline nlohmann::ordered_json profile_json(const SolveProfile& p) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const auto& [key, seconds] : profile_parts(p)) j[key] = seconds;
  // Per kernel (a breakdown of the phases above, not a part of total).
  nlohmann::ordered_json kernels = nlohmann::ordered_json::object();
  for (const auto& [name, seconds] : p.kernels) kernels[name] = seconds;
  j["kernels"] = kernels;
  // Device traffic, counted (the same on every device): in all and by phase.
  j["kernel_launches"] = p.kernel_launches;
  j["blocking_readbacks"] = p.blocking_readbacks;
  j["bytes_to_host"] = p.bytes_to_host;
  j["bytes_to_device"] = p.bytes_to_device;
  j["cg_iterations_past_convergence"] = p.cg_iterations_past_convergence;
  nlohmann::ordered_json traffic = nlohmann::ordered_json::object();
  for (const auto& [phase, t] : p.traffic)
    traffic[phase] = {{"kernel_launches", t.kernel_launches},
                      {"blocking_readbacks", t.blocking_readbacks},
                      {"bytes_to_host", t.bytes_to_host},
                      {"bytes_to_device", t.bytes_to_device}};
  j["traffic"] = traffic;
  return j;
}

// One object per Newton iteration; `recovery` only where the solver did
// something to get past trouble.
inline nlohmann::ordered_json history_json(const std::vector<NewtonIteration>& history) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const NewtonIteration& h : history) {
    nlohmann::ordered_json j = {{"step", h.step},
                                {"iteration", h.iteration},
                                {"residual", h.residual_norm},
                                {"energy", h.energy},
                                {"step_length", h.step_length},
                                {"cg_iterations", h.cg_iterations},
                                {"cg_stop", cg_stop_text(h)},
                                {"projected", h.projected},
                                {"seconds", h.seconds}};
    if (!h.recovery.empty()) j["recovery"] = to_string(h.recovery);
    out.push_back(j);
  }
  return out;
}

}  // namespace snh::scene_io
