// `snh-gpu-bench stability`: see stability.h.
#include "stability.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "record_writer.h"
#include "snh/error.h"
#include "snh/surface.h"
#include "snh/surface_intersections.h"
#include "solver/simulation/load_stepping.h"

namespace snh::bench {
namespace {

using json = nlohmann::ordered_json;
constexpr double kPi = 3.14159265358979323846;

double strain_tolerance(Precision p) { return p == Precision::single ? 1e-4 : 1e-6; }

// The scenes' stopping rule: |r| <= strain tol E h^2 sqrt(vertices).
void set_tolerance(Scene& s, Precision precision, double h) {
  s.options.relative_tolerance = 0.0;
  s.options.absolute_tolerance = strain_tolerance(precision) * s.material.youngs_modulus() * h * h *
                                 std::sqrt(static_cast<double>(s.mesh.vertex_count()));
}

std::vector<int32_t> on_plane(const Mesh& mesh, int axis, double value, double h) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions(v, axis) - value) <= 1e-9 * h) out.push_back(static_cast<int32_t>(v));
  return out;
}

// A unit cube lattice of res^3 hexes, nu = 0.49, its bottom face pinned.
Scene pinned_cube(int res, Precision precision) {
  Scene s;
  const double h = 1.0 / res;
  s.mesh = make_box_lattice(res, res, res, h);
  s.material = StableNeoHookean::from_youngs_modulus(1.0, 0.49);
  s.constraints = {ConstraintSet{"bottom_face", on_plane(s.mesh, 2, 0.0, h), {}, {}}};
  s.options.load_steps = 1;
  s.options.max_newton_iterations = 200;
  set_tolerance(s, precision, h);
  return s;
}

bool pinned(const Scene& s, size_t v) {
  for (const ConstraintSet& c : s.constraints)
    if (std::find(c.vertices.begin(), c.vertices.end(), static_cast<int32_t>(v)) != c.vertices.end()) return true;
  return false;
}

// Free vertices crushed to z = 0 ("plane"), onto the vertical axis x = y =
// 1/2 ("line") or to the cube's centre ("point"); then released.
Scene crush(const std::string& shape, int res, Precision precision) {
  Scene s = pinned_cube(res, precision);
  s.options.initial_positions = s.mesh.positions;
  s.options.max_newton_iterations = 2000;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v) {
    if (pinned(s, v)) continue;
    double* x = s.options.initial_positions.data() + 3 * v;
    if (shape == "plane") x[2] = 0.0;
    if (shape == "line" || shape == "point") x[0] = x[1] = 0.5;
    if (shape == "point") x[2] = 0.5;
  }
  s.description = "cube, bottom face pinned, free vertices crushed to a " + shape + ", released";
  return s;
}

// A unit cube (E = 1, density 1) in a box of six planes under implicit
// Euler: the floor and the four walls stand just clear of its faces (the
// edges of their contact layers a tenth of the thickness away), the lid
// closes from just above to `height` (a fraction of the body's height,
// kDefaultSquashHeight = 0.1) and opens again, then the body is left to
// recover (docs/validation.md). The walls keep it from
// spreading sideways, so the squash takes its volume to about `height`
// whatever nu is (a laterally free body at nu -> 1/2 would keep its volume
// and only get thinner). squash_nu*: frictionless planes; squash_rough_nu*:
// the floor and the lid grip the body with Coulomb friction (walls
// frictionless, a lubricated die). At height 0.05 each meets a limit (docs/validation.md): between frictionless planes
// the squashed state at nu = 0.499 is a saddle whose shear mode the body takes, and the rough body at nu = 0.46 folds
// through itself (no self-contact here).
constexpr double kSquashThickness = 0.01, kSquashGap = 0.001, kSquashStiffness = 1.0e4, kSquashFriction = 0.5;

Scene squash(double nu, int res, Precision precision, double friction, double height) {
  if (!(height > 0.0 && height < 1.0))
    throw Error("stability: squash height must be in (0, 1) of the body's height, got " + std::to_string(height));
  Scene s;
  const double h = 1.0 / res, d = kSquashThickness;
  s.mesh = make_box_lattice(res, res, res, h);
  s.material = StableNeoHookean::from_youngs_modulus(1.0, nu);
  DynamicsOptions dynamics;
  dynamics.time_step = 0.25;  // the shear wave crosses the cube in 1.7 time units (E = density = 1)
  dynamics.density = 1.0;
  dynamics.damping.mass = 1.0;
  s.options.dynamics = dynamics;
  s.options.load_steps = 80;
  s.options.max_newton_iterations = 1000;
  auto plane = [](std::array<double, 3> point, std::array<double, 3> normal) {
    Obstacle o;
    o.type = ObstacleType::plane;
    o.point = point;
    o.direction = normal;
    return o;
  };
  // The floor and the walls stand kSquashGap clear of the body's faces: a
  // vertex resting exactly at a layer's edge sits on the penalty's kink (its
  // Hessian jumps from 0 to k there), where Newton stagnated at residuals of
  // 2e-6 to 5e-5 once the body was back at rest (docs/validation.md).
  const double g = d + kSquashGap;
  s.options.obstacles = {plane({0, 0, -g}, {0, 0, 1}),     plane({-g, 0, 0}, {1, 0, 0}),
                         plane({1 + g, 0, 0}, {-1, 0, 0}), plane({0, -g, 0}, {0, 1, 0}),
                         plane({0, 1 + g, 0}, {0, -1, 0}), plane({0, 0, 1 + 2 * d}, {0, 0, -1})};
  // The lid: its layer's edge from d above the body down to `height` by
  // t = 0.3, held to 0.4, back up by 0.5; the second half is the recovery.
  // It moves geometrically (the same compression ratio every step: 9% of the
  // remaining height per step to 0.1 in 24 steps, 12% to 0.05) rather than
  // at constant speed, which would close the last 60% of the remaining
  // height in one step.
  const double start = 1 + d;
  s.options.obstacles.back().motion = [start, height](double t) {
    const double w = t < 0.3 ? t / 0.3 : t < 0.4 ? 1.0 : t < 0.5 ? (0.5 - t) / 0.1 : 0.0;
    const double lid = start * std::pow(height / start, w);
    return RigidTransform::translation_by({0.0, 0.0, lid - start});
  };
  // Rough platens (friction > 0): the floor and the lid grip the body
  // (Coulomb friction, Obstacle::friction); the walls stay frictionless.
  if (friction > 0.0) {
    s.options.obstacles.front().friction = friction;
    s.options.obstacles.back().friction = friction;
  }
  s.options.contact.stiffness = kSquashStiffness;
  s.options.contact.thickness = d;
  set_tolerance(s, precision, h);
  std::ostringstream text;
  text << "cube in a box of planes, lid closed to " << height << " of its height and opened, nu = " << nu
       << (friction > 0.0 ? ", floor and lid friction " : ", frictionless");
  if (friction > 0.0) text << friction;
  s.description = text.str();
  return s;
}

Scene make_case(const std::string& name, Precision precision, int resolution, double squash_height) {
  auto res_or = [&](int fallback) { return resolution > 0 ? resolution : fallback; };
  SceneParameters p;
  p.strain_tolerance = strain_tolerance(precision);
  if (name.rfind("nu", 0) == 0) {
    p.poisson_ratio = std::stod(name.substr(2));
    p.resolution = res_or(4);
    Scene s = make_scene("twist", p);
    s.description = "twist 2 x pi/2, nu = " + name.substr(2);
    return s;
  }
  if (name.rfind("scramble_seed", 0) == 0) {
    p.seed = static_cast<unsigned>(std::stoul(name.substr(13)));
    p.resolution = res_or(4);
    Scene s = make_scene("scramble", p);
    s.description = "scramble, seed " + name.substr(13);
    return s;
  }
  // squash_h<H>_nu<nu>: the frictionless squash with the lid closed to H
  // whatever --squash-height says: the heights where the body folds through
  // itself without self-contact, here with it on; each step's exact
  // self-intersection count in the record.
  if (name.rfind("squash_h", 0) == 0 && name.find("_nu") != std::string::npos) {
    const size_t nu_at = name.find("_nu");
    double height = 0.0, nu = 0.0;
    try {
      height = std::stod(name.substr(8, nu_at - 8));
      nu = std::stod(name.substr(nu_at + 3));
    } catch (const std::exception&) {
      throw Error("stability: case '" + name + "' is not squash_h<height>_nu<poisson ratio>");
    }
    Scene s = squash(nu, res_or(4), precision, 0.0, height);
    s.options.contact.self = true;  // barrier self-contact (ContactOptions::self_method)
    s.description += ", self-contact";
    return s;
  }
  if (name.rfind("squash_nu", 0) == 0)
    return squash(std::stod(name.substr(9)), res_or(4), precision, 0.0, squash_height);
  if (name.rfind("squash_rough_nu", 0) == 0)
    return squash(std::stod(name.substr(15)), res_or(4), precision, kSquashFriction, squash_height);
  if (name == "crush_plane") return crush("plane", res_or(4), precision);
  if (name == "crush_line") return crush("line", res_or(4), precision);
  if (name == "crush_point") return crush("point", res_or(4), precision);
  if (name == "twist_2pi") {
    p.resolution = res_or(4);
    p.steps = 4;
    Scene s = make_scene("twist", p);
    s.description = "twist by pi/2 steps to 2 pi";
    return s;
  }
  if (name == "stretch_3.4x" || name == "stretch_5x") {
    p.resolution = res_or(4);
    const bool five = name == "stretch_5x";
    if (five) p.steps = 12;
    Scene s = make_scene("stretch", p);
    if (five) {
      double top = 0.0;
      for (size_t v = 0; v < s.mesh.vertex_count(); ++v) top = std::max(top, s.mesh.positions(v, 2));
      for (ConstraintSet& c : s.constraints)
        if (c.name == "top_cap")
          c.motion = [top](double t) { return RigidTransform::translation_by({0.0, 0.0, t * 4.0 * top}); };
    }
    s.description = std::string("cylinder stretched to ") + (five ? "5x" : "3.4x") + " in " +
                    std::to_string(s.options.load_steps) + " steps";
    return s;
  }
  if (name == "inverted_start") {
    // One layer of interior vertices pushed through the next: the elements
    // between are inverted when the solve starts; the top is compressed 20%.
    const int res = res_or(4);
    const double h = 1.0 / res;
    Scene s = pinned_cube(res, precision);
    ConstraintSet top{"top_face", on_plane(s.mesh, 2, 1.0, h), {}, {}};
    top.motion = [](double t) { return RigidTransform::translation_by({0.0, 0.0, -0.2 * t}); };
    s.constraints.push_back(top);
    s.options.load_steps = 2;
    s.options.initial_positions = s.mesh.positions;
    for (size_t v = 0; v < s.mesh.vertex_count(); ++v) {
      const auto x = s.mesh.vertex(v);
      const bool interior_xy = x[0] > 0.5 * h && x[0] < 1.0 - 0.5 * h && x[1] > 0.5 * h && x[1] < 1.0 - 0.5 * h;
      if (interior_xy && std::abs(x[2] - h) < 0.5 * h) s.options.initial_positions(v, 2) = 2.6 * h;
    }
    s.description = "interior layer pushed through its neighbours (inverted at start), top compressed 20%";
    return s;
  }
  if (name == "flip_top") {
    // The top face turned upside down (pi about x) in one load step: its
    // layer starts inverted.
    const int res = res_or(4);
    const double h = 1.0 / res;
    Scene s = pinned_cube(res, precision);
    ConstraintSet top{"top_face", on_plane(s.mesh, 2, 1.0, h), {}, {}};
    top.motion = [](double t) { return RigidTransform::rotation_about({1.0, 0.0, 0.0}, t * kPi, {0.5, 0.5, 1.0}); };
    s.constraints.push_back(top);
    s.description = "top face flipped by pi about x in one load step";
    return s;
  }
  if (name == "push_through") {
    // The top face pushed down through the pinned bottom to z = -0.5 in two
    // load steps: the body must invert.
    const int res = res_or(4);
    const double h = 1.0 / res;
    Scene s = pinned_cube(res, precision);
    ConstraintSet top{"top_face", on_plane(s.mesh, 2, 1.0, h), {}, {}};
    top.motion = [](double t) { return RigidTransform::translation_by({0.0, 0.0, -1.5 * t}); };
    s.constraints.push_back(top);
    s.options.load_steps = 2;
    s.description = "top face pushed through the pinned bottom to z = -0.5 in 2 steps";
    return s;
  }
  std::string known;
  for (const std::string& n : stability_case_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("stability: unknown case '" + name + "' (known: " + known + ")");
}

// The first step's starting positions: the initial positions with the
// constraints at t = 1 / steps.
Points first_step_start(const Scene& s) {
  std::vector<double> x = (s.options.initial_positions.empty() ? s.mesh.positions : s.options.initial_positions).xyz();
  apply_constraints(s.mesh, s.constraints, 1.0 / s.options.load_steps, x);
  return Points::from_xyz(std::move(x));
}

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return std::isnan(v) ? "NaN" : (v > 0 ? "inf" : "-inf");
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

json run_json(const StabilityRun& r, const std::string& note) {
  json j;
  j["case"] = r.name;
  j["precision"] = r.precision;
  j["description"] = r.description;
  j["elements"] = r.elements;
  j["converged"] = r.converged;
  j["status"] = r.status;
  j["newton_iterations"] = r.newton_iterations;
  j["cg_iterations"] = r.cg_iterations;
  j["seconds"] = r.seconds;
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(fixed(v, 0)); };
  j["min_j"] = num(r.min_j);
  j["max_j"] = num(r.max_j);
  j["volume_ratio"] = num(r.volume_ratio);
  j["min_volume_ratio"] = num(r.min_volume_ratio);
  if (r.contact_thickness > 0.0) {
    j["max_penetration"] = num(r.max_penetration);
    j["contact_thickness"] = r.contact_thickness;
  }
  j["inverted_elements_at_start"] = r.initially_inverted_elements;
  j["inverted_elements"] = r.inverted_elements;
  j["surface_intersections"] = r.surface_intersections;
  j["max_surface_intersections"] = r.max_surface_intersections();
  j["degenerate_surface_triangles"] = r.degenerate_surface_triangles;
  j["non_finite_positions"] = r.non_finite_positions;
  j["nan_in_history"] = r.nan_in_history;
  j["recoveries"] = r.recoveries;
  j["precision_per_step"] = r.precisions_used;
  j["unconverged_steps"] = r.unconverged_steps;
  j["warnings"] = r.warnings;
  j["error"] = r.error;
  j["note"] = note;
  return j;
}

}  // namespace

StabilityReport stability_report(const std::vector<std::pair<StabilityRun, std::string>>& rows, int resolution,
                                 double squash_height) {
  StabilityReport report;
  json& all = report.document;
  all["suite"] = "stability";
  all["resolution"] = resolution;
  all["squash_height"] = squash_height;
  all["runs"] = json::array();
  report.csv.columns = {"case",
                        "precision",
                        "converged",
                        "status",
                        "newton",
                        "cg",
                        "seconds",
                        "min_j",
                        "max_j",
                        "inverted_at_start",
                        "inverted",
                        "volume_ratio",
                        "min_volume_ratio",
                        "max_penetration",
                        "contact_thickness",
                        "non_finite_positions",
                        "nan_in_history",
                        "recovery",
                        "max_surface_intersections",
                        "note"};
  report.markdown.columns = {"case",
                             "precision",
                             "converged",
                             "status",
                             "Newton",
                             "CG",
                             "s",
                             "min J",
                             "max J",
                             "inverted (start → end)",
                             "volume",
                             "min volume",
                             "penetration / thickness",
                             "NaN",
                             "recovery",
                             "self-intersections (most in a step)",
                             "note"};
  for (const auto& [r, note] : rows) {
    const int nan = r.non_finite_positions + r.nan_in_history;
    if (nan > 0 || !r.error.empty()) ++report.problems;
    all["runs"].push_back(run_json(r, note));
    const std::string rec = recovery_summary(r.recoveries);
    std::string csv_rec = rec;
    std::replace(csv_rec.begin(), csv_rec.end(), ',', ';');
    const bool contact = r.contact_thickness > 0.0;
    report.csv.add_row({r.name,
                        r.precision,
                        r.converged ? "yes" : "no",
                        r.status,
                        std::to_string(r.newton_iterations),
                        std::to_string(r.cg_iterations),
                        fixed(r.seconds, 3),
                        fixed(r.min_j, 6),
                        fixed(r.max_j, 6),
                        std::to_string(r.initially_inverted_elements),
                        std::to_string(r.inverted_elements),
                        fixed(r.volume_ratio, 6),
                        fixed(r.min_volume_ratio, 6),
                        contact ? fixed(r.max_penetration, 6) : "",
                        contact ? fixed(r.contact_thickness, 6) : "",
                        std::to_string(r.non_finite_positions),
                        std::to_string(r.nan_in_history),
                        csv_rec,
                        std::to_string(r.max_surface_intersections()),
                        note});
    const int64_t most = r.max_surface_intersections();
    report.markdown.add_row(
        {r.name, r.precision, r.converged ? "yes" : "**no**", r.error.empty() ? r.status : "error: " + r.error,
         std::to_string(r.newton_iterations), std::to_string(r.cg_iterations), fixed(r.seconds, 2), fixed(r.min_j, 3),
         fixed(r.max_j, 3), std::to_string(r.initially_inverted_elements) + " → " + std::to_string(r.inverted_elements),
         fixed(r.volume_ratio, 4), fixed(r.min_volume_ratio, 4),
         contact ? fixed(r.max_penetration, 5) + " / " + fixed(r.contact_thickness, 5) +
                       (r.max_penetration > r.contact_thickness ? " **deeper**" : "")
                 : "-",
         nan > 0 ? "**YES**" : "none", rec, most != 0 ? "**" + std::to_string(most) + "**" : "0", note});
  }
  all["runs_with_nan_or_error"] = report.problems;
  return report;
}

namespace {

struct StabilityOptions {
  int resolution = 0;
  std::string precision = "both";
  std::string out_dir = "bench-results";
  std::string device;
  std::string cases;
  double squash_height = kDefaultSquashHeight;
};

int run_stability(const StabilityOptions& o) {
  std::vector<std::string> names;
  if (o.cases.empty()) {
    names = stability_case_names();
  } else {
    std::stringstream in(o.cases);
    for (std::string item; std::getline(in, item, ',');) {
      if (item.empty()) continue;
      bool any = false;
      for (const std::string& n : stability_case_names())
        if (n == item || n.rfind(item + "_", 0) == 0 || (item == "nu" && n.rfind("nu", 0) == 0)) {
          names.push_back(n);
          any = true;
        }
      if (!any) make_case(item, Precision::double_, 0, o.squash_height);  // throws naming the known cases
    }
  }
  std::vector<Precision> precisions;
  if (o.precision != "double") precisions.push_back(Precision::single);
  if (o.precision != "float") precisions.push_back(Precision::double_);

  std::vector<std::pair<StabilityRun, std::string>> rows;
  for (const std::string& name : names) {
    std::map<std::string, StabilityRun> by_precision;
    for (Precision p : precisions) {
      StabilityRun r = run_stability_case(name, p, o.resolution, false, o.device, o.squash_height);
      std::cerr << "  " << std::left << std::setw(22) << name << std::setw(8) << r.precision << r.status << ", "
                << r.newton_iterations << " Newton, " << r.cg_iterations << " CG, " << fixed(r.seconds, 2) << " s\n";
      by_precision[r.precision] = r;
      rows.push_back({r, ""});
    }
    auto f = by_precision.find("float"), d = by_precision.find("double");
    if (f != by_precision.end() && d != by_precision.end() && !f->second.converged && d->second.converged) {
      for (auto& row : rows)
        if (row.first.name == name && row.first.precision == "float") row.second = "float fails, double converges";
      StabilityRun fb = run_stability_case(name, Precision::single, o.resolution, true, o.device, o.squash_height);
      std::cerr << "  " << std::left << std::setw(16) << name << std::setw(8) << "float+fallback " << fb.status << '\n';
      rows.push_back({fb, "float with fallback_to_double"});
    }
  }

  std::filesystem::create_directories(o.out_dir);
  const StabilityReport report = stability_report(rows, o.resolution, o.squash_height);
  const std::string md = markdown_text(report.markdown);
  write_text(o.out_dir + "/stability.csv", csv_text(report.csv));
  write_json(o.out_dir + "/stability.json", report.document);
  write_text(o.out_dir + "/stability.md", md);
  const int problems = report.problems;
  std::cout << md;
  std::cerr << "wrote " << o.out_dir << "/stability.{json,csv,md}" << (problems ? "; NaN or errors found!" : "")
            << '\n';
  return problems > 0 ? 3 : 0;
}

}  // namespace

std::vector<std::string> stability_case_names() {
  return {"nu0.45",
          "nu0.49",
          "nu0.499",
          "nu0.4999",
          "scramble_seed1",
          "scramble_seed2",
          "scramble_seed3",
          "scramble_seed4",
          "crush_plane",
          "crush_line",
          "crush_point",
          "twist_2pi",
          "stretch_3.4x",
          "stretch_5x",
          "inverted_start",
          "flip_top",
          "push_through",
          "squash_nu0.46",
          "squash_nu0.49",
          "squash_nu0.499",
          "squash_rough_nu0.46",
          "squash_rough_nu0.49",
          "squash_rough_nu0.499",
          "squash_h0.05_nu0.46",
          "squash_h0.05_nu0.49",
          "squash_h0.05_nu0.499",
          "squash_h0.03_nu0.46",
          "squash_h0.03_nu0.49",
          "squash_h0.03_nu0.499"};
}

Scene make_stability_case(const std::string& name, Precision precision, int resolution, double squash_height) {
  Scene s = make_case(name, precision, resolution, squash_height);
  s.name = name;
  s.options.precision = precision;
  return s;
}

std::string recovery_summary(const std::map<std::string, int>& recoveries) {
  if (recoveries.empty()) return "-";
  std::string out;
  for (const auto& [what, count] : recoveries) out += (out.empty() ? "" : "; ") + what + " x" + std::to_string(count);
  return out;
}

StabilityRun run_stability_case(const std::string& name, Precision precision, int resolution, bool fallback_to_double,
                                const std::string& device, double squash_height) {
  const Scene scene = make_stability_case(name, precision, resolution, squash_height);
  StabilityRun r;
  r.name = name;
  r.precision = std::string(to_string(precision)) + (fallback_to_double ? "+fallback" : "");
  r.description = scene.description;
  r.elements = scene.mesh.element_count();
  r.initially_inverted_elements = deformation_statistics(scene.mesh, first_step_start(scene)).inverted_elements;
  // The boundary surface: its exact self-intersection count at each step's end.
  const MeshBoundary boundary = boundary_surface(scene.mesh);
  Points surface(boundary.vertices.size());
  SolveOptions options = scene.options;
  options.device.match = device;
  options.fallback_to_double = fallback_to_double;
  try {
    QuasistaticSolver solver(scene.mesh, scene.material, scene.constraints, options);
    r.min_volume_ratio = std::numeric_limits<double>::infinity();
    const SolveResult s = solver.solve({}, [&](int, const Points& x) {
      for (double v : x.xyz())
        if (!std::isfinite(v)) {
          r.surface_intersections.push_back(-1);
          return;
        }
      for (size_t i = 0; i < boundary.vertices.size(); ++i)
        for (int d = 0; d < 3; ++d) surface(i, d) = x(size_t(boundary.vertices[i]), d);
      const SelfIntersections count = count_self_intersections(surface, boundary.surface.triangles);
      r.surface_intersections.push_back(int64_t(count.intersecting_pairs));
      r.degenerate_surface_triangles = std::max(r.degenerate_surface_triangles, count.degenerate_triangles);
      r.min_volume_ratio = std::min(r.min_volume_ratio, deformation_statistics(scene.mesh, x).volume_ratio);
    });
    r.converged = s.converged;
    r.status = "converged";
    for (const StepResult& step : s.steps) {
      r.newton_iterations += step.newton_iterations;
      r.cg_iterations += step.cg_iterations;
      r.precisions_used.push_back(to_string(step.precision_used));
      if (!step.converged && r.status == "converged") r.status = to_string(step.status);
      if (!step.converged) {
        std::ostringstream why;
        why << "step " << step.step << ": " << step.status << " after " << step.newton_iterations
            << " Newton, residual " << step.residual_norm << " of tolerance " << s.tolerance;
        r.unconverged_steps.push_back(why.str());
      }
      r.max_penetration = std::max(r.max_penetration, step.max_penetration);
    }
    if (!scene.options.obstacles.empty()) r.contact_thickness = scene.options.contact.thickness;
    for (const NewtonIteration& h : s.history) {
      if (!h.recovery.empty()) ++r.recoveries[to_string(h.recovery)];
      if (std::isnan(h.residual_norm) || std::isnan(h.energy)) ++r.nan_in_history;
    }
    for (double v : s.positions.xyz()) r.non_finite_positions += std::isfinite(v) ? 0 : 1;
    r.seconds = s.seconds;
    r.min_j = s.min_j;
    r.max_j = s.max_j;
    r.volume_ratio = s.volume_ratio;
    r.inverted_elements = s.inverted_elements;
    r.warnings = s.warnings;
    if (r.degenerate_surface_triangles > 0)
      r.warnings.push_back("degenerate_surface_triangles: up to " + std::to_string(r.degenerate_surface_triangles) +
                           " boundary triangles of zero area at a step's end (left out of the intersection count)");
  } catch (const Error& e) {
    r.status = "error";
    r.error = e.what();
  }
  return r;
}

void add_stability_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<StabilityOptions>();
  CLI::App* cmd = app.add_subcommand(
      "stability",
      "Stiff and extreme cases in float and double: nu to 0.4999, scramble, crush to a plane/line/point, twist to "
      "2 pi, stretch to 3.4x and 5x, elements inverted mid-solve, squash to a tenth of the volume in a box of "
      "planes and release, frictionless and with a rough floor and lid (nu 0.46, 0.49, 0.499)");
  cmd->add_option("--res", o->resolution, "cells across each case (0: the cases' small defaults)")
      ->capture_default_str();
  cmd->add_option("--precision", o->precision, "float, double or both")
      ->check(CLI::IsMember({"float", "double", "both"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out_dir, "folder for stability.{json,csv,md}")->capture_default_str();
  cmd->add_option("--device", o->device, "substring of '<platform> / <device>'");
  cmd->add_option("--squash-height", o->squash_height,
                  "the squash cases' lid height, a fraction of the body's (0.05: docs/validation.md)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--cases", o->cases,
                  "comma list of cases or groups (nu, scramble, crush, twist, stretch, ...); default: all");
  cmd->callback([o, &exit_code] { exit_code = run_stability(*o); });
}

}  // namespace snh::bench
