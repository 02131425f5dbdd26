#include "snh/scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "snh/error.h"
#include "snh/mesh_io.h"

namespace snh {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Vertices whose coordinate `axis` is within `tolerance` of `value`.
std::vector<int32_t> vertices_on_plane(const Mesh& mesh, int axis, double value, double tolerance) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions(v, axis) - value) <= tolerance) out.push_back(static_cast<int32_t>(v));
  return out;
}

int resolution_or(const SceneParameters& p, int fallback) {
  const int r = p.resolution.value_or(fallback);
  if (r > 400) throw Error("scene: resolution " + std::to_string(r) + " is too large");
  return r;
}

Scene stretch(const SceneParameters& p) {
  Scene s;
  const int res = resolution_or(p, 8);
  const double radius = 0.5, length = 2.0, h = 2.0 * radius / res;
  s.mesh = make_voxel_cylinder(radius, length, h);
  double top = 0.0;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v) top = std::max(top, s.mesh.positions(v, 2));
  ConstraintSet bottom{"bottom_cap", vertices_on_plane(s.mesh, 2, 0.0, 1e-9 * h), {}, {}};
  ConstraintSet cap{"top_cap", vertices_on_plane(s.mesh, 2, top, 1e-9 * h), {}, {}};
  cap.motion = [top](double t) { return RigidTransform::translation_by({0.0, 0.0, t * 2.4 * top}); };
  s.constraints = {bottom, cap};
  s.options.load_steps = p.steps.value_or(8);
  s.description = "hex cylinder stretched to 3.4x its length";
  return s;
}

Scene twist(const SceneParameters& p) {
  Scene s;
  const int res = resolution_or(p, 15);
  const double h = 1.0 / res;
  s.mesh = make_box_lattice(res, res, res, h);
  ConstraintSet bottom{"bottom_face", vertices_on_plane(s.mesh, 2, 0.0, 1e-9 * h), {}, {}};
  ConstraintSet top{"top_face", vertices_on_plane(s.mesh, 2, 1.0, 1e-9 * h), {}, {}};
  const int steps = p.steps.value_or(2);
  // pi/2 per load step: t in (0, 1] maps to a total of steps * pi/2.
  top.motion = [steps](double t) {
    return RigidTransform::rotation_about({0.0, 0.0, 1.0}, t * steps * 0.5 * kPi, {0.5, 0.5, 1.0});
  };
  s.constraints = {bottom, top};
  s.options.load_steps = steps;
  s.description = "unit cube, top face twisted by pi/2 per step";
  return s;
}

Scene scramble(const SceneParameters& p) {
  Scene s;
  const int res = resolution_or(p, 10);
  const double h = 1.0 / res;
  s.mesh = make_box_lattice(res, res, res, h);
  std::vector<int32_t> corners;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v) {
    const auto x = s.mesh.vertex(v);
    const bool corner =
        (x[0] < 0.5 * h || x[0] > 1.0 - 0.5 * h) && (x[1] < 0.5 * h || x[1] > 1.0 - 0.5 * h) && x[2] < 0.5 * h;
    if (corner) corners.push_back(static_cast<int32_t>(v));
  }
  s.constraints = {ConstraintSet{"bottom_corners", corners, {}, {}}};
  // Random positions inside a box of twice the cube's volume, centred on it.
  std::mt19937_64 rng(p.seed);
  const double side = std::cbrt(2.0);
  std::uniform_real_distribution<double> u(0.5 - 0.5 * side, 0.5 + 0.5 * side);
  s.options.initial_positions = Points(s.mesh.vertex_count());
  double* x = s.options.initial_positions.data();
  for (size_t i = 0; i < 3 * s.mesh.vertex_count(); ++i) x[i] = u(rng);
  s.options.load_steps = p.steps.value_or(1);
  s.options.max_newton_iterations = 2000;
  s.description = "cube scrambled in a box of twice its volume, four corners pinned";
  return s;
}

Scene flex(const SceneParameters& p) {
  Scene s;
  const int res = resolution_or(p, 4);
  const double w = 1.0, h = w / res;
  s.mesh = make_box_lattice(4 * res, res, res, h);
  const double length = 4.0 * w;
  // Bones: the lattice's core (within a quarter thickness of the axis), one
  // in each half, stopping short of the joint at the middle.
  ConstraintSet upper{"upper_bone", {}, {}, {}}, lower{"lower_bone", {}, {}, {}};
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v) {
    const auto x = s.mesh.vertex(v);
    const bool core = std::abs(x[1] - 0.5 * w) <= 0.25 * w + 1e-9 && std::abs(x[2] - 0.5 * w) <= 0.25 * w + 1e-9;
    if (!core) continue;
    if (x[0] >= 0.1 * length - 1e-9 && x[0] <= 0.4 * length + 1e-9) upper.vertices.push_back(static_cast<int32_t>(v));
    if (x[0] >= 0.6 * length - 1e-9 && x[0] <= 0.9 * length + 1e-9) lower.vertices.push_back(static_cast<int32_t>(v));
  }
  const std::array<double, 3> joint{0.5 * length, 0.5 * w, 0.5 * w};
  lower.motion = [joint](double t) { return RigidTransform::rotation_about({0.0, 1.0, 0.0}, t * 0.5 * kPi, joint); };
  s.constraints = {upper, lower};
  s.options.load_steps = p.steps.value_or(6);
  s.description = "limb-like lattice bent 90 degrees by two rigid bones";
  return s;
}

// A longer limb than flex, flexed 140 degrees so that the inner (z-) sides
// of the two halves meet. The bones lie in the upper half of the core
// (0.5 <= z <= 0.75 thicknesses, |y - 0.5| <= 0.25), leaving half a
// thickness of flesh below them (a biceps); the joint axis (along y) runs
// through the bones' centre line, and the bones stop 0.75 thicknesses short
// of it on either side. At 140 degrees (20 degrees from the joint to each
// arm) the rigid bones stay 2 (0.75 sin 20 - 0.125) = 0.26 thicknesses
// apart, while the inner surfaces, 0.625 below the axis, overlap from
// 0.625 / sin 20 = 1.83 thicknesses out: without self-contact that flesh
// passes through itself. 28 steps of 5 degrees: the bones' tips move about
// one cell per step (larger steps start Newton from states where the
// flesh next to the moved bones is tangled).
Scene elbow(const SceneParameters& p) {
  Scene s;
  const int res = resolution_or(p, 4);
  const double w = 1.0, h = w / res, length = 6.0 * w;
  s.mesh = make_box_lattice(6 * res, res, res, h);
  ConstraintSet upper{"upper_bone", {}, {}, {}}, lower{"lower_bone", {}, {}, {}};
  const double tol = 1e-9;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v) {
    const auto x = s.mesh.vertex(v);
    const bool core = std::abs(x[1] - 0.5 * w) <= 0.25 * w + tol && x[2] >= 0.5 * w - tol && x[2] <= 0.75 * w + tol;
    if (!core) continue;
    if (x[0] >= 0.25 * w - tol && x[0] <= 0.5 * length - 0.75 * w + tol)
      upper.vertices.push_back(static_cast<int32_t>(v));
    if (x[0] >= 0.5 * length + 0.75 * w - tol && x[0] <= length - 0.25 * w + tol)
      lower.vertices.push_back(static_cast<int32_t>(v));
  }
  const std::array<double, 3> joint{0.5 * length, 0.5 * w, 0.625 * w};
  const double angle = 140.0 / 180.0 * kPi;
  lower.motion = [joint, angle](double t) { return RigidTransform::rotation_about({0.0, 1.0, 0.0}, t * angle, joint); };
  s.constraints = {upper, lower};
  s.options.load_steps = p.steps.value_or(28);
  // Springs of 80 E h per sample (force per length): the contact pressure
  // at 140 degrees keeps samples within the thickness 0.1 h (hex8: 0.0133
  // deepest for 0.025). The tet4 split of the same lattice locks at
  // nu = 0.49 and presses harder: with 80 E h its deepest sample reached
  // 0.0267, with 120 E h 0.0185, with 160 E h 0.0128 (docs/performance.md), so tet4
  // gets 160 E h.
  s.options.contact.self = true;
  s.options.contact.self_method = SelfContactMethod::penalty;
  s.options.contact.stiffness = (p.element_type == ElementType::tet4 ? 160.0 : 80.0) * p.youngs_modulus * h;
  s.options.contact.thickness = 0.1 * h;
  s.description = "6:1:1 limb flexed 140 degrees by two rigid bones, inner side folding onto itself (self-contact)";
  return s;
}

// "drop" (docs/design.md), SI units. The keyframes of the
// squashing cylinder, on the load parameter t in [0, 1] over the scene's 2 s:
// waiting above while the body falls and settles (to t = 0.2), down to a gap
// of 6 mm above the middle lower cylinder (t = 0.45), held
// (to 0.55), back up (0.7), then away while the body recovers (to 1).
struct DropKey {
  double t, dz;
};
constexpr double kDropDuration = 2.0;  // s
// Three overlapping cylinders side by side (no gap for the body to be
// pressed through), their tops 3.5 cm below the body, between two walls
// tangent to the outer ones: contact is frictionless, and a body squeezed
// between round surfaces squirts out sideways (without the walls it did in
// trials, over an outer cylinder, before it was flat); along the cylinders'
// axes it is free. The upper cylinder is broad (radius 0.4 m) so that it
// presses the body against all three: at the squash 6 mm above the middle
// one (3 contact thicknesses) and 9.8 mm above the outer ones.
constexpr double kDropLowerZ = -0.105, kDropLowerRadius = 0.03;
constexpr double kDropOuterY = 0.055;  // the outer cylinders' axes at y = -0.055, 0.055
constexpr double kDropWallY = kDropOuterY + kDropLowerRadius;
constexpr double kDropUpperZ = 0.48, kDropUpperRadius = 0.4;
constexpr double kDropThickness = 0.002;                 // contact layer, m
constexpr double kDropStiffness = 1.0e5;                 // contact, N/m per vertex
constexpr double kDropSquashGap = 3.0 * kDropThickness;  // between the upper and the middle lower cylinder

std::vector<DropKey> drop_keys() {
  const double down = (kDropLowerZ + kDropLowerRadius + kDropSquashGap + kDropUpperRadius) - kDropUpperZ;
  return {{0.0, 0.0}, {0.2, 0.0}, {0.45, down}, {0.55, down}, {0.7, 0.0}};
}

// The file that holds the drop's body: data/meshes/blob.msh (resolution
// unset or 2) or blob_coarse.msh (1), under scene_data_dir().
std::string drop_mesh_path(std::optional<int> given) {
  const int resolution = given.value_or(2);
  if (resolution < 1 || resolution > 2)
    throw Error("scene drop: resolution " + std::to_string(resolution) +
                " (expected 1 for the coarse blob, 2 or unset for the default one)");
  const std::filesystem::path file =
      std::filesystem::path(scene_data_dir()) / "meshes" / (resolution == 1 ? "blob_coarse.msh" : "blob.msh");
  if (!std::filesystem::exists(file))
    throw Error("scene drop: " + file.string() + " not found (set SNH_DATA_DIR to the data/ folder of snh)");
  return file.string();
}

Scene drop(const SceneParameters& p) {
  Scene s;
  s.mesh = read_mesh(drop_mesh_path(p.resolution));
  s.material = StableNeoHookean::from_youngs_modulus(p.youngs_modulus, p.poisson_ratio, p.barrier);
  const int frames = p.steps.value_or(60);
  DynamicsOptions d;
  d.time_step = kDropDuration / frames;
  d.density = 1000.0;
  // b: a damping ratio b w / 2 of about 0.13 at the body's lowest modes
  // (about 20 Hz: shear wave speed sqrt(mu / rho) = 4.1 m/s over twice its 10 cm).
  d.damping.stiffness = 0.002;
  d.substeps = 4;
  s.options.dynamics = d;
  s.options.load_steps = frames;
  s.options.body_force = {0.0, 0.0, -9.81 * d.density};
  for (int k = -1; k <= 1; ++k) {
    Obstacle lower;
    lower.type = ObstacleType::cylinder;
    lower.point = {0.0, k * kDropOuterY, kDropLowerZ};
    lower.direction = {1.0, 0.0, 0.0};
    lower.radius = kDropLowerRadius;
    s.options.obstacles.push_back(lower);
  }
  for (int side : {-1, 1}) {
    Obstacle wall;
    wall.type = ObstacleType::plane;
    wall.point = {0.0, side * kDropWallY, 0.0};
    wall.direction = {0.0, -1.0 * side, 0.0};
    s.options.obstacles.push_back(wall);
  }
  Obstacle upper;
  upper.type = ObstacleType::cylinder;
  upper.point = {0.0, 0.0, kDropUpperZ};
  upper.direction = {1.0, 0.0, 0.0};
  upper.radius = kDropUpperRadius;
  upper.motion = [keys = drop_keys()](double t) {
    size_t i = 0;
    while (i + 1 < keys.size() && keys[i + 1].t < t) ++i;
    double dz = keys[i].dz;
    if (i + 1 < keys.size()) {
      const double w = std::clamp((t - keys[i].t) / (keys[i + 1].t - keys[i].t), 0.0, 1.0);
      dz = (1 - w) * keys[i].dz + w * keys[i + 1].dz;
    }
    return RigidTransform::translation_by({0.0, 0.0, dz});
  };
  s.options.obstacles.push_back(upper);
  s.options.contact.stiffness = kDropStiffness;
  s.options.contact.thickness = kDropThickness;
  // Squashed, with elements inverted, Newton on the projected Hessian
  // converges linearly (about 5% a step): 200 iterations a substep were
  // measured not to be enough there.
  s.options.max_newton_iterations = 1000;
  // The library's stopping rule (SolveOptions::strain_tolerance: h the
  // blob's mean vertex spacing), as its scene file has it.
  s.options.relative_tolerance = 0.0;
  s.options.strain_tolerance = p.strain_tolerance;
  s.description = "soft tet blob (nu = " + std::to_string(p.poisson_ratio).substr(0, 4) +
                  ") dropped on three cylinders, squashed by a fourth, released";
  return s;
}

// Edge length of the first element (the scenes' lattices are uniform).
// Edge length of the first hex (the scenes' lattices are uniform).
double scene_cell_size(const Mesh& mesh) {
  const auto a = mesh.vertex(mesh.elements[0]), b = mesh.vertex(mesh.elements[1]);
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

std::vector<std::string> scene_names() { return {"stretch", "twist", "scramble", "flex", "drop", "elbow"}; }

std::vector<std::string> lattice_scene_names() { return {"stretch", "twist", "scramble", "flex"}; }

std::string scene_data_dir() {
  if (const char* env = std::getenv("SNH_DATA_DIR"); env && *env) return env;
  return SNH_DEFAULT_DATA_DIR;
}

SceneParameters scene_defaults(const std::string& name) {
  SceneParameters p;
  if (name == "drop") {
    p.youngs_modulus = 5.0e4;  // Pa: a soft gel
    p.poisson_ratio = 0.46;    // the paper's octopus (Fig. 11)
  }
  return p;
}

Scene make_scene(const std::string& name, const SceneParameters& p) {
  Scene s;
  if (name == "drop") {
    s = drop(p);
    s.name = name;
    return s;
  }
  if (name == "stretch")
    s = stretch(p);
  else if (name == "twist")
    s = twist(p);
  else if (name == "scramble")
    s = scramble(p);
  else if (name == "flex")
    s = flex(p);
  else if (name == "elbow")
    s = elbow(p);
  else
    throw Error("scene: unknown scene '" + name + "' (known: stretch, twist, scramble, flex, drop, elbow)");
  s.name = name;
  const double h = scene_cell_size(s.mesh);
  // Vertices (and so the constraint sets) are the lattice's either way.
  if (p.element_type == ElementType::tet4) s.mesh = split_hexes_into_tets(s.mesh);
  s.material = StableNeoHookean::from_youngs_modulus(p.youngs_modulus, p.poisson_ratio, p.barrier);
  // Newton to a residual equivalent to a strain error of strain_tolerance:
  // a vertex force is about E h^2 times a strain, summed over the vertices.
  // (The paper's absolute 1e-2 assumes its own units; a tolerance relative to
  // the first residual would stop the scramble far from equilibrium.)
  s.options.relative_tolerance = 0.0;
  // Coarse tets under a sudden pi/2 twist need some 60 iterations: within
  // defaults::max_newton_iterations.
  s.options.absolute_tolerance =
      p.strain_tolerance * p.youngs_modulus * h * h * std::sqrt(static_cast<double>(s.mesh.vertex_count()));
  for (const ConstraintSet& c : s.constraints)
    if (c.vertices.empty()) throw Error("scene " + name + ": constraint set '" + c.name + "' selects no vertex");
  return s;
}

}  // namespace snh
