// Rest-state precomputation: shape-function gradients with respect to the rest
// coordinates and quadrature volumes, per element and quadrature point.
#pragma once

#include <vector>

#include "snh/mesh.h"

namespace snh::fem {

// Gauss points of the 2x2x2 rule on the reference cube [-1, 1]^3, in the
// order q = 4 k + 2 j + i over (xi_i, eta_j, zeta_k), xi_0 = -1/sqrt(3).
// Reference coordinates of the hex8 nodes in VTK order.
extern const double kHexNodeSigns[8][3];

struct RestState {
  ElementType type = ElementType::hex8;
  int nodes = 8;       // per element
  int quadrature = 8;  // points per element
  // True when every element has the same rest shape up to translation (a
  // lattice): then one element's data serves all and only that is stored.
  bool uniform = false;
  // dN_a/dX at each point, layout [element][q][a][3] (element 0 only when
  // uniform).
  std::vector<double> gradients;
  // Rest volume carried by each point (Gauss weight times det of the
  // reference-to-rest Jacobian), layout [element][q] (element 0 only when
  // uniform).
  std::vector<double> weights;
  double rest_volume = 0.0;

  const double* gradient(size_t element, int q, int a) const {
    const size_t e = uniform ? 0 : element;
    return gradients.data() + 3 * ((e * quadrature + q) * nodes + a);
  }
  double weight(size_t element, int q) const { return weights[(uniform ? 0 : element) * quadrature + q]; }
};

// Throws snh::Error naming the element when its rest volume at a quadrature
// point is zero, negative or not finite.
RestState compute_rest_state(const Mesh& mesh);

// det F of a column-major 3x3 matrix.
inline double determinant(const double f[9]) {
  return f[0] * (f[4] * f[8] - f[5] * f[7]) - f[3] * (f[1] * f[8] - f[2] * f[7]) + f[6] * (f[1] * f[5] - f[2] * f[4]);
}

// F at point q of element e for positions x (xyz per vertex), column-major.
void deformation_gradient(const Mesh& mesh, const RestState& rest, const double* x, size_t element, int q, double f[9]);

}  // namespace snh::fem
