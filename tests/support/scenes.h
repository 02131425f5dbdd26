// The built-in scenes at a test's size.
#pragma once

#include <string>

#include "snh/scenes.h"

namespace snh::test {

// make_scene(name) with its default parameters but `resolution` cells
// across the scene's thickness.
inline Scene scene_at(const std::string& name, int resolution) {
  SceneParameters p;
  p.resolution = resolution;
  return make_scene(name, p);
}

}  // namespace snh::test
