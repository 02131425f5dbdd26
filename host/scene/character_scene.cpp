// A scene file's "character" section (scene/character_scene.h).
#include "scene/character_scene.h"

#include <algorithm>

#include "scene/scene_progress.h"
#include "snh/error.h"

namespace snh::scene_io {

using nlohmann::json;

SceneFile::CharacterSection read_character_section(const SceneJson& r, const json& c,
                                                   const std::filesystem::path& folder) {
  r.keys(c, "character");
  if (!c.contains("file")) r.fail("character.file", "missing (a skinned .gltf, .glb, .fbx or .dae)");
  const std::string file = (folder / r.text(c, "character", "file", "")).string();
  CharacterReadOptions options;
  if (c.contains("clip")) {
    if (c["clip"].is_string())
      options.clip = c["clip"].get<std::string>();
    else if (c["clip"].is_number_integer() && c["clip"].get<int>() >= 0)
      options.clip_index = c["clip"].get<int>();
    else
      r.fail("character.clip", "expected a clip name or an index >= 0");
  }
  options.fps = r.number(c, "character", "fps", options.fps);
  if (!(options.fps > 0.0)) r.fail("character.fps", "must be > 0");
  if (c.contains("frames")) {
    const json& f = c["frames"];
    if (!f.is_array() || f.size() != 2 || !f[0].is_number_integer() || !f[1].is_number_integer())
      r.fail("character.frames", "expected [first, last], two integers");
    options.first_frame = f[0].get<int>();
    options.last_frame = f[1].get<int>();
    if (options.first_frame < 0 || *options.last_frame < options.first_frame)
      r.fail("character.frames", "expected 0 <= first <= last");
  }
  if (c.contains("weights")) {
    const json& w = c["weights"];
    if (!w.is_string() || (w != "normalize" && w != "strict"))
      r.fail("character.weights", "expected \"normalize\" or \"strict\"");
    options.weights = w == "strict" ? WeightPolicy::strict : WeightPolicy::normalize;
  }
  if (c.contains("cell") == c.contains("resolution"))
    r.fail(c.contains("cell") ? "character.resolution" : "character.cell",
           c.contains("cell") ? "give \"cell\" or \"resolution\", not both"
                              : "missing (a cube side, or \"resolution\": cells along the longest side)");
  PieceRule pieces = PieceRule::attach;
  if (c.contains("pieces")) {
    try {
      pieces = parse_piece_rule(r.text(c, "character", "pieces", "attach"));
    } catch (const Error& e) {
      r.fail("character.pieces", e.what());
    }
  }
  double cell = 0.0;
  int resolution = 0;
  if (c.contains("cell")) {
    cell = r.required_number(c, "character", "cell");
    if (!(cell > 0.0)) r.fail("character.cell", "expected a cube side > 0");
  } else {
    if (!c["resolution"].is_number_integer() || c["resolution"].get<int>() < 1)
      r.fail("character.resolution", "expected an integer >= 1 (cells along the bind pose's longest side)");
    resolution = c["resolution"].get<int>();
  }
  CharacterBoneOptions bones;
  if (c.contains("bones")) {
    const json& b = c["bones"];
    r.keys(b, "character.bones");
    bones.radius_fraction = r.number(b, "character.bones", "radius_fraction", bones.radius_fraction);
    if (!(bones.radius_fraction > 0.0)) r.fail("character.bones.radius_fraction", "must be > 0");
    bones.joint_clearance = r.number(b, "character.bones", "joint_clearance", bones.joint_clearance);
    if (b.contains("exclude")) {
      if (!b["exclude"].is_array()) r.fail("character.bones.exclude", "expected an array of names or patterns");
      for (const json& p : b["exclude"]) {
        if (!p.is_string()) r.fail("character.bones.exclude", "expected an array of names or patterns");
        bones.exclude.push_back(p.get<std::string>());
      }
    }
    if (b.contains("radius")) {
      if (!b["radius"].is_object()) r.fail("character.bones.radius", "expected an object {joint: radius}");
      for (const auto& item : b["radius"].items()) {
        if (!item.value().is_number() || !(item.value().get<double>() > 0.0))
          r.fail("character.bones.radius." + item.key(), "expected a radius > 0");
        bones.radius[item.key()] = item.value().get<double>();
      }
    }
  }
  SceneFile::CharacterSection out;
  if (c.contains("skinned_guess")) {
    if (!c["skinned_guess"].is_boolean()) r.fail("character.skinned_guess", "expected true or false");
    out.skinned_guess = c["skinned_guess"].get<bool>();
  }
  try {
    out.character = read_character(file, options);
  } catch (const Error& e) {
    r.fail("character.file", e.what());
  }
  try {
    if (resolution > 0) {
      cell = character_cell(out.character, resolution);
      out.resolution = resolution;
    }
    CharacterPrepareOptions prepare;
    prepare.bones = bones;
    prepare.pieces = pieces;
    out.rig = prepare_character(out.character, cell, prepare);
  } catch (const Error& e) {
    r.fail("character", e.what());
  }
  return out;
}

SceneRun run_character_scene(const SceneFile& file, const SolveOptions& options, const SceneRunOptions& run) {
  const SceneFile::CharacterSection& c = *file.character;
  Simulation simulation(file.scene.mesh, file.materials, file.scene.constraints, options);
  SceneRun out;
  out.options = options;
  out.resolved = simulation.configuration();
  out.device = simulation.device();
  CharacterFrameOptions frame_options;
  frame_options.frames.load_steps = options.load_steps;
  frame_options.skinned_guess = c.skinned_guess;
  int frames = static_cast<int>(c.character.clip.frame_count());
  if (run.max_frames > 0) frames = std::min(frames, run.max_frames);
  int done = 0;
  const std::vector<CharacterFrame> records =
      run_character_frames(simulation, c.character, c.rig, frame_options,
                           [&](const CharacterFrame& f, const Points& x, const Points& surface, const Points&) {
                             const FrameRecord& r = f.record;
                             ++done;
                             if (run.progress) run.progress(frame_progress(r, done, frames));
                             for (const SceneStepWriter& w : run.writers)
                               if (w) w(r.frame, r.time, x, surface);
                             return done < frames;
                           });
  for (const CharacterFrame& f : records) {
    out.frames.push_back(f.record);
    out.skin_deviation.push_back(f.lbs);
  }
  out.converged = !out.frames.empty() &&
                  std::all_of(out.frames.begin(), out.frames.end(), [](const FrameRecord& r) { return r.converged; });
  return out;
}

}  // namespace snh::scene_io
