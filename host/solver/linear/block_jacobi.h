// Block-Jacobi preconditioning of the elastic model: the inverted 3x3
// diagonal blocks of the (projected) Hessian per vertex, summed from the
// elements' diagonal blocks (fem.cl, snh_block_jacobi_setup) and applied as
// z <- M^-1 z (snh_block_jacobi_apply). Internal to the library.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "device/kernel_args.h"
#include "device/opencl_context.h"

namespace snh::solver {

template <typename Real>
class BlockJacobi {
 public:
  // `config`: the model's build (its per-vertex terms included).
  BlockJacobi(device::OpenClContext& cl, size_t vertex_count, const device::KernelConfig& config);

  // The blocks from the elements' diagonal blocks, gathered per vertex
  // through the slots (offsets, adjacency) and masked; `vertex_args` adds
  // the setup kernel's arguments of the per-vertex terms built in.
  void setup(cl_mem element_blocks, cl_mem offsets, cl_mem adjacency, cl_mem mask,
             const std::function<void(device::KernelArgs&)>& vertex_args) const;
  void apply(cl_mem z) const;  // z <- M^-1 z
  // The inverted blocks, column-major per vertex.
  std::vector<Real> blocks() const;
  size_t memory_bytes() const { return device::OpenClContext::bytes(inverse_blocks_.get()); }

 private:
  device::OpenClContext& cl_;
  size_t vertex_count_;
  device::Buffer inverse_blocks_;
  device::Kernel setup_k_, apply_k_;
};

}  // namespace snh::solver
