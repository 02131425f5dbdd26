// The typed kernel build (device/kernel_config.h): its switches written and
// read back through one table, the strings results report, and `snh
// programs`, whose list is what a solve of the scene compiles.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "device/kernel_config.h"
#include "device/material_args.h"
#include "programs.h"
#include "snh/error.h"
#include "snh/material.h"
#include "snh/scene.h"

namespace snh::test {
namespace {

using device::KernelConfig;

KernelConfig scene_like_config() {
  MaterialOptions barrier;
  barrier.barrier = Barrier::on;
  KernelConfig c =
      device::material_config(Material::from_youngs_modulus(MaterialModel::stable_neo_hookean, 1.0, 0.3, barrier));
  c.element = ElementType::hex8;
  c.uniform_rest = true;
  c.point_major = true;
  c.cache_tile = c.stencil_tile = 32;
  c.inertia = true;
  c.obstacles = 3;
  c.friction = true;
  return c;
}

TEST(KernelConfig, WritesTheSwitchesInTheReportedOrder) {
  KernelConfig c = scene_like_config();
  EXPECT_EQ(c.defines(),
            "-DSNH_HEX8=1 -DSNH_MODEL=0 -DSNH_BARRIER=1 -DSNH_NONLINEAR=0 -DSNH_UNIFORM_REST=1 -DSNH_POINT_MAJOR=1 "
            "-DSNH_CACHE_TILE=32 -DSNH_STENCIL_TILE=32 -DSNH_INERTIA=1 -DSNH_OBSTACLES=3 -DSNH_FRICTION=1");
  EXPECT_THROW(c.report(), Error);  // no precision yet
  c.precision = Precision::double_;
  EXPECT_EQ(c.report(), c.defines() + " -DSNH_DOUBLE=1");
  EXPECT_EQ(c.build_options(false), "-cl-std=CL1.2 -DSNH_DOUBLE=1 " + c.defines());
  EXPECT_EQ(c.build_options(true), "-cl-std=CL1.2 -DSNH_DOUBLE=1 " + c.defines() + " -DSNH_GPU=1");
  EXPECT_EQ(c.elastic().defines(),
            "-DSNH_HEX8=1 -DSNH_MODEL=0 -DSNH_BARRIER=1 -DSNH_NONLINEAR=0 -DSNH_UNIFORM_REST=1 -DSNH_POINT_MAJOR=1 "
            "-DSNH_CACHE_TILE=32 -DSNH_STENCIL_TILE=32");
  EXPECT_EQ(c.elastic().with_lanes(16).with_mixed().with_matrix_float().defines(),
            c.elastic().defines() + " -DSNH_LANES=16 -DSNH_MIXED=1 -DSNH_MATRIX_FLOAT=1");
  EXPECT_EQ(c.cache_key("fem.cl"), "fem.cl|" + c.defines());
  EXPECT_EQ(c.with_surface_contact().defines(), c.defines() + " -DSNH_SURFACE_CONTACT=1");
  EXPECT_EQ(c.with_surface_contact().elastic().defines(), c.elastic().defines());
}

TEST(KernelConfig, ParsesWhatItWrites) {
  KernelConfig c = scene_like_config();
  c.precision = Precision::single;
  c.lambda_model = MaterialModel::neohookean;
  c.regions = true;
  c.self_contact = true;
  const KernelConfig variant =
      c.with_surface_contact().with_lanes(8).with_mixed().with_float_cycle().with_stencil(27, 13);
  for (const KernelConfig& k : {c, variant, KernelConfig{}}) {
    const KernelConfig back = KernelConfig::parse(k.precision ? k.report() : k.defines());
    EXPECT_EQ(back, k) << k.defines();
    EXPECT_EQ(back.defines(), k.defines());
  }
  KernelConfig general = device::material_config(Material::from_youngs_modulus(MaterialModel::fung, 1.0, 0.3),
                                                 device::MaterialKernel::runtime);
  general.regions = true;
  EXPECT_EQ(general.defines(), "-DSNH_GENERAL_KERNEL=1 -DSNH_REGIONS=1");
  EXPECT_EQ(KernelConfig::parse(general.defines()), general);
  // Every switch the table writes is one it reads.
  for (const std::string& name : device::kernel_switch_names())
    EXPECT_NO_THROW(KernelConfig::parse("-D" + name + "=1")) << name;
}

TEST(KernelConfig, RefusesUnknownSwitchesAndValues) {
  auto message = [](const std::string& text) {
    try {
      KernelConfig::parse(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("-DSNH_HEX9=1").find("unknown switch SNH_HEX9"), std::string::npos);
  EXPECT_NE(message("-DSNH_HEX8=2").find("SNH_HEX8 cannot be 2"), std::string::npos);
  EXPECT_NE(message("-DSNH_MODEL=99").find("SNH_MODEL cannot be 99"), std::string::npos);
  EXPECT_NE(message("-DSNH_BARRIER=x").find("SNH_BARRIER has the value 'x'"), std::string::npos);
  EXPECT_NE(message("-DSNH_DOUBLE=3").find("SNH_DOUBLE"), std::string::npos);
  EXPECT_NE(message("SNH_HEX8=1").find("not a -DNAME=value switch"), std::string::npos);
}

std::set<std::string> keys(const std::vector<device::BuiltProgram>& programs) {
  std::set<std::string> out;
  for (const device::BuiltProgram& p : programs) out.insert(p.file + "  " + p.config.report());
  return out;
}

// What `snh programs` lists for a shipped scene (its setup and first Newton
// iteration) is what a whole solve of the scene compiles, and the list
// holds the build the result reports. max_newton bounds each step's
// iterations (0: the default), to keep the solve short.
void expect_programs_match_a_solve(const std::string& scene, int steps, int max_newton = 0) {
  SCOPED_TRACE(scene);
  const SceneFile file = load_scene(std::string(SNH_DATA_DIR) + "/scenes/" + scene);
  SolveOptions options = file.scene.options;
  options.load_steps = steps;
  if (max_newton > 0) options.max_newton_iterations = max_newton;
  const std::vector<device::BuiltProgram> listed = cli::scene_programs(file, options);
  ASSERT_FALSE(listed.empty());
  EXPECT_EQ(keys(listed).size(), listed.size()) << "a program built twice";
  std::vector<device::BuiltProgram> compiled;
  SceneRun run;
  {
    device::ProgramRecorder recorder;
    run = run_scene(file, options);
    compiled = recorder.programs();
  }
  EXPECT_EQ(keys(listed), keys(compiled));
  EXPECT_EQ(keys(listed).count("fem.cl  " + run.result.kernel_specialization), 1u) << run.result.kernel_specialization;
}

TEST(ProgramsCommand, ListsWhatASolveOfDropBlockCompiles) { expect_programs_match_a_solve("drop_block.json", 2); }

// Multigrid (12,288 DOFs) with its float fine level and cycle, built at the
// first linearization.
TEST(ProgramsCommand, ListsWhatASolveOfTwistCompiles) { expect_programs_match_a_solve("twist.json", 2, 3); }

TEST(ProgramsCommand, PrintsOneLineAProgram) {
  const std::string scene = std::string(SNH_DATA_DIR) + "/scenes/soft_stiff_bar.json";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((std::string(SNH_CLI_BINARY) + " programs " + scene).c_str(), "r"),
                                             pclose);
  ASSERT_TRUE(pipe);
  std::string out;
  std::array<char, 4096> buffer{};
  for (size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe.get())) > 0;) out.append(buffer.data(), n);
  const SceneFile file = load_scene(scene);
  std::ostringstream expected;
  cli::print_programs(expected, cli::scene_programs(file, file.scene.options));
  EXPECT_EQ(out, expected.str());
  // The scene's two materials share a model: the specialized build with
  // their parameters per element.
  EXPECT_NE(out.find("\nfem.cl  -DSNH_HEX8=1 -DSNH_MODEL=0 "), std::string::npos) << out;
  EXPECT_NE(out.find(" -DSNH_REGIONS=1 -DSNH_UNIFORM_REST=1"), std::string::npos) << out;
}

}  // namespace
}  // namespace snh::test
