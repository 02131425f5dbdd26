#include "solver/linear/block_jacobi.h"

namespace snh::solver {

template <typename Real>
BlockJacobi<Real>::BlockJacobi(device::OpenClContext& cl, size_t vertex_count, const device::KernelConfig& config)
    : cl_(cl), vertex_count_(vertex_count) {
  inverse_blocks_ = cl_.buffer(CL_MEM_READ_WRITE, vertex_count_ * 9 * sizeof(Real));
  setup_k_ = cl_.kernel("fem.cl", config, "snh_block_jacobi_setup");
  apply_k_ = cl_.kernel("fem.cl", config, "snh_block_jacobi_apply");
}

template <typename Real>
void BlockJacobi<Real>::setup(cl_mem element_blocks, cl_mem offsets, cl_mem adjacency, cl_mem mask,
                              const std::function<void(device::KernelArgs&)>& vertex_args) const {
  const int vertices = static_cast<int>(vertex_count_);
  device::KernelArgs args(setup_k_.get());
  args.add(element_blocks).add(offsets).add(adjacency).add(mask).add(vertices).add(inverse_blocks_.get());
  vertex_args(args);
  cl_.run(args.bind(), vertex_count_);
}

template <typename Real>
void BlockJacobi<Real>::apply(cl_mem z) const {
  const int vertices = static_cast<int>(vertex_count_);
  device::KernelArgs args(apply_k_.get());
  args.add(inverse_blocks_.get()).add(z).add(vertices).add(z);
  cl_.run(args.bind(), vertex_count_);
}

template <typename Real>
std::vector<Real> BlockJacobi<Real>::blocks() const {
  std::vector<Real> blocks(9 * vertex_count_);
  cl_.read(inverse_blocks_.get(), blocks.size() * sizeof(Real), blocks.data());
  return blocks;
}

template class BlockJacobi<float>;
template class BlockJacobi<double>;

}  // namespace snh::solver
