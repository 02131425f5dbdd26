// The elastic model's contact as its users set it up and query it, reached
// as ElasticModel::contact(): the kinematic obstacles and their friction,
// an embedded surface's points in their contact, penalty self-contact and
// barrier self-contact; their parameters for the coming solve, and what they
// find at some x. The terms themselves (solver/model/vertex_terms.h,
// solver/contact/self_contact_terms.h, solver/contact/barrier_terms.h)
// belong to the model, whose energy, residual, linearization, products and
// preconditioner carry them. Internal to the library.
#pragma once

#include <cstdint>
#include <vector>

#include "device/opencl_context.h"
#include "device/phase_profile.h"
#include "snh/mesh.h"
#include "snh/surface.h"
#include "solver/contact/barrier_terms.h"
#include "solver/contact/self_contact.h"
#include "solver/contact/self_contact_terms.h"
#include "solver/model/element_data.h"
#include "solver/model/vertex_terms.h"
#include "viennacl/vector.hpp"

namespace snh::solver {

struct ModelTerms;  // solver/model/elastic_model.h

// Contact with the obstacles, and self-contact, at some x.
struct ContactState {
  int contacts = 0;                   // vertices with g = thickness - phi > 0
  double max_penetration = 0.0;       // the largest g (0: none)
  int self_contacts = 0;              // surface vertices in self-contact (detected at x)
  double max_self_penetration = 0.0;  // their largest spring length (0: none)
};

template <typename Real>
class ModelContact {
 public:
  using VectorBase = viennacl::vector_base<Real>;

  // All belong to the elastic model and outlive this: its data, the terms
  // it is built with, its profiler, and its per-vertex, self-contact and
  // barrier terms (each null where the model has none).
  ModelContact(const ElementData<Real>& data, const ModelTerms& terms, PhaseProfiler* profiler,
               VertexTerms<Real>* vertex_terms, SelfContactTerms<Real>* self_contact, BarrierTerms<Real>* barrier);

  // The obstacles placed for the coming solve (ModelTerms::obstacles records
  // of solver/contact/obstacles.h) and the penalty's stiffness and thickness: the
  // energy gains sum over vertices of their contact energy, the residual
  // their contact force, the Hessian their Gauss-Newton blocks.
  void set_obstacles(const std::vector<double>& records, double stiffness, double thickness);
  // An embedded surface's points join the obstacle contact (VertexTerms).
  void set_contact_surface(const ContactSurface& surface);
  // Friction (ModelTerms::friction) for the coming solve: the step's start
  // positions (xyz per vertex), the anchors (xyz per vertex and obstacle,
  // vertex-major), the obstacles' records at the step's start, their
  // friction records (solver/contact/obstacles.h) and the slip eps > 0. The energy,
  // residual and Hessian blocks gain the lagged friction potential.
  void set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                    const std::vector<double>& start_records, const std::vector<double>& friction_records, double slip);
  // After the solve, at its end x: the anchors for the next step
  // (kernels/contact/obstacle.h, obstacle_friction_anchor), same layout.
  std::vector<double> next_friction_anchors(const VectorBase& x);
  ContactState contact_state(const VectorBase& x);
  // The vertices in an obstacle's contact layer at the last linearize(), as
  // a hash of their indices (0: none, or no obstacles): where it changes, so
  // do the per-vertex contact blocks of the Hessian (the multigrid's reuse
  // rule, solver/newton/device_problem.h). One read of two integers where the
  // device has fp64 (VertexTerms::contact_set_signature).
  uint64_t contact_set_signature();
  // The obstacle contact (and friction) 3x3 blocks of the last linearize(),
  // which a multigrid's coarse levels take in (null without obstacles).
  cl_mem contact_blocks_buffer() const { return vertex_terms_ ? vertex_terms_->contact_blocks_buffer() : nullptr; }
  // Self-contact (ModelTerms::self_contact): the springs' stiffness, and the
  // active set detected at x, frozen until the next refresh (energy,
  // residual, products and preconditioner all use it). Within a step
  // (new_step false) a sample still in contact keeps the spring it had.
  // Returns whether the set changed. contact_state(x) refreshes it at x.
  void set_self_contact_stiffness(double stiffness);
  bool refresh_self_contact(const VectorBase& x, bool new_step = false);
  const std::vector<SelfContactPair>& self_contacts() const;
  const SelfContactDetector* self_contact_detector() const {
    return self_contact_ ? &self_contact_->detector() : nullptr;
  }
  // Barrier self-contact (ModelTerms::self_barrier): its dhat and kappa
  // (snh::Error without the term or for values not finite and > 0). The
  // energy, residual, linearization, products and block-Jacobi then carry
  // kappa sum b over the surface pairs within dhat, detected at each x.
  void set_self_barrier(double dhat, double kappa);
  // Barrier self-contact on a surface carried by the mesh's cells
  // (ContactOptions::self_surface) instead of its boundary.
  void set_self_barrier_surface(const Mesh& mesh, const TriangleSurface& surface, const Embedding& embedding);
  // The largest alpha <= 1 that continuous collision detection clears along
  // x + alpha p; infinity without barrier self-contact.
  double step_bound(const VectorBase& x, const VectorBase& p);
  // Null without barrier self-contact.
  const BarrierTerms<Real>* self_barrier() const { return barrier_; }

 private:
  const ElementData<Real>& data_;
  const ModelTerms& terms_;
  PhaseProfiler* profiler_;
  VertexTerms<Real>* vertex_terms_;
  SelfContactTerms<Real>* self_contact_;
  BarrierTerms<Real>* barrier_;
};

}  // namespace snh::solver
