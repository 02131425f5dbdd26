// Choosing the OpenCL device and the working precision, in the user's terms.
#pragma once

#include <string>
#include <vector>

namespace snh {

enum class Precision { single, double_ };

Precision parse_precision(const std::string& text);  // "float" or "double"
const char* to_string(Precision p);

struct DeviceOptions {
  // Case-insensitive substring of "<platform name> / <device name>". Empty:
  // the environment variable SNH_DEVICE if set, else the first GPU, else the
  // first device of any type.
  std::string match;
};

struct DeviceInfo {
  std::string platform;
  std::string name;
  std::string version;
  bool is_gpu = false;
  bool has_fp64 = false;
  unsigned compute_units = 0;
  unsigned long long global_memory_bytes = 0;
  // CL_DEVICE_NATIVE_VECTOR_WIDTH_FLOAT / _DOUBLE: the SIMD width in lanes
  // (0 without fp64).
  unsigned native_vector_width_float = 0;
  unsigned native_vector_width_double = 0;
};

// Every OpenCL device on this machine; empty when no platform is installed.
std::vector<DeviceInfo> list_devices();

}  // namespace snh
