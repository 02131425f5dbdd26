// `snh-gpu-bench scale`: twist and stretch at growing resolution with each
// preconditioner, to see how time per step grows with DOF.
#include "scale.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "enum_names.h"
#include "iteration_traffic.h"
#include "product_precision_flag.h"
#include "record_writer.h"
#include "scene/profile_json.h"
#include "snh/error.h"
#include "snh/scenes.h"
#include "warm_up.h"

namespace snh::bench {
namespace {

using scene_io::profile_json;
using scene_io::profile_parts;

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

// Smith, Goes, Kim 2018, sec. 6: their largest flesh meshes on a GPU.
constexpr const char* kPaper =
    "Smith et al. 2018 (sec. 6, GPU): bicep 156k DOF at 25.6 s per step; 965k DOF at 100.6 s per frame";

SceneParameters scene_parameters(int resolution, const ScaleOptions& o) {
  SceneParameters p;
  p.resolution = resolution;
  p.youngs_modulus = o.youngs_modulus;
  p.poisson_ratio = o.poisson_ratio;
  // Float resolves J - alpha only to about FLT_EPSILON lambda / mu: its
  // stopping strain is 1e-4, as `scene --precision float` uses.
  if (parse_precision(o.precision) == Precision::single) p.strain_tolerance = 1e-4;
  return p;
}

std::string stop_status(const std::vector<StepResult>& steps) {
  std::map<std::string, int> counts;
  for (const StepResult& s : steps) ++counts[to_string(s.status)];
  std::string out;
  for (const auto& [status, n] : counts)
    out += (out.empty() ? "" : ", ") + status + (steps.size() > 1 ? " x" + std::to_string(n) : "");
  return out;
}

SolveOptions solve_options(const Scene& scene, const ScaleOptions& o, Preconditioner preconditioner) {
  SolveOptions options = scene.options;
  options.precision = parse_precision(o.precision);
  options.device.match = o.device;
  options.preconditioner = preconditioner;
  cli::apply_product_precision(o.product_precision, options);
  o.multigrid.apply(options.multigrid);
  if (o.cg_check_every >= 0) options.cg_check_every = o.cg_check_every;
  return options;
}

ScaleRecord run_one(const std::string& name, int resolution, const std::string& preconditioner, const ScaleOptions& o) {
  const Scene scene = make_scene(name, scene_parameters(resolution, o));
  ScaleRecord r;
  r.scene = name;
  r.resolution = resolution;
  r.element_type = to_string(scene.mesh.type);
  r.elements = scene.mesh.element_count();
  r.dofs = 3 * scene.mesh.vertex_count();
  r.preconditioner = preconditioner;
  r.load_steps = scene.options.load_steps;
  try {
    const SolveOptions options = solve_options(scene, o, parse_preconditioner(preconditioner));
    const Scene tiny = make_scene(name, scene_parameters(std::min(resolution, 3), o));
    warm_up_kernels(tiny, solve_options(tiny, o, *options.preconditioner));
    QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
    const SolveResult result = solver.solve();
    for (const StepResult& s : result.steps) {
      r.newton_iterations += s.newton_iterations;
      r.cg_iterations += s.cg_iterations;
    }
    r.cg_per_newton = r.newton_iterations > 0 ? static_cast<double>(r.cg_iterations) / r.newton_iterations : 0.0;
    r.seconds = result.seconds;
    r.seconds_per_step = result.steps.empty() ? 0.0 : result.seconds / static_cast<double>(result.steps.size());
    r.device_memory_bytes = result.device_memory_bytes;
    r.converged = result.converged;
    r.status = stop_status(result.steps);
    r.product = to_string(result.product);
    r.product_precision = to_string(result.product_precision);
    if (result.preconditioner == Preconditioner::multigrid) {
      r.smoother = std::string(name_or_automatic(result.multigrid_chebyshev)) + " " +
                   std::to_string(result.multigrid_smoother_degree.value_or(0));
      r.float_cycle = result.multigrid_float_cycle;
    }
    r.device = result.device.platform + " / " + result.device.name;
    r.profile = result.profile;
  } catch (const Error& e) {
    r.skipped = e.what();
  }
  return r;
}

IterationTraffic iteration_traffic(const ScaleRecord& r) {
  return snh::bench::iteration_traffic(r.profile, r.cg_iterations, r.newton_iterations);
}

json record_json(const ScaleRecord& r) {
  json j;
  j["scene"] = r.scene;
  j["resolution"] = r.resolution;
  j["element_type"] = r.element_type;
  j["elements"] = r.elements;
  j["dofs"] = r.dofs;
  j["preconditioner"] = r.preconditioner;
  if (!r.skipped.empty()) {
    j["skipped"] = r.skipped;
    return j;
  }
  j["load_steps"] = r.load_steps;
  j["newton_iterations"] = r.newton_iterations;
  j["cg_iterations"] = r.cg_iterations;
  j["cg_per_newton"] = r.cg_per_newton;
  // Kernel launches and blocking read-backs per CG iteration (the linear
  // solves' phases) and per Newton iteration (the whole solve).
  for (const auto& [key, value] : iteration_traffic_parts(iteration_traffic(r))) j[key] = value;
  j["seconds"] = r.seconds;
  j["seconds_per_step"] = r.seconds_per_step;
  j["device_memory_bytes"] = r.device_memory_bytes;
  j["converged"] = r.converged;
  j["status"] = r.status;
  j["product"] = r.product;
  j["product_precision"] = r.product_precision;
  if (!r.smoother.empty()) {
    j["smoother"] = r.smoother;
    j["multigrid_float_cycle"] = r.float_cycle;
  }
  j["device"] = r.device;
  j["profile"] = profile_json(r.profile);
  return j;
}

}  // namespace

std::vector<std::pair<int, size_t>> scale_resolutions(const std::string& scene, const ScaleOptions& o) {
  std::vector<std::pair<int, size_t>> out;
  auto dofs_at = [&](int res) { return 3 * make_scene(scene, scene_parameters(res, o)).mesh.vertex_count(); };
  int largest = 0;
  for (int res : o.resolutions) {
    const size_t dofs = dofs_at(res);
    if (o.max_dofs > 0 && dofs > static_cast<size_t>(o.max_dofs)) continue;
    out.push_back({res, dofs});
    largest = std::max(largest, res);
  }
  if (o.max_dofs > 0 && largest > 0) {
    const size_t limit = static_cast<size_t>(o.max_dofs);
    int res = largest;
    for (;;) {
      const int next = std::max(res + 1, static_cast<int>(std::lround(res * std::cbrt(2.0))));
      const size_t dofs = dofs_at(next);
      if (dofs > limit) {
        // Last, the largest resolution that fits (bisection between the
        // last that fit and the first that did not).
        int fits = res, too_big = next;
        while (too_big - fits > 1) {
          const int mid = (fits + too_big) / 2;
          (dofs_at(mid) <= limit ? fits : too_big) = mid;
        }
        if (fits > res) out.push_back({fits, dofs_at(fits)});
        break;
      }
      out.push_back({next, dofs});
      res = next;
    }
  }
  return out;
}

std::vector<ScaleRecord> run_scale(const ScaleOptions& o) {
  std::vector<ScaleRecord> records;
  for (const std::string& name : o.scenes)
    for (const auto& [res, dofs] : scale_resolutions(name, o))
      for (const std::string& pre : o.preconditioners) {
        std::cerr << "scale: " << name << " res " << res << " (" << thousands(static_cast<long long>(dofs)) << " DOF), "
                  << pre << " ... " << std::flush;
        records.push_back(run_one(name, res, pre, o));
        // The rows so far go to scale.{json,csv,md} after each run (the plot
        // waits for the end), so a run stopped part way keeps what it measured.
        ScaleOptions partial = o;
        partial.plots = false;
        write_scale(partial, records);
        const ScaleRecord& r = records.back();
        if (!r.skipped.empty())
          std::cerr << "skipped: " << r.skipped << '\n';
        else
          std::cerr << r.newton_iterations << " Newton, " << significant(r.cg_per_newton) << " CG per Newton, "
                    << significant(r.seconds_per_step) << " s per step (" << r.status << ")\n";
      }
  return records;
}

std::vector<ScaleSlope> fit_slopes(const std::vector<ScaleRecord>& records) {
  std::vector<ScaleSlope> out;
  std::map<std::pair<std::string, std::string>, std::vector<std::pair<double, double>>> points;
  std::vector<std::pair<std::string, std::string>> order;
  for (const ScaleRecord& r : records) {
    if (!r.skipped.empty() || !(r.seconds_per_step > 0.0)) continue;
    const auto key = std::make_pair(r.scene, r.preconditioner);
    if (!points.count(key)) order.push_back(key);
    points[key].push_back({std::log(static_cast<double>(r.dofs)), std::log(r.seconds_per_step)});
  }
  for (const auto& key : order) {
    const auto& p = points[key];
    if (p.size() < 2) continue;
    double mx = 0.0, my = 0.0;
    for (const auto& [x, y] : p) mx += x, my += y;
    mx /= static_cast<double>(p.size());
    my /= static_cast<double>(p.size());
    double sxy = 0.0, sxx = 0.0;
    for (const auto& [x, y] : p) sxy += (x - mx) * (y - my), sxx += (x - mx) * (x - mx);
    if (!(sxx > 0.0)) continue;
    out.push_back({key.first, key.second, sxy / sxx, static_cast<int>(p.size())});
  }
  return out;
}

void write_scale(const ScaleOptions& o, const std::vector<ScaleRecord>& records) {
  std::filesystem::create_directories(o.out_dir);
  const std::vector<ScaleSlope> slopes = fit_slopes(records);
  std::string device;
  for (const ScaleRecord& r : records)
    if (!r.device.empty()) device = r.device;
  const std::vector<std::pair<std::string, double>> parts = profile_parts(SolveProfile{});

  // CSV: one row per record; skipped rows keep their reason.
  Table csv;
  csv.columns = {"scene",
                 "res",
                 "elements",
                 "dofs",
                 "preconditioner",
                 "newton_iterations",
                 "cg_per_newton",
                 "seconds_per_step",
                 "device_memory_bytes",
                 "converged"};
  for (const auto& part : parts) csv.columns.push_back("profile_" + part.first);
  csv.columns.push_back("skipped");
  // Added after `skipped`, so that the columns before keep their places.
  const size_t skipped_column = csv.columns.size() - 1;
  for (const auto& part : iteration_traffic_parts(IterationTraffic{})) csv.columns.push_back(part.first);
  for (const ScaleRecord& r : records) {
    std::vector<std::string> row{r.scene, std::to_string(r.resolution), std::to_string(r.elements),
                                 std::to_string(r.dofs), r.preconditioner};
    if (r.skipped.empty()) {
      for (const std::string& cell :
           {std::to_string(r.newton_iterations), csv_number(r.cg_per_newton), csv_number(r.seconds_per_step),
            std::to_string(r.device_memory_bytes), std::string(r.converged ? "1" : "0")})
        row.push_back(cell);
      for (const auto& part : profile_parts(r.profile)) row.push_back(csv_number(part.second));
      row.push_back("");
      for (const auto& part : iteration_traffic_parts(iteration_traffic(r))) row.push_back(csv_number(part.second));
    } else {
      row.resize(skipped_column);
      row.push_back(csv_quoted(r.skipped));
      row.resize(csv.columns.size());
    }
    csv.add_row(std::move(row));
  }
  write_text(o.out_dir + "/scale.csv", csv_text(csv));

  json summary;
  summary["command"] = "scale";
  summary["device"] = device;
  summary["precision"] = o.precision;
  summary["product_precision"] = o.product_precision;
  summary["youngs_modulus"] = o.youngs_modulus;
  summary["poisson_ratio"] = o.poisson_ratio;
  summary["max_dofs"] = o.max_dofs;
  summary["paper"] = kPaper;
  summary["records"] = json::array();
  for (const ScaleRecord& r : records) summary["records"].push_back(record_json(r));
  summary["slopes"] = json::array();
  for (const ScaleSlope& s : slopes)
    summary["slopes"].push_back(
        {{"scene", s.scene}, {"preconditioner", s.preconditioner}, {"slope", s.slope}, {"points", s.points}});
  write_json(o.out_dir + "/scale.json", summary);

  std::ostringstream md;
  md << "# snh-gpu-bench scale\n\n"
     << "Device: " << (device.empty() ? "none ran" : device) << ". " << o.precision << ", E = " << o.youngs_modulus
     << ", nu = " << o.poisson_ratio
     << "; each scene's own load steps and tolerance (strain 1e-6 in double, 1e-4 in float).\n\n"
     << "Paper: " << kPaper << ". Ours, same quantity (seconds per load step):\n\n";
  Table runs;
  runs.columns = {"scene",  "res",           "elements",   "DOF",        "preconditioner",
                  "Newton", "CG per Newton", "s per step", "device MiB", "converged"};
  for (const ScaleRecord& r : records) {
    std::vector<std::string> row{r.scene, std::to_string(r.resolution), thousands(static_cast<long long>(r.elements)),
                                 thousands(static_cast<long long>(r.dofs)), r.preconditioner};
    if (!r.skipped.empty())
      row.insert(row.end(), {"-", "-", "-", "-", "skipped: " + r.skipped});
    else
      row.insert(row.end(),
                 {std::to_string(r.newton_iterations), significant(r.cg_per_newton), significant(r.seconds_per_step),
                  mebibytes(r.device_memory_bytes), r.converged ? "yes" : "no (" + r.status + ")"});
    runs.add_row(std::move(row));
  }
  Table fitted;
  fitted.columns = {"scene", "preconditioner", "slope", "points"};
  for (const ScaleSlope& s : slopes)
    fitted.add_row({s.scene, s.preconditioner, significant(s.slope, 3), std::to_string(s.points)});
  Table phases;
  phases.columns = {"scene", "res", "preconditioner"};
  for (const auto& part : parts) phases.columns.push_back(part.first);
  for (const ScaleRecord& r : records) {
    if (!r.skipped.empty()) continue;
    std::vector<std::string> row{r.scene, std::to_string(r.resolution), r.preconditioner};
    for (const auto& part : profile_parts(r.profile)) row.push_back(significant(part.second));
    phases.add_row(std::move(row));
  }
  Table traffic;
  traffic.columns = {"scene", "res", "DOF", "preconditioner", "Newton", "CG"};
  for (const std::string& heading : iteration_traffic_headings()) traffic.columns.push_back(heading);
  for (const ScaleRecord& r : records) {
    if (!r.skipped.empty()) continue;
    std::vector<std::string> row{
        r.scene,          std::to_string(r.resolution),   thousands(static_cast<long long>(r.dofs)),
        r.preconditioner, thousands(r.newton_iterations), thousands(r.cg_iterations)};
    for (const auto& part : iteration_traffic_parts(iteration_traffic(r))) row.push_back(significant(part.second));
    traffic.add_row(std::move(row));
  }
  md << markdown_text(runs) << "\n## Fitted slopes (seconds per step ~ DOF^slope)\n\n"
     << markdown_text(fitted) << "\n## Where the time went (seconds, whole solve)\n\n"
     << markdown_text(phases) << "\n## Kernel launches and blocking reads per iteration\n\n"
     << "Counted device traffic (the same on every device): per CG iteration, the linear solves' "
        "(products, preconditioner_apply and cg_vector_work) over the CG iterations; per Newton iteration, the "
        "whole solve's over the Newton iterations.\n\n"
     << markdown_text(traffic);
  write_text(o.out_dir + "/scale.md", md.str());
  if (o.plots) draw_plots("scale", "plot_scale.py", o.out_dir + "/scale.json", o.out_dir);
}

int run_scale_command(const ScaleOptions& o) {
  const auto start = Clock::now();
  const std::vector<ScaleRecord> records = run_scale(o);
  write_scale(o, records);
  std::cout << std::left << std::setw(9) << "scene" << std::setw(5) << "res" << std::setw(10) << "DOF" << std::setw(14)
            << "precond" << std::setw(8) << "newton" << std::setw(10) << "cg/newton" << std::setw(11) << "s/step"
            << std::setw(11) << "MiB" << std::setw(11) << "converged" << std::setw(11) << "launch/cg" << std::setw(9)
            << "read/cg" << std::setw(15) << "launch/newton"
            << "read/newton\n";
  bool any = false;
  for (const ScaleRecord& r : records) {
    std::cout << std::left << std::setw(9) << r.scene << std::setw(5) << r.resolution << std::setw(10) << r.dofs
              << std::setw(14) << r.preconditioner;
    if (!r.skipped.empty()) {
      std::cout << "skipped: " << r.skipped << '\n';
      continue;
    }
    any = true;
    std::cout << std::setw(8) << r.newton_iterations << std::setw(10) << significant(r.cg_per_newton) << std::setw(11)
              << significant(r.seconds_per_step) << std::setw(11) << mebibytes(r.device_memory_bytes) << std::setw(11)
              << (r.converged ? "yes" : "no");
    const IterationTraffic t = iteration_traffic(r);
    std::cout << std::setw(11) << significant(t.launches_per_cg_iteration) << std::setw(9)
              << significant(t.readbacks_per_cg_iteration) << std::setw(15)
              << significant(t.launches_per_newton_iteration) << significant(t.readbacks_per_newton_iteration) << '\n';
  }
  std::cout << "wrote " << o.out_dir << "/scale.csv, scale.json, scale.md" << (o.plots ? ", scale.png" : "") << " ("
            << std::setprecision(3) << std::chrono::duration<double>(Clock::now() - start).count() << " s)\n";
  return any ? 0 : 1;
}

void add_scale_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ScaleOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scale",
      "Twist and stretch at growing resolution with each preconditioner side by side: Newton, CG per Newton, seconds "
      "per step, device memory, kernel launches and blocking reads per CG and per Newton iteration and the per-phase "
      "profile against DOF; writes scale.{json,csv,md} and scale.png");
  cmd->add_option("--scenes", o->scenes, "comma-separated scenes")
      ->delimiter(',')
      ->check(CLI::IsMember(lattice_scene_names()))
      ->capture_default_str();
  cmd->add_option("--res", o->resolutions, "comma-separated resolutions (cells across each scene's thickness)")
      ->delimiter(',')
      ->check(CLI::Range(1, 400))
      ->capture_default_str();
  cmd->add_option("--preconditioner", o->preconditioners,
                  "comma-separated: none, block-jacobi, multigrid (one that is not built or does not apply is "
                  "reported as skipped)")
      ->delimiter(',')
      ->check(CLI::IsMember(cli::names_with(cli::preconditioner_names(), {}, {"automatic"})))
      ->capture_default_str();
  cmd->add_option("--max-dofs", o->max_dofs,
                  "grow the resolution past --res (DOF about x2 per row) while DOF <= N, e.g. 1000000 for the "
                  "paper's stretch cylinder (>= 300k hexes); 0: only --res")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--E", o->youngs_modulus, "Young's modulus")->capture_default_str();
  cmd->add_option("--nu", o->poisson_ratio, "Poisson's ratio")->capture_default_str();
  cmd->add_option("--precision", o->precision, "float or double")
      ->check(CLI::IsMember(cli::precision_names()))
      ->capture_default_str();
  cli::add_product_precision_option(cmd, o->product_precision);
  cmd->add_option("--cg-check-every", o->cg_check_every,
                  "CG's convergence test read back every N iterations (0: ViennaCL's CG, read every iteration; "
                  "default: SolverTuning::cg_check_every)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>' (default: $SNH_DEVICE, first GPU)");
  o->multigrid.add_to(cmd);
  cmd->add_option("--out", o->out_dir, "folder for scale.csv, scale.json, scale.md and scale.png")
      ->capture_default_str();
  cmd->add_flag("!--no-plots", o->plots, "do not draw scale.png");
  cmd->callback([o, &exit_code] { exit_code = run_scale_command(*o); });
}

}  // namespace snh::bench
