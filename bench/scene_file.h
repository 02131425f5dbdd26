// Scenes described in JSON files (`snh-gpu-bench scene --file F`): mesh (a
// file or a generator), material, regions with their own materials (element
// selectors: scene_selection.h), constraint vertex sets (selectors:
// scene_selection.h) with rigid or keyframed motion, body force, solver
// options, output.
// Unknown keys and wrong types are errors naming the key's path.
#pragma once

#include <string>

#include "snh/regions.h"
#include "snh/scenes.h"

namespace snh::bench {

struct SceneFile {
  Scene scene;
  Material material;      // the base material ("material")
  MaterialMap materials;  // every element's: the base and the "regions"
  // "output.vtu": a folder for a .vtu per step (displacement and the element
  // fields of snh/fields.h) and a .pvd; empty for none.
  std::string vtu_dir;
  // "output.json": the run's JSON summary, each step with its constraint
  // sets' reactions; empty for none.
  std::string json_path;
};

// Paths inside the file (mesh files) are relative to the file's folder.
// Throws snh::Error "<file>: <key path>: <what>".
SceneFile load_scene_file(const std::string& path);

}  // namespace snh::bench
