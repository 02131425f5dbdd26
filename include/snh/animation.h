// Bone animations: per frame, a 4x4 transform (snh/rig.h's Matrix4, rigid or
// not) for each animated bone, read from JSON or CSV.
//
// JSON (.json):
//   {"frames": [
//     {"time": 0.0, "bones": {"forearm": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}},
//     ...]}
//   Each matrix is four rows of four numbers. "time" is optional (default:
//   the frame's index) and must increase.
//
// CSV (.csv): one line per frame and bone,
//   frame,bone,m00,m01,m02,m03,m10,m11,m12,m13,m20,m21,m22,m23,m30,m31,m32,m33
//   the matrix row by row; frames numbered 0, 1, 2, ... (time = the number),
//   lines in any order. Blank lines and lines starting with '#' are skipped,
//   and so is a first line starting with "frame" (the header).
//
// Both: every frame gives every animated bone exactly once, each matrix's
// last row is 0 0 0 1, and all entries are finite. Bones of a rig that the
// animation does not name stay at rest. Errors (snh::Error) name the file,
// the line (CSV) or key path (JSON), and the bone.
#pragma once

#include <string>
#include <vector>

#include "snh/rig.h"

namespace snh {

struct Animation {
  std::vector<std::string> bones;  // the animated bones, in the order the file first names them
  std::vector<double> times;       // per frame, increasing
  // Per frame, one transform per entry of `bones`.
  std::vector<std::vector<Matrix4>> transforms;

  size_t frame_count() const { return times.size(); }
};

// By the file's extension (.json or .csv, any case).
Animation read_animation(const std::string& path);

// The same from text already read; `name` stands for the file in errors.
Animation parse_animation_json(const std::string& text, const std::string& name);
Animation parse_animation_csv(const std::string& text, const std::string& name);

}  // namespace snh
