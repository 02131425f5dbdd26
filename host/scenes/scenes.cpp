#include "snh/scenes.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "snh/error.h"

namespace snh {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Vertices whose coordinate `axis` is within `tolerance` of `value`.
std::vector<int32_t> vertices_on_plane(const Mesh& mesh, int axis, double value, double tolerance) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (std::abs(mesh.positions[3 * v + axis] - value) <= tolerance) out.push_back(static_cast<int32_t>(v));
  return out;
}

int resolution_or(const SceneParameters& p, int fallback) {
  const int r = p.resolution > 0 ? p.resolution : fallback;
  if (r > 400) throw Error("scene: resolution " + std::to_string(r) + " is too large");
  return r;
}

Scene stretch(const SceneParameters& p) {
  Scene s;
  const int res = resolution_or(p, 8);
  const double radius = 0.5, length = 2.0, h = 2.0 * radius / res;
  s.mesh = make_voxel_cylinder(radius, length, h);
  double top = 0.0;
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v) top = std::max(top, s.mesh.positions[3 * v + 2]);
  ConstraintSet bottom{"bottom_cap", vertices_on_plane(s.mesh, 2, 0.0, 1e-9 * h), {}, {}};
  ConstraintSet cap{"top_cap", vertices_on_plane(s.mesh, 2, top, 1e-9 * h), {}, {}};
  cap.motion = [top](double t) { return RigidTransform::translation_by({0.0, 0.0, t * 2.4 * top}); };
  s.constraints = {bottom, cap};
  s.options.load_steps = p.steps > 0 ? p.steps : 8;
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
  const int steps = p.steps > 0 ? p.steps : 2;
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
  s.options.initial_positions.resize(s.mesh.positions.size());
  for (double& c : s.options.initial_positions) c = u(rng);
  s.options.load_steps = p.steps > 0 ? p.steps : 1;
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
  s.options.load_steps = p.steps > 0 ? p.steps : 6;
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
  s.options.load_steps = p.steps > 0 ? p.steps : 28;
  // Springs of 80 E h per sample (force per length): the contact pressure
  // at 140 degrees keeps samples within the thickness 0.1 h.
  s.options.contact.self = true;
  s.options.contact.stiffness = 80.0 * p.youngs_modulus * h;
  s.options.contact.thickness = 0.1 * h;
  s.description = "6:1:1 limb flexed 140 degrees by two rigid bones, inner side folding onto itself (self-contact)";
  return s;
}

// Edge length of the first element (the scenes' lattices are uniform).
// Edge length of the first hex (the scenes' lattices are uniform).
double scene_cell_size(const Mesh& mesh) {
  const auto a = mesh.vertex(mesh.elements[0]), b = mesh.vertex(mesh.elements[1]);
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

std::vector<std::string> scene_names() { return {"stretch", "twist", "scramble", "flex", "elbow"}; }

Scene make_scene(const std::string& name, const SceneParameters& p) {
  Scene s;
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
    throw Error("scene: unknown scene '" + name + "' (known: stretch, twist, scramble, flex, elbow)");
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
  // Coarse tets under a sudden pi/2 twist need some 60 iterations.
  s.options.max_newton_iterations = std::max(s.options.max_newton_iterations, 200);
  s.options.absolute_tolerance =
      p.strain_tolerance * p.youngs_modulus * h * h * std::sqrt(static_cast<double>(s.mesh.vertex_count()));
  for (const ConstraintSet& c : s.constraints)
    if (c.vertices.empty()) throw Error("scene " + name + ": constraint set '" + c.name + "' selects no vertex");
  return s;
}

}  // namespace snh
