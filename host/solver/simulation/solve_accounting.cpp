#include "solver/simulation/solve_accounting.h"

#include <iterator>

namespace snh {

SolveProfile& SolveProfile::operator+=(const SolveProfile& o) {
  linearization += o.linearization;
  products += o.products;
  preconditioner_setup += o.preconditioner_setup;
  preconditioner_apply += o.preconditioner_apply;
  cg_vector_work += o.cg_vector_work;
  line_search_energies += o.line_search_energies;
  transfers += o.transfers;
  other += o.other;
  total += o.total;
  for (const auto& [name, seconds] : o.kernels) kernels[name] += seconds;
  kernel_launches += o.kernel_launches;
  blocking_readbacks += o.blocking_readbacks;
  bytes_to_host += o.bytes_to_host;
  bytes_to_device += o.bytes_to_device;
  for (const auto& [name, t] : o.traffic) traffic[name] += t;
  cg_iterations_past_convergence += o.cg_iterations_past_convergence;
  return *this;
}

DeviceTraffic& DeviceTraffic::operator+=(const DeviceTraffic& o) {
  kernel_launches += o.kernel_launches;
  blocking_readbacks += o.blocking_readbacks;
  bytes_to_host += o.bytes_to_host;
  bytes_to_device += o.bytes_to_device;
  return *this;
}

namespace solver {

std::map<std::string, double> kernel_difference(std::map<std::string, double> now,
                                                const std::map<std::string, double>& before) {
  for (auto it = now.begin(); it != now.end();) {
    const auto b = before.find(it->first);
    if (b != before.end()) it->second -= b->second;
    it = it->second > 0.0 ? std::next(it) : now.erase(it);  // not run since
  }
  return now;
}

SolveProfile profile_between(const Counters& since, const Counters& now, double seconds) {
  SolveProfile profile =
      make_profile(difference(now.phases, since.phases), seconds - (now.callback_seconds - since.callback_seconds));
  profile.kernels = kernel_difference(now.kernels, since.kernels);
  add_traffic(difference(now.traffic, since.traffic), profile);
  profile.cg_iterations_past_convergence = now.cg_iterations_past_convergence - since.cg_iterations_past_convergence;
  return profile;
}

void record_deformation(const Mesh& mesh, const Points& x, SolveResult& result) {
  const DeformationStatistics stats = deformation_statistics(mesh, x);
  result.volume_ratio = stats.volume_ratio;
  result.min_j = stats.min_j;
  result.max_j = stats.max_j;
  result.inverted_elements = stats.inverted_elements;
}

}  // namespace solver
}  // namespace snh
