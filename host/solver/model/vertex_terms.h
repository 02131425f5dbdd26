// The per-vertex terms of the elastic model beyond elasticity: implicit
// Euler's inertia (SNH_INERTIA), the kinematic obstacles' contact penalty
// (SNH_OBSTACLES) and lagged friction against them (SNH_FRICTION). Their
// device arrays, and the arguments the model's gather, mask and block-Jacobi
// kernels read. Internal to the library.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "device/kernel_args.h"
#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "snh/mesh.h"
#include "snh/surface.h"
#include "solver/linear/device_reduction.h"

namespace snh::solver {

// An embedded surface's points in contact with the obstacles
// (Simulation::set_contact_surface), arranged for a gather per lattice
// vertex: per point its cell's 8 vertices and trilinear weights; per lattice
// vertex v the entries offsets[v] .. offsets[v + 1] of the points whose cell
// holds it, each 8 point + slot, in point order (so each vertex sums its
// shares in a fixed order: no atomics).
struct ContactSurface {
  std::vector<int32_t> point_vertices;  // 8 per point
  std::vector<double> point_weights;    // 8 per point
  std::vector<int32_t> offsets;         // vertex_count + 1
  std::vector<int32_t> entries;
  bool empty() const { return point_vertices.empty(); }
};

// The contact surface of an embedding in `mesh` (hex8); throws snh::Error
// naming the surface vertex whose element or weights do not fit.
ContactSurface contact_surface(const Mesh& mesh, const Embedding& embedding);

// The vertices v with depth[v] > 0: 0 for none, else the sum modulo 2^64 of
// splitmix64's mix of each index (kernels/math/mix64.h), 1 where that sum is
// 0. Any order of the sum gives the same value; a vertex entering or leaving
// the set changes it (but for a collision of 64-bit sums).
template <typename Real>
uint64_t contact_set_signature(const std::vector<Real>& depth);

template <typename Real>
class VertexTerms {
 public:
  // `obstacles`: how many (0: none); friction needs obstacles (the caller
  // checks). `config`: the model's build.
  VertexTerms(device::OpenClContext& cl, size_t vertex_count, bool inertia, int obstacles, bool friction,
              const device::KernelConfig& config, PhaseProfiler* profiler);

  // Inertia (validated by the caller): c_v per vertex and the target y.
  void set_inertia(const std::vector<double>& coefficient, const std::vector<double>& target);
  // sum += 1/2 sum_v c_v |x_v - y_v|^2, entry by entry in order (x: xyz per
  // vertex): the host's sum, where the device has no fp64.
  void add_inertia_energy(const std::vector<Real>& x, double& sum) const;
  // The same energy at x reduced on the device into `slot` of `reduction`
  // (on_device() only): c and y in double there, as the host holds them,
  // so no vector crosses to the host.
  void queue_inertia_energy(const DeviceReduction& reduction, cl_mem x, int slot) const;
  void set_obstacles(const std::vector<double>& records, double stiffness, double thickness);
  // The embedded surface's points join the contact (SNH_SURFACE_CONTACT:
  // the contact kernel is rebuilt with them); an empty one leaves them out
  // again. Needs obstacles.
  void set_contact_surface(const ContactSurface& surface);
  void set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                    const std::vector<double>& start_records, const std::vector<double>& friction_records, double slip);
  std::vector<double> next_friction_anchors(cl_mem x) const;
  // snh_contact_vertices at x: energy, force, blocks (into the blocks the
  // products read when `linearization`, else scratch) and depth per vertex.
  void contact(cl_mem x, bool linearization = false) const;
  // Each vertex's contact depth g at the last contact() (> 0: in a layer).
  std::vector<Real> contact_depths() const;
  // The vertices in a layer at the last contact() as an order-independent
  // hash (contact_set_signature below), reduced on the device where it has
  // fp64 (kernels/reduce.cl): one read of two integers whatever the size.
  // Elsewhere the depths are read and hashed here, to the same value.
  uint64_t contact_set_signature() const;
  cl_mem contact_energy() const { return contact_energy_.get(); }

  // The gather's arguments (inertia c and y, contact force and blocks), and
  // the products' and block-Jacobi's (c, contact blocks).
  void add_gather_args(device::KernelArgs& args) const;
  void add_block_args(device::KernelArgs& args) const;
  // Null without the term.
  cl_mem inertia_buffer() const { return inertia_ ? inertia_mass_.get() : nullptr; }
  cl_mem contact_blocks_buffer() const { return obstacles_count_ > 0 ? contact_blocks_.get() : nullptr; }
  size_t memory_bytes() const;

 private:
  device::OpenClContext& cl_;
  PhaseProfiler* profiler_;
  size_t vertex_count_;
  bool inertia_;
  int obstacles_count_;
  bool friction_;
  device::Buffer inertia_mass_, inertia_target_;
  // c and y in double for the energy's device reduction (with fp64).
  device::Buffer inertia_mass_wide_, inertia_target_wide_;
  std::vector<double> inertia_mass_host_, inertia_target_host_;
  // contact_blocks_ holds the blocks of the last linearization, which the
  // products use; other evaluations write theirs to contact_scratch_.
  device::Buffer obstacles_, contact_energy_, contact_force_, contact_blocks_, contact_scratch_, contact_depth_;
  double contact_stiffness_ = 0.0, contact_thickness_ = 0.0;
  device::Buffer friction_start_, friction_anchors_, friction_start_records_, friction_records_;
  double friction_slip_ = 0.0;
  device::Kernel contact_k_, friction_anchors_k_;
  // The contact set's device reduction (none without fp64): per-group
  // partials and the two totals (count, hash).
  device::Kernel contact_set_k_, contact_set_total_k_;
  device::Buffer contact_set_partial_, contact_set_total_;
  device::KernelConfig config_;
  // The contact surface's arrays (ContactSurface), empty without one.
  device::Buffer surface_offsets_, surface_entries_, surface_vertices_, surface_weights_;
  bool surface_ = false;
};

}  // namespace snh::solver
