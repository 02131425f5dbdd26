// `snh hessian` and `snh-gpu-bench hessian` (cli/hessian_export.h): the exported system is
// the engine's. On a tiny twisted tet4 box after one Newton update, the
// matrix read back from the Matrix Market file times a vector on the free
// DOFs equals the device's masked product (solver::ElasticModel, every
// product variant) within 1e-12 relative, and the exported right-hand side
// equals the device's masked residual; the DOF table lists exactly the free
// DOFs with their rest positions.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "device/opencl_context.h"
#include "device/viennacl_binding.h"
#include "fem/rest_state.h"
#include "hessian_export.h"
#include "snh/scenes.h"
#include "solver/model/elastic_model.h"
#include "support/device_test_support.h"
#include "vector_compare.h"
#include "viennacl/vector.hpp"

namespace snh::test {
namespace {

std::vector<double> read_rhs(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "%%MatrixMarket matrix array real general");
  while (std::getline(in, line) && line[0] == '%') {
  }
  size_t rows = 0, cols = 0;
  std::sscanf(line.c_str(), "%zu %zu", &rows, &cols);
  EXPECT_EQ(cols, 1u);
  std::vector<double> v(rows);
  for (double& c : v) in >> c;
  return v;
}

TEST(HessianExport, MatrixTimesVectorIsTheEngineProductOnFreeDofs) {
  SceneParameters p;
  p.resolution = 3;
  p.element_type = ElementType::tet4;
  p.poisson_ratio = 0.45;
  const Scene scene = make_scene("twist", p);
  const MaterialMap materials = uniform_material(scene.mesh, scene.material);
  const cli::ExportedSystem s = cli::export_scene_system(scene, materials, 1);
  EXPECT_EQ(s.newton_iterations, 1);
  // Twist fixes the bottom and top faces: (res + 1)^2 vertices each.
  const size_t n = scene.mesh.vertex_count();
  ASSERT_EQ(s.free_dofs.size(), 3 * (n - 2 * 16));

  const std::string prefix = (std::filesystem::temp_directory_path() / "snh_hessian_export_test").string();
  cli::write_exported_system(prefix, scene.mesh, s);
  const Eigen::SparseMatrix<double> a = cli::read_matrix_market(prefix + ".mtx");
  ASSERT_EQ(size_t(a.rows()), s.free_dofs.size());
  EXPECT_EQ((Eigen::SparseMatrix<double>(a.transpose()) - a).norm(), 0.0);
  const std::vector<double> rhs = read_rhs(prefix + "_rhs.mtx");

  device::OpenClContext cl(DeviceOptions{}, Precision::double_);
  device::use_viennacl(device::bind_viennacl(cl));
  solver::ElasticModel<double> model(cl, scene.mesh, fem::compute_rest_state(scene.mesh), materials,
                                     ProductVariant::cached);
  std::vector<double> mask(3 * n, 0.0);
  for (int64_t d : s.free_dofs) mask[size_t(d)] = 1.0;
  model.set_mask(mask);

  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd p_free(a.rows());
  for (Eigen::Index i = 0; i < p_free.size(); ++i) p_free[i] = u(rng);
  std::vector<double> p_full(3 * n, 0.0);
  for (size_t i = 0; i < s.free_dofs.size(); ++i) p_full[size_t(s.free_dofs[i])] = p_free[Eigen::Index(i)];
  const Eigen::VectorXd y_export = a * p_free;
  const std::vector<double> expected(y_export.data(), y_export.data() + y_export.size());

  const viennacl::vector<double> xd = upload<double>(s.positions);
  viennacl::vector<double> r(model.dofs());
  model.residual(xd, r);
  const std::vector<double> r_full = download(r);
  std::vector<double> r_free;
  for (int64_t d : s.free_dofs) r_free.push_back(r_full[size_t(d)]);
  EXPECT_LT(relative_difference(rhs, r_free), 1e-12);

  for (ProductVariant variant : {ProductVariant::cached, ProductVariant::recompute, ProductVariant::element_matrices,
                                 ProductVariant::assembled}) {
    model.products().set_variant(variant);
    model.linearize(xd, true);
    viennacl::vector<double> y(model.dofs());
    model.product(upload<double>(p_full), y);
    const std::vector<double> y_full = download(y);
    std::vector<double> y_free;
    for (int64_t d : s.free_dofs) y_free.push_back(y_full[size_t(d)]);
    EXPECT_LT(relative_difference(y_free, expected), 1e-12) << to_string(variant);
  }

  // The DOF table: one row per free DOF with its vertex's rest position.
  std::ifstream csv(prefix + "_dofs.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "free_dof,vertex,component,rest_x,rest_y,rest_z,x,y,z");
  size_t rows = 0;
  while (std::getline(csv, line)) {
    size_t i = 0, v = 0;
    int c = 0;
    double X[3];
    ASSERT_EQ(std::sscanf(line.c_str(), "%zu,%zu,%d,%lf,%lf,%lf", &i, &v, &c, &X[0], &X[1], &X[2]), 6);
    ASSERT_EQ(i, rows);
    EXPECT_EQ(int64_t(3 * v + size_t(c)), s.free_dofs[i]);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(X[k], scene.mesh.positions(v, k));
    ++rows;
  }
  EXPECT_EQ(rows, s.free_dofs.size());
  for (const char* suffix : {".mtx", "_rhs.mtx", "_dofs.csv"}) std::filesystem::remove(prefix + suffix);
}

TEST(HessianExport, FreeDofsHonourPerComponentConstraints) {
  const Mesh mesh = make_tet_box(1, 1, 1, 1.0);
  ConstraintSet slide{"slide", {0, 1}, {}, {}, {false, false, true}};
  ConstraintSet fixed{"fixed", {2}, {}, {}, {true, true, true}};
  const std::vector<int64_t> free = cli::free_dofs(mesh, {slide, fixed});
  EXPECT_EQ(free.size(), 3 * mesh.vertex_count() - 2 - 3);
  for (int64_t d : {int64_t(2), int64_t(5), int64_t(6), int64_t(7), int64_t(8)})
    EXPECT_TRUE(std::find(free.begin(), free.end(), d) == free.end()) << d;
  EXPECT_TRUE(std::find(free.begin(), free.end(), int64_t(0)) != free.end());
}

}  // namespace
}  // namespace snh::test
