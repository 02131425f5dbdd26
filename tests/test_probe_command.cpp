// `snh-gpu-bench probe` and the default suite, run as a user would.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "support/snh_test_support.h"

namespace snh::test {
namespace {

struct CommandRun {
  int status;
  std::vector<std::string> lines;
};

CommandRun run_bench(const std::string& arguments, const std::string& input) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snh_probe_test";
  std::filesystem::create_directories(dir);
  // One file per process: ctest -j runs the tests of this file side by side.
  const std::filesystem::path in = dir / ("input_" + std::to_string(getpid()) + ".jsonl");
  std::ofstream(in) << input;
  const std::string command = std::string(SNH_BENCH_BINARY) + " " + arguments + " < " + in.string() + " 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  CommandRun r{-1, {}};
  if (!pipe) return r;
  std::string text;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) r.lines.push_back(line);
  return r;
}

TEST(ProbeCommand, AnswersEachLineAndNamesMalformedOnes) {
  const std::string input =
      "{\"F\": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n"
      "{\"F\": [[1, 0], [0, 1]]}\n"
      "{\"F\": [[1.2, 0.3, 0.0], [0.1, 0.9, -0.2], [0.0, 0.4, -0.8]]}\n"
      "not json\n";
  const CommandRun r = run_bench("probe --E 1 --nu 0.45 --precision double", input);
  EXPECT_EQ(r.status, 2);  // some lines were malformed
  ASSERT_EQ(r.lines.size(), 4u);
  const auto second = nlohmann::json::parse(r.lines[1]);
  EXPECT_EQ(second["line"], 2);
  EXPECT_NE(second["error"].get<std::string>().find("line 2"), std::string::npos);
  EXPECT_NE(nlohmann::json::parse(r.lines[3])["error"].get<std::string>().find("line 4"), std::string::npos);

  const auto rest = nlohmann::json::parse(r.lines[0]);
  EXPECT_EQ(rest["psi"].get<double>(), 0.0);
  const StableNeoHookean material = StableNeoHookean::from_youngs_modulus(1.0, 0.45);
  const reference::SnhParameters params{material.mu, material.lambda, material.barrier};

  const auto third = nlohmann::json::parse(r.lines[2]);
  Eigen::Matrix3d f;
  f << 1.2, 0.3, 0.0, 0.1, 0.9, -0.2, 0.0, 0.4, -0.8;
  const Eigen::Matrix3d p = to_eigen(reference::snh_pk1<double>(to_array<double>(f), params));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(third["P"][i][j].get<double>(), p(i, j), 1e-12);
  const Matrix9 h = projected_hessian<double>(f, params);
  ASSERT_EQ(third["H"].size(), 9u);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) EXPECT_NEAR(third["H"][i][j].get<double>(), h(i, j), 1e-12 * h.norm());
  const auto values = third["eigenvalues"].get<std::vector<double>>();
  ASSERT_EQ(values.size(), 9u);
  EXPECT_TRUE(std::is_sorted(values.begin(), values.end()));
  EXPECT_LT(values.front(), 0.0);  // inverted F: an indefinite Hessian before projection
  const auto sigma = third["sigma"].get<std::vector<double>>();
  ASSERT_EQ(sigma.size(), 3u);
  EXPECT_LT(sigma[2], 0.0);
}

TEST(ProbeCommand, LameParametersAndBarrierOption) {
  const CommandRun r = run_bench("probe --mu 1 --lambda 10 --barrier off --precision float",
                                 "{\"F\": [[2, 0, 0], [0, 1, 0], [0, 0, 1]]}\n");
  EXPECT_EQ(r.status, 0);
  ASSERT_EQ(r.lines.size(), 1u);
  // No barrier: psi = mu/2 (I_C - 3) + lambda/2 ((J - alpha)^2 - (1 - alpha)^2), mu = 1, lambda = 11.
  const double mu = 1.0, lambda = 11.0, alpha = 1.0 + mu / lambda;
  const double expected =
      0.5 * mu * 3.0 + 0.5 * lambda * ((2.0 - alpha) * (2.0 - alpha) - (1.0 - alpha) * (1.0 - alpha));
  EXPECT_NEAR(nlohmann::json::parse(r.lines[0])["psi"].get<double>(), expected, 1e-5 * expected);
}

TEST(ProbeCommand, RejectsOutOfRangeMaterial) {
  EXPECT_NE(run_bench("probe --E 1 --nu 0.5", "").status, 0);
  EXPECT_NE(run_bench("probe --E -1 --nu 0.3", "").status, 0);
  EXPECT_NE(run_bench("probe --alpha 0", "").status, 0);
  EXPECT_NE(run_bench("probe --lambda-model rubber", "").status, 0);
}

// --alpha (Chen and Barbic 2024, Eq. 16) on the device: the co-rotational energy with
// alpha = 2 is the Seth-Hill / StVK energy mu/4 sum (s^2 - 1)^2 +
// lambda/8 (sum s^2 - 3)^2, written out here; --lambda-model swaps the
// volume term (co-rotational mu part + (J - 1)^2 / 2 is fixed co-rotational).
TEST(ProbeCommand, AlphaAndLambdaModelOptions) {
  const std::string f = "{\"F\": [[1.5, 0, 0], [0, 0.8, 0], [0, 0, 0.9]]}\n";
  const double mu = 1.0, lambda = 10.0, s[3] = {1.5, 0.8, 0.9};
  double shear = 0.0, trace = -3.0, corot = 0.0;
  for (double x : s) {
    shear += (x * x - 1.0) * (x * x - 1.0);
    trace += x * x;
    corot += (x - 1.0) * (x - 1.0);
  }
  const CommandRun a = run_bench("probe --model corotational --mu 1 --lambda 10 --alpha 2", f);
  ASSERT_EQ(a.status, 0);
  ASSERT_EQ(a.lines.size(), 1u);
  const double stvk = mu / 4.0 * shear + lambda / 8.0 * trace * trace;
  EXPECT_NEAR(nlohmann::json::parse(a.lines[0])["psi"].get<double>(), stvk, 1e-12 * stvk);
  const CommandRun b =
      run_bench("probe --model corotational --lambda-model fixed-corotational --mu 1 --lambda 10 --precision float", f);
  ASSERT_EQ(b.status, 0);
  const double j = s[0] * s[1] * s[2], fixed = mu * corot + lambda / 2.0 * (j - 1.0) * (j - 1.0);
  EXPECT_NEAR(nlohmann::json::parse(b.lines[0])["psi"].get<double>(), fixed, 1e-5 * fixed);
}

TEST(DefaultSuite, WritesWellFormedSummaryAtTinySize) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_suite_test";
  std::filesystem::remove_all(out);
  const CommandRun r = run_bench("--quick --samples 40 --out " + out.string(), "");
  EXPECT_EQ(r.status, 0);
  std::ifstream in(out / "summary.json");
  ASSERT_TRUE(in.good());
  const auto summary = nlohmann::json::parse(in);
  ASSERT_EQ(summary["element"]["cases"].size(), 4u);
  for (const auto& c : summary["element"]["cases"]) {
    EXPECT_TRUE(c["all_finite"].get<bool>());
    EXPECT_GT(c["evaluations_per_second"].get<double>(), 0.0);
    const double bound = c["precision"] == "double" ? 1e-12 : 2e-4;
    EXPECT_LT(c["max_relative_error_hessian"].get<double>(), bound);
  }
  // Throughput: the roofline and every product variant side by side.
  ASSERT_TRUE(summary.contains("throughput"));
  const auto& roofline = summary["throughput"]["roofline"]["double"];
  EXPECT_GT(roofline["triad_bandwidth_gb_s"].get<double>(), 0.0);
  // The bound is the faster of the scalar and the 4-wide triad.
  EXPECT_EQ(roofline["triad_bandwidth_gb_s"].get<double>(),
            std::max(roofline["triad_scalar_gb_s"].get<double>(), roofline["triad_vector4_gb_s"].get<double>()));
  std::set<std::string> variants;
  for (const auto& p : summary["throughput"]["products"]) {
    variants.insert(p["variant"].get<std::string>());
    EXPECT_GT(p["product_seconds"].get<double>(), 0.0);
  }
  for (const char* v : {"recompute", "cached", "element-matrices", "assembled", "host-eigen-csr"})
    EXPECT_EQ(variants.count(v), 1u) << v;
  // Specialization: every build computes the same forces and products.
  ASSERT_TRUE(summary.contains("specialization"));
  ASSERT_EQ(summary["specialization"]["rows"].size(), 3u * 4u);  // 3 materials x 4 operations
  for (const auto& row : summary["specialization"]["rows"]) {
    EXPECT_TRUE(row["bitwise_equal"].get<bool>()) << row["material"];
    EXPECT_LT(row["all_terms_relative_difference"].get<double>(), 1e-9) << row["material"];
    EXPECT_GT(row["gain_material"].get<double>(), 0.0);
  }
  ASSERT_TRUE(summary.contains("errtime"));
  // A small scale run: none and block-Jacobi ran for both scenes.
  ASSERT_TRUE(summary.contains("scale"));
  int ran = 0;
  for (const auto& r : summary["scale"]["records"]) ran += r.contains("skipped") ? 0 : 1;
  EXPECT_GE(ran, 2 * 2 * 2);
  for (const char* file : {"summary.md", "element.md", "throughput.csv", "throughput.md", "specialization.md",
                           "errtime.csv", "errtime.md", "scale.csv", "scale.md"})
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
}

}  // namespace
}  // namespace snh::test

namespace snh::test {
namespace {

TEST(ProbeCommand, NoOpenClPlatformGetsClearError) {
  // An empty vendor folder: the ICD loader then finds no platform at all.
  const std::filesystem::path empty = std::filesystem::temp_directory_path() / "snh_no_icd";
  std::filesystem::create_directories(empty);
  const std::string command = "OCL_ICD_VENDORS=" + empty.string() + " " + SNH_BENCH_BINARY + " probe < /dev/null 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  char buffer[1024];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
  const int status = pclose(pipe);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << text;
  EXPECT_NE(text.find("no OpenCL platform or device found"), std::string::npos) << text;
}

}  // namespace
}  // namespace snh::test

namespace snh::test {
namespace {

TEST(SceneCommand, WritesJsonSummaryAndParaViewSeries) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snh_scene_test";
  std::filesystem::remove_all(dir);
  const std::string json_path = (dir / "twist.json").string();
  const CommandRun r = run_bench(
      "scene twist --res 2 --steps 2 --precision double --json " + json_path + " --vtu " + (dir / "vtu").string(), "");
  EXPECT_EQ(r.status, 0);
  std::ifstream in(json_path);
  ASSERT_TRUE(in.good());
  const auto j = nlohmann::json::parse(in);
  for (const char* key : {"scene", "elements", "dofs", "device", "precision", "steps", "wall_seconds", "final_residual",
                          "converged", "volume_ratio", "min_j", "inverted_elements", "history"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["scene"], "twist");
  EXPECT_EQ(j["elements"], 8);
  EXPECT_EQ(j["dofs"], 81);
  ASSERT_EQ(j["steps"].size(), 2u);
  EXPECT_GT(j["steps"][0]["newton_iterations"].get<int>(), 0);
  EXPECT_GT(j["steps"][0]["cg_iterations"].get<int>(), 0);
  EXPECT_TRUE(j["converged"].get<bool>());
  for (const char* file : {"twist.pvd", "twist_0000.vtu", "twist_0001.vtu", "twist_0002.vtu"})
    EXPECT_TRUE(std::filesystem::exists(dir / "vtu" / file)) << file;
}

// The alpha and mixing options reach the engine: the kernels are built for them
// and the JSON names the material.
TEST(SceneCommand, AlphaAndMixedMaterial) {
  const std::filesystem::path json_path = std::filesystem::temp_directory_path() / "snh_scene_alpha.json";
  std::filesystem::remove(json_path);
  const CommandRun r = run_bench(
      "scene stretch --res 2 --steps 2 --nu 0.4 --model stvk-kikuuwe --lambda-model snh "
      "--alpha 1.5 --alpha-lambda 0.8 --json " +
          json_path.string(),
      "");
  EXPECT_EQ(r.status, 0);
  std::ifstream in(json_path);
  ASSERT_TRUE(in.good());
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["material"], "stvk-kikuuwe+lambda:snh alpha=1.5 alpha_lambda=0.8");
  EXPECT_EQ(j["lambda_model"], "snh");
  EXPECT_DOUBLE_EQ(j["alpha"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["alpha_lambda"].get<double>(), 0.8);
  const std::string spec = j["kernel_specialization"];
  EXPECT_NE(spec.find("-DSNH_NONLINEAR=1"), std::string::npos) << spec;
  EXPECT_NE(spec.find("-DSNH_LAMBDA_MODEL=0"), std::string::npos) << spec;
  EXPECT_TRUE(j["converged"].get<bool>());
}

// Every step's JSON record carries each constraint set's reaction, and every
// .vtu the element fields.
TEST(SceneCommand, StepsCarryReactionsAndVtuFilesCarryElementFields) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snh_scene_fields";
  std::filesystem::remove_all(dir);
  const std::string json_path = (dir / "stretch.json").string();
  const CommandRun r = run_bench(
      "scene stretch --res 2 --steps 2 --precision double --json " + json_path + " --vtu " + (dir / "vtu").string(),
      "");
  EXPECT_EQ(r.status, 0);
  std::ifstream in(json_path);
  ASSERT_TRUE(in.good());
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["steps"].size(), 2u);
  for (int s = 0; s < 2; ++s) {
    SCOPED_TRACE(s);
    const auto& reactions = j["steps"][s]["reactions"];
    ASSERT_EQ(reactions.size(), 2u);
    EXPECT_EQ(reactions[0]["name"], "bottom_cap");
    EXPECT_EQ(reactions[1]["name"], "top_cap");
    const auto bottom = reactions[0]["force"].get<std::vector<double>>();
    const auto top = reactions[1]["force"].get<std::vector<double>>();
    ASSERT_EQ(top.size(), 3u);
    EXPECT_EQ(reactions[1]["torque"].size(), 3u);
    // The top cap is pulled up (+z) and the bottom holds it: they balance up
    // to the free DOFs' residual (strain tolerance 1e-6: far below 1e-3 of
    // the pull).
    EXPECT_GT(top[2], 0.0);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(top[i] + bottom[i], 0.0, 1e-3 * top[2]);
    // About the cap's current centroid: at z = 2 + 4.8 t, t = step / 2.
    EXPECT_NEAR(reactions[1]["about"][2].get<double>(), 2.0 + 4.8 * (s + 1) / 2.0, 1e-9);
  }
  for (const char* file : {"stretch_0000.vtu", "stretch_0002.vtu"}) {
    std::ifstream vtu(dir / "vtu" / file);
    std::stringstream text;
    text << vtu.rdbuf();
    for (const char* field : {"Name=\"F\" NumberOfComponents=\"9\"", "Name=\"cauchy\" NumberOfComponents=\"9\"",
                              "Name=\"von_mises\"", "Name=\"energy_density\"", "Name=\"displacement\""})
      EXPECT_NE(text.str().find(field), std::string::npos) << file << " " << field;
    EXPECT_EQ(text.str().find("nan"), std::string::npos) << file;
  }
}

// A scene file's output key writes the same: a block held at x = 0 under
// its own weight, whose wall carries minus the weight.
TEST(SceneCommand, SceneFileOutputCarriesTheWallsReaction) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snh_scene_file_fields";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string json_path = (dir / "out" / "sag.json").string();
  std::ofstream(dir / "sag.json") << R"({"name": "sag", "mesh": {"generator": "box", "cells": [2, 1, 1], "size": 0.5},
             "material": {"model": "snh", "E": 1000.0, "nu": 0.3},
             "constraints": [{"name": "wall", "select": {"plane": {"axis": "x", "value": 0.0, "tolerance": 1e-9}}}],
             "body_force": [0.0, 0.0, -8.0],
             "solver": {"steps": 1, "absolute_tolerance": 1e-11},
             "output": {"vtu": ")" << (dir / "out" / "vtu").string()
                                  << R"(", "json": ")" << json_path << R"("}})";
  const CommandRun r = run_bench("scene --file " + (dir / "sag.json").string(), "");
  EXPECT_EQ(r.status, 0);
  std::ifstream in(json_path);
  ASSERT_TRUE(in.good());
  const auto j = nlohmann::json::parse(in);
  const auto& wall = j["steps"][0]["reactions"][0];
  EXPECT_EQ(wall["name"], "wall");
  // Weight: 8 N/m^3 over 1 x 0.5 x 0.5 m = 2 N down; the wall pushes up.
  // The residual (1e-11) over 24 free DOFs bounds the imbalance far below 1e-9.
  EXPECT_NEAR(wall["force"][0].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(wall["force"][1].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(wall["force"][2].get<double>(), 2.0, 1e-9);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "vtu" / "sag_0001.vtu"));
}

TEST(SceneCommand, UnknownSceneIsRejected) { EXPECT_NE(run_bench("scene wobble", "").status, 0); }

}  // namespace
}  // namespace snh::test
