// Host reference in double precision.
#define SNH_DOUBLE 1
#include "material/element_reference_impl.inc"

namespace snh::reference {

// Precision-independent, so defined once, here.
MaterialSpec spec_of(const Material& m) {
  MaterialSpec s;
  s.model = static_cast<int>(m.model);
  s.barrier = m.barrier;
  s.mu = m.mu;
  s.lambda = m.lambda;
  s.c0 = m.c0;
  s.c1 = m.c1;
  s.lambda_model = m.lambda_model ? static_cast<int>(*m.lambda_model) : -1;
  s.lambda_c0 = m.lambda_c0;
  s.alpha_lambda = m.alpha_lambda;
  s.alpha_mu = m.alpha_mu;
  return s;
}

}  // namespace snh::reference
