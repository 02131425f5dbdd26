// What the engine asks of the device, counted where it is queued: kernel
// launches, blocking read-backs (a read the host waits for, be it a whole
// vector, a reduction's partials or a scalar) and the bytes that cross
// between host and device. Counted on the host at the call, so the figures
// are the same on every device (pocl included) and never depend on timing.
// Plain data without OpenCL types: the phase profiler
// (device/phase_profile.h) attributes the counts to phases.
#pragma once

#include <cstdint>

namespace snh::device {

struct TransferCounts {
  int64_t kernel_launches = 0;
  int64_t blocking_readbacks = 0;
  int64_t bytes_to_host = 0;
  int64_t bytes_to_device = 0;

  TransferCounts& operator+=(const TransferCounts& o) {
    kernel_launches += o.kernel_launches;
    blocking_readbacks += o.blocking_readbacks;
    bytes_to_host += o.bytes_to_host;
    bytes_to_device += o.bytes_to_device;
    return *this;
  }
  TransferCounts& operator-=(const TransferCounts& o) {
    kernel_launches -= o.kernel_launches;
    blocking_readbacks -= o.blocking_readbacks;
    bytes_to_host -= o.bytes_to_host;
    bytes_to_device -= o.bytes_to_device;
    return *this;
  }
};

inline TransferCounts operator-(TransferCounts a, const TransferCounts& b) { return a -= b; }
inline TransferCounts operator+(TransferCounts a, const TransferCounts& b) { return a += b; }

}  // namespace snh::device
