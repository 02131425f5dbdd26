// The one way device vectors cross to the host and back outside
// OpenClContext's own read() and write(): ViennaCL's copy() would read
// behind the counts (device/transfer_counts.h). Each call is one blocking
// transfer of the whole vector, counted by the context. Internal.
#pragma once

#include <vector>

#include "device/opencl_context.h"
#include "viennacl/vector.hpp"

namespace snh::device {

// host <- v (resized to v.size()).
template <typename T, typename H>
void read_back(OpenClContext& cl, const viennacl::vector_base<T>& v, std::vector<H>& host) {
  std::vector<T> raw(v.size());
  if (!raw.empty()) cl.read(v.handle().opencl_handle().get(), raw.size() * sizeof(T), raw.data());
  host.assign(raw.begin(), raw.end());
}

// v <- host (host.size() == v.size()).
template <typename T, typename H>
void write_to_device(OpenClContext& cl, const std::vector<H>& host, viennacl::vector_base<T>& v) {
  const std::vector<T> raw(host.begin(), host.end());
  if (!raw.empty()) cl.write(v.handle().opencl_handle().get(), raw.size() * sizeof(T), raw.data());
}

}  // namespace snh::device
