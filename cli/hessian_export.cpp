#include "hessian_export.h"

#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "fem/rest_state.h"
#include "reference/fem_reference.h"
#include "snh/error.h"
#include "snh/simulation.h"

namespace snh::cli {

std::vector<int64_t> free_dofs(const Mesh& mesh, const std::vector<ConstraintSet>& constraints) {
  const size_t n = mesh.vertex_count();
  std::vector<char> free(3 * n, 0);
  for (int32_t v : mesh.elements)
    for (int i = 0; i < 3; ++i) free[3 * size_t(v) + i] = 1;
  for (const ConstraintSet& c : constraints)
    for (int32_t v : c.vertices)
      for (int i = 0; i < 3; ++i)
        if (c.components[i]) free[3 * size_t(v) + i] = 0;
  std::vector<int64_t> out;
  for (size_t d = 0; d < free.size(); ++d)
    if (free[d]) out.push_back(int64_t(d));
  return out;
}

ExportedSystem linear_system_at(const Mesh& mesh, const MaterialMap& materials,
                                const std::vector<ConstraintSet>& constraints, const std::vector<double>& positions,
                                const std::vector<double>& external_force) {
  if (positions.size() != 3 * mesh.vertex_count())
    throw Error("hessian: positions have " + std::to_string(positions.size()) + " entries, the mesh needs " +
                std::to_string(3 * mesh.vertex_count()));
  ExportedSystem s;
  s.positions = positions;
  s.free_dofs = free_dofs(mesh, constraints);
  const fem::RestState rest = fem::compute_rest_state(mesh);
  const Eigen::SparseMatrix<double> k = reference::assembled_projected_stiffness(mesh, rest, materials, positions);
  std::vector<int64_t> index(3 * mesh.vertex_count(), -1);
  for (size_t i = 0; i < s.free_dofs.size(); ++i) index[size_t(s.free_dofs[i])] = int64_t(i);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(size_t(k.nonZeros()));
  for (int col = 0; col < k.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(k, col); it; ++it) {
      const int64_t r = index[size_t(it.row())], c = index[size_t(col)];
      if (r >= 0 && c >= 0) entries.emplace_back(int(r), int(c), it.value());
    }
  const int m = int(s.free_dofs.size());
  s.matrix.resize(m, m);
  s.matrix.setFromTriplets(entries.begin(), entries.end());
  std::vector<double> r = reference::assembled_forces(mesh, rest, materials, positions);
  if (!external_force.empty()) {
    if (external_force.size() != r.size()) throw Error("hessian: external force size does not match the mesh");
    for (size_t i = 0; i < r.size(); ++i) r[i] += external_force[i];
  }
  s.rhs.reserve(s.free_dofs.size());
  for (int64_t d : s.free_dofs) s.rhs.push_back(r[size_t(d)]);
  return s;
}

ExportedSystem export_scene_system(const Scene& scene, const MaterialMap& materials, int newton_iterations,
                                   const std::string& device_match) {
  if (newton_iterations < 1) throw Error("hessian: --newton-iterations must be >= 1");
  SolveOptions options = scene.options;
  options.device.match = device_match;
  // Positions after each update of step 1; the solve is cancelled after
  // the requested count, or at step 2's first update if step 1 converged
  // first (then the state is step 1's equilibrium).
  std::vector<double> x;
  int done = 0;
  options.on_iteration = [&](const NewtonIteration& rec, const Points& positions) {
    if (rec.step != 1) return;
    x = positions.xyz();
    done = rec.iteration + 1;
  };
  Simulation sim(scene.mesh, materials, scene.constraints, options);
  sim.solve(0, [&](const NewtonIteration& rec) { return rec.step == 1 && done < newton_iterations; });
  if (x.empty()) throw Error("hessian: scene " + scene.name + " took no Newton update in step 1");
  ExportedSystem s = linear_system_at(sim.mesh(), materials, scene.constraints, x, sim.applied_force().xyz());
  s.newton_iterations = done;
  return s;
}

namespace {

std::unique_ptr<std::FILE, int (*)(std::FILE*)> open_for_writing(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw Error("hessian: cannot write " + path);
  return f;
}

}  // namespace

void write_exported_system(const std::string& prefix, const Mesh& mesh, const ExportedSystem& s) {
  const Eigen::SparseMatrix<double>& a = s.matrix;
  int64_t lower = 0;
  for (int col = 0; col < a.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
      if (it.row() >= col) ++lower;
  {
    auto f = open_for_writing(prefix + ".mtx");
    std::fprintf(f.get(), "%%%%MatrixMarket matrix coordinate real symmetric\n");
    std::fprintf(f.get(), "%% snh projected stiffness on the free DOFs (lower triangle)\n");
    std::fprintf(f.get(), "%lld %lld %lld\n", (long long)a.rows(), (long long)a.cols(), (long long)lower);
    for (int col = 0; col < a.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(a, col); it; ++it)
        if (it.row() >= col) std::fprintf(f.get(), "%lld %d %.17g\n", (long long)it.row() + 1, col + 1, it.value());
  }
  {
    auto f = open_for_writing(prefix + "_rhs.mtx");
    std::fprintf(f.get(), "%%%%MatrixMarket matrix array real general\n");
    std::fprintf(f.get(), "%% snh residual -dE/dx on the free DOFs\n");
    std::fprintf(f.get(), "%zu 1\n", s.rhs.size());
    for (double v : s.rhs) std::fprintf(f.get(), "%.17g\n", v);
  }
  {
    auto f = open_for_writing(prefix + "_dofs.csv");
    std::fprintf(f.get(), "free_dof,vertex,component,rest_x,rest_y,rest_z,x,y,z\n");
    for (size_t i = 0; i < s.free_dofs.size(); ++i) {
      const size_t v = size_t(s.free_dofs[i] / 3);
      const int c = int(s.free_dofs[i] % 3);
      const double* X = mesh.positions.data() + 3 * v;
      const double* x = &s.positions[3 * v];
      std::fprintf(f.get(), "%zu,%zu,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", i, v, c, X[0], X[1], X[2], x[0], x[1],
                   x[2]);
    }
  }
}

Eigen::SparseMatrix<double> read_matrix_market(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("read_matrix_market: cannot open " + path);
  std::string line;
  std::getline(in, line);
  const bool symmetric = line.find("symmetric") != std::string::npos;
  if (line.rfind("%%MatrixMarket matrix coordinate real", 0) != 0 ||
      (!symmetric && line.find("general") == std::string::npos))
    throw Error("read_matrix_market: " + path + ": not a coordinate real symmetric/general Matrix Market file");
  while (std::getline(in, line) && !line.empty() && line[0] == '%') {
  }
  long long rows = 0, cols = 0, count = 0;
  if (std::sscanf(line.c_str(), "%lld %lld %lld", &rows, &cols, &count) != 3)
    throw Error("read_matrix_market: " + path + ": bad size line '" + line + "'");
  std::vector<Eigen::Triplet<double>> entries;
  for (long long k = 0; k < count; ++k) {
    long long i = 0, j = 0;
    double v = 0.0;
    if (!(in >> i >> j >> v) || i < 1 || j < 1 || i > rows || j > cols)
      throw Error("read_matrix_market: " + path + ": bad entry " + std::to_string(k + 1));
    entries.emplace_back(int(i - 1), int(j - 1), v);
    if (symmetric && i != j) entries.emplace_back(int(j - 1), int(i - 1), v);
  }
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

}  // namespace snh::cli
