#include "rig_frames.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "profile_json.h"
#include "scene_output.h"
#include "snh/error.h"
#include "snh/frames.h"
#include "snh/io.h"
#include "snh/regions.h"
#include "solver_json.h"

namespace snh::bench {
namespace {

void create_parent(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

}  // namespace

int run_rig_scene(const SceneFile& file, const SolveOptions& options, const RigRunOutputs& outputs) {
  if (!file.rig) throw Error("scene " + file.scene.name + ": no \"rig\"");
  const Scene& scene = file.scene;
  Animation animation = file.rig->animation;
  if (outputs.max_frames > 0 && static_cast<size_t>(outputs.max_frames) < animation.frame_count()) {
    animation.times.resize(outputs.max_frames);
    animation.transforms.resize(outputs.max_frames);
  }
  const Embedding* embedding = file.embedded ? &file.embedded->embedding : nullptr;
  std::cerr << "scene " << scene.name << ": " << scene.description << "; " << scene.mesh.element_count() << " "
            << to_string(scene.mesh.type) << " elements, " << 3 * scene.mesh.vertex_count() << " dofs, "
            << file.rig->bones.size() << " bones, " << animation.frame_count() << " frames of " << options.load_steps
            << " load step(s), " << to_string(options.precision);
  if (embedding) std::cerr << "; surface of " << file.embedded->surface.vertex_count() << " vertices";
  std::cerr << '\n';

  const MaterialMap& materials = file.materials;
  Simulation simulation(scene.mesh, materials, scene.constraints, options);
  if (!outputs.vtu_dir.empty()) std::filesystem::create_directories(outputs.vtu_dir);
  std::vector<PvdDataSet> written;
  FrameOptions frame_options;
  frame_options.load_steps = options.load_steps;
  const size_t frames = animation.frame_count();
  const std::vector<FrameRecord> records =
      run_frames(simulation, animation, embedding, frame_options,
                 [&](const FrameRecord& r, const std::vector<double>& x, const std::vector<double>& surface) {
                   std::cerr << "  frame " << r.frame + 1 << "/" << frames << " (t = " << r.time << "): " << r.status
                             << ", " << r.newton_iterations << " Newton, " << r.cg_iterations << " CG, "
                             << std::setprecision(3) << r.seconds << " s, min J " << r.min_j << '\n';
                   if (!outputs.surface_prefix.empty()) {
                     const std::string obj = surface_obj_path(outputs.surface_prefix, scene.name, r.frame);
                     create_parent(obj);
                     write_obj(obj, file.embedded->surface, surface);
                   }
                   if (!outputs.vtu_dir.empty()) {
                     char name[64];
                     std::snprintf(name, sizeof name, "_%04d.vtu", r.frame);
                     const std::string lattice = scene.name + name, skin = scene.name + "_surface" + name;
                     write_step_vtu(outputs.vtu_dir + "/" + lattice, scene.mesh, materials, x);
                     written.push_back({r.time, lattice, 0});
                     if (embedding) {
                       std::vector<double> displacement(surface.size());
                       for (size_t i = 0; i < surface.size(); ++i)
                         displacement[i] = surface[i] - file.embedded->surface.positions[i];
                       write_surface_vtu(outputs.vtu_dir + "/" + skin, file.embedded->surface, surface,
                                         {{"displacement", 3, displacement}});
                       written.push_back({r.time, skin, 1});
                     }
                   }
                   return true;
                 });
  if (!outputs.vtu_dir.empty()) write_pvd_parts(outputs.vtu_dir + "/" + scene.name + ".pvd", written);

  bool all = true;
  double seconds = 0.0;
  SolveProfile profile;
  size_t device_memory = 0;
  std::cout << "frame  newton  cg      status                 residual   min J\n";
  for (const FrameRecord& r : records) {
    all = all && r.converged;
    seconds += r.seconds;
    profile += r.profile;
    device_memory = std::max(device_memory, r.device_memory_bytes);
    std::cout << std::left << std::setw(7) << r.frame << std::setw(8) << r.newton_iterations << std::setw(8)
              << r.cg_iterations << std::setw(23) << r.status << std::setw(11) << std::setprecision(3)
              << r.residual_norm << std::setprecision(4) << r.min_j << '\n';
  }
  std::cout << "all frames converged " << (all ? "yes" : "no") << ", " << std::setprecision(4) << seconds
            << " s solving, " << records.size() << " frames\n";
  if (!outputs.json_path.empty()) {
    create_parent(outputs.json_path);
    std::ofstream out(outputs.json_path);
    if (!out) throw Error("cannot write " + outputs.json_path);
    nlohmann::ordered_json j;
    j["scene"] = scene.name;
    j["element_type"] = to_string(scene.mesh.type);
    j["elements"] = scene.mesh.element_count();
    j["dofs"] = 3 * scene.mesh.vertex_count();
    j["device"] = simulation.device().platform + " / " + simulation.device().name;
    j["precision"] = to_string(options.precision);
    if (!records.empty()) {  // every frame runs on the same engine: the last frame's
      j["kernel_specialization"] = records.back().kernel_specialization;
      add_solver_json(j, options, records.back());
    }
    j["load_steps_per_frame"] = options.load_steps;
    j["converged"] = all;
    j["seconds"] = seconds;
    j["profile"] = profile_json(profile);      // summed over the frames
    j["device_memory_bytes"] = device_memory;  // the largest frame's
    j["frames"] = nlohmann::ordered_json::array();
    for (const FrameRecord& r : records)
      j["frames"].push_back({{"frame", r.frame},
                             {"time", r.time},
                             {"converged", r.converged},
                             {"status", to_string(r.status)},
                             {"newton_iterations", r.newton_iterations},
                             {"cg_iterations", r.cg_iterations},
                             {"residual", r.residual_norm},
                             {"seconds", r.seconds},
                             {"profile", profile_json(r.profile)},
                             {"volume_ratio", r.volume_ratio},
                             {"min_j", r.min_j},
                             {"inverted_elements", r.inverted_elements},
                             {"history", history_json(r.history)}});
    out << j.dump(2) << '\n';
  }
  return all ? 0 : 3;
}

}  // namespace snh::bench
