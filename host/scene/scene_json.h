// Reading a scene file's JSON with errors that name the file and the key's
// path ("scene.json: constraints[0].select.box.min: expected ...").
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "scene/scene_schema.h"
#include "snh/error.h"

namespace snh::scene_io {

struct SceneJson {
  std::string file;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw Error(file + ": " + key + ": " + what);
  }
  // Rejects keys the schema does not list for the object at `key` (its
  // schema path: the key path without indices, unless given; scene_schema.h).
  void keys(const nlohmann::json& object, const std::string& key, const std::string& schema = "",
            const std::string& variant = "") const {
    if (!object.is_object()) fail(key, "expected an object");
    const std::set<std::string>& allowed = allowed_keys(schema.empty() ? schema_path(key) : schema, variant);
    for (const auto& item : object.items())
      if (!allowed.count(item.key())) fail(key + "." + item.key(), "unknown key");
  }
  double number(const nlohmann::json& object, const std::string& key, const std::string& name, double fallback) const {
    if (!object.contains(name)) return fallback;
    if (!object[name].is_number()) fail(key + "." + name, "expected a number");
    return object[name].get<double>();
  }
  int integer(const nlohmann::json& object, const std::string& key, const std::string& name, int fallback) const {
    if (!object.contains(name)) return fallback;
    if (!object[name].is_number_integer()) fail(key + "." + name, "expected an integer");
    return object[name].get<int>();
  }
  std::string text(const nlohmann::json& object, const std::string& key, const std::string& name,
                   const std::string& fallback) const {
    if (!object.contains(name)) return fallback;
    if (!object[name].is_string()) fail(key + "." + name, "expected a string");
    return object[name].get<std::string>();
  }
  std::array<double, 3> vec3(const nlohmann::json& object, const std::string& key, const std::string& name,
                             std::array<double, 3> fallback) const {
    if (!object.contains(name)) return fallback;
    const nlohmann::json& v = object[name];
    if (!v.is_array() || v.size() != 3) fail(key + "." + name, "expected an array of 3 numbers");
    std::array<double, 3> out;
    for (int i = 0; i < 3; ++i) {
      if (!v[i].is_number()) fail(key + "." + name, "expected an array of 3 numbers");
      out[i] = v[i].get<double>();
    }
    return out;
  }
  // Like vec3, for a key that must be present.
  std::array<double, 3> required_vec3(const nlohmann::json& object, const std::string& key,
                                      const std::string& name) const {
    if (!object.contains(name)) fail(key + "." + name, "missing (expected an array of 3 numbers)");
    return vec3(object, key, name, {0, 0, 0});
  }
  double required_number(const nlohmann::json& object, const std::string& key, const std::string& name) const {
    if (!object.contains(name)) fail(key + "." + name, "missing (expected a number)");
    return number(object, key, name, 0.0);
  }
};

}  // namespace snh::scene_io
