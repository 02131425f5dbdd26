#include "device/kernel_args.h"

#include <cstring>

#include "snh/error.h"

namespace snh::device {

cl_uint kernel_arg_count(cl_kernel kernel) {
  cl_uint count = 0;
  check(clGetKernelInfo(kernel, CL_KERNEL_NUM_ARGS, sizeof count, &count, nullptr), "clGetKernelInfo");
  return count;
}

std::string kernel_name(cl_kernel kernel) {
  size_t size = 0;
  if (clGetKernelInfo(kernel, CL_KERNEL_FUNCTION_NAME, 0, nullptr, &size) != CL_SUCCESS || size == 0)
    return "(unnamed)";
  std::string name(size, '\0');
  if (clGetKernelInfo(kernel, CL_KERNEL_FUNCTION_NAME, size, name.data(), nullptr) != CL_SUCCESS) return "(unnamed)";
  name.resize(std::strlen(name.c_str()));
  return name;
}

void KernelArgs::mismatch(cl_uint bound) const {
  throw Error("device: kernel " + kernel_name(kernel_) + " takes " + std::to_string(count_) + " arguments, " +
              std::to_string(bound) + " bound");
}

cl_kernel KernelArgs::bind() const {
  if (next_ != count_) mismatch(next_);
  return kernel_;
}

}  // namespace snh::device
