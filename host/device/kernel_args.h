// A kernel launch's arguments as one list, set in order and checked against
// the kernel's own parameter count. The kernels' parameter lists depend on
// build switches (#if SNH_INERTIA, SNH_FRICTION, ...); a host list that
// disagrees with them would otherwise run with a stale or missing argument
// and give wrong numbers, not an error. Internal.
#pragma once

#include <string>

#include "device/opencl_context.h"

namespace snh::device {

// CL_KERNEL_NUM_ARGS and CL_KERNEL_FUNCTION_NAME of a kernel.
cl_uint kernel_arg_count(cl_kernel kernel);
std::string kernel_name(cl_kernel kernel);

// Usage: KernelArgs(k).add(x).add(n)...; then cl.run(args.bind(), n).
// An argument past the kernel's count throws at add(), a list that ends
// short at bind(); both name the kernel and the two counts. `first`: the
// index to start from, for lists that continue one set elsewhere.
class KernelArgs {
 public:
  explicit KernelArgs(cl_kernel kernel, cl_uint first = 0)
      : kernel_(kernel), next_(first), count_(kernel_arg_count(kernel)) {}

  template <typename T>
  KernelArgs& add(const T& value) {
    if (next_ >= count_) mismatch(next_ + 1);
    set_arg(kernel_, next_++, value);
    return *this;
  }
  // The index of the next argument (the count bound so far).
  cl_uint next() const { return next_; }
  // The kernel, once the arguments bound number exactly its parameters;
  // else throws snh::Error naming the kernel and both counts.
  cl_kernel bind() const;

 private:
  [[noreturn]] void mismatch(cl_uint bound) const;

  cl_kernel kernel_;
  cl_uint next_, count_;
};

}  // namespace snh::device
