#include "solver/model/elastic_model.h"

#include <algorithm>
#include <cmath>

#include "device/material_args.h"
#include "device/readback.h"
#include "fem/vertex_slots.h"
#include "snh/error.h"
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
    layout = lanes_by_default() ? PointDataLayout::value_major : PointDataLayout::tiled;
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
  data_.cache = cl.buffer(CL_MEM_READ_WRITE, cache_values() * sizeof(Real));
  energies_ = cl.buffer(CL_MEM_READ_WRITE, element_count * sizeof(Real));
  min_j_ = cl.buffer(CL_MEM_READ_WRITE, element_count * sizeof(Real));
  if (terms.inertia || terms.obstacles > 0)
    vertex_terms_ = std::make_unique<VertexTerms<Real>>(cl, vertex_count, terms.inertia, terms.obstacles,
                                                        terms.friction, config, &profiler_);
  data_.elements_host = elements;

  energy_k_ = cl.kernel("fem.cl", config, "snh_element_energy");
  forces_k_ = cl.kernel("fem.cl", config, "snh_element_forces");
  products_ = std::make_unique<ProductVariants<Real>>(data_, material_, variant, &profiler_);
  set_point_lanes(point_lanes_available() && lanes_by_default());
  gather_k_ = cl.kernel("fem.cl", config, "snh_gather_vectors");
  block_jacobi_ = std::make_unique<BlockJacobi<Real>>(cl, vertex_count, config);
  mask_k_ = cl.kernel("fem.cl", config, "snh_apply_mask");
  if (terms.self_contact) self_contact_ = std::make_unique<SelfContactTerms<Real>>(cl, mesh, config, &profiler_);
  if (terms.self_barrier) {
    barrier_ = std::make_unique<BarrierTerms<Real>>(cl, mesh, &profiler_);
    barrier_->set_candidates_on_host(terms.self_broad_phase == SelfBroadPhase::automatic
                                         ? !cl.info().is_gpu
                                         : terms.self_broad_phase == SelfBroadPhase::host);
  }
  for (size_t e = 0; e < element_count; ++e) {
    const Material& m = materials.of_element(e);
    double volume = 0.0;
    for (int q = 0; q < data_.quadrature; ++q) volume += rest.weight(e, q);
    elastic_magnitude_ += (std::abs(m.mu) + std::abs(m.lambda)) * volume;
  }
  set_variant(variant);
}

template <typename Real>
void ElasticModel<Real>::set_variant(ProductVariant v) {
  products_->set_variant(v);
}

template <typename Real>
bool ElasticModel<Real>::point_lanes_available() const {
  // tet4 lanes hold 8 elements, so they share one material; the lanes read
  // the value-major or point-major cache.
  return data_.cache_tile == 1 && (data_.nodes == 8 || !material_.per_element());
}

template <typename Real>
void ElasticModel<Real>::set_point_lanes(bool on) {
  if (on && data_.cache_tile > 1)
    throw Error(
        "solver: the per-point lanes program reads the value-major or point-major cache, not the tiled one "
        "(PointDataLayout)");
  if (on && !point_lanes_available())
    throw Error("solver: per-point lanes of tet4 meshes need one material for the mesh (this map has regions)");
  data_.point_lanes = on;
  set_material_lanes(on ? default_material_lanes() : ElementData<Real>::kCacheLanes);
  products_->set_point_lanes(material_lanes_);
  diagonal_k_ = data_.point_kernel("snh_element_diagonal");
}

template <typename Real>
int ElasticModel<Real>::default_material_lanes() const {
  // Two of the device's native vectors per lane vector where it has 8-wide
  // ones for Real (AVX-512 in double, AVX and up in float): the SVD's chains
  // of dependent square roots and divisions bound one vector's throughput,
  // and a second, independent one fills their latency (twice the elements
  // per work-item). 8 where hex8 elements carry their own material (a
  // work-item's material is one element's).
  const DeviceInfo& info = data_.cl.info();
  const unsigned native =
      sizeof(Real) == sizeof(double) ? info.native_vector_width_double : info.native_vector_width_float;
  return native >= 8 && !hex8_materials_per_element() ? 16 : ElementData<Real>::kCacheLanes;
}

template <typename Real>
void ElasticModel<Real>::set_material_lanes(int lanes) {
  if (lanes != 8 && lanes != 16) throw Error("solver: material lanes are 8 or 16, not " + std::to_string(lanes));
  if (lanes == 16 && hex8_materials_per_element())
    throw Error(
        "solver: 16 material lanes hold two hex8 elements, so they need one material for the mesh (this map has "
        "regions)");
  material_lanes_ = data_.point_lanes ? lanes : 0;
  linearize_k_ = data_.point_kernel("snh_element_linearize", material_lanes_);
  products_->set_material_lanes(material_lanes_);
}

template <typename Real>
void ElasticModel<Real>::set_float_products(bool on) {
  products_->set_float_products(on);
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
void ElasticModel<Real>::set_obstacles(const std::vector<double>& records, double stiffness, double thickness) {
  if (terms_.obstacles == 0) throw Error("solver: set_obstacles on a model built without obstacles");
  if (records.size() != static_cast<size_t>(8 * terms_.obstacles))
    throw Error("solver: " + std::to_string(records.size()) + " obstacle record entries, expected " +
                std::to_string(8 * terms_.obstacles));
  vertex_terms_->set_obstacles(records, stiffness, thickness);
}

template <typename Real>
void ElasticModel<Real>::set_contact_surface(const ContactSurface& surface) {
  if (terms_.obstacles == 0) throw Error("solver: set_contact_surface on a model built without obstacles");
  vertex_terms_->set_contact_surface(surface);
}

template <typename Real>
void ElasticModel<Real>::set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                                      const std::vector<double>& start_records,
                                      const std::vector<double>& friction_records, double slip) {
  if (!terms_.friction) throw Error("solver: set_friction on a model built without friction");
  if (start_positions.size() != dofs() || anchors.size() != terms_.obstacles * dofs() ||
      start_records.size() != static_cast<size_t>(8 * terms_.obstacles) ||
      friction_records.size() != static_cast<size_t>(16 * terms_.obstacles))
    throw Error("solver: set_friction with arrays of the wrong size");
  if (!(slip > 0.0) || !std::isfinite(slip)) throw Error("solver: friction slip must be finite and > 0");
  vertex_terms_->set_friction(start_positions, anchors, start_records, friction_records, slip);
}

template <typename Real>
std::vector<double> ElasticModel<Real>::next_friction_anchors(const VectorBase& x) {
  if (!terms_.friction) throw Error("solver: next_friction_anchors on a model built without friction");
  return vertex_terms_->next_friction_anchors(mem(x));
}

template <typename Real>
void ElasticModel<Real>::contact(const VectorBase& x, bool linearization) const {
  vertex_terms_->contact(mem(x), linearization);
}

template <typename Real>
ContactState ElasticModel<Real>::contact_state(const VectorBase& x) {
  ContactState state;
  if (terms_.self_contact) {
    // The springs the penalty has at x: the set refreshed there (samples
    // already in contact keep theirs).
    refresh_self_contact(x);
    std::vector<Real> xh(dofs());
    device::read_back(data_.cl, x, xh);
    const std::vector<double> xd(xh.begin(), xh.end());
    for (const SelfContactPair& c : self_contact_->pairs()) {
      ++state.self_contacts;
      state.max_self_penetration = std::max(state.max_self_penetration, self_contact_length(c, xd));
    }
  }
  if (terms_.obstacles == 0) return state;
  contact(x);
  for (Real g : vertex_terms_->contact_depths())
    if (g > Real(0)) {
      ++state.contacts;
      state.max_penetration = std::max(state.max_penetration, static_cast<double>(g));
    }
  return state;
}

template <typename Real>
uint64_t ElasticModel<Real>::contact_set_signature() {
  return terms_.obstacles == 0 ? 0 : vertex_terms_->contact_set_signature();
}

template <typename Real>
void ElasticModel<Real>::set_self_contact_stiffness(double stiffness) {
  if (!terms_.self_contact) throw Error("solver: self-contact stiffness on a model built without self-contact");
  if (!(stiffness > 0.0) || !std::isfinite(stiffness)) throw Error("solver: self-contact stiffness not finite and > 0");
  self_contact_->set_stiffness(stiffness);
}

template <typename Real>
bool ElasticModel<Real>::refresh_self_contact(const VectorBase& x, bool new_step) {
  if (!terms_.self_contact) return false;
  std::vector<Real> xh(dofs());
  {
    PhaseScope transfer(&profiler_, Phase::transfers);
    device::read_back(data_.cl, x, xh);
  }
  return self_contact_->refresh(std::vector<double>(xh.begin(), xh.end()), new_step);
}

template <typename Real>
const std::vector<SelfContactPair>& ElasticModel<Real>::self_contacts() const {
  static const std::vector<SelfContactPair> none;
  return self_contact_ ? self_contact_->pairs() : none;
}

template <typename Real>
std::vector<double> ElasticModel<Real>::host_positions(const VectorBase& x) const {
  std::vector<double> xd;
  PhaseScope transfer(&profiler_, Phase::transfers);
  device::read_back(data_.cl, x, xd);
  return xd;
}

template <typename Real>
void ElasticModel<Real>::set_self_barrier(double dhat, double kappa) {
  if (!barrier_) throw Error("solver: barrier self-contact parameters on a model built without it");
  if (!(dhat > 0.0) || !std::isfinite(dhat)) throw Error("solver: self-contact distance not finite and > 0");
  if (!(kappa > 0.0) || !std::isfinite(kappa)) throw Error("solver: barrier stiffness not finite and > 0");
  barrier_->set_parameters(dhat, kappa);
}

template <typename Real>
void ElasticModel<Real>::set_self_barrier_surface(const Mesh& mesh, const TriangleSurface& surface,
                                                  const Embedding& embedding) {
  if (!barrier_) throw Error("solver: a barrier self-contact surface on a model built without it");
  barrier_->set_surface(BarrierContact(mesh, surface, embedding));
}

template <typename Real>
double ElasticModel<Real>::step_bound(const VectorBase& x, const VectorBase& p) {
  if (!barrier_) return std::numeric_limits<double>::infinity();
  return barrier_->step_bound(mem(x), mem(p));
}

template <typename Real>
void ElasticModel<Real>::self_differences(const VectorBase& u) const {
  if (self_contact_) self_contact_->differences(mem(u));
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
    contact(x);
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
  if (terms_.obstacles > 0) contact(x);
  self_differences(x);
  gather(data_.element_scratch, r, true, &x, 1, elastic_scale_);
  if (barrier_) barrier_->add_force(mem(x), data_.mask.get(), mem(r));
}

template <typename Real>
void ElasticModel<Real>::linearize(const VectorBase& x, bool projected) {
  PhaseScope timed(&profiler_, Phase::linearization);
  data_.cl.copy(mem(x), mem(linearized_x_), dofs() * sizeof(Real));  // in queue order, no ViennaCL kernel
  projected_ = projected ? 1 : 0;
  const int count = static_cast<int>(data_.element_count);
  KernelArgs args(linearize_k_.get());
  args.add(mem(x)).add(data_.elements.get()).add(data_.gradients.get()).add(count);
  material_.add_to(args).add(projected_).add(data_.cache.get());
  // Double: the cache's float copy for float products (null: none).
  if (sizeof(Real) > sizeof(float)) args.add(products_->float_cache_buffer());
  data_.run_point_kernel(args.bind(), material_lanes_);
  if (terms_.obstacles > 0) contact(x, true);  // the Gauss-Newton blocks at x
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
    self_differences(p);
    if (terms_.self_contact) self_contact_->add_args(terms);
    data_.cl.run(terms.bind(), dofs());
    if (barrier_) barrier_->add_product(data_.mask.get(), mem(p), mem(y));
    return;
  }
  products_->element_product(p, linearized_x_, projected_);
  self_differences(p);
  gather(data_.element_scratch, y, false, &p, 2, elastic_scale_);
  if (barrier_) barrier_->add_product(data_.mask.get(), mem(p), mem(y));
}

template <typename Real>
void ElasticModel<Real>::setup_preconditioner() {
  PhaseScope timed(&profiler_, Phase::preconditioner_setup);
  const int count = static_cast<int>(data_.element_count);
  if (!(projected_ && element_matrices_buffer())) {
    // Else the projected element matrices' kernel wrote their diagonal
    // blocks already.
    KernelArgs args(diagonal_k_.get());
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

template class ElasticModel<float>;
template class ElasticModel<double>;

}  // namespace snh::solver
