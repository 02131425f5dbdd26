#include "device/opencl_context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "device/kernel_source.h"
#include "snh/error.h"

namespace snh {

Precision parse_precision(const std::string& text) {
  if (text == "float" || text == "single") return Precision::single;
  if (text == "double") return Precision::double_;
  throw Error("precision: expected float or double, got '" + text + "'");
}

const char* to_string(Precision p) { return p == Precision::single ? "float" : "double"; }

namespace {

struct Candidate {
  cl_device_id id;
  DeviceInfo info;
};

std::string device_string(cl_device_id d, cl_device_info what) {
  size_t size = 0;
  if (clGetDeviceInfo(d, what, 0, nullptr, &size) != CL_SUCCESS || size == 0) return {};
  std::string s(size, '\0');
  clGetDeviceInfo(d, what, size, s.data(), nullptr);
  s.resize(std::strlen(s.c_str()));
  return s;
}

std::string platform_name(cl_platform_id p) {
  size_t size = 0;
  if (clGetPlatformInfo(p, CL_PLATFORM_NAME, 0, nullptr, &size) != CL_SUCCESS || size == 0) return {};
  std::string s(size, '\0');
  clGetPlatformInfo(p, CL_PLATFORM_NAME, size, s.data(), nullptr);
  s.resize(std::strlen(s.c_str()));
  return s;
}

std::vector<Candidate> all_devices() {
  std::vector<Candidate> out;
  cl_uint platform_count = 0;
  // No ICD or no platform: CL_PLATFORM_NOT_FOUND_KHR or a zero count.
  if (clGetPlatformIDs(0, nullptr, &platform_count) != CL_SUCCESS || platform_count == 0) return out;
  std::vector<cl_platform_id> platforms(platform_count);
  clGetPlatformIDs(platform_count, platforms.data(), nullptr);
  for (cl_platform_id p : platforms) {
    cl_uint count = 0;
    if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &count) != CL_SUCCESS || count == 0) continue;
    std::vector<cl_device_id> ids(count);
    clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr);
    for (cl_device_id d : ids) {
      Candidate c{d, {}};
      c.info.platform = platform_name(p);
      c.info.name = device_string(d, CL_DEVICE_NAME);
      c.info.version = device_string(d, CL_DEVICE_VERSION);
      cl_device_type type = 0;
      clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof type, &type, nullptr);
      c.info.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
      cl_device_fp_config fp64 = 0;
      clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof fp64, &fp64, nullptr);
      c.info.has_fp64 = fp64 != 0 || device_string(d, CL_DEVICE_EXTENSIONS).find("cl_khr_fp64") != std::string::npos;
      cl_uint units = 0;
      clGetDeviceInfo(d, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof units, &units, nullptr);
      c.info.compute_units = units;
      cl_ulong mem = 0;
      clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, nullptr);
      c.info.global_memory_bytes = mem;
      cl_uint width = 0;
      clGetDeviceInfo(d, CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT, sizeof width, &width, nullptr);
      c.info.native_vector_width_float = width;
      width = 0;
      clGetDeviceInfo(d, CL_DEVICE_NATIVE_VECTOR_WIDTH_DOUBLE, sizeof width, &width, nullptr);
      c.info.native_vector_width_double = width;
      out.push_back(c);
    }
  }
  return out;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string describe(const DeviceInfo& i) { return i.platform + " / " + i.name; }

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> out;
  for (const Candidate& c : all_devices()) out.push_back(c.info);
  return out;
}

namespace device {

void check(cl_int status, const char* what) {
  if (status != CL_SUCCESS) {
    std::string hint;
    if (status == CL_MEM_OBJECT_ALLOCATION_FAILURE) hint = " (the device ran out of memory)";
    if (status == CL_OUT_OF_RESOURCES) hint = " (the device ran out of resources, or of memory)";
    if (status == CL_OUT_OF_HOST_MEMORY)
      hint = " (the OpenCL implementation ran out of host memory; with a GPU, too many contexts at once can do this)";
    if (status == CL_INVALID_BUFFER_SIZE)
      hint = " (the buffer exceeds the device's memory or its largest allocation: the mesh is too large for it)";
    throw Error(std::string("OpenCL: ") + what + " failed with error " + std::to_string(status) + hint);
  }
}

OpenClContext::OpenClContext(const DeviceOptions& options, Precision precision) : precision_(precision) {
  const std::vector<Candidate> devices = all_devices();
  if (devices.empty())
    throw Error("OpenCL: no OpenCL platform or device found (is an ICD such as pocl-opencl-icd installed?)");
  std::string match = options.match;
  if (match.empty()) {
    if (const char* env = std::getenv("SNH_DEVICE")) match = env;
  }
  const Candidate* chosen = nullptr;
  if (!match.empty()) {
    for (const Candidate& c : devices)
      if (lower(describe(c.info)).find(lower(match)) != std::string::npos) {
        chosen = &c;
        break;
      }
    if (!chosen) {
      std::string names;
      for (const Candidate& c : devices) names += "\n  " + describe(c.info);
      throw Error("OpenCL: no device matches '" + match + "'; devices are:" + names);
    }
  } else {
    for (const Candidate& c : devices)
      if (c.info.is_gpu) {
        chosen = &c;
        break;
      }
    if (!chosen) chosen = &devices.front();
  }
  info_ = chosen->info;
  device_ = chosen->id;
  cl_ulong largest = 0;
  clGetDeviceInfo(device_, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof largest, &largest, nullptr);
  max_allocation_bytes_ = largest;
  if (precision == Precision::double_ && !info_.has_fp64)
    throw Error("OpenCL: device '" + describe(info_) +
                "' has no double precision (cl_khr_fp64); choose --precision float or another device");
  cl_int status = CL_SUCCESS;
  context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &status);
  check(status, "clCreateContext");
  // Profiling events time each kernel without waiting for it (run()).
  queue_ = clCreateCommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE, &status);
  if (status != CL_SUCCESS) {
    clReleaseContext(context_);
    check(status, "clCreateCommandQueue");
  }
}

OpenClContext::~OpenClContext() {
  if (queue_) clFinish(queue_);
  for (auto& p : pending_) clReleaseEvent(p.second);
  programs_.clear();
  if (queue_) clReleaseCommandQueue(queue_);
  if (context_) clReleaseContext(context_);
}

std::string OpenClContext::build_options(const KernelConfig& config) const {
  KernelConfig c = config;
  c.precision = precision_;
  // SNH_GPU: a work-item's data-dependent loops cost a GPU nothing beyond
  // its warp's slowest point, where pocl's CPU kernels vectorize across
  // work-items only without them (kernels/snh_portable.h).
  return c.build_options(info_.is_gpu);
}

cl_program OpenClContext::program(const std::string& file, const KernelConfig& config) {
  const std::string key = config.cache_key(file);
  auto found = programs_.find(key);
  if (found != programs_.end()) return found->second.get();
  const std::string source = kernel_program_source(file);
  const char* text = source.c_str();
  const size_t length = source.size();
  cl_int status = CL_SUCCESS;
  Program program(clCreateProgramWithSource(context_, 1, &text, &length, &status));
  check(status, "clCreateProgramWithSource");
  const std::string flags = build_options(config);
  status = clBuildProgram(program.get(), 1, &device_, flags.c_str(), nullptr, nullptr);
  if (status != CL_SUCCESS) {
    size_t size = 0;
    clGetProgramBuildInfo(program.get(), device_, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
    std::string log(size, '\0');
    clGetProgramBuildInfo(program.get(), device_, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
    throw Error("OpenCL: building kernels/" + file + " (" + flags + ") failed with error " + std::to_string(status) +
                "; build log:\n" + log);
  }
  cl_program raw = program.get();
  programs_.emplace(key, std::move(program));
  KernelConfig built = config;
  built.precision = precision_;
  built_.push_back(BuiltProgram{file, built});
  ProgramRecorder::record(file, built);
  return raw;
}

Kernel OpenClContext::kernel(const std::string& file, const KernelConfig& config, const char* name) {
  cl_int status = CL_SUCCESS;
  Kernel k(clCreateKernel(program(file, config), name, &status));
  check(status, "clCreateKernel");
  return k;
}

Buffer OpenClContext::buffer(cl_mem_flags flags, size_t bytes, const void* host) {
  cl_int status = CL_SUCCESS;
  if (host) flags |= CL_MEM_COPY_HOST_PTR;
  if (max_allocation_bytes_ > 0 && bytes > max_allocation_bytes_)
    throw Error("OpenCL: clCreateBuffer failed: " + std::to_string(bytes) +
                " bytes exceed the device's largest allocation (" + std::to_string(max_allocation_bytes_) +
                " bytes, CL_DEVICE_MAX_MEM_ALLOC_SIZE): the mesh is too large for the device's memory");
  const size_t size = std::max<size_t>(bytes, 1);
  Buffer b(clCreateBuffer(context_, flags, size, const_cast<void*>(host), &status));
  check(status, "clCreateBuffer");
  if (host) counts_.bytes_to_device += static_cast<int64_t>(bytes);
  if (!host) {
    // The widest pattern OpenCL allows that divides the size (pocl copies
    // the pattern at a time).
    size_t pattern = 128;
    while (size % pattern != 0) pattern /= 2;
    static const cl_uchar zeros[128] = {};
    check(clEnqueueFillBuffer(queue_, b.get(), zeros, pattern, 0, size, 0, nullptr, nullptr), "clEnqueueFillBuffer");
  }
  return b;
}

void OpenClContext::write(cl_mem buffer, size_t bytes, const void* data) {
  counts_.bytes_to_device += static_cast<int64_t>(bytes);
  check(clEnqueueWriteBuffer(queue_, buffer, CL_TRUE, 0, bytes, data, 0, nullptr, nullptr), "clEnqueueWriteBuffer");
}

void OpenClContext::read(cl_mem buffer, size_t bytes, void* data) {
  ++counts_.blocking_readbacks;
  counts_.bytes_to_host += static_cast<int64_t>(bytes);
  check(clEnqueueReadBuffer(queue_, buffer, CL_TRUE, 0, bytes, data, 0, nullptr, nullptr), "clEnqueueReadBuffer");
}

void OpenClContext::copy(cl_mem from, cl_mem to, size_t bytes) {
  check(clEnqueueCopyBuffer(queue_, from, to, 0, 0, bytes, 0, nullptr, nullptr), "clEnqueueCopyBuffer");
}

size_t OpenClContext::bytes(cl_mem buffer) {
  if (!buffer) return 0;
  size_t size = 0;
  check(clGetMemObjectInfo(buffer, CL_MEM_SIZE, sizeof size, &size, nullptr), "clGetMemObjectInfo");
  return size;
}

void OpenClContext::finish() { check(clFinish(queue_), "clFinish"); }

void OpenClContext::run(cl_kernel kernel, size_t global_size) {
  if (global_size == 0) return;
  // An explicit work-group size: left to itself pocl picks groups of
  // thousands of work-items, whose private arrays overflow its thread stacks.
  size_t local = kWorkGroupSize;
  size_t kernel_max = 0;
  if (clGetKernelWorkGroupInfo(kernel, device_, CL_KERNEL_WORK_GROUP_SIZE, sizeof kernel_max, &kernel_max, nullptr) ==
          CL_SUCCESS &&
      kernel_max > 0)
    local = std::min(local, kernel_max);
  const size_t global = (global_size + local - 1) / local * local;  // kernels bound-check their index
  char name[256] = {0};  // asked each time: a released kernel's handle may be reused
  if (clGetKernelInfo(kernel, CL_KERNEL_FUNCTION_NAME, sizeof name - 1, name, nullptr) != CL_SUCCESS)
    std::strcpy(name, "(unnamed)");
  if (pending_.size() >= kMaxPending) collect_pending();
  cl_event event = nullptr;
  check(clEnqueueNDRangeKernel(queue_, kernel, 1, nullptr, &global, &local, 0, nullptr, &event),
        "clEnqueueNDRangeKernel");
  pending_.emplace_back(name, event);
  ++counts_.kernel_launches;
}

void OpenClContext::collect_pending() const {
  if (pending_.empty()) return;
  std::vector<cl_event> events;
  events.reserve(pending_.size());
  for (const auto& p : pending_) events.push_back(p.second);
  const cl_int waited = clWaitForEvents(static_cast<cl_uint>(events.size()), events.data());
  std::string failed;
  for (const auto& [name, event] : pending_) {
    cl_int status = CL_COMPLETE;
    clGetEventInfo(event, CL_EVENT_COMMAND_EXECUTION_STATUS, sizeof status, &status, nullptr);
    if (status < 0 && failed.empty()) failed = name + " (" + std::to_string(status) + ")";
    double& seconds = kernel_seconds_[name];  // listed as run even where the device gives no times
    cl_ulong start = 0, end = 0;
    if (clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr) == CL_SUCCESS &&
        clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr) == CL_SUCCESS &&
        end > start)
      seconds += 1e-9 * static_cast<double>(end - start);
    clReleaseEvent(event);
  }
  pending_.clear();
  if (!failed.empty()) throw Error("OpenCL: kernel " + failed + " failed on the device");
  check(waited, "clWaitForEvents");
}

const std::map<std::string, double>& OpenClContext::kernel_seconds() const {
  collect_pending();
  return kernel_seconds_;
}

}  // namespace device
}  // namespace snh
