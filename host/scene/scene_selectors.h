// The selector objects of scene files: which vertices a constraint holds and
// which elements a region covers. Exactly one selector key per object:
//
//   vertices: {"ids": [0, 5]}
//             {"box": {"min": [x, y, z], "max": [x, y, z]}}
//             {"plane": {"axis": "x", "value": 0, "tolerance": 1e-9}}
//             {"plane": {"point": [x, y, z], "normal": [x, y, z], "tolerance": 1e-9}}
//             {"sphere": {"center": [x, y, z], "radius": r}}
//             {"group": "fixed"} or {"group": 7, "dimension": 2}  (name or tag)
//             {"point_array": {"name": "id", "value": 3}} or {..., "min": lo, "max": hi}
//   elements: {"ids": [...]}, {"box": ...}, {"sphere": ...} by centroid,
//             {"group": "left"} or {"group": 3} (volume groups),
//             {"cell_array": {"name": "material", "value": 2}} or {..., "min", "max"}
//
// Their keys are those of the schema (scene_schema.h) at the selector's path.
// Errors name the file and the key's path. An empty selection is returned
// empty; the caller says whether that is an error.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene_json.h"
#include "snh/mesh.h"

namespace snh::scene_io {

std::vector<int32_t> parse_vertex_selection(const SceneJson& r, const nlohmann::json& selector, const std::string& key,
                                            const Mesh& mesh);

std::vector<int32_t> parse_element_selection(const SceneJson& r, const nlohmann::json& selector, const std::string& key,
                                             const Mesh& mesh);

}  // namespace snh::scene_io
