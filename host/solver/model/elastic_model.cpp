#include "solver/model/elastic_model.h"

#include <cmath>

#include "device/material_args.h"
#include "device/readback.h"
#include "fem/vertex_slots.h"
#include "snh/error.h"
#include "solver/contact/obstacles.h"
#include "viennacl/linalg/prod.hpp"

namespace snh::solver {

namespace {

using device::KernelArgs;

const MaterialMap& validated(const Mesh& mesh, const MaterialMap& map) {
  validate_material_map(mesh, map);
  return map;
}

}  // namespace

template <typename Real>
ElasticModel<Real>::ElasticModel(device::OpenClContext& cl, const Mesh& mesh, const fem::RestState& rest,
                                 const MaterialMap& materials, ProductVariant variant, device::MaterialKernel build,
                                 const ModelTerms& terms)
    : data_(cl),
      profiler_([&cl] { cl.finish(); }),
      reduction_(cl, sizeof(Real), &profiler_),
      material_(cl, validated(mesh, materials), build),
      max_poisson_ratio_(snh::max_poisson_ratio(materials)),
      linearized_x_(3 * mesh.vertex_count()) {
  data_.vertex_count = mesh.vertex_count();
  data_.element_count = mesh.element_count();
  data_.nodes = rest.nodes;
  data_.quadrature = rest.quadrature;
  // Build-time specialization: only what this scene uses is compiled in.
  device::KernelConfig& config = data_.config;
  config = material_.config();
  config.element = mesh.type;
  config.uniform_rest = rest.uniform;
  // Every program that reads the cache or the gradients (multigrid.cl and
  // stencil.cl too) builds from these defines, so they all agree on the
  // layout.
  PointDataLayout layout = terms.hex8_point_data;
  if (layout == PointDataLayout::automatic)
    layout = PointLanes<Real>::lanes_by_default(cl) ? PointDataLayout::value_major : PointDataLayout::tiled;
  const bool value_major = layout == PointDataLayout::value_major;
  config.point_major = mesh.type == ElementType::hex8 && !value_major;
  if (layout == PointDataLayout::tiled) {
    data_.cache_tile = 32;
    config.cache_tile = config.stencil_tile = static_cast<int>(data_.cache_tile);
  }
  data_.elastic_config = config;
  terms_ = terms;
  if (terms.friction && terms.obstacles == 0) throw Error("solver: friction needs obstacles");
  config.inertia = terms.inertia;
  config.obstacles = terms.obstacles;
  config.self_contact = terms.self_contact;
  config.self_barrier = terms.self_barrier;
  config.friction = terms.friction;

  const size_t vertex_count = data_.vertex_count, element_count = data_.element_count;
  const fem::VertexSlots slots = fem::vertex_slots(mesh.elements, vertex_count);

  // The device's gradients value-major per element, [element][3 a + j][q]
  // (kernels/fem/element_data.h): a hex8 element's 8 points of one value
  // are one vector for the lanes kernels; point-major, the host's RestState
  // layout [element][q][a][3], with SNH_POINT_MAJOR.
  const size_t per_point = 3 * static_cast<size_t>(rest.nodes), points = static_cast<size_t>(rest.quadrature);
  std::vector<Real> gradients(rest.gradients.size());
  for (size_t e = 0; e < rest.gradients.size() / (per_point * points); ++e)
    for (size_t q = 0; q < points; ++q)
      for (size_t i = 0; i < per_point; ++i)
        gradients[value_major ? (e * per_point + i) * points + q : (e * points + q) * per_point + i] =
            static_cast<Real>(rest.gradients[(e * points + q) * per_point + i]);
  const std::vector<Real> weights(rest.weights.begin(), rest.weights.end());
  const std::vector<int> elements(mesh.elements.begin(), mesh.elements.end());
  data_.elements = cl.buffer(CL_MEM_READ_ONLY, elements.size() * sizeof(int), elements.data());
  data_.gradients = cl.buffer(CL_MEM_READ_ONLY, gradients.size() * sizeof(Real), gradients.data());
  data_.weights = cl.buffer(CL_MEM_READ_ONLY, weights.size() * sizeof(Real), weights.data());
  data_.offsets = cl.buffer(CL_MEM_READ_ONLY, slots.offsets.size() * sizeof(int), slots.offsets.data());
  data_.adjacency = cl.buffer(CL_MEM_READ_ONLY, slots.adjacency.size() * sizeof(int), slots.adjacency.data());
  const std::vector<Real> ones(dofs(), Real(1));
  data_.mask = cl.buffer(CL_MEM_READ_ONLY, dofs() * sizeof(Real), ones.data());
  external_ = cl.buffer(CL_MEM_READ_ONLY, dofs() * sizeof(Real));
  data_.element_scratch = cl.buffer(CL_MEM_READ_WRITE, element_count * data_.nodes * 3 * sizeof(Real));
  data_.element_blocks = cl.buffer(CL_MEM_READ_WRITE, element_count * data_.nodes * 9 * sizeof(Real));
  data_.cache = cl.buffer(CL_MEM_READ_WRITE, data_.cache_values() * sizeof(Real));
  energies_ = cl.buffer(CL_MEM_READ_WRITE, element_count * sizeof(Real));
  min_j_ = cl.buffer(CL_MEM_READ_WRITE, element_count * sizeof(Real));
  if (terms.inertia || terms.obstacles > 0)
    vertex_terms_ = std::make_unique<VertexTerms<Real>>(cl, vertex_count, terms.inertia, terms.obstacles,
                                                        terms.friction, config, &profiler_);
  data_.elements_host = elements;

  energy_k_ = cl.kernel("fem.cl", config, "snh_element_energy");
  forces_k_ = cl.kernel("fem.cl", config, "snh_element_forces");
  products_ = std::make_unique<ProductVariants<Real>>(data_, material_, variant, &profiler_);
  lanes_ = std::make_unique<PointLanes<Real>>(data_, material_, *products_);
  lanes_->set_point_lanes(lanes_->point_lanes_available() && PointLanes<Real>::lanes_by_default(cl));
  gather_k_ = cl.kernel("fem.cl", config, "snh_gather_vectors");
  block_jacobi_ = std::make_unique<BlockJacobi<Real>>(cl, vertex_count, config);
  mask_k_ = cl.kernel("fem.cl", config, "snh_apply_mask");
  if (terms.self_contact) self_contact_ = std::make_unique<SelfContactTerms<Real>>(cl, mesh, config, &profiler_);
  if (terms.self_barrier) {
    barrier_ = std::make_unique<BarrierTerms<Real>>(cl, mesh, &profiler_);
    barrier_->set_candidates_on_host(!terms.self_broad_phase ? !cl.info().is_gpu
                                                             : *terms.self_broad_phase == SelfBroadPhase::host);
  }
  contact_ = std::make_unique<ModelContact<Real>>(data_, terms_, &profiler_, vertex_terms_.get(), self_contact_.get(),
                                                  barrier_.get());
  for (size_t e = 0; e < element_count; ++e) {
    const Material& m = materials.of_element(e);
    double volume = 0.0;
    for (int q = 0; q < data_.quadrature; ++q) volume += rest.weight(e, q);
    elastic_magnitude_ += (std::abs(m.mu) + std::abs(m.lambda)) * volume;
  }
  products_->set_variant(variant);
}

template <typename Real>
size_t ElasticModel<Real>::memory_bytes() const {
  size_t bytes = material_.memory_bytes() + linearized_x_.size() * sizeof(Real);
  for (const device::Buffer* b :
       {&data_.elements, &data_.gradients, &data_.weights, &data_.offsets, &data_.adjacency, &data_.mask, &external_,
        &data_.element_scratch, &data_.element_blocks, &data_.cache, &energies_, &min_j_})
    bytes += device::OpenClContext::bytes(b->get());
  if (vertex_terms_) bytes += vertex_terms_->memory_bytes();
  bytes += block_jacobi_->memory_bytes();
  return bytes + products_->memory_bytes();
}

template <typename Real>
void ElasticModel<Real>::set_mask(const std::vector<Real>& mask) {
  if (mask.size() != dofs()) throw Error("solver: constraint mask has the wrong size");
  PhaseScope transfer(&profiler_, Phase::transfers);
  data_.cl.write(data_.mask.get(), mask.size() * sizeof(Real), mask.data());
}

template <typename Real>
void ElasticModel<Real>::set_external_force(const std::vector<double>& force) {
  has_external_ = !force.empty();
  if (!has_external_) return;
  if (force.size() != dofs())
    throw Error("solver: external force has " + std::to_string(force.size()) + " entries, expected " +
                std::to_string(dofs()) + " (xyz per vertex)");
  for (double f : force)
    if (!std::isfinite(f)) throw Error("solver: external force has a non-finite entry");
  external_host_ = force;
  const std::vector<Real> f(force.begin(), force.end());
  PhaseScope transfer(&profiler_, Phase::transfers);
  data_.cl.write(external_.get(), f.size() * sizeof(Real), f.data());
  if (reduction_.on_device()) {
    if (!external_work_) external_work_ = data_.cl.buffer(CL_MEM_READ_ONLY, dofs() * sizeof(double));
    data_.cl.write(external_work_.get(), force.size() * sizeof(double), force.data());
  }
}

template <typename Real>
void ElasticModel<Real>::set_inertia(const std::vector<double>& coefficient, const std::vector<double>& target,
                                     double elastic_scale) {
  if (!terms_.inertia) throw Error("solver: set_inertia on a model built without the inertia term");
  if (coefficient.size() != data_.vertex_count || target.size() != dofs())
    throw Error("solver: inertia has " + std::to_string(coefficient.size()) + " coefficients and " +
                std::to_string(target.size()) + " target entries, expected " + std::to_string(data_.vertex_count) +
                " and " + std::to_string(dofs()));
  for (double c : coefficient)
    if (!(c >= 0.0) || !std::isfinite(c)) throw Error("solver: inertia coefficient not finite and >= 0");
  for (double y : target)
    if (!std::isfinite(y)) throw Error("solver: inertia target has a non-finite entry");
  if (!(elastic_scale > 0.0) || !std::isfinite(elastic_scale)) throw Error("solver: elastic scale not finite and > 0");
  elastic_scale_ = elastic_scale;
  vertex_terms_->set_inertia(coefficient, target);
}

template <typename Real>
void ElasticModel<Real>::run_forces_kernel(const VectorBase& x) const {
  const int count = static_cast<int>(data_.element_count);
  KernelArgs args(forces_k_.get());
  args.add(mem(x)).add(data_.elements.get()).add(data_.gradients.get()).add(data_.weights.get()).add(count);
  material_.add_to(args).add(data_.element_scratch.get());
  data_.run_element_kernel(args.bind());
}

template <typename Real>
void ElasticModel<Real>::elastic_forces(const VectorBase& x, VectorBase& out) {
  run_forces_kernel(x);
  gather(data_.element_scratch, out, false);
}

template <typename Real>
double ElasticModel<Real>::energy(const VectorBase& x) {
  PhaseScope timed(&profiler_, Phase::line_search_energies);
  const int count = static_cast<int>(data_.element_count);
  KernelArgs args(energy_k_.get());
  args.add(mem(x)).add(data_.elements.get()).add(data_.gradients.get()).add(data_.weights.get()).add(count);
  material_.add_to(args).add(energies_.get()).add(min_j_.get());
  data_.run_element_kernel(args.bind());
  // One read for the sums and the minimum (slots: elastic, min J, then as
  // the terms present: contact, external work and its magnitude, inertia).
  const bool work_on_device = has_external_ && reduction_.on_device();
  const bool inertia_on_device = terms_.inertia && reduction_.on_device();
  reduction_.queue_sum(energies_.get(), data_.element_count, 0);
  reduction_.queue_min(min_j_.get(), data_.element_count, 1);
  int slots = 2;
  const int contact_slot = terms_.obstacles > 0 ? slots++ : -1;
  const int work_slot = work_on_device ? (slots += 2) - 2 : -1;
  const int inertia_slot = inertia_on_device ? slots++ : -1;
  if (contact_slot >= 0) {
    vertex_terms_->contact(mem(x));
    reduction_.queue_sum(vertex_terms_->contact_energy(), data_.vertex_count, contact_slot);
  }
  if (work_slot >= 0) reduction_.queue_work(mem(x), external_work_.get(), dofs(), work_slot);
  if (inertia_slot >= 0) vertex_terms_->queue_inertia_energy(reduction_, mem(x), inertia_slot);
  const double* totals = reduction_.read_totals(slots);
  double sum = totals[0] * elastic_scale_;
  last_min_j_ = totals[1];
  last_energy_magnitude_ = elastic_magnitude_ * elastic_scale_;
  if (contact_slot >= 0) sum += totals[contact_slot];
  if (work_slot >= 0) {
    sum -= totals[work_slot];
    last_energy_magnitude_ += totals[work_slot + 1];
  }
  if (inertia_slot >= 0) sum += totals[inertia_slot];
  if ((has_external_ && !work_on_device) || (terms_.inertia && !inertia_on_device) || terms_.self_contact) {
    std::vector<Real> xh(dofs());
    {
      PhaseScope transfer(&profiler_, Phase::transfers);
      device::read_back(data_.cl, x, xh);
    }
    if (has_external_ && !work_on_device)
      for (size_t i = 0; i < xh.size(); ++i) {
        sum -= external_host_[i] * static_cast<double>(xh[i]);
        last_energy_magnitude_ += std::abs(external_host_[i] * static_cast<double>(xh[i]));
      }
    if (terms_.inertia && !inertia_on_device) vertex_terms_->add_inertia_energy(xh, sum);
    if (terms_.self_contact && !self_contact_->pairs().empty()) {
      // The frozen springs, in contact order, in double.
      const double springs = self_contact_energy(self_contact_->pairs(), self_contact_->stiffness(),
                                                 std::vector<double>(xh.begin(), xh.end()));
      sum += springs;
      last_energy_magnitude_ += springs;
    }
  }
  if (barrier_) {
    const double barrier = barrier_->energy(mem(x));
    sum += barrier;
    last_energy_magnitude_ += barrier;
  }
  return sum;
}

template <typename Real>
void ElasticModel<Real>::gather(const device::Buffer& element_values, VectorBase& out, bool external,
                                const VectorBase* u, int vertex_mode, double scale) const {
  const int use_external = external && has_external_ ? 1 : 0;
  const Real sign = static_cast<Real>(scale);
  const int count = static_cast<int>(data_.vertex_count);
  KernelArgs args(gather_k_.get());
  args.add(element_values.get())
      .add(data_.offsets.get())
      .add(data_.adjacency.get())
      .add(data_.mask.get())
      .add(external_.get())
      .add(use_external)
      .add(sign)
      .add(count)
      .add(mem(out));
  if (vertex_terms()) args.add(u ? mem(*u) : mem(out)).add(u ? vertex_mode : 0);  // u read only when vertex_mode > 0
  if (vertex_terms_) vertex_terms_->add_gather_args(args);
  if (terms_.self_contact) self_contact_->add_args(args);
  data_.cl.run(args.bind(), data_.vertex_count);
}

template <typename Real>
void ElasticModel<Real>::residual(const VectorBase& x, VectorBase& r) {
  PhaseScope timed(&profiler_, Phase::line_search_energies);
  run_forces_kernel(x);
  if (terms_.obstacles > 0) vertex_terms_->contact(mem(x));
  if (self_contact_) self_contact_->differences(mem(x));
  gather(data_.element_scratch, r, true, &x, 1, elastic_scale_);
  if (barrier_) barrier_->add_force(mem(x), data_.mask.get(), mem(r));
}

template <typename Real>
void ElasticModel<Real>::linearize(const VectorBase& x, bool projected) {
  PhaseScope timed(&profiler_, Phase::linearization);
  data_.cl.copy(mem(x), mem(linearized_x_), dofs() * sizeof(Real));  // in queue order, no ViennaCL kernel
  const int projection = projected ? 1 : 0;
  const int count = static_cast<int>(data_.element_count);
  KernelArgs args(lanes_->linearize_kernel());
  args.add(mem(x)).add(data_.elements.get()).add(data_.gradients.get()).add(count);
  material_.add_to(args).add(projection).add(data_.cache.get());
  // Double: the cache's float copy for float products (null: none).
  if (sizeof(Real) > sizeof(float)) args.add(products_->float_cache_buffer());
  data_.run_point_kernel(args.bind(), lanes_->material_lanes());
  if (terms_.obstacles > 0) vertex_terms_->contact(mem(x), true);  // the Gauss-Newton blocks at x
  if (barrier_) barrier_->linearize(mem(x));
  products_->linearized(projected);
}

template <typename Real>
void ElasticModel<Real>::product(const VectorBase& p, VectorBase& y) const {
  PhaseScope timed(&profiler_, Phase::products);
  if (products_->stencil_product(p, y)) {
    // The per-vertex terms as after the element products (mask * mask = mask).
    if (!vertex_terms()) {
      if (barrier_) barrier_->add_product(data_.mask.get(), mem(p), mem(y));
      return;
    }
    const int size = static_cast<int>(dofs());
    KernelArgs terms(mask_k_.get());
    terms.add(data_.mask.get()).add(size).add(mem(y)).add(static_cast<Real>(elastic_scale_)).add(mem(p));
    if (vertex_terms_) vertex_terms_->add_block_args(terms);
    if (self_contact_) self_contact_->differences(mem(p));
    if (terms_.self_contact) self_contact_->add_args(terms);
    data_.cl.run(terms.bind(), dofs());
    if (barrier_) barrier_->add_product(data_.mask.get(), mem(p), mem(y));
    return;
  }
  products_->element_product(p, linearized_x_);
  if (self_contact_) self_contact_->differences(mem(p));
  gather(data_.element_scratch, y, false, &p, 2, elastic_scale_);
  if (barrier_) barrier_->add_product(data_.mask.get(), mem(p), mem(y));
}

template <typename Real>
void ElasticModel<Real>::setup_preconditioner() {
  PhaseScope timed(&profiler_, Phase::preconditioner_setup);
  const int count = static_cast<int>(data_.element_count);
  if (!(products_->projected() && products_->element_matrices_buffer())) {
    // Else the projected element matrices' kernel wrote their diagonal
    // blocks already.
    KernelArgs args(lanes_->diagonal_kernel());
    args.add(data_.elements.get())
        .add(data_.gradients.get())
        .add(data_.weights.get())
        .add(count)
        .add(data_.cache.get())
        .add(data_.element_blocks.get());
    data_.run_point_kernel(args.bind(), data_.point_lanes ? ElementData<Real>::kCacheLanes : 0);
  }
  block_jacobi_->setup(data_.element_blocks.get(), data_.offsets.get(), data_.adjacency.get(), data_.mask.get(),
                       [this](KernelArgs& args) {
                         if (vertex_terms()) args.add(static_cast<Real>(elastic_scale_));
                         if (vertex_terms_) vertex_terms_->add_block_args(args);
                         if (terms_.self_contact) args.add(self_contact_->diagonal());
                         if (barrier_) args.add(barrier_->diagonal());
                       });
}

template <typename Real>
void ElasticModel<Real>::apply_preconditioner(VectorBase& z) const {
  PhaseScope timed(&profiler_, Phase::preconditioner_apply);
  block_jacobi_->apply(mem(z));
}

template <typename Real>
std::vector<Real> ElasticModel<Real>::preconditioner_blocks() const {
  PhaseScope transfer(&profiler_, Phase::transfers);
  return block_jacobi_->blocks();
}

ModelTerms model_terms(const SolveOptions& options) {
  ModelTerms terms;
  terms.inertia = options.dynamics.has_value();
  terms.obstacles = static_cast<int>(options.obstacles.size());
  terms.self_contact = options.contact.self && options.contact.self_method == SelfContactMethod::penalty;
  terms.self_barrier = options.contact.self && options.contact.self_method == SelfContactMethod::barrier;
  terms.self_broad_phase = options.contact.self_broad_phase;
  terms.friction = has_friction(options.obstacles, options.contact);
  return terms;
}

template class ElasticModel<float>;
template class ElasticModel<double>;

}  // namespace snh::solver
