// The pieces ViennaCL's CG is handed: the matrix-free projected Hessian
// (apply + sizes, as in ViennaCL's matrix-free tutorial) and the
// preconditioner with apply() (ViennaCL's own need an assembled matrix):
// none, block-Jacobi or the multigrid V-cycle.
#pragma once

#include <cmath>
#include <limits>

#include "solver/model/elastic_model.h"
#include "solver/multigrid/multigrid.h"

namespace snh::solver {

template <typename Real>
class HessianOperator {
 public:
  explicit HessianOperator(const ElasticModel<Real>& model) : model_(model) {}

  // y = K p. A direction of non-positive or non-finite curvature (possible
  // only for a singular K or through rounding, K being PSD by construction)
  // is reported and answered with an infinitely stiff response, y = big * p,
  // so that CG's step along it vanishes; the monitor then ends the solve.
  // Both reduced by the model's DeviceReduction (a fixed order, one kernel
  // and one read; ViennaCL's inner_prod allocates, runs two kernels and
  // reads), and p^T p only when p^T K p is not positive and finite (a zero
  // p, or one of those directions): one reduction per product, not two.
  void apply(const viennacl::vector_base<Real>& p, viennacl::vector_base<Real>& y) const {
    model_.product(p, y);
    const double pkp = model_.reduction().dot(mem(p), mem(y), p.size());
    if (pkp > 0.0 && std::isfinite(pkp)) return;
    const double pp = model_.reduction().sum_of_squares(mem(p), p.size());
    if (!(pp > 0.0)) return;
    if (!std::isfinite(pkp)) {
      breakdown_ = true;
      y = p * kStiff;
    } else if (!(pkp > 0.0)) {
      negative_curvature_ = true;
      y = p * kStiff;
    }
  }
  size_t size1() const { return model_.dofs(); }
  size_t size2() const { return model_.dofs(); }

  bool negative_curvature() const { return negative_curvature_; }
  bool breakdown() const { return breakdown_; }
  void reset() const { negative_curvature_ = breakdown_ = false; }

 private:
  static constexpr Real kStiff =
      Real(1) / (std::numeric_limits<Real>::epsilon() * std::numeric_limits<Real>::epsilon());
  const ElasticModel<Real>& model_;
  mutable bool negative_curvature_ = false;
  mutable bool breakdown_ = false;
};

template <typename Real>
class CgPreconditioner {
 public:
  // multigrid: the V-cycle when kind is multigrid, else null.
  CgPreconditioner(const ElasticModel<Real>& model, Preconditioner kind, const MultigridPreconditioner<Real>* multigrid)
      : model_(model), kind_(kind), multigrid_(multigrid) {}
  void apply(viennacl::vector_base<Real>& z) const {
    if (kind_ == Preconditioner::block_jacobi) model_.apply_preconditioner(z);
    if (kind_ == Preconditioner::multigrid) multigrid_->apply(z);
  }

 private:
  const ElasticModel<Real>& model_;
  Preconditioner kind_;
  const MultigridPreconditioner<Real>* multigrid_;
};

}  // namespace snh::solver
