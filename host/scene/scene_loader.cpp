
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "scene/character_scene.h"
#include "scene/scene_json.h"
#include "scene/scene_selectors.h"
#include "snh/error.h"
#include "snh/loads.h"
#include "snh/mesh_io.h"
#include "snh/pieces.h"
#include "snh/rig.h"
#include "snh/scene.h"
#include "solver/contact/obstacles.h"

namespace snh {
namespace {

using nlohmann::json;

using Reader = scene_io::SceneJson;
using scene_io::parse_element_selection;
using scene_io::parse_vertex_selection;

// A file the scene refers to, relative to the scene file's folder, read by
// `read`; its errors (which name the resolved path) get the key in front.
template <class Read>
auto read_referenced(const Reader& r, const std::string& key, const std::filesystem::path& folder,
                     const std::string& file, Read read) {
  const std::string resolved = (folder / file).string();
  try {
    return read(resolved);
  } catch (const Error& e) {
    const std::string what = e.what();
    r.fail(key, what.find(resolved) == std::string::npos ? resolved + ": " + what : what);
  }
}

// SolveOptions::product_precision; "automatic" leaves it unset.
void apply_product_precision(const std::string& value, SolveOptions& options) {
  if (value != "automatic") options.product_precision = parse_precision(value);
}

Mesh read_scene_mesh(const Reader& r, const json& m, const std::filesystem::path& folder) {
  r.keys(m, "mesh");
  if (m.contains("allow_coincident_vertices") && !m["allow_coincident_vertices"].is_boolean())
    r.fail("mesh.allow_coincident_vertices", "expected true or false");
  if (m.contains("allow_coincident_vertices") && !m.contains("file"))
    r.fail("mesh.allow_coincident_vertices", "only a mesh \"file\" takes it");
  Mesh mesh;
  if (m.contains("file")) {
    const std::string file = r.text(m, "mesh", "file", "");
    MeshReadOptions options;
    options.allow_coincident_vertices = m.value("allow_coincident_vertices", false);
    mesh = read_referenced(r, "mesh.file", folder, file,
                           [&](const std::string& resolved) { return read_mesh(resolved, options); });
  } else {
    const std::string generator = r.text(m, "mesh", "generator", "box");
    const double h = r.number(m, "mesh", "size", 0.1);
    if (generator == "box") {
      if (!m.contains("cells") || !m["cells"].is_array() || m["cells"].size() != 3)
        r.fail("mesh.cells", "expected an array of 3 integers");
      int n[3];
      for (int i = 0; i < 3; ++i) {
        if (!m["cells"][i].is_number_integer()) r.fail("mesh.cells", "expected an array of 3 integers");
        n[i] = m["cells"][i].get<int>();
      }
      try {
        mesh = make_box_lattice(n[0], n[1], n[2], h);
      } catch (const Error& error) {
        r.fail("mesh.cells", error.what());
      }
    } else if (generator == "cylinder") {
      const double radius = r.number(m, "mesh", "radius", 0.5), length = r.number(m, "mesh", "length", 2.0);
      try {
        mesh = make_voxel_cylinder(radius, length, h);
      } catch (const Error& error) {
        r.fail("mesh.radius", error.what());
      }
    } else {
      r.fail("mesh.generator", "expected box or cylinder, got '" + generator + "'");
    }
  }
  ElementType element = mesh.type;
  try {
    element = parse_element_type(r.text(m, "mesh", "element", element_type_name(mesh.type)));
  } catch (const Error& error) {
    r.fail("mesh.element", error.what());
  }
  if (element == ElementType::tet4 && mesh.type == ElementType::hex8)
    mesh = split_hexes_into_tets(mesh);
  else if (element != mesh.type)
    r.fail("mesh.element", std::string(element_type_name(element)) + " does not match the mesh's " +
                               element_type_name(mesh.type) + " elements");
  return mesh;
}

// A material's keys ("material" and each region's), defaults as in
// snh::MaterialOptions; E defaults to 1 and nu to 0.45.
Material read_material(const Reader& r, const json& material, const std::string& key) {
  r.keys(material, key);
  MaterialOptions mo;
  const std::string barrier = r.text(material, key, "barrier", "auto");
  mo.fung_gamma = r.number(material, key, "fung_gamma", mo.fung_gamma);
  mo.fung_mu1 = r.number(material, key, "fung_mu1", mo.fung_mu1);
  mo.arruda_boyce_beta1 = r.number(material, key, "ab_beta1", mo.arruda_boyce_beta1);
  mo.arruda_boyce_beta2 = r.number(material, key, "ab_beta2", mo.arruda_boyce_beta2);
  mo.kikuuwe_kappa = r.number(material, key, "kappa", mo.kikuuwe_kappa);
  mo.neohookean_j0 = r.number(material, key, "j0", mo.neohookean_j0);
  mo.alpha = r.number(material, key, "alpha", mo.alpha);
  const std::string lambda_model = r.text(material, key, "lambda_model", "");
  if (material.contains("alpha_lambda")) mo.alpha_lambda = r.number(material, key, "alpha_lambda", mo.alpha);
  const double e = r.number(material, key, "E", 1.0), nu = r.number(material, key, "nu", 0.45);
  const std::string model = r.text(material, key, "model", "snh");
  try {
    mo.barrier = parse_barrier(barrier);
    if (material.contains("lambda_model")) mo.lambda_model = parse_material_model(lambda_model);
    return Material::from_youngs_modulus(parse_material_model(model), e, nu, mo);
  } catch (const Error& error) {
    r.fail(key, error.what());
  }
}

// "regions": [{"name", "select", "material"}], over the base material.
MaterialMap read_regions(const Reader& r, const json& doc, const Mesh& mesh, const Material& base) {
  std::vector<MaterialRegion> regions;
  if (doc.contains("regions")) {
    if (!doc["regions"].is_array()) r.fail("regions", "expected an array");
    for (size_t i = 0; i < doc["regions"].size(); ++i) {
      const std::string key = "regions[" + std::to_string(i) + "]";
      const json& g = doc["regions"][i];
      r.keys(g, key);
      MaterialRegion region;
      region.name = r.text(g, key, "name", key);
      if (!g.contains("select")) r.fail(key + ".select", "missing");
      region.elements = parse_element_selection(r, g["select"], key + ".select", mesh);
      if (region.elements.empty()) r.fail(key + ".select", "selects no element");
      if (!g.contains("material")) r.fail(key + ".material", "missing");
      region.material = read_material(r, g["material"], key + ".material");
      regions.push_back(std::move(region));
    }
  }
  try {
    return make_material_map(mesh, base, regions);
  } catch (const Error& e) {
    r.fail("regions", e.what());
  }
}

struct RigidKey {
  double t = 0.0, angle = 0.0;
  std::array<double, 3> translation{0, 0, 0};
};

// `keys_schema`: the schema path of the keys' entries where the keys are not
// at <key>.keys[] in the file (an obstacle's "keyframes" array).
std::function<RigidTransform(double)> read_motion(const Reader& r, const json& m, const std::string& key,
                                                  const std::string& keys_schema = "") {
  r.keys(m, key);
  const std::string type = r.text(m, key, "type", "rigid");
  const auto axis = r.vec3(m, key, "axis", {0, 0, 1});
  const auto center = r.vec3(m, key, "center", {0, 0, 0});
  std::vector<RigidKey> keys;
  if (type == "rigid") {
    // Full motion at t = 1, linear in t from rest.
    keys.push_back({0.0, 0.0, {0, 0, 0}});
    keys.push_back({1.0, r.number(m, key, "angle", 0.0), r.vec3(m, key, "translation", {0, 0, 0})});
  } else if (type == "keyframes") {
    if (!m.contains("keys") || !m["keys"].is_array() || m["keys"].empty())
      r.fail(key + ".keys", "expected a non-empty array of {t, angle, translation}");
    for (size_t i = 0; i < m["keys"].size(); ++i) {
      const std::string k = key + ".keys[" + std::to_string(i) + "]";
      r.keys(m["keys"][i], k, keys_schema);
      keys.push_back({r.number(m["keys"][i], k, "t", 0.0), r.number(m["keys"][i], k, "angle", 0.0),
                      r.vec3(m["keys"][i], k, "translation", {0, 0, 0})});
      if (i > 0 && !(keys[i].t > keys[i - 1].t)) r.fail(k + ".t", "key times must increase");
    }
  } else {
    r.fail(key + ".type", "expected rigid or keyframes, got '" + type + "'");
  }
  return [keys, axis, center](double t) {
    size_t i = 0;
    while (i + 1 < keys.size() && keys[i + 1].t < t) ++i;
    RigidKey k = keys[i];
    if (i + 1 < keys.size()) {
      const double w = std::clamp((t - keys[i].t) / (keys[i + 1].t - keys[i].t), 0.0, 1.0);
      k.angle = (1 - w) * keys[i].angle + w * keys[i + 1].angle;
      for (int d = 0; d < 3; ++d) k.translation[d] = (1 - w) * keys[i].translation[d] + w * keys[i + 1].translation[d];
    }
    RigidTransform pose = RigidTransform::rotation_about(axis, k.angle, center);
    pose.translation = k.translation;
    return pose;
  };
}

// "obstacles": planes, spheres and cylinders, each with optional
// "keyframes": the keys of a keyframed constraint motion
// ([{"t", "angle", "translation"}], rotation about z through the origin), or
// an object as a constraint's "motion" (with "axis" and "center"), and an
// optional "friction" coefficient (else contact.friction).
std::vector<Obstacle> read_obstacles(const Reader& r, const json& list) {
  if (!list.is_array()) r.fail("obstacles", "expected an array");
  std::vector<Obstacle> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string key = "obstacles[" + std::to_string(i) + "]";
    const json& o = list[i];
    if (!o.is_object()) r.fail(key, "expected an object");
    Obstacle obstacle;
    const std::string type = r.text(o, key, "type", "");
    if (type == "plane") {
      r.keys(o, key, "", type);
      obstacle.type = ObstacleType::plane;
      obstacle.point = r.required_vec3(o, key, "point");
      obstacle.direction = r.required_vec3(o, key, "normal");
    } else if (type == "sphere") {
      r.keys(o, key, "", type);
      obstacle.type = ObstacleType::sphere;
      obstacle.point = r.required_vec3(o, key, "center");
      obstacle.radius = r.required_number(o, key, "radius");
    } else if (type == "cylinder") {
      r.keys(o, key, "", type);
      obstacle.type = ObstacleType::cylinder;
      obstacle.point = r.required_vec3(o, key, "point");
      obstacle.direction = r.required_vec3(o, key, "axis");
      obstacle.radius = r.required_number(o, key, "radius");
    } else {
      r.fail(key + ".type", type.empty() ? "missing (plane, sphere or cylinder)"
                                         : "expected plane, sphere or cylinder, got '" + type + "'");
    }
    if (o.contains("friction")) {
      obstacle.friction = r.required_number(o, key, "friction");
      if (!(*obstacle.friction >= 0.0)) r.fail(key + ".friction", "must be >= 0");
    }
    if (o.contains("keyframes")) {
      const json& k = o["keyframes"];
      if (k.is_array())
        obstacle.motion =
            read_motion(r, json{{"type", "keyframes"}, {"keys", k}}, key + ".keyframes", "obstacles[].keyframes[]");
      else
        obstacle.motion = read_motion(r, k, key + ".keyframes");
    }
    out.push_back(std::move(obstacle));
  }
  return out;
}

SceneFile::Embedded read_embed(const Reader& r, const json& e, const std::filesystem::path& folder) {
  r.keys(e, "embed");
  if (!e.contains("surface")) r.fail("embed.surface", "missing (a closed surface: .obj, .ply or .stl)");
  SceneFile::Embedded out;
  out.surface = read_referenced(r, "embed.surface", folder, r.text(e, "embed", "surface", ""), read_surface);
  const double cell = r.required_number(e, "embed", "cell");
  if (!(cell > 0.0)) r.fail("embed.cell", "expected a cube side > 0");
  VoxelizeOptions options;
  if (e.contains("cover_surface")) {
    if (!e["cover_surface"].is_boolean()) r.fail("embed.cover_surface", "expected true or false");
    options.cover_surface = e["cover_surface"].get<bool>();
  }
  if (e.contains("pieces")) {
    try {
      out.piece_rule = parse_piece_rule(r.text(e, "embed", "pieces", "error"));
    } catch (const Error& error) {
      r.fail("embed.pieces", error.what());
    }
  }
  if (e.contains("strict_surface")) {
    if (!e["strict_surface"].is_boolean()) r.fail("embed.strict_surface", "expected true or false");
    options.strict = e["strict_surface"].get<bool>();
  }
  options.name = (folder / r.text(e, "embed", "surface", "")).string();
  try {
    out.voxels = voxelize(out.surface, cell, options);
  } catch (const Error& error) {
    r.fail("embed.surface", error.what());
  }
  out.embedding = embed(out.voxels, out.surface);
  return out;
}

std::vector<Bone> read_bones(const Reader& r, const json& rig, const std::filesystem::path& folder) {
  if (!rig.contains("bones") || !rig["bones"].is_array() || rig["bones"].empty())
    r.fail("rig.bones", "expected a non-empty array of {name, capsule | surface}");
  std::vector<Bone> bones;
  for (size_t i = 0; i < rig["bones"].size(); ++i) {
    const std::string key = "rig.bones[" + std::to_string(i) + "]";
    const json& b = rig["bones"][i];
    r.keys(b, key);
    Bone bone;
    if (!b.contains("name")) r.fail(key + ".name", "missing");
    bone.name = r.text(b, key, "name", "");
    if (b.contains("capsule") == b.contains("surface")) r.fail(key, "expected one of \"capsule\" and \"surface\"");
    if (b.contains("capsule")) {
      const json& c = b["capsule"];
      const std::string ck = key + ".capsule";
      r.keys(c, ck);
      bone.shape =
          Capsule{r.required_vec3(c, ck, "a"), r.required_vec3(c, ck, "b"), r.required_number(c, ck, "radius")};
    } else {
      bone.shape = read_referenced(r, key + ".surface", folder, r.text(b, key, "surface", ""), read_surface);
    }
    bones.push_back(std::move(bone));
  }
  return bones;
}

// "embed.pieces": the lattice's pieces nothing holds refused, joined or
// left out (snh/pieces.h), before anything per vertex (forces, initial
// positions) is laid on the lattice; the constraint sets and the regions'
// elements follow the new lattice. Obstacles at rest and dynamics hold
// pieces too, so they are read here as well as below.
void resolve_scene_pieces(const Reader& r, const json& doc, SceneFile& file) {
  SceneFile::Embedded& embedded = *file.embedded;
  PieceOptions options;
  options.rule = embedded.piece_rule;
  options.rule_name = "embed.pieces";
  options.dynamic = doc.contains("dynamics");
  options.loaded = doc.contains("body_force");
  if (doc.contains("obstacles")) options.obstacles = read_obstacles(r, doc["obstacles"]);
  if (doc.contains("contact") && doc["contact"].is_object())
    options.contact_thickness = r.number(doc["contact"], "contact", "thickness", 0.0);
  PiecedLattice pieced;
  try {
    pieced = resolve_pieces(embedded.voxels, embedded.embedding, embedded.surface, file.scene.constraints,
                            file.rig ? file.rig->bones : std::vector<Bone>{}, options);
  } catch (const Error& error) {
    r.fail("embed.pieces", error.what());
  }
  embedded.pieces = std::move(pieced.pieces);
  embedded.piece_warnings = std::move(pieced.warnings);
  if (!pieced.changed) return;
  embedded.voxels = std::move(pieced.voxels);
  embedded.embedding = std::move(pieced.embedding);
  file.scene.mesh = embedded.voxels.lattice;
  std::vector<int32_t> element_material(pieced.element_source.size());
  for (size_t e = 0; e < element_material.size(); ++e)
    element_material[e] = file.materials.element_material[pieced.element_source[e]];
  file.materials.element_material = std::move(element_material);
}

// The scene file's JSON.
json parse_scene_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the scene file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond double's range.
    throw Error(path + ": not valid JSON (" + e.what() + ")");
  }
  return doc;
}

// The body: "character", "embed" or "mesh" (one of them).
void read_body(const Reader& r, const json& doc, const std::filesystem::path& folder, SceneFile& out) {
  Scene& s = out.scene;
  if (doc.contains("character")) {
    for (const char* other : {"mesh", "embed", "rig"})
      if (doc.contains(other))
        r.fail("character", std::string("replaces \"mesh\", \"embed\" and \"rig\": give \"character\" or \"") + other +
                                "\", not both");
    out.character = scene_io::read_character_section(r, doc["character"], folder);
    const SceneFile::CharacterSection& c = *out.character;
    out.embedded.emplace();
    out.embedded->surface = c.character.surface;
    out.embedded->voxels = c.rig.voxels;
    out.embedded->embedding = c.rig.embedding;
    s.mesh = c.rig.voxels.lattice;
  } else if (doc.contains("mesh") == doc.contains("embed")) {
    r.fail("mesh",
           doc.contains("mesh") ? "give \"mesh\" or \"embed\", not both" : "missing (or \"embed\" or \"character\")");
  } else if (doc.contains("embed")) {
    out.embedded = read_embed(r, doc["embed"], folder);
    s.mesh = out.embedded->voxels.lattice;
  } else {
    s.mesh = read_scene_mesh(r, doc["mesh"], folder);
  }
}

// "constraints": [{"name", "select", "motion"}].
void read_constraints(const Reader& r, const json& doc, Scene& s) {
  if (doc.contains("constraints")) {
    if (!doc["constraints"].is_array()) r.fail("constraints", "expected an array");
    for (size_t i = 0; i < doc["constraints"].size(); ++i) {
      const std::string key = "constraints[" + std::to_string(i) + "]";
      const json& c = doc["constraints"][i];
      r.keys(c, key);
      ConstraintSet set;
      set.name = r.text(c, key, "name", key);
      if (!c.contains("select")) r.fail(key + ".select", "missing");
      set.vertices = parse_vertex_selection(r, c["select"], key + ".select", s.mesh);
      if (set.vertices.empty()) r.fail(key + ".select", "selects no vertex");
      if (c.contains("motion")) set.motion = read_motion(r, c["motion"], key + ".motion");
      s.constraints.push_back(set);
    }
  }
}

// The rig: the character's, or "rig" (bones and their animation), with
// the constraints its bones make.
void read_rig(const Reader& r, const json& doc, const std::filesystem::path& folder, SceneFile& out) {
  Scene& s = out.scene;
  if (out.character) {
    for (const ConstraintSet& set : out.character->rig.constraints) s.constraints.push_back(set);
    out.rig = SceneFile::Rig{out.character->rig.bones.bones, out.character->rig.bones.animation};
  }
  if (doc.contains("rig")) {
    const json& rig = doc["rig"];
    r.keys(rig, "rig");
    SceneFile::Rig out_rig;
    out_rig.bones = read_bones(r, rig, folder);
    try {
      for (ConstraintSet& set : bone_constraints(s.mesh, out_rig.bones)) s.constraints.push_back(std::move(set));
    } catch (const Error& error) {
      r.fail("rig.bones", error.what());
    }
    if (!rig.contains("animation")) r.fail("rig.animation", "missing (a .json or .csv animation file)");
    out_rig.animation =
        read_referenced(r, "rig.animation", folder, r.text(rig, "rig", "animation", ""), read_animation);
    for (const std::string& bone : out_rig.animation.bones)
      if (std::none_of(out_rig.bones.begin(), out_rig.bones.end(), [&](const Bone& b) { return b.name == bone; }))
        r.fail("rig.animation", "the animation moves bone '" + bone + "', which is not in rig.bones");
    out.rig = std::move(out_rig);
  }
}

// "initial": scrambled initial positions, uniform in the mesh's bounding
// box grown to scramble_volume_factor times its volume.
void read_initial(const Reader& r, const json& init, Scene& s) {
  r.keys(init, "initial");
  const double factor = r.number(init, "initial", "scramble_volume_factor", 2.0);
  std::mt19937_64 rng(static_cast<unsigned>(r.integer(init, "initial", "seed", 1)));
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t v = 0; v < s.mesh.vertex_count(); ++v)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], s.mesh.positions(v, d));
      hi[d] = std::max(hi[d], s.mesh.positions(v, d));
    }
  const double scale = std::cbrt(factor);
  s.options.initial_positions = Points(s.mesh.vertex_count());
  double* x = s.options.initial_positions.data();
  for (size_t i = 0; i < 3 * s.mesh.vertex_count(); ++i) {
    const int d = static_cast<int>(i % 3);
    const double mid = 0.5 * (lo[d] + hi[d]), half = 0.5 * scale * (hi[d] - lo[d]);
    x[i] = std::uniform_real_distribution<double>(mid - half, mid + half)(rng);
  }
}

// "dynamics": time step, density, damping and substeps.
void read_dynamics(const Reader& r, const json& doc, Scene& s) {
  const json& d = doc["dynamics"];
  r.keys(d, "dynamics");
  DynamicsOptions dynamics;
  dynamics.time_step = r.required_number(d, "dynamics", "time_step");
  dynamics.density = r.required_number(d, "dynamics", "density");
  if (d.contains("damping")) {
    r.keys(d["damping"], "dynamics.damping");
    dynamics.damping.mass = r.number(d["damping"], "dynamics.damping", "mass", 0.0);
    dynamics.damping.stiffness = r.number(d["damping"], "dynamics.damping", "stiffness", 0.0);
  }
  dynamics.substeps = r.integer(d, "dynamics", "substeps", 1);
  if (!(dynamics.time_step > 0.0)) r.fail("dynamics.time_step", "must be > 0");
  if (!(dynamics.density > 0.0)) r.fail("dynamics.density", "must be > 0");
  if (!(dynamics.damping.mass >= 0.0)) r.fail("dynamics.damping.mass", "must be >= 0");
  if (!(dynamics.damping.stiffness >= 0.0)) r.fail("dynamics.damping.stiffness", "must be >= 0");
  if (dynamics.substeps < 1) r.fail("dynamics.substeps", "must be >= 1");
  if (doc.contains("rig") || doc.contains("character"))
    r.fail("dynamics", "not supported with \"rig\" or \"character\" yet (frames are quasistatic)");
  s.options.dynamics = dynamics;
}

// A "contact" number the file may leave out or give as 0 (both: unset, the
// library chooses); else > 0.
std::optional<double> unset_at_zero(const Reader& r, const json& c, const char* key) {
  const double value = r.number(c, "contact", key, 0.0);
  if (!(value >= 0.0)) r.fail(std::string("contact.") + key, "must be >= 0 (0: automatic)");
  if (value == 0.0) return std::nullopt;
  return value;
}

// "contact": obstacle and self-contact.
void read_contact(const Reader& r, const json& c, ContactOptions& contact) {
  r.keys(c, "contact");
  contact.friction = r.number(c, "contact", "friction", 0.0);
  if (!(contact.friction >= 0.0)) r.fail("contact.friction", "must be >= 0");
  contact.friction_slip = unset_at_zero(r, c, "friction_slip");
  contact.stiffness = r.number(c, "contact", "stiffness", 0.0);
  contact.thickness = r.number(c, "contact", "thickness", 0.0);
  if (c.contains("self")) {
    if (!c["self"].is_boolean()) r.fail("contact.self", "expected true or false");
    contact.self = c["self"].get<bool>();
  }
  if (c.contains("self_method")) {
    const json& m = c["self_method"];
    if (!m.is_string() || (m != "barrier" && m != "penalty"))
      r.fail("contact.self_method", "expected \"barrier\" or \"penalty\"");
    contact.self_method = m == "penalty" ? SelfContactMethod::penalty : SelfContactMethod::barrier;
  }
  contact.self_distance = unset_at_zero(r, c, "self_distance");
  contact.self_stiffness = unset_at_zero(r, c, "self_stiffness");
  if (contact.self && contact.self_method == SelfContactMethod::penalty && !(contact.stiffness > 0.0) &&
      !contact.self_stiffness)
    r.fail("contact.stiffness", "missing (penalty self-contact needs stiffness or self_stiffness > 0)");
  if (!(contact.thickness >= 0.0)) r.fail("contact.thickness", "must be >= 0");
  if (contact.stiffness < 0.0) r.fail("contact.stiffness", "must be > 0");
}

// Self-contact's defaults for characters and embedded surfaces, then the
// obstacles checked against the contact options.
void finish_contact(const Reader& r, const json& doc, SceneFile& out) {
  Scene& s = out.scene;
  // A rigged or skinned character folds at its joints (an arm raised into
  // the head, a bent elbow): self-contact is on unless the file says
  // "contact": {"self": false}.
  const bool self_given = doc.contains("contact") && doc["contact"].is_object() && doc["contact"].contains("self");
  if (!self_given && (out.character || (out.embedded && out.rig))) s.options.contact.self = true;
  // An embedded surface is what the user sees, and it reaches outside the
  // lattice's boundary (snh/surface.h embed): barrier self-contact acts on it.
  if (out.embedded && s.options.contact.self && s.options.contact.self_method == SelfContactMethod::barrier) {
    s.options.contact.self_surface = out.embedded->surface;
    s.options.contact.self_embedding = out.embedded->embedding;
  }
  if (!s.options.obstacles.empty() && !(s.options.contact.stiffness > 0.0))
    r.fail("contact.stiffness", "missing (the obstacles need a contact stiffness > 0)");
  try {
    solver::validate_obstacles(s.options.obstacles, s.options.contact);
  } catch (const Error& error) {
    r.fail("obstacles", error.what());
  }
}

// "solver": steps, precision, iterations, preconditioner, Hessian and the
// stopping rule.
void read_solver(const Reader& r, const json& doc, const std::string& path, SceneFile& out) {
  Scene& s = out.scene;
  const json solver = doc.value("solver", json::object());
  r.keys(solver, "solver");
  s.options.load_steps = r.integer(solver, "solver", "steps", defaults::load_steps);
  s.options.precision = parse_precision(r.text(solver, "solver", "precision", "double"));
  s.options.max_newton_iterations =
      r.integer(solver, "solver", "max_newton_iterations", defaults::max_newton_iterations);
  if (solver.contains("fail_on_inverted")) {
    if (!solver["fail_on_inverted"].is_boolean()) r.fail("solver.fail_on_inverted", "expected true or false");
    s.options.fail_on_inverted = solver["fail_on_inverted"].get<bool>();
  }
  try {
    s.options.preconditioner =
        parse_optional(r.text(solver, "solver", "preconditioner", kAutomatic), parse_preconditioner);
  } catch (const Error& error) {
    throw Error(path + ": solver.preconditioner: " + error.what());
  }
  try {
    s.options.hessian = parse_hessian_mode(r.text(solver, "solver", "hessian", "adaptive"));
  } catch (const Error& error) {
    throw Error(path + ": solver.hessian: " + error.what());
  }
  // SolveOptions::product_precision; absent or "automatic": unset.
  const std::string product_precision = r.text(solver, "solver", "product_precision", "automatic");
  try {
    apply_product_precision(product_precision, s.options);
  } catch (const Error& error) {
    throw Error(path + ": solver.product_precision: " + error.what());
  }
  // The stopping rule: an absolute residual tolerance when the file gives
  // one, else a strain error (SolveOptions::strain_tolerance: the library
  // scales it by the smallest Young's modulus and the mesh's mean vertex
  // spacing), the precision's default unless given.
  out.tolerance_given = solver.contains("strain_tolerance") || solver.contains("absolute_tolerance");
  if (solver.contains("absolute_tolerance"))
    s.options.absolute_tolerance = r.number(solver, "solver", "absolute_tolerance", 0.0);
  else
    s.options.strain_tolerance =
        r.number(solver, "solver", "strain_tolerance", defaults::strain_tolerance(s.options.precision));
}

// "output": the files to write.
void read_output(const Reader& r, const json& doc, SceneFile& out) {
  const json output = doc.value("output", json::object());
  r.keys(output, "output");
  out.vtu_dir = r.text(output, "output", "vtu", "");
  out.json_path = r.text(output, "output", "json", "");
  out.surface_prefix = r.text(output, "output", "surface", "");
  if (!out.surface_prefix.empty() && !out.embedded) r.fail("output.surface", "needs \"embed\" (a surface to write)");
  out.pc2_path = r.text(output, "output", "pc2", "");
  out.mdd_path = r.text(output, "output", "mdd", "");
  out.lbs_path = r.text(output, "output", "lbs", "");
  if (output.contains("check_intersections")) {
    if (!output["check_intersections"].is_boolean()) r.fail("output.check_intersections", "expected true or false");
    out.check_intersections = output["check_intersections"].get<bool>();
    if (out.check_intersections && out.character)
      r.fail("output.check_intersections", "is not available for \"character\" scenes");
  }
  for (const char* key : {"pc2", "mdd", "lbs"})
    if (output.contains(key) && !out.character)
      r.fail(std::string("output.") + key, "needs \"character\" (a skinned surface to cache)");
}

}  // namespace

SceneFile load_scene(const std::string& path) {
  const json doc = parse_scene_file(path);
  const Reader r{path};
  r.keys(doc, "scene");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  SceneFile out;
  Scene& s = out.scene;
  s.name = r.text(doc, "scene", "name", std::filesystem::path(path).stem().string());
  s.description = r.text(doc, "scene", "description", "");
  read_body(r, doc, folder, out);

  const json material = doc.value("material", json::object());
  out.material = read_material(r, material, "material");
  out.materials = read_regions(r, doc, s.mesh, out.material);

  read_constraints(r, doc, s);
  read_rig(r, doc, folder, out);
  if (out.embedded) resolve_scene_pieces(r, doc, out);
  if (doc.contains("body_force"))
    s.options.external_force = lump_body_force(s.mesh, r.vec3(doc, "scene", "body_force", {0, 0, 0}));
  if (doc.contains("initial")) read_initial(r, doc["initial"], s);
  if (doc.contains("dynamics")) read_dynamics(r, doc, s);
  if (doc.contains("obstacles")) s.options.obstacles = read_obstacles(r, doc["obstacles"]);
  if (doc.contains("contact")) read_contact(r, doc["contact"], s.options.contact);
  finish_contact(r, doc, out);
  read_solver(r, doc, path, out);
  read_output(r, doc, out);
  return out;
}

}  // namespace snh
