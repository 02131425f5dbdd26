// libFuzzer entry point for the skinned-character readers (snh/character.h):
// the input is written to a temporary file with the format's extension
// (-DSNH_FUZZ_FORMAT=dae, fbx or gltf; the extension picks the reader: ufbx
// for FBX, assimp and the Collada <vertices> reader for the others), then
// read_character reads it without requiring a clip, at 10 fps and frames
// 0..3 (0..0 for a shorter clip), so that a clip of any length costs at most
// four frames; what reads is prepared on a coarse lattice (8 cells along the
// longest side: the voxelizer, the embedding, the bones). fuzz_entry.h says
// what counts as a bug.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "fuzz_entry.h"
#include "snh/character.h"

namespace {

std::string input_path() {
  static const std::string path = [] {
    char folder[] = "/tmp/snh-fuzz-character-XXXXXX";
    if (!mkdtemp(folder)) std::abort();
    return std::string(folder) + "/fuzz." + snh::fuzz::format;
  }();
  return path;
}

snh::Character read(const std::string& path) {
  snh::CharacterReadOptions options;
  options.require_clip = false;
  options.fps = 10.0;
  options.last_frame = 3;
  try {
    return snh::read_character(path, options);
  } catch (const snh::Error& e) {
    // A clip shorter than frame 3: its first frame alone.
    if (std::string(e.what()).find("are outside the clip's frames") == std::string::npos) throw;
  }
  options.last_frame = 0;
  return snh::read_character(path, options);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return snh::fuzz::read_input(data, size, [](const std::string& input) {
    const std::string path = input_path();
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << input;
    }
    const snh::Character c = read(path);
    snh::prepare_character(c, snh::character_cell(c, 8));
  });
}
