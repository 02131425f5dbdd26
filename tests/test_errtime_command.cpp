// `snh-gpu-bench errtime` at a tiny size, run as a user would: the CSV, the
// JSON summary, the markdown table and (where matplotlib is installed) the PNGs.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace snh::test {
namespace {

int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream s(line);
  while (std::getline(s, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

const std::vector<std::string> kPerIteration{"launches_per_cg_iteration", "readbacks_per_cg_iteration",
                                             "launches_per_newton_iteration", "readbacks_per_newton_iteration"};

// A series' launches and read-backs per CG and per Newton iteration. Device
// series: finite, > 0 (CG ran), and times the iterations the series' own
// counts: the linear solves' phases (products, preconditioner_apply,
// cg_vector_work) per CG iteration, the whole solve per Newton iteration.
// host-eigen, which asks nothing of the device: 0.
void expect_per_iteration_traffic(const nlohmann::json& s) {
  const std::string what = s["series"].get<std::string>();
  for (const std::string& key : kPerIteration) {
    ASSERT_TRUE(s.contains(key)) << what << ": " << key;
    const double v = s[key].get<double>();
    EXPECT_TRUE(std::isfinite(v)) << what << ": " << key;
    if (what == "host-eigen")
      EXPECT_EQ(v, 0.0) << what << ": " << key;
    else
      EXPECT_GT(v, 0.0) << what << ": " << key;
  }
  if (what == "host-eigen") return;
  const auto& p = s["profile"];
  double launches = 0.0, reads = 0.0;
  for (const char* phase : {"products", "preconditioner_apply", "cg_vector_work"}) {
    if (!p["traffic"].contains(phase)) continue;
    launches += p["traffic"][phase]["kernel_launches"].get<double>();
    reads += p["traffic"][phase]["blocking_readbacks"].get<double>();
  }
  const double cg = s["cg_iterations"].get<double>(), newton = s["newton_iterations"].get<double>();
  const auto near = [&](const char* key, double iterations, double count) {
    EXPECT_NEAR(s[key].get<double>() * iterations, count, 1e-9 * std::max(1.0, count)) << what << ": " << key;
  };
  near("launches_per_cg_iteration", cg, launches);
  near("readbacks_per_cg_iteration", cg, reads);
  near("launches_per_newton_iteration", newton, p["kernel_launches"].get<double>());
  near("readbacks_per_newton_iteration", newton, p["blocking_readbacks"].get<double>());
}

TEST(ErrtimeCommand, WritesCsvJsonMarkdownAndPlots) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "snh_errtime_test";
  std::filesystem::remove_all(out);
  ASSERT_EQ(run_command(std::string(SNH_BENCH_BINARY) + " errtime --scenes twist,flex --res 2 --out " + out.string() +
                        " > /dev/null 2>&1"),
            0);

  // CSV: the header, then one row per step start and Newton update, each
  // with its series' launches and read-backs per iteration.
  std::ifstream csv(out / "errtime.csv");
  ASSERT_TRUE(csv.good());
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line,
            "scene,series,precision,preconditioner,step,newton_iteration,newton_total,cg_total,seconds,residual,error,"
            "projected,launches_per_cg_iteration,readbacks_per_cg_iteration,launches_per_newton_iteration,"
            "readbacks_per_newton_iteration");
  std::map<std::string, std::vector<std::vector<std::string>>> by_series;  // "scene series" -> rows
  while (std::getline(csv, line)) {
    const auto f = split(line);
    ASSERT_EQ(f.size(), 16u) << line;
    by_series[f[0] + " " + f[1]].push_back(f);
  }
  const std::set<std::string> series{"double/block-jacobi", "double/none", "float/block-jacobi", "float/none",
                                     "host-eigen"};
  for (const std::string scene : {"twist", "flex"})
    for (const std::string& s : series) {
      const auto it = by_series.find(scene + " " + s);
      ASSERT_NE(it, by_series.end()) << scene << " " << s;
      const auto& rows = it->second;
      ASSERT_GE(rows.size(), 3u);
      EXPECT_EQ(rows.front()[4], "1");  // the first step's start
      EXPECT_EQ(rows.front()[5], "0");
      EXPECT_EQ(rows.front()[11], "");
      double previous_seconds = 0.0;
      int previous_cg = 0;
      for (const auto& r : rows) {
        const double seconds = std::stod(r[8]), residual = std::stod(r[9]), error = std::stod(r[10]);
        EXPECT_GE(seconds, previous_seconds) << scene << " " << s;
        EXPECT_GE(std::stoi(r[7]), previous_cg);
        EXPECT_TRUE(std::isfinite(residual) && residual >= 0.0);
        EXPECT_TRUE(std::isfinite(error) && error >= 0.0);
        previous_seconds = seconds;
        previous_cg = std::stoi(r[7]);
      }
      // Double reaches the series tolerance, 1e-7, and lands near the reference.
      if (s.rfind("float", 0) != 0) {
        EXPECT_LE(std::stod(rows.back()[9]), 1e-7) << scene << " " << s;
        EXPECT_LT(std::stod(rows.back()[10]), 1e-4) << scene << " " << s;
      }
    }

  // JSON summary.
  std::ifstream in(out / "errtime.json");
  ASSERT_TRUE(in.good());
  const auto summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["command"], "errtime");
  ASSERT_EQ(summary["scenes"].size(), 2u);
  EXPECT_EQ(summary["scenes"][0]["scene"], "twist");
  EXPECT_EQ(summary["scenes"][1]["scene"], "flex");
  for (const auto& scene : summary["scenes"]) {
    EXPECT_TRUE(scene["reference"]["converged"].get<bool>());
    for (const auto& step : scene["reference"]["steps"])
      EXPECT_LE(step["reached_relative_residual"].get<double>(), 1e-10);
    ASSERT_EQ(scene["series"].size(), 5u);
    for (const auto& s : scene["series"]) {
      expect_per_iteration_traffic(s);
      // The CSV's rows of the series carry the same figures (to its nine
      // digits), on every row.
      const auto rows = by_series.find(scene["scene"].get<std::string>() + " " + s["series"].get<std::string>());
      ASSERT_NE(rows, by_series.end()) << s["series"];
      for (const auto& row : rows->second)
        for (size_t k = 0; k < kPerIteration.size(); ++k) {
          const double expected = s[kPerIteration[k]].get<double>();
          EXPECT_NEAR(std::stod(row[12 + k]), expected, 1e-8 * expected) << s["series"] << " " << kPerIteration[k];
        }
      for (const char* key :
           {"series", "precision", "preconditioner", "converged", "newton_iterations", "cg_iterations", "wall_seconds",
            "seconds_to_residual", "final_residual", "final_error", "device", "kernel_specialization"})
        EXPECT_TRUE(s.contains(key)) << key;
      for (const char* threshold : {"1e-2", "1e-4", "1e-6"})
        EXPECT_TRUE(s["seconds_to_residual"].contains(threshold)) << threshold;
      EXPECT_GT(s["newton_iterations"].get<int>(), 0);
      EXPECT_GT(s["cg_iterations"].get<int>(), 0);
      // Where the time went: every phase, none negative, adding up.
      ASSERT_TRUE(s.contains("profile")) << s["series"];
      double parts = 0.0;
      for (const char* key : {"linearization", "products", "preconditioner_setup", "preconditioner_apply",
                              "cg_vector_work", "line_search_energies", "transfers", "other"}) {
        ASSERT_TRUE(s["profile"].contains(key)) << s["series"] << " " << key;
        EXPECT_GE(s["profile"][key].get<double>(), 0.0) << s["series"] << " " << key;
        parts += s["profile"][key].get<double>();
      }
      EXPECT_NEAR(parts, s["profile"]["total"].get<double>(), 1e-9) << s["series"];
      EXPECT_GT(s["profile"]["linearization"].get<double>(), 0.0) << s["series"];
      if (s["series"] != "host-eigen") {
        EXPECT_GT(s["profile"]["products"].get<double>(), 0.0) << s["series"];
      }
      if (s["precision"] == "double") {
        EXPECT_TRUE(s["converged"].get<bool>()) << s["series"];
        const auto& t = s["seconds_to_residual"];
        ASSERT_FALSE(t["1e-6"].is_null()) << s["series"];
        EXPECT_LE(t["1e-2"].get<double>(), t["1e-4"].get<double>());
        EXPECT_LE(t["1e-4"].get<double>(), t["1e-6"].get<double>());
        EXPECT_LE(t["1e-6"].get<double>(), s["wall_seconds"].get<double>());
      }
    }
  }

  // Markdown table with the paper's figures beside ours.
  std::ifstream md_file(out / "errtime.md");
  ASSERT_TRUE(md_file.good());
  std::stringstream md;
  md << md_file.rdbuf();
  EXPECT_NE(md.str().find("| scene | series | Newton | CG |"), std::string::npos);
  EXPECT_NE(md.str().find("| twist | double/block-jacobi |"), std::string::npos);
  EXPECT_NE(md.str().find("3,278 + 4,956 CG"), std::string::npos);
  // Launches and reads per iteration, for the device series only.
  const auto traffic_at = md.str().find("## Kernel launches and blocking reads per iteration");
  ASSERT_NE(traffic_at, std::string::npos);
  const std::string traffic = md.str().substr(traffic_at);
  EXPECT_NE(traffic.find("| scene | series | Newton | CG | launches per CG iteration | reads per CG iteration | "
                         "launches per Newton iteration | reads per Newton iteration |"),
            std::string::npos);
  EXPECT_NE(traffic.find("| twist | double/block-jacobi |"), std::string::npos);
  EXPECT_NE(traffic.find("| flex | float/none |"), std::string::npos);
  EXPECT_EQ(traffic.find("| host-eigen |"), std::string::npos);

  // PNGs, where Debian's matplotlib is there to draw them.
  if (run_command("/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") == 0) {
    for (const char* png : {"errtime_twist.png", "errtime_flex.png"}) {
      std::ifstream f(out / png, std::ios::binary);
      ASSERT_TRUE(f.good()) << png;
      char magic[4] = {};
      f.read(magic, 4);
      EXPECT_EQ(std::string(magic + 1, 3), "PNG") << png;
    }
  }
}

TEST(ErrtimeCommand, RejectsUnknownSceneAndBadChoice) {
  const std::string bench = std::string(SNH_BENCH_BINARY) + " errtime --out /dev/null/x";
  EXPECT_NE(run_command(bench + " --scenes twist,wobble > /dev/null 2>&1"), 0);
  EXPECT_NE(run_command(bench + " --precision half > /dev/null 2>&1"), 0);
}

}  // namespace
}  // namespace snh::test
