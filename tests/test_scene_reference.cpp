// The scene-file reference (docs/scene-files.md) lists every key the loader
// accepts and no other: each Markdown table row whose first cell is a
// backticked key path (| `mesh.file` | ...) documents that key, and
// snh::scene_file_keys() is the loader's schema.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "snh/scene.h"

namespace snh::test {
namespace {

// The reference in the source tree, or the file SNH_SCENE_REFERENCE names.
std::string reference_path() {
  if (const char* path = std::getenv("SNH_SCENE_REFERENCE")) return path;
  return std::string(SNH_SOURCE_DIR) + "/docs/scene-files.md";
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// The first cells of the document's table rows that are one backticked path.
std::set<std::string> documented_keys(std::istream& in) {
  std::set<std::string> keys;
  for (std::string line; std::getline(in, line);) {
    line = trim(line);
    if (line.size() < 2 || line[0] != '|') continue;
    const size_t end = line.find('|', 1);
    if (end == std::string::npos) continue;
    const std::string cell = trim(line.substr(1, end - 1));
    if (cell.size() < 3 || cell.front() != '`' || cell.back() != '`') continue;
    const std::string key = cell.substr(1, cell.size() - 2);
    if (key.find('`') == std::string::npos) keys.insert(key);
  }
  return keys;
}

std::string listed(const std::vector<std::string>& keys) {
  std::string out;
  for (const std::string& k : keys) out += "\n  " + k;
  return out;
}

TEST(SceneReference, ParsesTheFirstCellOfTableRows) {
  std::istringstream doc(
      "# Scene files\n| Key | Meaning |\n|---|---|\n| `mesh.file` | a mesh |\n|  `regions[].select.box.min` | lo |\n"
      "Text with `mesh.size` in it.\n| `a` and `b` | two |\n| plain | no |\n");
  EXPECT_EQ(documented_keys(doc), (std::set<std::string>{"mesh.file", "regions[].select.box.min"}));
}

TEST(SceneReference, SchemaHasTheKeysOfEveryObject) {
  const std::vector<std::string> keys = scene_file_keys();
  const std::set<std::string> set(keys.begin(), keys.end());
  EXPECT_EQ(set.size(), keys.size());
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  for (const char* key :
       {"mesh", "mesh.file", "regions[].select", "regions[].select.box.min", "constraints[].select.box",
        "constraints[].select.plane.tolerance", "constraints[].motion.keys[].t", "obstacles[].keyframes[].angle",
        "obstacles[].keyframes.keys[].translation", "rig.bones[].capsule.radius", "dynamics.damping.mass",
        "solver.product_precision", "output.surface"})
    EXPECT_TRUE(set.count(key)) << key;
}

TEST(SceneReference, DocumentListsEveryKeyTheLoaderAccepts) {
  const std::string path = reference_path();
  std::ifstream in(path);
  ASSERT_TRUE(in) << "cannot read " << path;
  const std::set<std::string> documented = documented_keys(in);
  const std::vector<std::string> accepted = scene_file_keys();
  std::vector<std::string> undocumented, unknown;
  for (const std::string& k : accepted)
    if (!documented.count(k)) undocumented.push_back(k);
  for (const std::string& k : documented)
    if (!std::binary_search(accepted.begin(), accepted.end(), k)) unknown.push_back(k);
  EXPECT_TRUE(undocumented.empty()) << path << " does not list these keys the loader accepts:" << listed(undocumented);
  EXPECT_TRUE(unknown.empty()) << path << " lists these keys the loader does not accept:" << listed(unknown);
}

}  // namespace
}  // namespace snh::test
