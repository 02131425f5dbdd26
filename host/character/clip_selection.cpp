// The clip selection and frame range shared by the character readers
// (character/clip_selection.h).
#include "character/clip_selection.h"

#include <cmath>

#include "character/reader_messages.h"
#include "snh/error.h"

namespace snh::detail {

int select_clip(const std::string& path, const std::vector<std::string>& names, const CharacterReadOptions& options) {
  const auto listing = [&]() {
    std::string s;
    for (size_t a = 0; a < names.size(); ++a) s += (a ? ", " : "") + std::to_string(a) + " '" + names[a] + "'";
    return s.empty() ? std::string("none") : s;
  };
  int clip = -1;
  if (!options.clip.empty()) {
    for (size_t a = 0; a < names.size() && clip < 0; ++a)
      if (names[a] == options.clip) clip = static_cast<int>(a);
    if (clip < 0) fail(path, "no animation clip named '" + options.clip + "' (clips: " + listing() + ")");
  } else if (options.clip_index) {
    if (*options.clip_index < 0 || *options.clip_index >= static_cast<int>(names.size()))
      fail(path, "no animation clip " + std::to_string(*options.clip_index) + " (clips: " + listing() + ")");
    clip = *options.clip_index;
  } else if (!names.empty()) {
    clip = 0;
  }
  if (clip < 0 && options.require_clip) fail(path, "no animation (an animation clip is needed)");
  return clip;
}

int begin_clip(const std::string& path, const std::string& clip_name, double duration, int clip,
               const CharacterReadOptions& options, Character& c) {
  // Key times are often float32 (glTF): 20 / 24 s stored as 0.83333331 is
  // frame 20 all the same.
  const int clip_last = static_cast<int>(std::floor(duration * options.fps * (1 + 1e-6) + 1e-9));
  const int last = options.last_frame.value_or(clip_last);
  if (options.first_frame > last || last > clip_last)
    fail(path, clip_name + ": frames " + std::to_string(options.first_frame) + ".." + std::to_string(last) +
                   " are outside the clip's frames 0.." + std::to_string(clip_last) + " at " + number(options.fps) +
                   " fps");
  c.has_clip = true;
  c.clip.name = c.clip_names[clip];
  c.clip.index = clip;
  c.clip.fps = options.fps;
  c.clip.first_frame = options.first_frame;
  return last;
}

}  // namespace snh::detail
