// Scenes described in JSON files (`snh-gpu-bench scene --file F`): mesh (a
// file or a generator), material, regions with their own materials (elements
// selected by ids or by a box around their centroids), constraint vertex sets
// selected by ids, box or plane with rigid or keyframed motion, body force,
// solver options, output. Unknown keys and wrong types are errors naming the
// key's path.
#pragma once

#include <string>

#include "snh/regions.h"
#include "snh/scenes.h"

namespace snh::bench {

struct SceneFile {
  Scene scene;
  Material material;      // the base material ("material")
  MaterialMap materials;  // every element's: the base and the "regions"
  std::string vtu_dir;    // "output.vtu", empty for none
  std::string json_path;  // "output.json", empty for none
};

// Paths inside the file (mesh files) are relative to the file's folder.
// Throws snh::Error "<file>: <key path>: <what>".
SceneFile load_scene_file(const std::string& path);

}  // namespace snh::bench
