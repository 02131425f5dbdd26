#include "solver/model/vertex_terms.h"

#include <algorithm>
#include <cmath>

#include "snh/error.h"

namespace snh::solver {

namespace kernel {
#include "math/mix64.h"
}  // namespace kernel

namespace {
constexpr size_t kReduceGroup = 64;                // SNH_REDUCE_GROUP, kernels/reduce.cl
constexpr size_t kReduceSpan = kReduceGroup * 64;  // SNH_REDUCE_SPAN

uint64_t signature_of(uint64_t count, uint64_t hash) { return count == 0 ? 0 : hash == 0 ? 1 : hash; }
}  // namespace

template <typename Real>
uint64_t contact_set_signature(const std::vector<Real>& depth) {
  uint64_t count = 0, hash = 0;
  for (size_t v = 0; v < depth.size(); ++v)
    if (depth[v] > Real(0)) {
      ++count;
      hash += kernel::snh_mix64(v);
    }
  return signature_of(count, hash);
}

template <typename Real>
VertexTerms<Real>::VertexTerms(device::OpenClContext& cl, size_t vertex_count, bool inertia, int obstacles,
                               bool friction, const device::KernelConfig& config, PhaseProfiler* profiler)
    : cl_(cl),
      profiler_(profiler),
      vertex_count_(vertex_count),
      inertia_(inertia),
      obstacles_count_(obstacles),
      friction_(friction),
      config_(config) {
  const size_t dofs = 3 * vertex_count_;
  if (inertia) {
    inertia_mass_host_.assign(vertex_count_, 0.0);
    inertia_target_host_.assign(dofs, 0.0);
    const std::vector<Real> zeros(dofs, Real(0));
    inertia_mass_ = cl_.buffer(CL_MEM_READ_ONLY, vertex_count_ * sizeof(Real), zeros.data());
    inertia_target_ = cl_.buffer(CL_MEM_READ_ONLY, dofs * sizeof(Real), zeros.data());
    if (cl_.info().has_fp64) {
      inertia_mass_wide_ = cl_.buffer(CL_MEM_READ_ONLY, vertex_count_ * sizeof(double), inertia_mass_host_.data());
      inertia_target_wide_ = cl_.buffer(CL_MEM_READ_ONLY, dofs * sizeof(double), inertia_target_host_.data());
    }
  }
  if (obstacles > 0) {
    const std::vector<Real> zeros(9 * vertex_count_, Real(0));
    obstacles_ = cl_.buffer(CL_MEM_READ_ONLY, 8 * obstacles * sizeof(Real), zeros.data());
    contact_energy_ = cl_.buffer(CL_MEM_READ_WRITE, vertex_count_ * sizeof(Real));
    contact_force_ = cl_.buffer(CL_MEM_READ_WRITE, dofs * sizeof(Real), zeros.data());
    contact_blocks_ = cl_.buffer(CL_MEM_READ_WRITE, 9 * vertex_count_ * sizeof(Real), zeros.data());
    contact_scratch_ = cl_.buffer(CL_MEM_READ_WRITE, 9 * vertex_count_ * sizeof(Real));
    contact_depth_ = cl_.buffer(CL_MEM_READ_WRITE, vertex_count_ * sizeof(Real));
  }
  if (friction) {
    // Until set_friction: coefficients of 0, no friction.
    const std::vector<Real> zeros(std::max<size_t>(obstacles * dofs, 16 * obstacles), Real(0));
    friction_start_ = cl_.buffer(CL_MEM_READ_ONLY, dofs * sizeof(Real), zeros.data());
    friction_anchors_ = cl_.buffer(CL_MEM_READ_WRITE, obstacles * dofs * sizeof(Real), zeros.data());
    friction_start_records_ = cl_.buffer(CL_MEM_READ_ONLY, 8 * obstacles * sizeof(Real), zeros.data());
    friction_records_ = cl_.buffer(CL_MEM_READ_ONLY, 16 * obstacles * sizeof(Real), zeros.data());
    friction_slip_ = 1.0;
  }
  if (obstacles > 0) contact_k_ = cl_.kernel("fem.cl", config, "snh_contact_vertices");
  // reduce.cl reads the depths as its `real`: the context's precision.
  const size_t context_real = cl_.precision() == Precision::double_ ? sizeof(double) : sizeof(float);
  if (obstacles > 0 && cl_.info().has_fp64 && context_real == sizeof(Real)) {
    contact_set_k_ = cl_.kernel("reduce.cl", "", "snh_partial_contact_set");
    contact_set_total_k_ = cl_.kernel("reduce.cl", "", "snh_contact_set_total");
    const size_t groups = std::max<size_t>(1, (vertex_count_ + kReduceSpan - 1) / kReduceSpan);
    contact_set_partial_ = cl_.buffer(CL_MEM_READ_WRITE, 2 * groups * sizeof(uint64_t));
    contact_set_total_ = cl_.buffer(CL_MEM_READ_WRITE, 2 * sizeof(uint64_t));
  }
  if (friction) friction_anchors_k_ = cl_.kernel("fem.cl", config, "snh_friction_anchors");
}

template <typename Real>
void VertexTerms<Real>::set_inertia(const std::vector<double>& coefficient, const std::vector<double>& target) {
  inertia_mass_host_ = coefficient;
  inertia_target_host_ = target;
  const std::vector<Real> c(coefficient.begin(), coefficient.end()), y(target.begin(), target.end());
  cl_.write(inertia_mass_.get(), c.size() * sizeof(Real), c.data());
  cl_.write(inertia_target_.get(), y.size() * sizeof(Real), y.data());
  if (inertia_mass_wide_) {
    cl_.write(inertia_mass_wide_.get(), coefficient.size() * sizeof(double), coefficient.data());
    cl_.write(inertia_target_wide_.get(), target.size() * sizeof(double), target.data());
  }
}

template <typename Real>
void VertexTerms<Real>::add_inertia_energy(const std::vector<Real>& x, double& sum) const {
  for (size_t i = 0; i < x.size(); ++i) {
    const double d = static_cast<double>(x[i]) - inertia_target_host_[i];
    sum += 0.5 * inertia_mass_host_[i / 3] * d * d;
  }
}

template <typename Real>
void VertexTerms<Real>::queue_inertia_energy(const DeviceReduction& reduction, cl_mem x, int slot) const {
  if (!inertia_mass_wide_ || !reduction.on_device())
    throw Error("solver: the inertia energy's device reduction needs fp64 on the device");
  reduction.queue_inertia(x, inertia_target_wide_.get(), inertia_mass_wide_.get(), 3 * vertex_count_, slot);
}

template <typename Real>
void VertexTerms<Real>::set_obstacles(const std::vector<double>& records, double stiffness, double thickness) {
  const std::vector<Real> r(records.begin(), records.end());
  cl_.write(obstacles_.get(), r.size() * sizeof(Real), r.data());
  contact_stiffness_ = stiffness;
  contact_thickness_ = thickness;
}

template <typename Real>
void VertexTerms<Real>::set_contact_surface(const ContactSurface& surface) {
  if (obstacles_count_ == 0) throw Error("solver: a contact surface needs obstacles");
  if (!surface.empty() && surface.offsets.size() != vertex_count_ + 1)
    throw Error("solver: a contact surface of " + std::to_string(surface.offsets.size() - 1) + " vertices, expected " +
                std::to_string(vertex_count_));
  surface_ = !surface.empty();
  if (!surface_) {
    contact_k_ = cl_.kernel("fem.cl", config_, "snh_contact_vertices");
    for (device::Buffer* b : {&surface_offsets_, &surface_entries_, &surface_vertices_, &surface_weights_}) *b = {};
    return;
  }
  const std::vector<Real> weights(surface.point_weights.begin(), surface.point_weights.end());
  // An empty entry list still needs a buffer.
  const std::vector<int32_t> entries = surface.entries.empty() ? std::vector<int32_t>{0} : surface.entries;
  surface_offsets_ = cl_.buffer(CL_MEM_READ_ONLY, surface.offsets.size() * sizeof(int32_t), surface.offsets.data());
  surface_entries_ = cl_.buffer(CL_MEM_READ_ONLY, entries.size() * sizeof(int32_t), entries.data());
  surface_vertices_ =
      cl_.buffer(CL_MEM_READ_ONLY, surface.point_vertices.size() * sizeof(int32_t), surface.point_vertices.data());
  surface_weights_ = cl_.buffer(CL_MEM_READ_ONLY, weights.size() * sizeof(Real), weights.data());
  contact_k_ = cl_.kernel("fem.cl", config_.with_surface_contact(), "snh_contact_vertices");
}

template <typename Real>
void VertexTerms<Real>::set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                                     const std::vector<double>& start_records,
                                     const std::vector<double>& friction_records, double slip) {
  const std::vector<Real> a(anchors.begin(), anchors.end());
  cl_.write(friction_anchors_.get(), a.size() * sizeof(Real), a.data());
  const std::vector<Real> x0(start_positions.begin(), start_positions.end());
  const std::vector<Real> r0(start_records.begin(), start_records.end());
  const std::vector<Real> fr(friction_records.begin(), friction_records.end());
  cl_.write(friction_start_.get(), x0.size() * sizeof(Real), x0.data());
  cl_.write(friction_start_records_.get(), r0.size() * sizeof(Real), r0.data());
  cl_.write(friction_records_.get(), fr.size() * sizeof(Real), fr.data());
  friction_slip_ = slip;
}

template <typename Real>
std::vector<double> VertexTerms<Real>::next_friction_anchors(cl_mem x) const {
  const int count = static_cast<int>(vertex_count_);
  device::KernelArgs args(friction_anchors_k_.get());
  args.add(x)
      .add(friction_start_.get())
      .add(obstacles_.get())
      .add(friction_start_records_.get())
      .add(friction_records_.get())
      .add(static_cast<Real>(contact_thickness_))
      .add(static_cast<Real>(friction_slip_))
      .add(count)
      .add(friction_anchors_.get());
  cl_.run(args.bind(), vertex_count_);
  std::vector<Real> a(obstacles_count_ * 3 * vertex_count_);
  {
    PhaseScope transfer(profiler_, Phase::transfers);
    cl_.read(friction_anchors_.get(), a.size() * sizeof(Real), a.data());
  }
  return std::vector<double>(a.begin(), a.end());
}

template <typename Real>
void VertexTerms<Real>::contact(cl_mem x, bool linearization) const {
  const Real stiffness = static_cast<Real>(contact_stiffness_), thickness = static_cast<Real>(contact_thickness_);
  const int count = static_cast<int>(vertex_count_);
  device::KernelArgs args(contact_k_.get());
  args.add(x)
      .add(obstacles_.get())
      .add(stiffness)
      .add(thickness)
      .add(count)
      .add(contact_energy_.get())
      .add(contact_force_.get())
      .add(linearization ? contact_blocks_.get() : contact_scratch_.get())
      .add(contact_depth_.get());
  if (friction_)
    args.add(friction_start_.get())
        .add(friction_anchors_.get())
        .add(friction_start_records_.get())
        .add(friction_records_.get())
        .add(static_cast<Real>(friction_slip_));
  if (surface_)
    args.add(surface_offsets_.get())
        .add(surface_entries_.get())
        .add(surface_vertices_.get())
        .add(surface_weights_.get());
  cl_.run(args.bind(), vertex_count_);
}

template <typename Real>
std::vector<Real> VertexTerms<Real>::contact_depths() const {
  std::vector<Real> depth(vertex_count_);
  cl_.read(contact_depth_.get(), depth.size() * sizeof(Real), depth.data());
  return depth;
}

template <typename Real>
uint64_t VertexTerms<Real>::contact_set_signature() const {
  if (obstacles_count_ == 0) return 0;
  if (!contact_set_k_) {
    std::vector<Real> depth;
    {
      PhaseScope transfer(profiler_, Phase::transfers);
      depth = contact_depths();
    }
    return solver::contact_set_signature(depth);
  }
  const size_t groups = (vertex_count_ + kReduceSpan - 1) / kReduceSpan;
  const int count = static_cast<int>(vertex_count_);
  if (groups > 0)
    cl_.run(device::KernelArgs(contact_set_k_.get())
                .add(contact_depth_.get())
                .add(count)
                .add(contact_set_partial_.get())
                .bind(),
            groups * kReduceGroup);
  cl_.run(device::KernelArgs(contact_set_total_k_.get())
              .add(contact_set_partial_.get())
              .add(static_cast<int>(groups))
              .add(contact_set_total_.get())
              .bind(),
          1);
  uint64_t total[2] = {0, 0};
  {
    PhaseScope transfer(profiler_, Phase::transfers);
    cl_.read(contact_set_total_.get(), sizeof(total), total);
  }
  return signature_of(total[0], total[1]);
}

template <typename Real>
void VertexTerms<Real>::add_gather_args(device::KernelArgs& args) const {
  if (inertia_) args.add(inertia_mass_.get()).add(inertia_target_.get());
  if (obstacles_count_ > 0) args.add(contact_force_.get()).add(contact_blocks_.get());
}

template <typename Real>
void VertexTerms<Real>::add_block_args(device::KernelArgs& args) const {
  if (inertia_) args.add(inertia_mass_.get());
  if (obstacles_count_ > 0) args.add(contact_blocks_.get());
}

template <typename Real>
size_t VertexTerms<Real>::memory_bytes() const {
  size_t bytes = 0;
  for (const device::Buffer* b :
       {&inertia_mass_, &inertia_target_, &inertia_mass_wide_, &inertia_target_wide_, &obstacles_, &contact_energy_,
        &contact_force_, &contact_blocks_, &contact_scratch_, &contact_depth_, &friction_start_, &friction_anchors_,
        &friction_start_records_, &friction_records_, &surface_offsets_, &surface_entries_, &surface_vertices_,
        &surface_weights_})
    bytes += device::OpenClContext::bytes(b->get());
  bytes +=
      device::OpenClContext::bytes(contact_set_partial_.get()) + device::OpenClContext::bytes(contact_set_total_.get());
  return bytes;
}

ContactSurface contact_surface(const Mesh& mesh, const Embedding& embedding) {
  ContactSurface out;
  const size_t points = embedding.element.size();
  if (points == 0) return out;
  if (mesh.type != ElementType::hex8) throw Error("contact surface: an embedding needs a hex8 lattice");
  if (embedding.weights.size() != 8 * points)
    throw Error("contact surface: " + std::to_string(embedding.weights.size()) + " weights for " +
                std::to_string(points) + " surface vertices (8 per vertex)");
  out.point_vertices.resize(8 * points);
  out.point_weights = embedding.weights;
  std::vector<int32_t> count(mesh.vertex_count() + 1, 0);
  for (size_t p = 0; p < points; ++p) {
    const int32_t e = embedding.element[p];
    if (e < 0 || static_cast<size_t>(e) >= mesh.element_count())
      throw Error("contact surface: surface vertex " + std::to_string(p) + " lies in element " + std::to_string(e) +
                  " of a mesh of " + std::to_string(mesh.element_count()));
    double sum = 0.0;
    for (int i = 0; i < 8; ++i) {
      const double w = embedding.weights[8 * p + i];
      if (!std::isfinite(w))
        throw Error("contact surface: surface vertex " + std::to_string(p) + " has a non-finite weight");
      sum += w;
      const int32_t v = mesh.elements[8 * static_cast<size_t>(e) + i];
      out.point_vertices[8 * p + i] = v;
      ++count[v + 1];
    }
    if (std::abs(sum - 1.0) > 1e-6)
      throw Error("contact surface: the weights of surface vertex " + std::to_string(p) + " sum to " +
                  std::to_string(sum) + ", not 1");
  }
  out.offsets.assign(mesh.vertex_count() + 1, 0);
  for (size_t v = 0; v < mesh.vertex_count(); ++v) out.offsets[v + 1] = out.offsets[v] + count[v + 1];
  out.entries.resize(out.offsets.back());
  std::vector<int32_t> next(out.offsets.begin(), out.offsets.end() - 1);
  for (size_t p = 0; p < points; ++p)
    for (int i = 0; i < 8; ++i) out.entries[next[out.point_vertices[8 * p + i]]++] = static_cast<int32_t>(8 * p + i);
  return out;
}

template class VertexTerms<float>;
template class VertexTerms<double>;
template uint64_t contact_set_signature(const std::vector<float>&);
template uint64_t contact_set_signature(const std::vector<double>&);

}  // namespace snh::solver
