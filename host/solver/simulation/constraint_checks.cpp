#include "solver/simulation/constraint_checks.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "snh/error.h"
#include "snh/pieces.h"

namespace snh::solver {

std::vector<char> prescribed_dofs(const Mesh& mesh, const std::vector<ConstraintSet>& sets) {
  std::vector<char> prescribed(3 * mesh.vertex_count(), 0);
  for (const ConstraintSet& c : sets)
    for (int32_t v : c.vertices)
      for (int d = 0; d < 3; ++d)
        if (c.components[d]) prescribed[3 * v + d] = 1;
  return prescribed;
}

namespace {

// place_by_callback into x, xyz per vertex.
void place_by_callback_into(const Mesh& mesh, const ConstraintSet& c, double t, double* x) {
  if (c.targets) {
    Points xyz(c.vertices.size());
    c.targets(t, xyz);
    if (xyz.size() != c.vertices.size())
      throw Error("constraint set '" + c.name + "': targets callback returned " + std::to_string(xyz.xyz().size()) +
                  " values, expected " + std::to_string(3 * c.vertices.size()));
    for (size_t k = 0; k < c.vertices.size(); ++k)
      for (int d = 0; d < 3; ++d)
        if (c.components[d]) x[3 * c.vertices[k] + d] = xyz(k, d);
  } else {
    const RigidTransform motion = c.motion ? c.motion(t) : RigidTransform::identity();
    for (int32_t v : c.vertices) {
      const auto p = motion.apply(mesh.vertex(v));
      for (int d = 0; d < 3; ++d)
        if (c.components[d]) x[3 * v + d] = p[d];
    }
  }
  for (int32_t v : c.vertices)
    for (int d = 0; d < 3; ++d)
      if (!std::isfinite(x[3 * v + d]))
        throw Error("constraint set '" + c.name + "': non-finite target position for vertex " + std::to_string(v) +
                    " at load parameter " + std::to_string(t));
}

}  // namespace

void place_by_callback(const Mesh& mesh, const ConstraintSet& c, double t, std::vector<double>& x) {
  place_by_callback_into(mesh, c, t, x.data());
}

void place_by_callback(const Mesh& mesh, const ConstraintSet& c, double t, Points& x) {
  place_by_callback_into(mesh, c, t, x.data());
}

namespace {

// The rigid motions one piece of the mesh (the vertices marked in `used`)
// is left free, checked against the force on that piece; `piece`, when not
// empty, names it in the error and the warning.
void check_piece_rigid_modes(const Mesh& mesh, const std::vector<char>& used, const std::vector<char>& prescribed,
                             const std::vector<double>& force, const std::string& piece,
                             std::vector<std::string>& warnings) {
  const size_t n = mesh.vertex_count();
  // Rigid velocities u = t + w x (X - c) / L, centred and scaled for
  // conditioning; each prescribed DOF (v, d) asks u_d(X_v) = 0.
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  size_t count = 0;
  for (size_t v = 0; v < n; ++v)
    if (used[v]) c += Eigen::Vector3d(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)), ++count;
  if (count == 0) return;
  c /= static_cast<double>(count);
  double length = 0.0;
  for (size_t v = 0; v < n; ++v)
    if (used[v])
      length = std::max(length,
                        (Eigen::Vector3d(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)) - c).norm());
  if (!(length > 0.0)) length = 1.0;
  auto mode_row = [&](size_t v, int d) {
    const Eigen::Vector3d r =
        (Eigen::Vector3d(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)) - c) / length;
    Eigen::Matrix<double, 1, 6> row = Eigen::Matrix<double, 1, 6>::Zero();
    row[d] = 1.0;
    // (w x r)_d = sum_k w_k (e_k x r)_d
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[k] = 1.0;
      row[3 + k] = e.cross(r)[d];
    }
    return row;
  };
  Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
  for (size_t v = 0; v < n; ++v)
    for (int d = 0; d < 3; ++d)
      if (prescribed[3 * v + d] && used[v]) {
        const auto row = mode_row(v, d);
        normal += row.transpose() * row;
      }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(normal);
  // A mode counts as held when some prescribed DOF moves under it by more
  // than a round-off fraction of a unit motion.
  const double threshold = 1e-8;
  static const char* kNames[6] = {"translation along x", "translation along y", "translation along z",
                                  "rotation about x",    "rotation about y",    "rotation about z"};
  std::vector<Eigen::Matrix<double, 6, 1>> free_modes;
  for (int k = 0; k < 6; ++k)
    if (eigen.eigenvalues()[k] <= threshold) free_modes.push_back(eigen.eigenvectors().col(k));
  if (free_modes.empty()) return;
  auto describe = [&](const Eigen::Matrix<double, 6, 1>& mode) {
    int largest = 0;
    for (int k = 1; k < 6; ++k)
      if (std::abs(mode[k]) > std::abs(mode[largest])) largest = k;
    return std::string(kNames[largest]);
  };
  // Work of the external force on the piece along each free mode, against
  // the size of the whole force.
  double force_norm = 0.0;
  for (double f : force) force_norm += f * f;
  force_norm = std::sqrt(force_norm);
  for (const auto& mode : free_modes) {
    double work = 0.0, motion = 0.0;
    for (size_t v = 0; v < n && !force.empty(); ++v) {
      if (!used[v]) continue;
      for (int d = 0; d < 3; ++d) {
        const double u = mode_row(v, d).dot(mode.transpose());
        work += force[3 * v + d] * u;
        motion += u * u;
      }
    }
    if (force_norm > 0.0 && std::abs(work) > 1e-9 * force_norm * std::sqrt(motion)) {
      if (piece.empty())
        throw Error("the constraints leave the body free to move by " + describe(mode) +
                    " and the external force pushes it that way: there is no static equilibrium (quasistatic "
                    "solves have no inertia); prescribe more vertices or components");
      throw Error("the constraints leave " + piece + " free to move by " + describe(mode) +
                  " and the external force pushes it that way: there is no static equilibrium (quasistatic solves "
                  "have no inertia); hold a vertex of that piece, or join it to the body or leave it out (a voxelized "
                  "lattice's pieces: snh/pieces.h, scene key embed.pieces)");
    }
  }
  std::ostringstream note;
  note << "constraints: " << (piece.empty() ? "" : piece + ": ") << free_modes.size()
       << " rigid motion(s) left free (e.g. " << describe(free_modes[0])
       << "); the equilibrium is defined only up to them";
  const std::string text = note.str();
  if (std::find(warnings.begin(), warnings.end(), text) == warnings.end()) warnings.push_back(text);
}

}  // namespace

void check_rigid_modes(const Mesh& mesh, const std::vector<char>& prescribed, const std::vector<double>& force,
                       std::vector<std::string>& warnings) {
  const size_t n = mesh.vertex_count();
  if (n == 0) return;
  // Each piece (elements joined through shared vertices) moves on its own.
  const std::vector<std::vector<int32_t>> pieces = mesh_pieces(mesh);
  const int nodes = nodes_per_element(mesh.type);
  std::vector<char> used(n, 0);
  for (size_t p = 0; p < pieces.size(); ++p) {
    std::fill(used.begin(), used.end(), 0);
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int32_t e : pieces[p])
      for (int k = 0; k < nodes; ++k) {
        const int32_t v = mesh.elements[static_cast<size_t>(nodes) * e + k];
        used[v] = 1;
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min(lo[d], mesh.positions(v, d));
          hi[d] = std::max(hi[d], mesh.positions(v, d));
        }
      }
    std::string name;
    if (pieces.size() > 1) {
      std::ostringstream s;
      s << "piece " << p + 1 << " of " << pieces.size() << " (" << pieces[p].size() << " elements, rest bounding box ("
        << lo[0] << ", " << lo[1] << ", " << lo[2] << ") to (" << hi[0] << ", " << hi[1] << ", " << hi[2] << "))";
      name = s.str();
    }
    check_piece_rigid_modes(mesh, used, prescribed, force, name, warnings);
  }
}

}  // namespace snh::solver
