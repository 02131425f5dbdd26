// Inputs on which a fuzzed surface reader, animation parser or the scene
// loader once crashed, hung or tripped a sanitizer (tests/fuzz_regressions/,
// fuzz/run.sh): each must now be rejected with an snh::Error naming the
// file. The mesh readers' inputs are MeshIoFuzzRegressions' (test_mesh_io.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

#include "snh/animation.h"
#include "snh/error.h"
#include "snh/scene.h"
#include "snh/surface.h"
#include "support/errors.h"

namespace snh {
namespace {

namespace fs = std::filesystem;
using test::error_of;

// Reads every file in tests/fuzz_regressions/<folder>/ but README.md; returns how many.
int expect_each_rejected(const std::string& folder, const std::function<void(const std::string&)>& read) {
  const fs::path root = fs::path(SNH_DATA_DIR).parent_path() / "tests" / "fuzz_regressions" / folder;
  int count = 0;
  if (!fs::exists(root)) return 0;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (!entry.is_regular_file() || entry.path().filename() == "README.md") continue;
    SCOPED_TRACE(entry.path().string());
    const std::string message = error_of([&] { read(entry.path().string()); });
    EXPECT_NE(message.find(entry.path().filename().string()), std::string::npos) << message;
    ++count;
  }
  return count;
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

}  // namespace
}  // namespace snh
