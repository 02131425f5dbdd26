#include "scene/scene_selectors.h"

#include <algorithm>

#include "snh/selection.h"

namespace snh::scene_io {
namespace {

using nlohmann::json;

// The one selector key of `s` among `kinds`; the schema's other keys at
// `key` modify it ("dimension").
std::string selector_kind(const SceneJson& r, const json& s, const std::string& key, const std::string& schema,
                          const std::vector<std::string>& kinds) {
  if (!s.is_object()) r.fail(key, "expected an object");
  std::string found, all;
  for (const std::string& k : kinds) {
    all += (all.empty() ? "" : ", ") + k;
    if (!s.contains(k)) continue;
    if (!found.empty()) r.fail(key, "give one selector, found both " + found + " and " + k);
    found = k;
  }
  const std::set<std::string>& allowed = allowed_keys(schema);
  for (const auto& item : s.items())
    if (!allowed.count(item.key())) r.fail(key + "." + item.key(), "unknown key (selectors: " + all + ")");
  if (found.empty()) r.fail(key, "expected one of " + all);
  return found;
}

// Library selectors report a missing group or array in their own words;
// the scene file's key is added in front.
template <class Select>
std::vector<int32_t> at_key(const SceneJson& r, const std::string& key, Select select) {
  try {
    return select();
  } catch (const Error& e) {
    r.fail(key, e.what());
  }
}

std::vector<int32_t> ids(const SceneJson& r, const json& list, const std::string& key, size_t count, const char* noun) {
  const std::string expected = std::string("expected an array of ") + noun + " indices";
  if (!list.is_array()) r.fail(key, expected);
  std::vector<int32_t> out;
  for (const json& id : list) {
    if (!id.is_number_integer()) r.fail(key, expected);
    const long v = id.get<long>();
    if (v < 0 || static_cast<size_t>(v) >= count)
      r.fail(key, std::string(noun) + " " + std::to_string(v) + " is out of range (the mesh has " +
                      std::to_string(count) + " " + noun + "s)");
    out.push_back(static_cast<int32_t>(v));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

struct Box {
  std::array<double, 3> lo, hi;
};

Box box(const SceneJson& r, const json& b, const std::string& key, const std::string& schema) {
  r.keys(b, key, schema);
  return {r.required_vec3(b, key, "min"), r.required_vec3(b, key, "max")};
}

struct Sphere {
  std::array<double, 3> center;
  double radius;
};

Sphere sphere(const SceneJson& r, const json& b, const std::string& key, const std::string& schema) {
  r.keys(b, key, schema);
  return {r.required_vec3(b, key, "center"), r.required_number(b, key, "radius")};
}

// "group": a name (string) or a tag (integer).
template <class ByName, class ByTag>
std::vector<int32_t> group(const SceneJson& r, const json& g, const std::string& key, ByName by_name, ByTag by_tag) {
  if (g.is_string()) return at_key(r, key, [&] { return by_name(g.get<std::string>()); });
  if (g.is_number_integer()) return at_key(r, key, [&] { return by_tag(g.get<int>()); });
  r.fail(key, "expected a group name (a string) or tag (an integer)");
}

// {"name": ..., "value": v} or {"name": ..., "min": lo, "max": hi}.
template <class Equal, class Within>
std::vector<int32_t> array_value(const SceneJson& r, const json& a, const std::string& key, const std::string& schema,
                                 Equal equal, Within within) {
  r.keys(a, key, schema);
  if (!a.contains("name")) r.fail(key + ".name", "missing (the array's name)");
  const std::string name = r.text(a, key, "name", "");
  const bool range = a.contains("min") || a.contains("max");
  if (a.contains("value") == range) r.fail(key, "give either value, or min and max");
  if (!range) {
    const double value = r.number(a, key, "value", 0.0);
    return at_key(r, key, [&] { return equal(name, value); });
  }
  const double lo = r.required_number(a, key, "min"), hi = r.required_number(a, key, "max");
  return at_key(r, key, [&] { return within(name, lo, hi); });
}

// Selectors take the same keys wherever they appear: the schema's entries
// for the constraints' (vertices) and the regions' (elements).
const std::string kVertexSelector = "constraints[].select";
const std::string kElementSelector = "regions[].select";

}  // namespace

std::vector<int32_t> parse_vertex_selection(const SceneJson& r, const json& s, const std::string& key,
                                            const Mesh& mesh) {
  const std::string kind =
      selector_kind(r, s, key, kVertexSelector, {"ids", "box", "plane", "sphere", "group", "point_array"});
  const std::string at = key + "." + kind;
  if (s.contains("dimension") && kind != "group") r.fail(key + ".dimension", "only a group selector takes one");
  const json& v = s[kind];
  if (kind == "ids") return ids(r, v, at, mesh.vertex_count(), "vertex");
  if (kind == "box") {
    const Box b = box(r, v, at, kVertexSelector + ".box");
    return at_key(r, at, [&] { return vertices_in_box(mesh, b.lo, b.hi); });
  }
  if (kind == "plane") {
    r.keys(v, at, kVertexSelector + ".plane");
    const double tolerance = r.number(v, at, "tolerance", 1e-9);
    std::array<double, 3> point{0, 0, 0}, normal{0, 0, 0};
    if (v.contains("normal") || v.contains("point")) {
      if (v.contains("axis") || v.contains("value")) r.fail(at, "give axis and value, or point and normal, not both");
      point = r.required_vec3(v, at, "point");
      normal = r.required_vec3(v, at, "normal");
    } else {
      const std::string axis = r.text(v, at, "axis", "z");
      if (axis != "x" && axis != "y" && axis != "z") r.fail(at + ".axis", "expected x, y or z");
      const int a = axis[0] - 'x';
      normal[a] = 1.0;
      point[a] = r.number(v, at, "value", 0.0);
    }
    return at_key(r, at, [&] { return vertices_on_plane(mesh, point, normal, tolerance); });
  }
  if (kind == "sphere") {
    const Sphere b = sphere(r, v, at, kVertexSelector + ".sphere");
    return at_key(r, at, [&] { return vertices_in_sphere(mesh, b.center, b.radius); });
  }
  if (kind == "group") {
    const int dimension = r.integer(s, key, "dimension", -1);
    return group(
        r, v, at, [&](const std::string& name) { return vertices_in_group(mesh, name, dimension); },
        [&](int tag) { return vertices_in_group(mesh, tag, dimension); });
  }
  return array_value(
      r, v, at, kVertexSelector + ".point_array",
      [&](const std::string& name, double value) { return vertices_with_value(mesh, name, value); },
      [&](const std::string& name, double lo, double hi) { return vertices_with_value_in(mesh, name, lo, hi); });
}

std::vector<int32_t> parse_element_selection(const SceneJson& r, const json& s, const std::string& key,
                                             const Mesh& mesh) {
  const std::string kind = selector_kind(r, s, key, kElementSelector, {"ids", "box", "sphere", "group", "cell_array"});
  const std::string at = key + "." + kind;
  const json& v = s[kind];
  if (kind == "ids") return ids(r, v, at, mesh.element_count(), "element");
  if (kind == "box") {
    const Box b = box(r, v, at, kElementSelector + ".box");
    return at_key(r, at, [&] { return elements_in_box(mesh, b.lo, b.hi); });
  }
  if (kind == "sphere") {
    const Sphere b = sphere(r, v, at, kElementSelector + ".sphere");
    return at_key(r, at, [&] { return elements_in_sphere(mesh, b.center, b.radius); });
  }
  if (kind == "group")
    return group(
        r, v, at, [&](const std::string& name) { return elements_in_group(mesh, name); },
        [&](int tag) { return elements_in_group(mesh, tag); });
  return array_value(
      r, v, at, kElementSelector + ".cell_array",
      [&](const std::string& name, double value) { return elements_with_value(mesh, name, value); },
      [&](const std::string& name, double lo, double hi) { return elements_with_value_in(mesh, name, lo, hi); });
}

}  // namespace snh::scene_io
