// Inputs on which a fuzzed surface reader, animation parser, the scene
// loader or a character reader once crashed, hung or tripped a sanitizer
// (tests/fuzz_regressions/, fuzz/run.sh): each must now be rejected with an
// snh::Error naming the file (a character may also read and prepare
// cleanly). The mesh readers' inputs are MeshIoFuzzRegressions'
// (test_mesh_io.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "snh/animation.h"
#include "snh/character.h"
#include "snh/error.h"
#include "snh/scene.h"
#include "snh/surface.h"
#include "support/errors.h"

namespace snh {
namespace {

namespace fs = std::filesystem;
using test::error_of;

// Reads every file in tests/fuzz_regressions/<folder>/ but README.md; returns how many.
// With may_read, a file may also be read without an error.
int expect_each_rejected(const std::string& folder, const std::function<void(const std::string&)>& read,
                         bool may_read = false) {
  const fs::path root = fs::path(SNH_DATA_DIR).parent_path() / "tests" / "fuzz_regressions" / folder;
  int count = 0;
  if (!fs::exists(root)) return 0;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    SCOPED_TRACE(entry.path().string());
    ++count;
    if (may_read) {
      try {
        read(entry.path().string());
        continue;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(entry.path().filename().string()), std::string::npos) << e.what();
        continue;
      }
    }
    const std::string message = error_of([&] { read(entry.path().string()); });
    EXPECT_NE(message.find(entry.path().filename().string()), std::string::npos) << message;
  }
  return count;
}

// As fuzz/fuzz_read_character.cpp: no clip required, 10 fps, frames 0..3
// (0..0 for a shorter clip), then a coarse lattice of 8 cells.
void read_and_prepare_character(const std::string& path) {
  CharacterReadOptions options;
  options.require_clip = false;
  options.fps = 10.0;
  options.last_frame = 3;
  Character c;
  try {
    c = read_character(path, options);
  } catch (const Error& e) {
    if (std::string(e.what()).find("are outside the clip's frames") == std::string::npos) throw;
    options.last_frame = 0;
    c = read_character(path, options);
  }
  prepare_character(c, character_cell(c, 8));
}

TEST(FuzzRegressions, SurfacesAnimationsAndScenesAreRejectedCleanly) {
  int count = 0;
  for (const char* format : {"obj", "ply", "stl"})
    count += expect_each_rejected(format, [](const std::string& path) {
      // Through the voxelizer too: what reads must be welded and reported.
      const TriangleSurface s = read_surface(path);
      surface_report(s, path);
      VoxelizeOptions named;
      named.name = path;
      voxelize(s, 1e300, named);
    });
  for (const char* format : {"json", "csv"})
    count += expect_each_rejected(format, [](const std::string& path) { read_animation(path); });
  count += expect_each_rejected("scene", [](const std::string& path) { load_scene(path); });
  if (count == 0) GTEST_SKIP() << "no regression inputs for surfaces, animations or scenes";
}

TEST(FuzzRegressions, CharactersAreRejectedCleanlyOrRead) {
  int count = 0;
  for (const char* format : {"dae", "fbx", "gltf"})
    count += expect_each_rejected(format, read_and_prepare_character, /*may_read=*/true);
  if (count == 0) GTEST_SKIP() << "no regression inputs for characters";
}

}  // namespace
}  // namespace snh
