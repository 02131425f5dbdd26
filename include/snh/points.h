// Point arrays: how positions, displacements, velocities and forces per
// vertex cross the API. Points holds n points as a row-major n x 3 array
// of doubles, x0 y0 z0 x1 y1 z1 ..., the layout of a C-ordered NumPy
// (n, 3) array and of Eigen's Matrix<double, Dynamic, 3, RowMajor>, so
// data() maps to either without a copy (docs/design.md, "Conventions of
// the public API").
#pragma once

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "snh/error.h"

namespace snh {

// One point or direction, x y z.
using Vec3 = std::array<double, 3>;

class Points {
 public:
  Points() = default;
  // `count` points, each `value`.
  explicit Points(std::size_t count, const Vec3& value = {0, 0, 0}) : xyz_(3 * count) {
    for (std::size_t i = 0; i < count; ++i) set(i, value);
  }
  Points(std::initializer_list<Vec3> points) {
    xyz_.reserve(3 * points.size());
    for (const Vec3& p : points) push_back(p);
  }
  // From the row-major values x0 y0 z0 x1 ...; snh::Error, naming `what`,
  // unless their number is a multiple of 3.
  static Points from_xyz(std::vector<double> xyz, const std::string& what = "point array") {
    if (xyz.size() % 3 != 0) throw Error(what + ": " + std::to_string(xyz.size()) + " values, not three per point");
    Points p;
    p.xyz_ = std::move(xyz);
    return p;
  }

  std::size_t size() const noexcept { return xyz_.size() / 3; }  // points
  bool empty() const noexcept { return xyz_.empty(); }
  Vec3 operator[](std::size_t i) const { return {xyz_[3 * i], xyz_[3 * i + 1], xyz_[3 * i + 2]}; }
  // Coordinate `axis` (0, 1, 2) of point i.
  double& operator()(std::size_t i, int axis) { return xyz_[3 * i + axis]; }
  double operator()(std::size_t i, int axis) const { return xyz_[3 * i + axis]; }
  void set(std::size_t i, const Vec3& p) {
    xyz_[3 * i] = p[0];
    xyz_[3 * i + 1] = p[1];
    xyz_[3 * i + 2] = p[2];
  }
  void push_back(const Vec3& p) { xyz_.insert(xyz_.end(), p.begin(), p.end()); }
  void append(const Points& other) { xyz_.insert(xyz_.end(), other.xyz_.begin(), other.xyz_.end()); }
  void resize(std::size_t count, const Vec3& value = {0, 0, 0}) {
    const std::size_t old = size();
    xyz_.resize(3 * count);
    for (std::size_t i = old; i < count; ++i) set(i, value);
  }
  void reserve(std::size_t count) { xyz_.reserve(3 * count); }
  void clear() noexcept { xyz_.clear(); }

  // The 3 size() values, row-major.
  double* data() noexcept { return xyz_.data(); }
  const double* data() const noexcept { return xyz_.data(); }
  const std::vector<double>& xyz() const noexcept { return xyz_; }
  // Moves the values out, leaving no points.
  std::vector<double> release() noexcept { return std::exchange(xyz_, {}); }

  friend bool operator==(const Points& a, const Points& b) { return a.xyz_ == b.xyz_; }
  friend bool operator!=(const Points& a, const Points& b) { return a.xyz_ != b.xyz_; }

 private:
  std::vector<double> xyz_;
};

}  // namespace snh
