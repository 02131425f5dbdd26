// `snh-gpu-bench scene --file F` for a scene with a rig: the animation run
// frame by frame on one Simulation (each frame's bone matrices, a warm-
// started solve of solver.steps load steps), the embedded surface written
// per frame. The scene command's load-step run does not fit: its targets are
// one motion over the load parameter of a single solve, while a rig's are
// absolute per frame, solved from the previous frame.
#pragma once

#include <string>

#include "scene_file.h"
#include "snh/simulation.h"

namespace snh::bench {

struct RigRunOutputs {
  std::string vtu_dir;         // lattice and surface .vtu per frame and <scene>.pvd (parts 0 and 1); empty: none
  std::string json_path;       // per-frame records; empty: none
  std::string surface_prefix;  // OBJ per frame (surface_obj_path); empty: none
  int max_frames = 0;          // run only the first frames; 0: all
};

// Progress per frame on stderr, a table on stdout. Returns 0 when every frame
// converged, else 3.
int run_rig_scene(const SceneFile& file, const SolveOptions& options, const RigRunOutputs& outputs);

}  // namespace snh::bench
