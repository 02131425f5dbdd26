#include "device/viennacl_binding.h"

#include <atomic>

#include "viennacl/linalg/opencl/kernels/vector.hpp"
#include "viennacl/ocl/backend.hpp"

namespace snh::device {

long bind_viennacl(const OpenClContext& cl) {
  static std::atomic<long> next_id{1000};
  const long id = next_id++;
  viennacl::ocl::setup_context(id, cl.context(), cl.device(), cl.queue());
  viennacl::ocl::switch_context(id);
  return id;
}

void use_viennacl(long id) { viennacl::ocl::switch_context(id); }

namespace {

size_t element_wise_local_size(size_t size, size_t device_max) {
  // The largest power of two at most size / 512, or ViennaCL's 1 below 16:
  // measured fastest on pocl across sizes (docs/performance.md, "ViennaCL
  // work-group sizes").
  size_t local = 1;
  while (local * 2 <= size / 512 && local * 2 <= device_max && local < 4096) local *= 2;
  return local < 16 ? 1 : local;
}

}  // namespace

template <typename Real>
size_t tune_viennacl_vector_kernels(size_t size) {
  viennacl::ocl::context& ctx = viennacl::ocl::current_context();
  const viennacl::ocl::device& device = ctx.current_device();
  if (device.type() & (CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_ACCELERATOR)) return 0;
  using VectorKernels = viennacl::linalg::opencl::kernels::vector<Real>;
  VectorKernels::init(ctx);
  viennacl::ocl::program& program = ctx.get_program(VectorKernels::program_name());
  const size_t local = element_wise_local_size(size, device.max_work_group_size());
  // generate_avbv's kernels (x = a y, x = a y + b z, x += a y + b z, each
  // factor a host or a device scalar) and assign_cpu.
  for (const char* name : {"av_cpu", "av_gpu", "avbv_cpu_cpu", "avbv_cpu_gpu", "avbv_gpu_cpu", "avbv_gpu_gpu",
                           "avbv_v_cpu_cpu", "avbv_v_cpu_gpu", "avbv_v_gpu_cpu", "avbv_v_gpu_gpu", "assign_cpu"})
    program.get_kernel(name).local_work_size(0, local);
  return local;
}

template size_t tune_viennacl_vector_kernels<float>(size_t);
template size_t tune_viennacl_vector_kernels<double>(size_t);

}  // namespace snh::device
