// The user's command line, build/snh: every shipped scene file runs through
// `snh run`, a missing referenced file is named by its resolved path, and
// voxelize, probe and hessian run as snh-gpu-bench's subcommands of the
// same names do.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "snh/mesh_io.h"
#include "support/cli_run.h"
#include "support/scratch.h"

namespace snh::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(SNH_DATA_DIR) / "scenes"))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Cheaper runs of the long scenes, to keep this suite short: drop's 2 s in 3
// frames (not 60), drop_block's first 6 of its 60 time steps, the arm's
// first 2 frames. The others run as shipped.
const std::map<std::string, std::string> kCheap = {
    {"drop", "--steps 3"}, {"drop_block", "--steps 6"}, {"arm", "--frames 2"}};

class ShippedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, RunsToConvergenceAndWritesItsSummary) {
  const std::string name = GetParam();
  const fs::path dir = fresh_dir("snh_cli_" + name);
  const auto cheap = kCheap.find(name);
  const CliRun r = run_cli("run " + (fs::path(SNH_DATA_DIR) / "scenes" / (name + ".json")).string() + " --quiet " +
                           (cheap == kCheap.end() ? "" : cheap->second) + " --json " + (dir / "out.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("  step "), std::string::npos) << "--quiet prints no progress\n" << r.output;
  nlohmann::json j;
  std::ifstream(dir / "out.json") >> j;
  EXPECT_EQ(j["scene"], name);
  EXPECT_EQ(j["converged"], true);
  EXPECT_FALSE(j.contains("frames") ? j["frames"].empty() : j["steps"].empty());
  // A scene with barrier self-contact that counts its surface's
  // intersections: none in any step or frame.
  for (const auto& record : j.contains("frames") ? j["frames"] : j["steps"])
    if (record.contains("self_contact_pairs") && record.contains("surface_intersections")) {
      EXPECT_EQ(record["surface_intersections"], 0) << name << " " << record.value("step", record.value("frame", -1));
    }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Cli, ShippedScene, ::testing::ValuesIn(shipped_scenes()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(Cli, VersionAndProgress) {
  const CliRun version = run_cli("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output.rfind("snh ", 0), 0u) << version.output;
  // One line per load step on stderr: step k/n, Newton and CG iterations, seconds.
  const CliRun r = run_cli("run " + (fs::path(SNH_DATA_DIR) / "scenes" / "soft_stiff_bar.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("  step 1/2: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  step 2/2: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" Newton, "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("converged yes"), std::string::npos) << r.output;
}

TEST(Cli, MissingReferencedFileIsNamedByItsResolvedPath) {
  const fs::path dir = fresh_dir("snh_cli_missing");
  fs::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes" / "s.json") << R"({"mesh": {"file": "../meshes/gone.msh"}})";
  const CliRun r = run_cli("run " + (dir / "scenes" / "s.json").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("mesh.file: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((dir / "scenes" / "../meshes/gone.msh").string()), std::string::npos) << r.output;
  EXPECT_NE(run_cli("run " + (dir / "none.json").string()).status, 0);
  fs::remove_all(dir);
}

TEST(Cli, VoxelizeProbeAndHessianRun) {
  const fs::path dir = fresh_dir("snh_cli_tools");
  const fs::path surface = fs::path(SNH_DATA_DIR) / "surfaces" / "sphere.stl";
  const CliRun voxelize = run_cli("voxelize " + surface.string() + " --cell 0.2 --out " + (dir / "s.vtu").string());
  ASSERT_EQ(voxelize.status, 0) << voxelize.output;
  EXPECT_GT(read_mesh((dir / "s.vtu").string()).element_count(), 0u);

  std::ofstream(dir / "f.jsonl") << R"({"F": [[1, 0, 0], [0, 1, 0], [0, 0, 1.1]]})" << '\n' << "bad\n";
  const CliRun probe = run_cli("probe --E 1 --nu 0.45 < " + (dir / "f.jsonl").string());
  EXPECT_EQ(probe.status, 2) << probe.output;  // the malformed second line
  EXPECT_NE(probe.output.find("\"psi\""), std::string::npos) << probe.output;
  EXPECT_NE(probe.output.find("snh probe: line 2: "), std::string::npos) << probe.output;

  const CliRun hessian = run_cli("hessian twist --res 2 --newton-iterations 1 --out " + (dir / "h").string());
  ASSERT_EQ(hessian.status, 0) << hessian.output;
  for (const char* file : {"h.mtx", "h_rhs.mtx", "h_dofs.csv", "h.json"}) EXPECT_TRUE(fs::exists(dir / file)) << file;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace snh::test
