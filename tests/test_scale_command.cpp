// The per-phase profile in the scene command's JSON, and `snh-gpu-bench
// scale` at a tiny size, run as a user would.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scale.h"

namespace snh::test {
namespace {

const std::vector<std::string> kProfileParts{"linearization",
                                             "products",
                                             "preconditioner_setup",
                                             "preconditioner_apply",
                                             "cg_vector_work",
                                             "line_search_energies",
                                             "transfers",
                                             "other"};

int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Every key, each part >= 0, the parts summing to total.
void expect_profile(const nlohmann::json& p, const std::string& what) {
  ASSERT_TRUE(p.is_object()) << what;
  double sum = 0.0;
  for (const std::string& key : kProfileParts) {
    ASSERT_TRUE(p.contains(key)) << what << ": " << key;
    EXPECT_GE(p[key].get<double>(), 0.0) << what << ": " << key;
    sum += p[key].get<double>();
  }
  ASSERT_TRUE(p.contains("total")) << what;
  for (const char* key : {"kernel_launches", "blocking_readbacks", "bytes_to_host", "bytes_to_device", "traffic"})
    EXPECT_TRUE(p.contains(key)) << what << ": " << key;
  EXPECT_NEAR(sum, p["total"].get<double>(), 1e-9 * std::max(1.0, p["total"].get<double>())) << what;
}

nlohmann::json run_scene(const std::string& preconditioner) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "snh_profile_scene_test";
  std::filesystem::create_directories(dir);
  const std::string json_path = (dir / (preconditioner + ".json")).string();
  std::filesystem::remove(json_path);
  EXPECT_EQ(run_command(std::string(SNH_BENCH_BINARY) + " scene twist --res 3 --preconditioner " + preconditioner +
                        " --json " + json_path + " > /dev/null 2>&1"),
            0);
  std::ifstream in(json_path);
  return in.good() ? nlohmann::json::parse(in) : nlohmann::json();
}

TEST(SceneCommand, JsonCarriesTheProfile) {
  for (const std::string pre : {"block-jacobi", "none"}) {
    const auto j = run_scene(pre);
    ASSERT_TRUE(j.contains("profile")) << pre;
    const auto& p = j["profile"];
    expect_profile(p, pre);
    ASSERT_TRUE(p.contains("kernels") && p["kernels"].is_object()) << pre;
    EXPECT_GT(p["kernels"]["snh_element_linearize"].get<double>(), 0.0) << pre;
    const double wall = j["wall_seconds"].get<double>(), total = p["total"].get<double>();
    EXPECT_NEAR(total, wall, std::max(0.1 * wall, 0.005)) << pre;
    EXPECT_GT(p["products"].get<double>(), 0.0) << pre;
    if (pre == "none") {
      EXPECT_EQ(p["preconditioner_setup"].get<double>(), 0.0);
      EXPECT_EQ(p["preconditioner_apply"].get<double>(), 0.0);
    } else {
      EXPECT_GT(p["preconditioner_setup"].get<double>(), 0.0);
      EXPECT_GT(p["preconditioner_apply"].get<double>(), 0.0);
    }
    for (const auto& step : j["steps"]) expect_profile(step["profile"], pre + " step");
    EXPECT_GT(j["device_memory_bytes"].get<double>(), 0.0);
  }
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  out.push_back(field);
  return out;
}

const std::vector<std::string> kPerIteration{"launches_per_cg_iteration", "readbacks_per_cg_iteration",
                                             "launches_per_newton_iteration", "readbacks_per_newton_iteration"};

// A record's launches and read-backs per CG and per Newton iteration: finite,
// > 0 (CG ran), and times the iterations the record's own counts: the
// linear solves' phases (products, preconditioner_apply, cg_vector_work)
// per CG iteration, the whole solve per Newton iteration.
void expect_per_iteration_traffic(const nlohmann::json& r, const std::string& what) {
  for (const std::string& key : kPerIteration) {
    ASSERT_TRUE(r.contains(key)) << what << ": " << key;
    const double v = r[key].get<double>();
    EXPECT_TRUE(std::isfinite(v)) << what << ": " << key;
    EXPECT_GT(v, 0.0) << what << ": " << key;
  }
  const auto& p = r["profile"];
  double launches = 0.0, reads = 0.0;
  for (const char* phase : {"products", "preconditioner_apply", "cg_vector_work"}) {
    if (!p["traffic"].contains(phase)) continue;
    launches += p["traffic"][phase]["kernel_launches"].get<double>();
    reads += p["traffic"][phase]["blocking_readbacks"].get<double>();
  }
  const double cg = r["cg_iterations"].get<double>(), newton = r["newton_iterations"].get<double>();
  ASSERT_GT(cg, 0.0) << what;
  const auto near = [&](const char* key, double iterations, double count) {
    EXPECT_NEAR(r[key].get<double>() * iterations, count, 1e-9 * std::max(1.0, count)) << what << ": " << key;
  };
  near("launches_per_cg_iteration", cg, launches);
  near("readbacks_per_cg_iteration", cg, reads);
  near("launches_per_newton_iteration", newton, p["kernel_launches"].get<double>());
  near("readbacks_per_newton_iteration", newton, p["blocking_readbacks"].get<double>());
  // The whole solve's launches hold the linear solves'.
  EXPECT_GE(p["kernel_launches"].get<double>(), launches) << what;
}

// The records of a scale run: every key, each converged.
void expect_records(const nlohmann::json& records, std::set<std::string>& ran) {
  for (const auto& r : records) {
    const std::string what = r["scene"].get<std::string>() + " " + std::to_string(r["resolution"].get<int>()) + " " +
                             r["preconditioner"].get<std::string>();
    for (const char* key : {"scene", "resolution", "elements", "dofs", "preconditioner"})
      EXPECT_TRUE(r.contains(key)) << what << ": " << key;
    if (r.contains("skipped")) {
      // Only a preconditioner that is not built (or does not apply) may be
      // skipped, with its reason.
      EXPECT_EQ(r["preconditioner"], "multigrid") << what;
      EXPECT_FALSE(r["skipped"].get<std::string>().empty());
      continue;
    }
    ran.insert(r["preconditioner"].get<std::string>());
    for (const char* key :
         {"newton_iterations", "cg_per_newton", "seconds_per_step", "device_memory_bytes", "converged", "profile"})
      EXPECT_TRUE(r.contains(key)) << what << ": " << key;
    EXPECT_TRUE(r["converged"].get<bool>()) << what;
    EXPECT_GT(r["newton_iterations"].get<int>(), 0) << what;
    EXPECT_GT(r["cg_per_newton"].get<double>(), 0.0) << what;
    EXPECT_GT(r["seconds_per_step"].get<double>(), 0.0) << what;
    EXPECT_GT(r["device_memory_bytes"].get<double>(), 0.0) << what;
    // The smoothing as used; double lattices' V-cycles run in float
    // (MultigridOptions::float_cycle's default, a built fine level).
    if (r["preconditioner"] == "multigrid") {
      EXPECT_FALSE(r["smoother"].get<std::string>().empty()) << what;
      EXPECT_TRUE(r["multigrid_float_cycle"].get<bool>()) << what;
    }
    expect_profile(r["profile"], what);
    EXPECT_GT(r["profile"]["products"].get<double>(), 0.0) << what;
    expect_per_iteration_traffic(r, what);
  }
}

nlohmann::json run_scale(const std::filesystem::path& out, const std::string& arguments) {
  std::filesystem::remove_all(out);
  if (run_command(std::string(SNH_BENCH_BINARY) + " scale " + arguments + " --out " + out.string() +
                  " > /dev/null 2>&1") != 0)
    return nlohmann::json();
  std::ifstream in(out / "scale.json");
  return in.good() ? nlohmann::json::parse(in) : nlohmann::json();
}

TEST(ScaleCommand, WritesRecordsForEachSceneResolutionAndPreconditioner) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_scale_test";
  // Without a preconditioner only twist: the stretch cylinder passes a
  // bifurcation (necking) at load step 7 of 8, where the true Hessian meets
  // negative curvature and projected Newton leaves the unstable branch only
  // slowly (res 3 and 4 measured: energy still falling after 200
  // iterations), so whether it stops on that branch within the limit
  // depends on rounding (docs/performance.md, has the figures).
  const nlohmann::json unpreconditioned = run_scale(std::filesystem::temp_directory_path() / "snh_scale_test_none",
                                                    "--scenes twist --res 2,3 --preconditioner none --no-plots");
  ASSERT_FALSE(unpreconditioned.is_null());
  const nlohmann::json summary =
      run_scale(out, "--scenes twist,stretch --res 2,3 --preconditioner block-jacobi,multigrid");
  ASSERT_FALSE(summary.is_null());
  EXPECT_EQ(summary["command"], "scale");
  EXPECT_NE(summary["paper"].get<std::string>().find("25.6"), std::string::npos);
  const auto& records = summary["records"];
  ASSERT_EQ(records.size(), 2u * 2u * 2u);
  ASSERT_EQ(unpreconditioned["records"].size(), 2u);
  std::set<std::string> ran;
  expect_records(records, ran);
  expect_records(unpreconditioned["records"], ran);
  EXPECT_EQ(ran.count("none"), 1u);
  EXPECT_EQ(ran.count("block-jacobi"), 1u);
  // A slope per scene and preconditioner that ran at both sizes.
  std::set<std::string> fitted;
  for (const auto& s : summary["slopes"]) {
    EXPECT_EQ(s["points"].get<int>(), 2);
    EXPECT_TRUE(std::isfinite(s["slope"].get<double>()));
    fitted.insert(s["scene"].get<std::string>() + " " + s["preconditioner"].get<std::string>());
  }
  for (const auto& s : unpreconditioned["slopes"]) fitted.insert(s["scene"].get<std::string>() + " none");
  for (const char* f : {"twist none", "twist block-jacobi", "stretch block-jacobi", "stretch multigrid"})
    EXPECT_EQ(fitted.count(f), 1u) << f;

  // CSV: the header and one row per record.
  std::ifstream csv(out / "scale.csv");
  ASSERT_TRUE(csv.good());
  std::string line;
  std::getline(csv, line);
  const auto header = split(line);
  for (const char* column :
       {"scene", "res", "elements", "dofs", "preconditioner", "newton_iterations", "cg_per_newton", "seconds_per_step",
        "device_memory_bytes", "converged", "profile_products", "profile_total", "skipped"})
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  // The launches and read-backs per iteration, after `skipped`: the JSON's
  // figures to the CSV's nine digits, empty in a skipped row.
  const auto skipped_at = std::find(header.begin(), header.end(), "skipped") - header.begin();
  std::vector<size_t> per_iteration_at;
  for (const std::string& column : kPerIteration) {
    const auto at = std::find(header.begin(), header.end(), column);
    ASSERT_NE(at, header.end()) << column;
    EXPECT_GT(at - header.begin(), skipped_at) << column;
    per_iteration_at.push_back(static_cast<size_t>(at - header.begin()));
  }
  size_t rows = 0;
  while (std::getline(csv, line)) {
    const auto cells = split(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    ASSERT_LT(rows, records.size()) << line;
    const auto& r = records[rows];
    for (size_t k = 0; k < kPerIteration.size() && cells.size() == header.size(); ++k) {
      const std::string& cell = cells[per_iteration_at[k]];
      if (r.contains("skipped")) {
        EXPECT_EQ(cell, "") << line;
        continue;
      }
      const double expected = r[kPerIteration[k]].get<double>();
      EXPECT_NEAR(std::stod(cell), expected, 1e-8 * expected) << kPerIteration[k] << ": " << line;
    }
    ++rows;
  }
  EXPECT_EQ(rows, records.size());

  // Markdown with the paper's figures beside ours.
  std::ifstream md_file(out / "scale.md");
  ASSERT_TRUE(md_file.good());
  std::stringstream md;
  md << md_file.rdbuf();
  for (const char* text : {"25.6", "100.6", "156k", "965k", "| twist | 3 |", "| stretch | 2 |", "slope",
                           "## Kernel launches and blocking reads per iteration", "launches per CG iteration",
                           "reads per Newton iteration"})
    EXPECT_NE(md.str().find(text), std::string::npos) << text;
  if (std::filesystem::exists("/usr/bin/python3") &&
      run_command("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") == 0) {
    EXPECT_TRUE(std::filesystem::exists(out / "scale.png"));
  }
}

TEST(ScaleCommand, MaxDofsGrowsTheResolution) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_scale_grow_test";
  std::filesystem::remove_all(out);
  // twist res r has 3 (r + 1)^3 DOF: 4 has 375, 5 has 648, 6 has 1,029; from 3 the rows grow by about
  // 2^(1/3) (at least 1) while DOF <= 700.
  ASSERT_EQ(
      run_command(std::string(SNH_BENCH_BINARY) +
                  " scale --scenes twist --res 2,3 --preconditioner block-jacobi --max-dofs 700 --no-plots --out " +
                  out.string() + " > /dev/null 2>&1"),
      0);
  std::ifstream in(out / "scale.json");
  ASSERT_TRUE(in.good());
  const auto summary = nlohmann::json::parse(in);
  std::vector<int> resolutions;
  for (const auto& r : summary["records"]) {
    resolutions.push_back(r["resolution"].get<int>());
    EXPECT_LE(r["dofs"].get<int>(), 700);
  }
  EXPECT_EQ(resolutions, (std::vector<int>{2, 3, 4, 5}));
}

TEST(ScaleCommand, ResolutionsGrowToTheLargestThatFits) {
  bench::ScaleOptions o;
  o.resolutions = {8};
  o.max_dofs = 3500;  // twist: res 8 has 2,187 DOF, 9 has 3,000, 10 (the 2^(1/3) step) 3,993
  const auto grown = bench::scale_resolutions("twist", o);
  ASSERT_EQ(grown.size(), 2u);
  EXPECT_EQ(grown[0], std::make_pair(8, size_t{2187}));
  EXPECT_EQ(grown[1], std::make_pair(9, size_t{3000}));
  o.resolutions = {2, 3, 20};  // 20 exceeds the limit and is left out
  o.max_dofs = 3000;
  std::vector<int> res;
  for (const auto& [r, dofs] : bench::scale_resolutions("twist", o)) {
    res.push_back(r);
    EXPECT_LE(dofs, 3000u);
  }
  EXPECT_EQ(res, (std::vector<int>{2, 3, 4, 5, 6, 8, 9}));
  o.max_dofs = 0;  // only the resolutions asked for
  EXPECT_EQ(bench::scale_resolutions("twist", o).size(), 3u);
}

}  // namespace
}  // namespace snh::test
