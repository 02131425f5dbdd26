#include "solver/model/model_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "device/readback.h"
#include "snh/error.h"
#include "solver/model/elastic_model.h"

namespace snh::solver {

template <typename Real>
ModelContact<Real>::ModelContact(const ElementData<Real>& data, const ModelTerms& terms, PhaseProfiler* profiler,
                                 VertexTerms<Real>* vertex_terms, SelfContactTerms<Real>* self_contact,
                                 BarrierTerms<Real>* barrier)
    : data_(data),
      terms_(terms),
      profiler_(profiler),
      vertex_terms_(vertex_terms),
      self_contact_(self_contact),
      barrier_(barrier) {}

template <typename Real>
void ModelContact<Real>::set_obstacles(const std::vector<double>& records, double stiffness, double thickness) {
  if (terms_.obstacles == 0) throw Error("solver: set_obstacles on a model built without obstacles");
  if (records.size() != static_cast<size_t>(8 * terms_.obstacles))
    throw Error("solver: " + std::to_string(records.size()) + " obstacle record entries, expected " +
                std::to_string(8 * terms_.obstacles));
  vertex_terms_->set_obstacles(records, stiffness, thickness);
}

template <typename Real>
void ModelContact<Real>::set_contact_surface(const ContactSurface& surface) {
  if (terms_.obstacles == 0) throw Error("solver: set_contact_surface on a model built without obstacles");
  vertex_terms_->set_contact_surface(surface);
}

template <typename Real>
void ModelContact<Real>::set_friction(const std::vector<double>& start_positions, const std::vector<double>& anchors,
                                      const std::vector<double>& start_records,
                                      const std::vector<double>& friction_records, double slip) {
  if (!terms_.friction) throw Error("solver: set_friction on a model built without friction");
  if (start_positions.size() != data_.dofs() || anchors.size() != terms_.obstacles * data_.dofs() ||
      start_records.size() != static_cast<size_t>(8 * terms_.obstacles) ||
      friction_records.size() != static_cast<size_t>(16 * terms_.obstacles))
    throw Error("solver: set_friction with arrays of the wrong size");
  if (!(slip > 0.0) || !std::isfinite(slip)) throw Error("solver: friction slip must be finite and > 0");
  vertex_terms_->set_friction(start_positions, anchors, start_records, friction_records, slip);
}

template <typename Real>
std::vector<double> ModelContact<Real>::next_friction_anchors(const VectorBase& x) {
  if (!terms_.friction) throw Error("solver: next_friction_anchors on a model built without friction");
  return vertex_terms_->next_friction_anchors(mem(x));
}

template <typename Real>
ContactState ModelContact<Real>::contact_state(const VectorBase& x) {
  ContactState state;
  if (terms_.self_contact) {
    // The springs the penalty has at x: the set refreshed there (samples
    // already in contact keep theirs).
    refresh_self_contact(x);
    std::vector<Real> xh(data_.dofs());
    device::read_back(data_.cl, x, xh);
    const std::vector<double> xd(xh.begin(), xh.end());
    for (const SelfContactPair& c : self_contact_->pairs()) {
      ++state.self_contacts;
      state.max_self_penetration = std::max(state.max_self_penetration, self_contact_length(c, xd));
    }
  }
  if (terms_.obstacles == 0) return state;
  vertex_terms_->contact(mem(x));
  for (Real g : vertex_terms_->contact_depths())
    if (g > Real(0)) {
      ++state.contacts;
      state.max_penetration = std::max(state.max_penetration, static_cast<double>(g));
    }
  return state;
}

template <typename Real>
uint64_t ModelContact<Real>::contact_set_signature() {
  return terms_.obstacles == 0 ? 0 : vertex_terms_->contact_set_signature();
}

template <typename Real>
void ModelContact<Real>::set_self_contact_stiffness(double stiffness) {
  if (!terms_.self_contact) throw Error("solver: self-contact stiffness on a model built without self-contact");
  if (!(stiffness > 0.0) || !std::isfinite(stiffness)) throw Error("solver: self-contact stiffness not finite and > 0");
  self_contact_->set_stiffness(stiffness);
}

template <typename Real>
bool ModelContact<Real>::refresh_self_contact(const VectorBase& x, bool new_step) {
  if (!terms_.self_contact) return false;
  std::vector<Real> xh(data_.dofs());
  {
    PhaseScope transfer(profiler_, Phase::transfers);
    device::read_back(data_.cl, x, xh);
  }
  return self_contact_->refresh(std::vector<double>(xh.begin(), xh.end()), new_step);
}

template <typename Real>
const std::vector<SelfContactPair>& ModelContact<Real>::self_contacts() const {
  static const std::vector<SelfContactPair> none;
  return self_contact_ ? self_contact_->pairs() : none;
}

template <typename Real>
void ModelContact<Real>::set_self_barrier(double dhat, double kappa) {
  if (!barrier_) throw Error("solver: barrier self-contact parameters on a model built without it");
  if (!(dhat > 0.0) || !std::isfinite(dhat)) throw Error("solver: self-contact distance not finite and > 0");
  if (!(kappa > 0.0) || !std::isfinite(kappa)) throw Error("solver: barrier stiffness not finite and > 0");
  barrier_->set_parameters(dhat, kappa);
}

template <typename Real>
void ModelContact<Real>::set_self_barrier_surface(const Mesh& mesh, const TriangleSurface& surface,
                                                  const Embedding& embedding) {
  if (!barrier_) throw Error("solver: a barrier self-contact surface on a model built without it");
  barrier_->set_surface(BarrierContact(mesh, surface, embedding));
}

template <typename Real>
double ModelContact<Real>::step_bound(const VectorBase& x, const VectorBase& p) {
  if (!barrier_) return std::numeric_limits<double>::infinity();
  return barrier_->step_bound(mem(x), mem(p));
}

template class ModelContact<float>;
template class ModelContact<double>;

}  // namespace snh::solver
