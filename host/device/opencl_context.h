// A chosen OpenCL device with its context and in-order queue, and program
// building with the build log in the error. Internal: public headers never
// show OpenCL types.
#pragma once

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "device/kernel_config.h"
#include "device/transfer_counts.h"
#include "snh/device.h"

namespace snh::device {

// Throws snh::Error naming the call and the OpenCL error code.
void check(cl_int status, const char* what);

// clSetKernelArg for one value, checked.
template <typename T>
void set_arg(cl_kernel k, cl_uint index, const T& value) {
  check(clSetKernelArg(k, index, sizeof(T), &value), "clSetKernelArg");
}

// Owning handles released on destruction.
struct ProgramDeleter {
  void operator()(cl_program p) const { clReleaseProgram(p); }
};
struct KernelDeleter {
  void operator()(cl_kernel k) const { clReleaseKernel(k); }
};
struct MemDeleter {
  void operator()(cl_mem m) const { clReleaseMemObject(m); }
};
using Program = std::unique_ptr<std::remove_pointer_t<cl_program>, ProgramDeleter>;
using Kernel = std::unique_ptr<std::remove_pointer_t<cl_kernel>, KernelDeleter>;
using Buffer = std::unique_ptr<std::remove_pointer_t<cl_mem>, MemDeleter>;

class OpenClContext {
 public:
  // Picks the device (see DeviceOptions); throws snh::Error when none matches
  // or none exists, and when `precision` is double on a device without fp64.
  OpenClContext(const DeviceOptions& options, Precision precision);
  ~OpenClContext();
  OpenClContext(const OpenClContext&) = delete;
  OpenClContext& operator=(const OpenClContext&) = delete;

  const DeviceInfo& info() const { return info_; }
  Precision precision() const { return precision_; }
  cl_context context() const { return context_; }
  cl_command_queue queue() const { return queue_; }
  cl_device_id device() const { return device_; }

  // Builds kernels/<file> with `config` (device/kernel_config.h) in this
  // context's precision; cached per (file, config.defines()). A failed
  // build throws snh::Error carrying the compiler's log.
  cl_program program(const std::string& file, const KernelConfig& config = {});
  Kernel kernel(const std::string& file, const KernelConfig& config, const char* name);
  // The same from written switches ("-DSNH_BARRIER=1 ..."), parsed by
  // KernelConfig::parse (an unknown switch throws snh::Error).
  cl_program program(const std::string& file, const std::string& defines) {
    return program(file, KernelConfig::parse(defines));
  }
  Kernel kernel(const std::string& file, const std::string& defines, const char* name) {
    return kernel(file, KernelConfig::parse(defines), name);
  }
  Kernel kernel(const std::string& file, const char* defines, const char* name) {
    return kernel(file, std::string(defines), name);
  }
  // The programs built so far, in build order.
  const std::vector<BuiltProgram>& programs() const { return built_; }
  // The build options of `config` on this device (KernelConfig::build_options).
  std::string build_options(const KernelConfig& config) const;

  // A buffer of `bytes` (at least 1): a copy of `host`, else zeros. The
  // zeros are written when the buffer is made, in queue order: its contents
  // never depend on what the memory held before, and a device whose memory
  // is the host's (pocl) maps its pages here rather than in the first kernel
  // that writes them, inside a solve, where that slowed the first
  // linearization (docs/performance.md, "Buffers zero-filled when made").
  Buffer buffer(cl_mem_flags flags, size_t bytes, const void* host = nullptr);
  // The size of a buffer (0 for none).
  static size_t bytes(cl_mem buffer);
  // Blocking transfers, counted in counts(); device vectors go through these
  // (device/readback.h), never through ViennaCL's copy().
  void write(cl_mem buffer, size_t bytes, const void* data);
  void read(cl_mem buffer, size_t bytes, void* data);
  // The first `bytes` of `from` into `to`, on the device (in queue order).
  void copy(cl_mem from, cl_mem to, size_t bytes);
  // Queues `kernel` over global_size work-items (rounded up to whole groups)
  // without waiting for it: the queue is in order, and reads, phase
  // boundaries (device/phase_profile.h) and finish() wait. A wait after each
  // launch measured slower on pocl (docs/performance.md, "Kernel launches
  // without a wait").
  void run(cl_kernel kernel, size_t global_size);
  // Seconds each kernel run() queued ran on the device (its profiling
  // event's start to end), by kernel name, since this context was made
  // (ViennaCL's own kernels not included); waits for those still queued.
  const std::map<std::string, double>& kernel_seconds() const;
  // Waits for everything queued (ViennaCL's operations share the queue).
  void finish();
  // Launches, blocking reads and bytes each way since this context was made,
  // counted at the call: run(), read(), write() and buffers made from host
  // data. ViennaCL's own operations do not pass here; the solver's loops do
  // not use them (tests/test_device_traffic.cpp checks the counts against
  // the OpenCL calls themselves).
  const TransferCounts& counts() const { return counts_; }

  static constexpr size_t kWorkGroupSize = 64;

 private:
  DeviceInfo info_;
  Precision precision_;
  cl_device_id device_ = nullptr;
  // CL_DEVICE_MAX_MEM_ALLOC_SIZE: checked here because some drivers (NVIDIA's)
  // accept larger buffers and fail only later, or not at all until used.
  unsigned long long max_allocation_bytes_ = 0;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  std::map<std::string, Program> programs_;
  std::vector<BuiltProgram> built_;
  TransferCounts counts_;
  // Kernels queued by run() whose events are not yet read, by name; read
  // (and released) by kernel_seconds(), and every kMaxPending launches.
  static constexpr size_t kMaxPending = 512;
  mutable std::vector<std::pair<std::string, cl_event>> pending_;
  mutable std::map<std::string, double> kernel_seconds_;
  void collect_pending() const;
};

}  // namespace snh::device
