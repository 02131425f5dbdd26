// Bone animations from JSON and CSV (snh/animation.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <locale>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "snh/animation.h"
#include "snh/error.h"

namespace snh {
namespace {

// The last row of an affine map and finite entries; `where` names the file,
// line or key, and the bone.
void check_matrix(const Matrix4& m, const std::string& where) {
  for (int i = 0; i < 16; ++i)
    if (!std::isfinite(m[i]))
      throw Error(where + ": entry m" + std::to_string(i / 4) + std::to_string(i % 4) + " is not finite");
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
    std::ostringstream s;
    s << where << ": the last row is " << m[12] << " " << m[13] << " " << m[14] << " " << m[15] << ", not 0 0 0 1";
    throw Error(s.str());
  }
}

size_t bone_index(Animation& a, const std::string& bone) {
  const auto found = std::find(a.bones.begin(), a.bones.end(), bone);
  if (found != a.bones.end()) return static_cast<size_t>(found - a.bones.begin());
  a.bones.push_back(bone);
  return a.bones.size() - 1;
}

// Every frame has every bone once; `given[f][b]` says whether it was given,
// `where(f, b)` how to name the gap.
template <typename Where>
void check_complete(const Animation& a, const std::vector<std::vector<bool>>& given, const Where& where) {
  for (size_t f = 0; f < given.size(); ++f)
    for (size_t b = 0; b < a.bones.size(); ++b)
      if (b >= given[f].size() || !given[f][b]) throw Error(where(f, b));
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

Animation parse_animation_json(const std::string& text, const std::string& name) {
  using nlohmann::json;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond double's range.
    throw Error(name + ": not valid JSON (" + e.what() + ")");
  }
  auto fail = [&](const std::string& key, const std::string& what) -> Error {
    return Error(name + ": " + key + ": " + what);
  };
  if (!doc.is_object()) throw fail("(top)", "expected an object with \"frames\"");
  for (const auto& item : doc.items())
    if (item.key() != "frames") throw fail(item.key(), "unknown key (expected \"frames\")");
  if (!doc.contains("frames") || !doc["frames"].is_array() || doc["frames"].empty())
    throw fail("frames", "expected a non-empty array of {\"time\", \"bones\"}");
  Animation a;
  std::vector<std::vector<bool>> given;
  const json& frames = doc["frames"];
  for (size_t f = 0; f < frames.size(); ++f) {
    const std::string key = "frames[" + std::to_string(f) + "]";
    const json& frame = frames[f];
    if (!frame.is_object()) throw fail(key, "expected an object {\"time\", \"bones\"}");
    for (const auto& item : frame.items())
      if (item.key() != "time" && item.key() != "bones") throw fail(key + "." + item.key(), "unknown key");
    double time = static_cast<double>(f);
    if (frame.contains("time")) {
      if (!frame["time"].is_number() || !std::isfinite(frame["time"].get<double>()))
        throw fail(key + ".time", "expected a finite number");
      time = frame["time"].get<double>();
    }
    if (f > 0 && !(time > a.times.back())) throw fail(key + ".time", "frame times must increase");
    a.times.push_back(time);
    if (!frame.contains("bones") || !frame["bones"].is_object())
      throw fail(key + ".bones", "expected an object of bone name: 4x4 matrix");
    a.transforms.emplace_back(a.bones.size(), identity_matrix4());
    given.emplace_back(a.bones.size(), false);
    for (const auto& item : frame["bones"].items()) {
      const std::string bone_key = key + ".bones." + item.key();
      const json& rows = item.value();
      Matrix4 m{};
      if (!rows.is_array() || rows.size() != 4) throw fail(bone_key, "expected 4 rows of 4 numbers");
      for (int r = 0; r < 4; ++r) {
        if (!rows[r].is_array() || rows[r].size() != 4) throw fail(bone_key, "expected 4 rows of 4 numbers");
        for (int c = 0; c < 4; ++c) {
          if (!rows[r][c].is_number()) throw fail(bone_key, "expected 4 rows of 4 numbers");
          m[4 * r + c] = rows[r][c].get<double>();
        }
      }
      check_matrix(m, name + ": " + bone_key);
      const size_t b = bone_index(a, item.key());
      if (f > 0 && b >= given[0].size())
        throw fail(bone_key, "bone '" + item.key() + "' is not in frame 0 (every frame gives every bone)");
      a.transforms[f].resize(a.bones.size(), identity_matrix4());
      given[f].resize(a.bones.size(), false);
      a.transforms[f][b] = m;
      given[f][b] = true;
    }
  }
  check_complete(a, given, [&](size_t f, size_t b) {
    return name + ": frames[" + std::to_string(f) + "].bones: bone '" + a.bones[b] +
           "' is missing (every frame gives every bone)";
  });
  if (a.bones.empty()) throw fail("frames", "no frame names a bone");
  return a;
}

Animation parse_animation_csv(const std::string& text, const std::string& name) {
  struct Row {
    size_t frame;
    std::string bone;
    Matrix4 m;
    int line;
  };
  std::vector<Row> rows;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    const bool header = first && line.compare(start, 5, "frame") == 0;
    first = false;
    if (header) continue;
    std::vector<std::string> fields;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      const size_t a = cell.find_first_not_of(" \t"), b = cell.find_last_not_of(" \t");
      fields.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
    }
    if (!line.empty() && line.back() == ',') fields.push_back("");
    const std::string where = name + ":" + std::to_string(number);
    if (fields.size() != 18) {
      throw Error(where + ": expected 18 comma-separated values (frame, bone, m00 .. m33 row by row), got " +
                  std::to_string(fields.size()));
    }
    Row row;
    row.line = number;
    {
      std::istringstream f(fields[0]);
      f.imbue(std::locale::classic());
      long long frame = -1;
      if (!(f >> frame) || !f.eof() || frame < 0)
        throw Error(where + ": the frame '" + fields[0] + "' is not an integer >= 0");
      row.frame = static_cast<size_t>(frame);
    }
    row.bone = fields[1];
    if (row.bone.empty()) throw Error(where + ": the bone name is empty");
    for (int i = 0; i < 16; ++i) {
      std::istringstream v(fields[2 + i]);
      v.imbue(std::locale::classic());
      double value = 0.0;
      if (!(v >> value) || !(v >> std::ws).eof())
        throw Error(where + ": bone '" + row.bone + "': m" + std::to_string(i / 4) + std::to_string(i % 4) + " '" +
                    fields[2 + i] + "' is not a number");
      row.m[i] = value;
    }
    check_matrix(row.m, where + ": bone '" + row.bone + "'");
    rows.push_back(row);
  }
  if (rows.empty()) throw Error(name + ": no animation lines (frame,bone,m00..m33)");

  Animation a;
  size_t frames = 0;
  for (const Row& r : rows) {
    bone_index(a, r.bone);
    // Frames are numbered from 0 without gaps, each with a line per bone: a
    // number beyond the line count is a gap (and must not size the tables;
    // one past it still names the missing frame below).
    if (r.frame > rows.size())
      throw Error(name + ":" + std::to_string(r.line) + ": frame " + std::to_string(r.frame) + ", but the file has " +
                  std::to_string(rows.size()) +
                  " animation lines (frames are numbered from 0 without gaps, every frame gives every bone)");
    frames = std::max(frames, r.frame + 1);
  }
  a.times.resize(frames);
  for (size_t f = 0; f < frames; ++f) a.times[f] = static_cast<double>(f);
  a.transforms.assign(frames, std::vector<Matrix4>(a.bones.size(), identity_matrix4()));
  std::vector<std::vector<int>> line_of(frames, std::vector<int>(a.bones.size(), 0));
  for (const Row& r : rows) {
    const size_t b = bone_index(a, r.bone);
    if (line_of[r.frame][b])
      throw Error(name + ":" + std::to_string(r.line) + ": bone '" + r.bone + "' of frame " + std::to_string(r.frame) +
                  " was given already on line " + std::to_string(line_of[r.frame][b]));
    line_of[r.frame][b] = r.line;
    a.transforms[r.frame][b] = r.m;
  }
  std::vector<std::vector<bool>> given(frames, std::vector<bool>(a.bones.size()));
  for (size_t f = 0; f < frames; ++f)
    for (size_t b = 0; b < a.bones.size(); ++b) given[f][b] = line_of[f][b] != 0;
  check_complete(a, given, [&](size_t f, size_t b) {
    return name + ": frame " + std::to_string(f) + " has no line for bone '" + a.bones[b] +
           "' (every frame gives every bone; frames are numbered from 0 without gaps)";
  });
  return a;
}

Animation read_animation(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the animation file");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string extension = lower(std::filesystem::path(path).extension().string());
  if (extension == ".json") return parse_animation_json(text.str(), path);
  if (extension == ".csv") return parse_animation_csv(text.str(), path);
  throw Error(path + ": unknown animation format '" + extension + "' (expected .json or .csv)");
}

}  // namespace snh
