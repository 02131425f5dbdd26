// libFuzzer entry point for the scene-file loader (snh/scene.h): the input
// is written to scenes/fuzz.json in a private temporary folder whose
// meshes/, surfaces/ and arm/ link to data/ (so that the seed scenes' files
// resolve), then load_scene reads it; fuzz_entry.h says what counts as a
// bug (also an exception such as one of nlohmann::json's). SNH_DATA_DIR is
// the repository's data/ folder.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_entry.h"
#include "snh/scene.h"

#ifndef SNH_DATA_DIR
#error "define SNH_DATA_DIR as the repository's data folder"
#endif

namespace {

std::string scene_path() {
  static const std::string path = [] {
    char folder[] = "/tmp/snh-fuzz-scene-XXXXXX";
    if (!mkdtemp(folder)) std::abort();
    const std::filesystem::path root(folder);
    std::filesystem::create_directories(root / "scenes");
    for (const char* sub : {"meshes", "surfaces", "arm"})
      std::filesystem::create_directory_symlink(std::filesystem::path(SNH_DATA_DIR) / sub, root / sub);
    return (root / "scenes" / "fuzz.json").string();
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return snh::fuzz::read_input(data, size, [](const std::string& input) {
    const std::string path = scene_path();
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << input;
    }
    snh::load_scene(path);
  });
}
