// `snh-gpu-bench errtime`: for each scene, a reference solution (double,
// solved to a relative residual of 1e-10 per load step), then every series
// (precision x preconditioner on the device, and the Eigen host baseline)
// with the force residual and the error against the reference recorded after
// every Newton iteration, against wall time.
#include "errtime.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <utility>

#include "commands.h"
#include "enum_names.h"
#include "host_baseline.h"
#include "iteration_traffic.h"
#include "record_writer.h"
#include "scene/profile_json.h"
#include "snh/error.h"
#include "snh/scenes.h"
#include "snh/simulation.h"
#include "solver/simulation/load_stepping.h"
#include "warm_up.h"

namespace snh::bench {
namespace {

using scene_io::profile_json;
using scene_io::profile_parts;

using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

constexpr double kThresholds[] = {1e-2, 1e-4, 1e-6};
constexpr const char* kThresholdNames[] = {"1e-2", "1e-4", "1e-6"};

const char* kErrorMetric =
    "||x - x_ref(step)||_2 / max(||x_ref(step) - X_rest||_2, ||x_initial - X_rest||_2) over all vertices, x_ref the "
    "reference at the same load step (the second term matters only for scramble, whose reference is the rest shape)";
const char* kTimeDefinition =
    "first wall time (seconds since the solve began, callbacks excluded) at which the residual of the LAST load step "
    "is <= the threshold; null if never";

// One CSV row: the state at a step's start (newton_iteration 0) or after a
// Newton update.
struct Row {
  int step = 0;
  int newton_iteration = 0;  // within the step; 0: the step's start, before any update
  int newton_total = 0;      // updates so far, all steps
  int cg_total = 0;          // CG iterations so far, all steps
  double seconds = 0.0;
  double residual = 0.0;  // L2 norm of the free-DOF force residual at this state
  double error = 0.0;
  int projected = -1;  // the Hessian of the update: 1 projected, 0 true; -1 none (a step's start)
};

struct Reference {
  SolveResult result;
  std::vector<std::vector<double>> positions;  // after each load step
  std::vector<double> scale;                   // the error's denominator per step
  std::vector<double> reached_relative;        // per step: final / initial residual
};

struct Series {
  std::string name, precision, preconditioner, variant, hessian, device, specialization;
  std::vector<Row> rows;
  std::vector<StepResult> steps;
  bool converged = false;
  double seconds = 0.0;
  SolveProfile profile;   // where the solve's time went
  std::string skipped;    // why the series did not run, if it did not
  bool on_device = true;  // false: the host baseline, which has no device traffic
};

struct SceneRun {
  Scene scene;
  int resolution = 0;
  Reference reference;
  std::vector<Series> series;
  std::string skipped;
};

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

// The constrained vertices at their targets for load parameter t, as the
// solver places them at the start of a step.
void apply_constraints(const Scene& scene, double t, std::vector<double>& x) {
  snh::apply_constraints(scene.mesh, scene.constraints, t, x);
}

std::vector<double> initial_positions(const Scene& scene) {
  return (scene.options.initial_positions.empty() ? scene.mesh.positions : scene.options.initial_positions).xyz();
}

// Collects the error after every Newton update (as on_iteration) and turns
// it, with the solve's history, into rows.
class Recorder {
 public:
  Recorder(const Scene& scene, const Reference& reference)
      : scene_(scene), reference_(reference), steps_(scene.options.load_steps), last_(initial_positions(scene)) {}

  void operator()(const NewtonIteration& rec, const std::vector<double>& x) {
    fill_starts(rec.step);
    updates_.push_back({rec.step, rec.iteration, error(rec.step, x)});
    last_ = x;
  }

  std::vector<Row> rows(const std::vector<NewtonIteration>& history) {
    fill_starts(steps_);
    std::map<std::pair<int, int>, size_t> index;
    std::vector<int> cg_through(history.size());
    std::vector<double> seconds_through(history.size());
    for (size_t i = 0; i < history.size(); ++i) {
      index[{history[i].step, history[i].iteration}] = i;
      cg_through[i] = (i > 0 ? cg_through[i - 1] : 0) + history[i].cg_iterations;
      seconds_through[i] = std::max(i > 0 ? seconds_through[i - 1] : 0.0, history[i].seconds);
    }
    std::vector<Row> out;
    int newton_total = 0;
    size_t next_update = 0;
    for (int s = 1; s <= steps_; ++s) {
      const auto first = index.find({s, 0});
      if (first == index.end()) break;
      const size_t i0 = first->second;
      Row start;
      start.step = s;
      start.newton_total = newton_total;
      start.cg_total = i0 > 0 ? cg_through[i0 - 1] : 0;
      start.seconds = i0 > 0 ? seconds_through[i0 - 1] : 0.0;
      start.residual = history[i0].residual_norm;
      start.error = start_errors_[s - 1];
      out.push_back(start);
      for (; next_update < updates_.size() && updates_[next_update].step == s; ++next_update) {
        const Update& u = updates_[next_update];
        const auto at = index.find({s, u.iteration}), after = index.find({s, u.iteration + 1});
        if (at == index.end()) continue;
        const NewtonIteration& h = history[at->second];
        Row r;
        r.step = s;
        r.newton_iteration = u.iteration + 1;
        r.newton_total = ++newton_total;
        r.cg_total = cg_through[at->second];
        r.seconds = h.seconds;
        r.residual = after != index.end() ? history[after->second].residual_norm : std::nan("");
        r.error = u.error;
        r.projected = h.projected ? 1 : 0;
        out.push_back(r);
      }
    }
    return out;
  }

 private:
  struct Update {
    int step, iteration;
    double error;
  };

  double error(int step, const std::vector<double>& x) const {
    return distance(x, reference_.positions[step - 1]) / reference_.scale[step - 1];
  }

  // The error at the start of every step up to `step` not yet recorded: the
  // last positions with that step's constraint targets.
  void fill_starts(int step) {
    for (int s = static_cast<int>(start_errors_.size()) + 1; s <= step; ++s) {
      std::vector<double> x = last_;
      apply_constraints(scene_, static_cast<double>(s) / steps_, x);
      start_errors_.push_back(error(s, x));
    }
  }

  const Scene& scene_;
  const Reference& reference_;
  int steps_;
  std::vector<double> last_;
  std::vector<double> start_errors_;
  std::vector<Update> updates_;
};

Reference solve_reference(const Scene& scene, const ErrtimeOptions& o) {
  SolveOptions options = scene.options;
  options.precision = Precision::double_;
  options.device.match = o.device;
  options.relative_tolerance = o.reference_tolerance;
  options.absolute_tolerance = 0.0;
  options.max_newton_iterations = std::max(options.max_newton_iterations, 200);
  options.hessian = HessianMode::adaptive;
  options.preconditioner = Preconditioner::block_jacobi;
  options.product = ProductVariant::cached;
  Reference ref;
  QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
  ref.result = solver.solve({}, [&](int, const Points& x) { ref.positions.push_back(x.xyz()); });
  const double initial = distance(initial_positions(scene), scene.mesh.positions.xyz());
  for (const auto& x : ref.positions) {
    const double scale = std::max(distance(x, scene.mesh.positions.xyz()), initial);
    ref.scale.push_back(scale > 0.0 ? scale : 1.0);
  }
  for (const StepResult& s : ref.result.steps) {
    double first = 0.0;
    for (const NewtonIteration& h : ref.result.history)
      if (h.step == s.step && h.iteration == 0) first = h.residual_norm;
    ref.reached_relative.push_back(first > 0.0 ? s.residual_norm / first : 0.0);
  }
  return ref;
}

SolveOptions series_options(const Scene& scene, const ErrtimeOptions& o) {
  SolveOptions options = scene.options;
  options.device.match = o.device;
  options.absolute_tolerance = o.absolute_tolerance;
  options.relative_tolerance = 0.0;
  options.max_newton_iterations = std::max(options.max_newton_iterations, 100);
  options.product = parse_optional(o.variant, parse_product_variant);
  options.hessian = parse_hessian_mode(o.hessian);
  return options;
}

Series run_device_series(const Scene& scene, const SceneParameters& parameters, const Reference& ref,
                         const ErrtimeOptions& o, Precision precision, Preconditioner preconditioner) {
  Series s;
  s.precision = to_string(precision);
  s.preconditioner = to_string(preconditioner);
  s.name = s.precision + "/" + s.preconditioner;
  s.variant = o.variant;
  s.hessian = o.hessian;
  SolveOptions options = series_options(scene, o);
  options.precision = precision;
  options.preconditioner = preconditioner;
  try {
    {
      SceneParameters small = parameters;
      if (parameters.resolution) small.resolution = std::min(*parameters.resolution, 3);
      const Scene tiny = make_scene(scene.name, small);
      SolveOptions warm = options;
      warm.initial_positions = tiny.options.initial_positions;
      warm_up_kernels(tiny, warm);
    }
    Recorder recorder(scene, ref);
    options.on_iteration = [&recorder](const NewtonIteration& rec, const Points& x) { recorder(rec, x.xyz()); };
    QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
    const SolveResult r = solver.solve();
    s.rows = recorder.rows(r.history);
    s.steps = r.steps;
    s.converged = r.converged;
    s.profile = r.profile;
    for (const NewtonIteration& h : r.history) s.seconds = std::max(s.seconds, h.seconds);
    s.device = r.device.platform + " / " + r.device.name;
    s.specialization = r.kernel_specialization;
    s.variant = to_string(r.product);  // resolved
  } catch (const Error& e) {
    s.skipped = e.what();
  }
  return s;
}

Series run_host_series(const Scene& scene, const Reference& ref, const ErrtimeOptions& o) {
  Series s;
  s.name = "host-eigen";
  s.precision = "double";
  s.preconditioner = "diagonal";
  s.variant = "assembled";
  s.hessian = "projected";
  s.device = "host CPU (Eigen, assembled projected stiffness)";
  s.on_device = false;
  SolveOptions options = series_options(scene, o);
  options.precision = Precision::double_;
  options.hessian = HessianMode::projected;
  try {
    Recorder recorder(scene, ref);
    const HostBaselineResult r = solve_on_host(
        scene, options, [&recorder](const NewtonIteration& rec, const std::vector<double>& x) { recorder(rec, x); });
    s.rows = recorder.rows(r.history);
    s.steps = r.steps;
    s.converged = r.converged;
    s.profile = r.profile;
    for (const NewtonIteration& h : r.history) s.seconds = std::max(s.seconds, h.seconds);
  } catch (const Error& e) {
    s.skipped = e.what();
  }
  return s;
}

// Seconds at which the last load step's residual first is <= threshold.
std::optional<double> time_to(const Series& s, int last_step, double threshold) {
  for (const Row& r : s.rows)
    if (r.step == last_step && r.residual <= threshold) return r.seconds;
  return std::nullopt;
}

int total_newton(const Series& s) {
  int n = 0;
  for (const StepResult& st : s.steps) n += st.newton_iterations;
  return n;
}

int total_cg(const Series& s) {
  int n = 0;
  for (const StepResult& st : s.steps) n += st.cg_iterations;
  return n;
}

// Best (lowest) residual of the last load step: the precision floor when a
// series stagnates.
double best_residual(const Series& s, int last_step) {
  double best = std::numeric_limits<double>::infinity();
  for (const Row& r : s.rows)
    if (r.step == last_step && r.residual < best) best = r.residual;
  return best;
}

// Launches and read-backs per CG and per Newton iteration (iteration_traffic.h);
// all 0 for the host baseline, which asks nothing of the device.
IterationTraffic series_traffic(const Series& s) {
  if (!s.on_device) return IterationTraffic{};
  return iteration_traffic(s.profile, total_cg(s), total_newton(s));
}

std::string fmt_seconds(const std::optional<double>& v) { return v ? significant(*v, 3) : "never"; }

// "21 + 22" for up to two load steps (the paper's twist reports per step), else the total.
std::string per_step(const Series& s, bool cg) {
  const int total = cg ? total_cg(s) : total_newton(s);
  if (s.steps.size() < 2 || s.steps.size() > 2) return thousands(total);
  std::string out;
  for (const StepResult& st : s.steps)
    out += (out.empty() ? "" : " + ") + thousands(cg ? st.cg_iterations : st.newton_iterations);
  return out;
}

std::string stop_status(const Series& s) {
  std::map<std::string, int> counts;
  for (const StepResult& st : s.steps) ++counts[to_string(st.status)];
  std::string out;
  for (const auto& [status, n] : counts)
    out += (out.empty() ? "" : ", ") + status + (s.steps.size() > 1 ? " x" + std::to_string(n) : "");
  return out;
}

std::string paper_figures(const SceneRun& run) {
  const SolveResult& r = run.reference.result;
  std::ostringstream s;
  if (run.scene.name == "twist")
    s << "12 + 16 Newton, 3,278 + 4,956 CG (two pi/2 steps, 15^3 hexes, no preconditioner stated)";
  else if (run.scene.name == "stretch")
    s << "volume +4.3% (306,406 hexes); reference here: " << std::showpos << std::fixed << std::setprecision(2)
      << 100.0 * (r.volume_ratio - 1.0) << "%";
  else if (run.scene.name == "scramble")
    s << "recovers; reference here: volume " << std::fixed << std::setprecision(4) << r.volume_ratio << ", min J "
      << std::setprecision(3) << r.min_j;
  else
    s << "none";
  return s.str();
}

json series_json(const Series& s, int last_step) {
  json j;
  j["series"] = s.name;
  j["precision"] = s.precision;
  j["preconditioner"] = s.preconditioner;
  j["variant"] = s.variant;
  j["hessian"] = s.hessian;
  if (!s.skipped.empty()) {
    j["skipped"] = s.skipped;
    return j;
  }
  j["converged"] = s.converged;
  j["newton_iterations"] = total_newton(s);
  j["cg_iterations"] = total_cg(s);
  for (const auto& [key, value] : iteration_traffic_parts(series_traffic(s))) j[key] = value;
  j["steps"] = json::array();
  for (const StepResult& st : s.steps)
    j["steps"].push_back({{"step", st.step},
                          {"newton_iterations", st.newton_iterations},
                          {"cg_iterations", st.cg_iterations},
                          {"status", to_string(st.status)},
                          {"residual", st.residual_norm}});
  j["wall_seconds"] = s.seconds;
  json t;
  for (size_t k = 0; k < std::size(kThresholds); ++k) {
    const auto v = time_to(s, last_step, kThresholds[k]);
    t[kThresholdNames[k]] = v ? json(*v) : json(nullptr);
  }
  j["seconds_to_residual"] = t;
  j["profile"] = profile_json(s.profile);
  const Row* last = s.rows.empty() ? nullptr : &s.rows.back();
  j["final_residual"] = last ? json(last->residual) : json(nullptr);
  j["best_residual_last_step"] = s.rows.empty() ? json(nullptr) : json(best_residual(s, last_step));
  j["final_error"] = last ? json(last->error) : json(nullptr);
  j["device"] = s.device;
  j["kernel_specialization"] = s.specialization.empty() ? json(nullptr) : json(s.specialization);
  return j;
}

json reference_json(const Reference& ref) {
  const SolveResult& r = ref.result;
  json j;
  j["precision"] = "double";
  j["converged"] = r.converged;
  int newton = 0, cg = 0;
  for (const StepResult& s : r.steps) newton += s.newton_iterations, cg += s.cg_iterations;
  j["newton_iterations"] = newton;
  j["cg_iterations"] = cg;
  j["wall_seconds"] = r.seconds;
  j["steps"] = json::array();
  for (size_t k = 0; k < r.steps.size(); ++k)
    j["steps"].push_back({{"step", r.steps[k].step},
                          {"status", to_string(r.steps[k].status)},
                          {"residual", r.steps[k].residual_norm},
                          {"reached_relative_residual", ref.reached_relative[k]},
                          {"newton_iterations", r.steps[k].newton_iterations},
                          {"cg_iterations", r.steps[k].cg_iterations}});
  j["volume_ratio"] = r.volume_ratio;
  j["min_j"] = r.min_j;
  j["inverted_elements"] = r.inverted_elements;
  j["device"] = r.device.platform + " / " + r.device.name;
  j["kernel_specialization"] = r.kernel_specialization;
  return j;
}

double worst_reached(const Reference& ref) {
  double worst = 0.0;
  for (double v : ref.reached_relative) worst = std::max(worst, v);
  return worst;
}

std::vector<std::string> expand(const std::string& choice, std::vector<std::string> all) {
  return choice == "both" ? all : std::vector<std::string>{choice};
}

}  // namespace

int default_errtime_resolution(const std::string& scene) {
  if (scene == "stretch") return 6;
  if (scene == "twist") return 8;
  if (scene == "scramble") return 5;
  if (scene == "flex") return 3;
  return 0;
}

namespace {

// Every scene's reference and series; `device` the references' device.
std::vector<SceneRun> run_errtime_series(const ErrtimeOptions& o, std::string& device) {
  std::vector<SceneRun> runs;
  for (const std::string& name : o.scenes) {
    SceneRun run;
    SceneParameters p;
    run.resolution = o.resolution > 0 ? o.resolution : default_errtime_resolution(name);
    p.resolution = run.resolution;
    p.youngs_modulus = o.youngs_modulus;
    p.poisson_ratio = o.poisson_ratio;
    p.seed = o.seed;
    p.element_type = cli::element_type_named(o.element);
    run.scene = make_scene(name, p);
    const Scene& scene = run.scene;
    std::cerr << "errtime: " << name << " (" << scene.mesh.element_count() << " " << to_string(scene.mesh.type) << ", "
              << 3 * scene.mesh.vertex_count() << " dofs, " << scene.options.load_steps << " steps)\n";
    try {
      run.reference = solve_reference(scene, o);
    } catch (const Error& e) {
      run.skipped = e.what();
      std::cerr << "errtime:   reference failed, scene skipped: " << e.what() << '\n';
      runs.push_back(std::move(run));
      continue;
    }
    const SolveResult& ref = run.reference.result;
    device = ref.device.platform + " / " + ref.device.name;
    std::cerr << "errtime:   reference: " << ref.history.size() << " records, " << std::setprecision(3) << ref.seconds
              << " s, worst reached relative residual " << worst_reached(run.reference)
              << (ref.converged ? "" : " (did not reach the tolerance in every step)") << '\n';
    for (const std::string& precision : expand(o.precision, {"double", "float"}))
      for (const std::string& pre : o.preconditioner == "all"
                                        ? std::vector<std::string>{"block-jacobi", "multigrid", "none"}
                                        : expand(o.preconditioner, {"block-jacobi", "none"})) {
        run.series.push_back(
            run_device_series(scene, p, run.reference, o, parse_precision(precision), parse_preconditioner(pre)));
        const Series& s = run.series.back();
        if (!s.skipped.empty())
          std::cerr << "errtime:   " << s.name << " skipped: " << s.skipped << '\n';
        else
          std::cerr << "errtime:   " << s.name << ": " << total_newton(s) << " Newton, " << total_cg(s) << " CG, "
                    << std::setprecision(3) << s.seconds << " s, final residual " << s.rows.back().residual
                    << ", error " << s.rows.back().error << " (" << stop_status(s) << ")\n";
      }
    if (o.host_baseline) {
      run.series.push_back(run_host_series(scene, run.reference, o));
      const Series& s = run.series.back();
      if (!s.skipped.empty())
        std::cerr << "errtime:   host-eigen skipped: " << s.skipped << '\n';
      else
        std::cerr << "errtime:   host-eigen: " << total_newton(s) << " Newton, " << total_cg(s) << " CG, "
                  << std::setprecision(3) << s.seconds << " s, final residual " << s.rows.back().residual << ", error "
                  << s.rows.back().error << " (" << stop_status(s) << ")\n";
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

// errtime.csv, errtime.json and errtime.md from the runs.
void write_errtime(const ErrtimeOptions& o, const std::string& device, const std::vector<SceneRun>& runs) {
  // CSV: one row per step start and per Newton update; after `projected`,
  // its series' launches and read-backs per iteration, the same on each of
  // the series' rows.
  Table csv;
  csv.columns = {"scene",        "series",   "precision", "preconditioner", "step",  "newton_iteration",
                 "newton_total", "cg_total", "seconds",   "residual",       "error", "projected"};
  for (const auto& part : iteration_traffic_parts(IterationTraffic{})) csv.columns.push_back(part.first);
  for (const SceneRun& run : runs)
    for (const Series& s : run.series) {
      const auto traffic = iteration_traffic_parts(series_traffic(s));
      for (const Row& r : s.rows) {
        std::vector<std::string> row{run.scene.name,
                                     s.name,
                                     s.precision,
                                     s.preconditioner,
                                     std::to_string(r.step),
                                     std::to_string(r.newton_iteration),
                                     std::to_string(r.newton_total),
                                     std::to_string(r.cg_total),
                                     csv_number(r.seconds),
                                     csv_number(r.residual),
                                     csv_number(r.error),
                                     r.projected >= 0 ? std::to_string(r.projected) : std::string()};
        for (const auto& part : traffic) row.push_back(csv_number(part.second));
        csv.add_row(std::move(row));
      }
    }
  write_text(o.out_dir + "/errtime.csv", csv_text(csv));

  // JSON summary.
  json summary;
  summary["command"] = "errtime";
  summary["device"] = device;
  summary["youngs_modulus"] = o.youngs_modulus;
  summary["poisson_ratio"] = o.poisson_ratio;
  summary["series_absolute_tolerance"] = o.absolute_tolerance;
  summary["reference_relative_tolerance"] = o.reference_tolerance;
  summary["variant"] = o.variant;
  summary["hessian"] = o.hessian;
  summary["error_metric"] = kErrorMetric;
  summary["seconds_to_residual_definition"] = kTimeDefinition;
  summary["scenes"] = json::array();
  for (const SceneRun& run : runs) {
    json j;
    j["scene"] = run.scene.name;
    j["description"] = run.scene.description;
    j["resolution"] = run.resolution;
    j["element_type"] = to_string(run.scene.mesh.type);
    j["elements"] = run.scene.mesh.element_count();
    j["dofs"] = 3 * run.scene.mesh.vertex_count();
    j["load_steps"] = run.scene.options.load_steps;
    if (!run.skipped.empty()) {
      j["skipped"] = run.skipped;
      summary["scenes"].push_back(j);
      continue;
    }
    j["paper"] = paper_figures(run);
    j["reference"] = reference_json(run.reference);
    j["series"] = json::array();
    for (const Series& s : run.series) j["series"].push_back(series_json(s, run.scene.options.load_steps));
    summary["scenes"].push_back(j);
  }
  write_json(o.out_dir + "/errtime.json", summary);

  // Markdown.
  std::ostringstream md;
  md << "# snh-gpu-bench errtime\n\n"
     << "Device: " << device << ". E = " << o.youngs_modulus << ", nu = " << o.poisson_ratio << ", product "
     << o.variant << ", Hessian " << o.hessian << ".\n\n"
     << "Series stop at an absolute residual of " << significant(o.absolute_tolerance)
     << " (or when they stagnate at their precision floor). References: double, block-Jacobi, adaptive Hessian, "
        "solved to a relative residual of "
     << significant(o.reference_tolerance) << " per load step.\n\n"
     << "- t(r <= x): " << kTimeDefinition << ".\n"
     << "- error: " << kErrorMetric << ".\n"
     << "- Newton and CG: per load step when the scene has two (as the paper reports the twist), else totals.\n\n"
     << "## References\n\n";
  Table references;
  references.columns = {"scene",  "res", "elements / dofs", "steps",
                        "Newton", "CG",  "wall s",          "worst reached relative residual",
                        "status"};
  for (const SceneRun& run : runs) {
    std::vector<std::string> row{run.scene.name, std::to_string(run.resolution),
                                 thousands(static_cast<long long>(run.scene.mesh.element_count())) + " / " +
                                     thousands(static_cast<long long>(3 * run.scene.mesh.vertex_count())),
                                 std::to_string(run.scene.options.load_steps)};
    if (!run.skipped.empty()) {
      row.insert(row.end(), {"-", "-", "-", "-", "skipped: " + run.skipped});
    } else {
      Series as_series;
      as_series.steps = run.reference.result.steps;
      row.insert(row.end(),
                 {per_step(as_series, false), per_step(as_series, true), significant(run.reference.result.seconds),
                  significant(worst_reached(run.reference), 2), stop_status(as_series)});
    }
    references.add_row(std::move(row));
  }
  Table series;
  series.columns = {"scene",          "series",         "Newton",         "CG",          "wall s", "t(r <= 1e-2) s",
                    "t(r <= 1e-4) s", "t(r <= 1e-6) s", "final residual", "final error", "stop",   "paper"};
  for (const SceneRun& run : runs) {
    if (!run.skipped.empty()) continue;
    const int last = run.scene.options.load_steps;
    bool first = true;
    for (const Series& s : run.series) {
      const std::string paper = first ? paper_figures(run) : "";
      if (!s.skipped.empty())
        series.add_row(
            {run.scene.name, s.name, "-", "-", "-", "-", "-", "-", "-", "-", "skipped: " + s.skipped, paper});
      else
        series.add_row({run.scene.name, s.name, per_step(s, false), per_step(s, true), significant(s.seconds),
                        fmt_seconds(time_to(s, last, 1e-2)), fmt_seconds(time_to(s, last, 1e-4)),
                        fmt_seconds(time_to(s, last, 1e-6)), significant(s.rows.back().residual, 2),
                        significant(s.rows.back().error, 2), stop_status(s), paper});
      first = false;
    }
  }
  Table phases;
  phases.columns = {"scene", "series"};
  for (const auto& part : profile_parts(SolveProfile{})) phases.columns.push_back(part.first);
  for (const SceneRun& run : runs) {
    if (!run.skipped.empty()) continue;
    for (const Series& s : run.series) {
      if (!s.skipped.empty()) continue;
      std::vector<std::string> row{run.scene.name, s.name};
      for (const auto& part : profile_parts(s.profile)) row.push_back(significant(part.second));
      phases.add_row(std::move(row));
    }
  }
  Table traffic;
  traffic.columns = {"scene", "series", "Newton", "CG"};
  for (const std::string& heading : iteration_traffic_headings()) traffic.columns.push_back(heading);
  for (const SceneRun& run : runs) {
    if (!run.skipped.empty()) continue;
    for (const Series& s : run.series) {
      if (!s.skipped.empty() || !s.on_device) continue;
      std::vector<std::string> row{run.scene.name, s.name, thousands(total_newton(s)), thousands(total_cg(s))};
      for (const auto& part : iteration_traffic_parts(series_traffic(s))) row.push_back(significant(part.second));
      traffic.add_row(std::move(row));
    }
  }
  md << markdown_text(references) << "\n## Series\n\n"
     << markdown_text(series) << "\n## Where the time went\n\n"
     << "Seconds per phase of each series' solve (SolveProfile; callbacks excluded, so `total` may exceed the wall "
        "seconds above by the final statistics). host-eigen: Eigen's CG solve is one call whose parts cannot be told "
        "apart; its time is in `other`.\n\n"
     << markdown_text(phases) << "\n## Kernel launches and blocking reads per iteration\n\n"
     << "Counted device traffic of the device series (the same on every device): per CG iteration, the linear "
        "solves' (products, preconditioner_apply and cg_vector_work) over the CG iterations; per Newton iteration, "
        "the whole solve's over the Newton iterations. host-eigen asks nothing of the device and is left out (0 in "
        "errtime.json and errtime.csv).\n\n"
     << markdown_text(traffic);
  write_text(o.out_dir + "/errtime.md", md.str());
}

}  // namespace

int run_errtime(const ErrtimeOptions& o) {
  const auto start = Clock::now();
  std::filesystem::create_directories(o.out_dir);
  std::string device;
  const std::vector<SceneRun> runs = run_errtime_series(o, device);
  write_errtime(o, device, runs);

  // Short table on stdout.
  std::cout << std::left << std::setw(10) << "scene" << std::setw(20) << "series" << std::setw(8) << "newton"
            << std::setw(8) << "cg" << std::setw(9) << "wall s" << std::setw(9) << "t 1e-2" << std::setw(9) << "t 1e-4"
            << std::setw(9) << "t 1e-6" << std::setw(11) << "residual" << std::setw(9) << "error" << std::setw(11)
            << "launch/cg" << std::setw(9) << "read/cg" << std::setw(15) << "launch/newton"
            << "read/newton\n";
  bool any = false;
  for (const SceneRun& run : runs)
    for (const Series& s : run.series) {
      if (!s.skipped.empty()) continue;
      any = true;
      const int last = run.scene.options.load_steps;
      std::cout << std::left << std::setw(10) << run.scene.name << std::setw(20) << s.name << std::setw(8)
                << total_newton(s) << std::setw(8) << total_cg(s) << std::setw(9) << significant(s.seconds)
                << std::setw(9) << fmt_seconds(time_to(s, last, 1e-2)) << std::setw(9)
                << fmt_seconds(time_to(s, last, 1e-4)) << std::setw(9) << fmt_seconds(time_to(s, last, 1e-6))
                << std::setw(11) << significant(s.rows.back().residual, 2) << std::setw(9)
                << significant(s.rows.back().error, 2);
      // host-eigen: "-" (no device traffic; 0 in the files).
      const IterationTraffic t = series_traffic(s);
      const auto cell = [&s](double v) { return s.on_device ? significant(v) : std::string("-"); };
      std::cout << std::setw(11) << cell(t.launches_per_cg_iteration) << std::setw(9)
                << cell(t.readbacks_per_cg_iteration) << std::setw(15) << cell(t.launches_per_newton_iteration)
                << cell(t.readbacks_per_newton_iteration) << '\n';
    }
  if (o.plots) draw_plots("errtime", "plot_errtime.py", o.out_dir + "/errtime.csv", o.out_dir);
  std::cout << "wrote " << o.out_dir << "/errtime.csv, errtime.json, errtime.md (" << std::setprecision(3)
            << std::chrono::duration<double>(Clock::now() - start).count() << " s)\n";
  return any ? 0 : 1;
}

void add_errtime_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ErrtimeOptions>();
  auto host = std::make_shared<std::string>("on");
  CLI::App* cmd = app.add_subcommand(
      "errtime",
      "Force residual and error against a double reference (relative residual 1e-10) versus wall time, per Newton "
      "iteration, for each scene, precision and preconditioner, with the device series' kernel launches and blocking "
      "reads per CG and per Newton iteration; writes errtime.csv, errtime.json, errtime.md and errtime_<scene>.png");
  cmd->add_option("--scenes", o->scenes, "comma-separated scenes")
      ->delimiter(',')
      ->check(CLI::IsMember(lattice_scene_names()))
      ->capture_default_str();
  cmd->add_option("--element", o->element, "hex8 (the paper's lattices) or tet4 (each lattice hex split in six)")
      ->check(CLI::IsMember(cli::element_type_names()))
      ->capture_default_str();
  cmd->add_option("--res", o->resolution,
                  "cells across each scene's thickness (0: stretch 6, twist 8, scramble 5, flex 3)")
      ->check(CLI::Range(0, 400))
      ->capture_default_str();
  cmd->add_option("--precision", o->precision, "float, double or both")
      ->check(CLI::IsMember(cli::names_with(cli::precision_names(), {"both"})))
      ->capture_default_str();
  cmd->add_option("--preconditioner", o->preconditioner,
                  "block-jacobi, multigrid (hex8 lattices), none, both (block-jacobi and none) or all three")
      ->check(CLI::IsMember(cli::names_with(cli::preconditioner_names(), {"both", "all"}, {"automatic"})))
      ->capture_default_str();
  cmd->add_option("--variant", o->variant,
                  "Hessian product of the device series: automatic (measured default), cached, recompute, "
                  "element-matrices, assembled (the reference always uses cached)")
      ->check(CLI::IsMember(cli::product_variant_names()))
      ->capture_default_str();
  cmd->add_option("--hessian", o->hessian,
                  "projected (always the PSD projection) or adaptive (true Hessian near convergence)")
      ->check(CLI::IsMember(cli::hessian_mode_names()))
      ->capture_default_str();
  cmd->add_option("--host-baseline", *host, "also solve on the host with Eigen (double) as series host-eigen: on, off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>' (default: $SNH_DEVICE, first GPU)");
  cmd->add_option("--out", o->out_dir, "folder for errtime.csv, errtime.json, errtime.md and the PNGs")
      ->capture_default_str();
  cmd->add_option("--E", o->youngs_modulus, "Young's modulus")->capture_default_str();
  cmd->add_option("--nu", o->poisson_ratio, "Poisson's ratio")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed (scramble)")->capture_default_str();
  cmd->add_option("--atol", o->absolute_tolerance, "absolute residual at which the series stop")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--ref-rtol", o->reference_tolerance, "relative residual per load step of the reference")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("!--no-plots", o->plots, "do not draw the PNGs");
  cmd->callback([o, host, &exit_code] {
    o->host_baseline = *host == "on";
    exit_code = run_errtime(*o);
  });
}

}  // namespace snh::bench
