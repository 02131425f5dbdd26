// A frame's progress report (SceneProgress) from its record, for every
// kind of scene that runs frames (a rig's, a character's).
#pragma once

#include "snh/frames.h"
#include "snh/scene.h"

namespace snh::scene_io {

// index: frames done (1 for the first); count: frames in the run.
inline SceneProgress frame_progress(const FrameRecord& r, int index, int count) {
  SceneProgress p;
  p.frame = true;
  p.index = index;
  p.count = count;
  p.newton_iterations = r.newton_iterations;
  p.cg_iterations = r.cg_iterations;
  p.residual_norm = r.residual_norm;
  p.status = r.status;
  p.seconds = r.seconds;
  p.time = r.time;
  p.min_j = r.min_j;
  p.inverted_elements = r.inverted_elements;
  p.warnings = r.warnings;
  return p;
}

}  // namespace snh::scene_io
