// A scene file's "character" section (docs/scene-files.md): read by the
// loader, run by run_scene.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "scene/scene_json.h"
#include "snh/scene.h"

namespace snh::scene_io {

// Reads "character": the skinned file, its clip, the lattice and the bones.
SceneFile::CharacterSection read_character_section(const SceneJson& r, const nlohmann::json& c,
                                                   const std::filesystem::path& folder);

// The character's frames on one simulation (run_character_frames), each
// handed to the progress callback and the writers.
SceneRun run_character_scene(const SceneFile& file, const SolveOptions& options, const SceneRunOptions& run);

}  // namespace snh::scene_io
