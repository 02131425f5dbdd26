#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "snh/error.h"
#include "snh/shape.h"

namespace snh {

ShapeDeviation shape_deviation(const Mesh& mesh, const Points& x) {
  const size_t n = mesh.vertex_count();
  if (x.size() != n)
    throw Error("shape_deviation: the positions have " + std::to_string(x.xyz().size()) + " values, the mesh " +
                std::to_string(n) + " vertices");
  std::vector<char> used(n, 0);
  for (int32_t v : mesh.elements) used[static_cast<size_t>(v)] = 1;
  Eigen::Vector3d rest_centroid = Eigen::Vector3d::Zero(), centroid = Eigen::Vector3d::Zero();
  size_t count = 0;
  for (size_t v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const Eigen::Vector3d p(x(v, 0), x(v, 1), x(v, 2));
    if (!p.allFinite()) throw Error("shape_deviation: the positions are not finite at vertex " + std::to_string(v));
    rest_centroid += Eigen::Vector3d(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2));
    centroid += p;
    ++count;
  }
  if (count == 0) throw Error("shape_deviation: the mesh has no element");
  rest_centroid /= static_cast<double>(count);
  centroid /= static_cast<double>(count);
  // Cross-covariance H = sum (X - X_c)(x - x_c)^T; the best rotation maps the
  // rest offsets onto the deformed ones, and the residual is
  // sum |X'|^2 + sum |x'|^2 - 2 tr(R H) (Horn 1987), tr(R H) the sum of H's
  // singular values with the last one's sign flipped if a reflection fits better.
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  double rest_square = 0.0, square = 0.0;
  for (size_t v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const Eigen::Vector3d a =
        Eigen::Vector3d(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)) - rest_centroid;
    const Eigen::Vector3d b = Eigen::Vector3d(x(v, 0), x(v, 1), x(v, 2)) - centroid;
    h += a * b.transpose();
    rest_square += a.squaredNorm();
    square += b.squaredNorm();
  }
  if (!(rest_square > 0.0)) throw Error("shape_deviation: the mesh's vertices all coincide");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const double reflection = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const double fit = svd.singularValues()(0) + svd.singularValues()(1) + reflection * svd.singularValues()(2);
  const double residual = std::max(0.0, rest_square + square - 2.0 * fit);
  ShapeDeviation out;
  out.rms_distance = std::sqrt(residual / static_cast<double>(count));
  out.radius_of_gyration = std::sqrt(rest_square / static_cast<double>(count));
  return out;
}

}  // namespace snh
