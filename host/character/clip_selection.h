// A character's animation clip as both readers choose it (glTF and Collada
// through assimp, FBX through ufbx): which clip the options select, and its
// frame range at the options' fps.
#pragma once

#include <string>
#include <vector>

#include "snh/character.h"

namespace snh::detail {

// The index among `names` the options select (CharacterReadOptions::clip by
// name, else clip_index, else the first), or -1 for none; snh::Error
// "<path>: ..." for a name or index that is not there, and for no clip
// where options.require_clip.
int select_clip(const std::string& path, const std::vector<std::string>& names, const CharacterReadOptions& options);

// Checks the options' frames against a clip of `duration` seconds (finite,
// >= 0) named `clip_name` ("clip '<name>'") and sets c.has_clip and c.clip's
// name, index, fps and first frame for clip `clip` (c.clip_names filled).
// Returns the last frame to sample.
int begin_clip(const std::string& path, const std::string& clip_name, double duration, int clip,
               const CharacterReadOptions& options, Character& c);

}  // namespace snh::detail
