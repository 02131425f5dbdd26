// Matrix helpers for skeletons and linear blend skinning (snh/character.h).
#include <cmath>
#include <string>

#include "snh/character.h"
#include "snh/error.h"

namespace snh {

Matrix4 compose_trs(const std::array<double, 3>& t, const std::array<double, 4>& q, const std::array<double, 3>& s) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  // The rotation of a unit quaternion (glTF 2.0 §3.5.3; assimp's aiQuaternion::GetMatrix).
  const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                       2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                       2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
  Matrix4 m{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[4 * i + j] = r[3 * i + j] * s[j];  // R * S: column j scaled
    m[4 * i + 3] = t[i];
  }
  m[15] = 1.0;
  return m;
}

Matrix4 multiply_matrix4(const Matrix4& a, const Matrix4& b) {
  Matrix4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += a[4 * i + k] * b[4 * k + j];
      c[4 * i + j] = s;
    }
  return c;
}

Matrix4 inverse_matrix4(const Matrix4& m) {
  // Gauss-Jordan with partial pivoting on [m | I].
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[4 * i + j] : (j - 4 == i ? 1.0 : 0.0);
  double scale = 0.0;
  for (double v : m) scale = std::max(scale, std::abs(v));
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int i = c + 1; i < 4; ++i)
      if (std::abs(a[i][c]) > std::abs(a[p][c])) p = i;
    if (!(std::abs(a[p][c]) > 1e-14 * scale)) throw Error("inverse_matrix4: the matrix is singular");
    for (int j = 0; j < 8; ++j) std::swap(a[c][j], a[p][j]);
    const double d = a[c][c];
    for (int j = 0; j < 8; ++j) a[c][j] /= d;
    for (int i = 0; i < 4; ++i) {
      if (i == c) continue;
      const double f = a[i][c];
      for (int j = 0; j < 8; ++j) a[i][j] -= f * a[c][j];
    }
  }
  Matrix4 out{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[4 * i + j] = a[i][j + 4];
  return out;
}

Points linear_blend_skinning(const Points& rest, const SkinWeights& weights, const std::vector<Matrix4>& matrices) {
  const size_t n = rest.size();
  if (weights.vertex_count() != n)
    throw Error("linear_blend_skinning: " + std::to_string(weights.vertex_count()) + " weight rows for " +
                std::to_string(n) + " vertices");
  Points out(n);
  for (size_t v = 0; v < n; ++v) {
    const double* x = rest.data() + 3 * v;
    for (int32_t k = weights.offset[v]; k < weights.offset[v + 1]; ++k) {
      const int32_t j = weights.joint[k];
      if (j < 0 || static_cast<size_t>(j) >= matrices.size())
        throw Error("linear_blend_skinning: vertex " + std::to_string(v) + " names joint " + std::to_string(j) +
                    " of " + std::to_string(matrices.size()));
      const Matrix4& m = matrices[j];
      const double w = weights.weight[k];
      for (int d = 0; d < 3; ++d)
        out(v, d) += w * (m[4 * d] * x[0] + m[4 * d + 1] * x[1] + m[4 * d + 2] * x[2] + m[4 * d + 3]);
    }
  }
  return out;
}

}  // namespace snh
