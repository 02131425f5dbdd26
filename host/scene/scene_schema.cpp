#include "scene/scene_schema.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <stdexcept>
#include <vector>

#include "snh/scene.h"

namespace snh::scene_io {
namespace {

using Keys = std::set<std::string>;

// The motion of a constraint (and the object form of an obstacle's
// keyframes): rigid, or keyframes with "keys".
void add_motion(std::map<std::string, Keys>& t, const std::string& at) {
  t[at] = {"type", "axis", "angle", "center", "translation", "keys"};
  t[at + ".keys[]"] = {"t", "angle", "translation"};
}

// A vertex selector (constraints) or an element selector (regions): one
// selector key, its object's keys below it.
void add_vertex_selector(std::map<std::string, Keys>& t, const std::string& at) {
  t[at] = {"ids", "box", "plane", "sphere", "group", "point_array", "dimension"};
  t[at + ".box"] = {"min", "max"};
  t[at + ".plane"] = {"axis", "value", "point", "normal", "tolerance"};
  t[at + ".sphere"] = {"center", "radius"};
  t[at + ".point_array"] = {"name", "value", "min", "max"};
}

void add_element_selector(std::map<std::string, Keys>& t, const std::string& at) {
  t[at] = {"ids", "box", "sphere", "group", "cell_array"};
  t[at + ".box"] = {"min", "max"};
  t[at + ".sphere"] = {"center", "radius"};
  t[at + ".cell_array"] = {"name", "value", "min", "max"};
}

const Keys kMaterial = {"model",    "E",     "nu", "barrier", "fung_gamma",   "fung_mu1",    "ab_beta1",
                        "ab_beta2", "kappa", "j0", "alpha",   "lambda_model", "alpha_lambda"};

// Object path (with "#variant" for a form of an object) -> its keys.
std::map<std::string, Keys> make_table() {
  std::map<std::string, Keys> t;
  t[""] = {"name",       "description", "mesh",     "embed",     "material", "regions", "constraints", "rig",
           "body_force", "initial",     "dynamics", "obstacles", "contact",  "solver",  "output",      "character"};
  t["mesh"] = {"file", "generator", "cells", "size", "radius", "length", "element", "allow_coincident_vertices"};
  t["embed"] = {"surface", "cell", "cover_surface", "pieces", "strict_surface"};
  t["material"] = kMaterial;
  t["regions[]"] = {"name", "select", "material"};
  add_element_selector(t, "regions[].select");
  t["regions[].material"] = kMaterial;
  t["constraints[]"] = {"name", "select", "motion"};
  add_vertex_selector(t, "constraints[].select");
  add_motion(t, "constraints[].motion");
  t["rig"] = {"bones", "animation"};
  t["rig.bones[]"] = {"name", "capsule", "surface"};
  t["rig.bones[].capsule"] = {"a", "b", "radius"};
  t["character"] = {"file",       "clip",    "fps",    "frames", "cell",
                    "resolution", "weights", "pieces", "bones",  "skinned_guess"};
  // "radius" is an object of joint names (any key), so it has no entry.
  t["character.bones"] = {"radius_fraction", "exclude", "radius", "joint_clearance"};
  t["initial"] = {"scramble_volume_factor", "seed"};
  t["dynamics"] = {"time_step", "density", "damping", "substeps"};
  t["dynamics.damping"] = {"mass", "stiffness"};
  t["obstacles[]#plane"] = {"type", "point", "normal", "keyframes", "friction"};
  t["obstacles[]#sphere"] = {"type", "center", "radius", "keyframes", "friction"};
  t["obstacles[]#cylinder"] = {"type", "point", "axis", "radius", "keyframes", "friction"};
  // "keyframes": an array of keys, or an object as a constraint's motion.
  t["obstacles[].keyframes[]"] = {"t", "angle", "translation"};
  add_motion(t, "obstacles[].keyframes");
  t["contact"] = {"stiffness",     "thickness",      "self",     "self_method",
                  "self_distance", "self_stiffness", "friction", "friction_slip"};
  t["solver"] = {"steps",          "precision", "strain_tolerance",  "absolute_tolerance", "max_newton_iterations",
                 "preconditioner", "hessian",   "product_precision", "fail_on_inverted"};
  t["output"] = {"vtu", "json", "surface", "pc2", "mdd", "lbs", "check_intersections"};
  return t;
}

const std::map<std::string, Keys>& table() {
  static const std::map<std::string, Keys> t = make_table();
  return t;
}

}  // namespace

const std::set<std::string>& allowed_keys(const std::string& path, const std::string& variant) {
  const auto it = table().find(variant.empty() ? path : path + "#" + variant);
  if (it == table().end()) throw std::logic_error("scene file schema: no object '" + path + "'");
  return it->second;
}

std::string schema_path(const std::string& key_path) {
  if (key_path == "scene") return "";
  std::string out;
  for (size_t i = 0; i < key_path.size(); ++i) {
    out += key_path[i];
    if (key_path[i] != '[') continue;
    while (i + 1 < key_path.size() && std::isdigit(static_cast<unsigned char>(key_path[i + 1]))) ++i;
  }
  return out;
}

}  // namespace snh::scene_io

namespace snh {

std::vector<std::string> scene_file_keys() {
  std::set<std::string> keys;
  for (const auto& [object, names] : scene_io::table()) {
    const std::string path = object.substr(0, object.find('#'));
    for (const std::string& name : names) {
      keys.insert(path.empty() ? name : path + "." + name);
    }
  }
  return {keys.begin(), keys.end()};
}

}  // namespace snh
