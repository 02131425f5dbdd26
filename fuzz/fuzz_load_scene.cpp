// libFuzzer entry point for the scene-file loader (snh/scene.h): the input
// is written to scenes/fuzz.json in a private temporary folder whose
// meshes/, surfaces/ and arm/ link to data/ (so that the seed scenes' files
// resolve), then load_scene reads it; fuzz_entry.h says what counts as a
// bug (also an exception such as one of nlohmann::json's). SNH_DATA_DIR is
// the repository's data/ folder. Scenes that ask for a large body (a
// generated lattice of more than kMaxFuzzCells cells, or an embedding cell
// under kMinFuzzCell) are skipped: they are valid, and only slow to build
// under the sanitizers.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "fuzz_entry.h"
#include "snh/scene.h"

#ifndef SNH_DATA_DIR
#error "define SNH_DATA_DIR as the repository's data folder"
#endif

namespace {

constexpr double kMaxFuzzCells = 2e5;
constexpr double kMinFuzzCell = 0.02;  // the data/ surfaces are about unit size

double number_or(const nlohmann::json& object, const char* key, double fallback) {
  if (!object.is_object() || !object.contains(key) || !object[key].is_number()) return fallback;
  return object[key].get<double>();
}

// Whether the scene asks for a body too large to build within the fuzzer's
// time limit (the loader's own defaults for missing keys).
bool too_large(const uint8_t* data, size_t size) {
  const nlohmann::json doc = nlohmann::json::parse(data, data + size, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return false;
  if (doc.contains("mesh") && doc["mesh"].is_object()) {
    const nlohmann::json& m = doc["mesh"];
    const double h = number_or(m, "size", 0.1);
    if (!(h > 0.0)) return false;
    double cells = 1.0;
    if (m.contains("cells") && m["cells"].is_array()) {
      for (const auto& n : m["cells"])
        if (n.is_number()) cells *= std::max(1.0, std::abs(n.get<double>()));
    } else {
      const double across = 2.0 * std::abs(number_or(m, "radius", 0.5)) / h;
      cells = across * across * std::abs(number_or(m, "length", 2.0)) / h;
    }
    if (!(cells <= kMaxFuzzCells)) return true;
  }
  for (const char* section : {"embed", "character"})
    if (doc.contains(section) && doc[section].is_object()) {
      const double cell = number_or(doc[section], "cell", 1.0);
      if (!(std::abs(cell) >= kMinFuzzCell)) return true;
    }
  return false;
}

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
  if (too_large(data, size)) return 0;
  return snh::fuzz::read_input(data, size, [](const std::string& input) {
    const std::string path = scene_path();
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << input;
    }
    snh::load_scene(path);
  });
}
