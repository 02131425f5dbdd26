#include "solver/newton/implicit_euler.h"

namespace snh::solver {

EulerStep euler_step(const DynamicsOptions& d, const std::vector<double>& x, const std::vector<double>& v,
                     const std::vector<double>& mass, double h) {
  EulerStep e;
  e.start = x;
  const double ah = d.damping.mass * h, c = (1.0 + ah) / (h * h);
  e.coefficient.resize(mass.size());
  for (size_t i = 0; i < mass.size(); ++i) e.coefficient[i] = c * mass[i];
  // c M (x - y) = M (x - x~) / h^2 + a M (x - x_n) / h, x~ = x_n + h v_n.
  e.target.resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) e.target[i] = (x[i] + h * v[i] + ah * x[i]) / (1.0 + ah);
  e.stiffness_damping = d.damping.stiffness / h;
  return e;
}

void add_substep(const StepResult& sub, StepResult& total) {
  total.newton_iterations += sub.newton_iterations;
  total.cg_iterations += sub.cg_iterations;
  total.converged = total.converged && sub.converged;
  total.residual_norm = sub.residual_norm;
  total.status = sub.status;
  total.precision_used = sub.precision_used;
  total.contacts = sub.contacts;
  total.max_penetration = sub.max_penetration;
  total.self_contacts = sub.self_contacts;
  total.max_self_penetration = sub.max_self_penetration;
  total.self_contact_pairs = sub.self_contact_pairs;
  total.min_self_distance = sub.min_self_distance;
  total.self_contact_seconds += sub.self_contact_seconds;
  if (!sub.fallback.empty()) total.fallback = sub.fallback;
}

}  // namespace snh::solver
