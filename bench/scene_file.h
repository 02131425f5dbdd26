// Scenes described in JSON files (`snh-gpu-bench scene --file F`): mesh (a
// file or a generator), material, constraint vertex sets (selectors:
// scene_selection.h) with rigid or keyframed motion, body force, solver
// options, output.
// Unknown keys and wrong types are errors naming the key's path.
#pragma once

#include <string>

#include "snh/scenes.h"

namespace snh::bench {

struct SceneFile {
  Scene scene;
  Material material;
  std::string vtu_dir;    // "output.vtu", empty for none
  std::string json_path;  // "output.json", empty for none
};

// Paths inside the file (mesh files) are relative to the file's folder.
// Throws snh::Error "<file>: <key path>: <what>".
SceneFile load_scene_file(const std::string& path);

}  // namespace snh::bench
