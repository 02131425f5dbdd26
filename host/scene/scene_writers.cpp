// The outputs of a scene run: the .vtu series with its .pvd, the embedded
// surface as OBJ, and the JSON summary of the records.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scene/obstacle_surface.h"
#include "scene/profile_json.h"
#include "scene/solver_json.h"
#include "snh/error.h"
#include "snh/fields.h"
#include "snh/io.h"
#include "snh/pieces.h"
#include "snh/rig.h"
#include "snh/scene.h"

namespace snh {
namespace {

using json = nlohmann::ordered_json;
using scene_io::add_solver_json;
using scene_io::history_json;
using scene_io::profile_json;

// The skin's bind-pose bounding box.
std::pair<std::array<double, 3>, std::array<double, 3>> character_bounds(const Character& c) {
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  const std::vector<double>& x = c.surface.positions.xyz();
  for (size_t i = 0; i + 2 < x.size(); i += 3)
    for (int d = 0; d < 3; ++d) {
      lo[d] = i == 0 ? x[d] : std::min(lo[d], x[i + d]);
      hi[d] = i == 0 ? x[d] : std::max(hi[d], x[i + d]);
    }
  return {lo, hi};
}

// What reading and preparing a character repaired, the voxelizer's surface
// warnings (printed with the surface's defects) left out.
std::vector<std::string> character_repairs(const SceneFile::CharacterSection& c) {
  std::vector<std::string> out = c.character.warnings;
  const size_t surface = c.rig.voxels.warnings.size();
  for (size_t k = surface; k < c.rig.warnings.size(); ++k) out.push_back(c.rig.warnings[k]);
  return out;
}

void create_parent(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

// Displacement per vertex and the element fields (F, J, P, Cauchy, von
// Mises, energy density) of positions x, for ParaView. Where the fields are
// undefined (a non-finite state, or an inverted element of a material
// undefined for J <= 0) the file still shows the positions, without them.
void write_step_vtu(const std::string& path, const Mesh& mesh, const MaterialMap& materials, const Points& x,
                    std::vector<std::string>& warnings) {
  std::vector<double> displacement(x.xyz().size());
  const double *now = x.data(), *rest = mesh.positions.data();
  for (size_t i = 0; i < displacement.size(); ++i) displacement[i] = now[i] - rest[i];
  std::vector<VtuCellField> cell_fields;
  try {
    cell_fields = element_fields_for_vtu(compute_element_fields(mesh, materials, x), materials);
  } catch (const Error& e) {
    warnings.push_back(path + " has no element fields: " + e.what());
  }
  write_vtu(path, mesh, x, {{"displacement", 3, displacement}}, cell_fields);
}

std::string numbered(const std::string& stem, int index) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d.vtu", index);
  return stem + number;
}

json summary_json(const Scene& scene, const SolveOptions& options, const SolveResult& r,
                  const std::vector<SceneStep>& shapes) {
  json j;
  j["scene"] = scene.name;
  j["element_type"] = to_string(scene.mesh.type);
  j["elements"] = scene.mesh.element_count();
  j["dofs"] = 3 * scene.mesh.vertex_count();
  j["device"] = r.device.platform + " / " + r.device.name;
  j["precision"] = to_string(options.precision);
  j["kernel_specialization"] = r.kernel_specialization;
  j["youngs_modulus"] = scene.material.youngs_modulus();
  j["poisson_ratio"] = scene.material.poisson_ratio();
  j["barrier"] = scene.material.barrier;
  add_solver_json(j, options, r);
  if (options.dynamics) {
    const DynamicsOptions& d = *options.dynamics;
    j["dynamics"] = {{"time_step", d.time_step},
                     {"density", d.density},
                     {"damping", {{"mass", d.damping.mass}, {"stiffness", d.damping.stiffness}}},
                     {"substeps", d.substeps}};
  }
  if (!options.obstacles.empty() || options.contact.self) {
    j["obstacles"] = options.obstacles.size();
    j["contact"] = {{"stiffness", options.contact.stiffness},
                    {"thickness", options.contact.thickness},
                    {"self", options.contact.self}};
    if (options.contact.self && options.contact.self_method == SelfContactMethod::penalty)
      j["contact"]["self_stiffness"] = options.contact.self_stiffness.value_or(0.0);  // 0: unset
    if (options.contact.self)
      j["contact"]["self_method"] = options.contact.self_method == SelfContactMethod::penalty ? "penalty" : "barrier";
  }
  j["steps"] = json::array();
  for (const StepResult& s : r.steps) {
    json step = {{"step", s.step},
                 {"newton_iterations", s.newton_iterations},
                 {"cg_iterations", s.cg_iterations},
                 {"converged", s.converged},
                 {"status", to_string(s.status)},
                 {"residual", s.residual_norm},
                 {"seconds", s.seconds},
                 {"contacts", s.contacts},
                 {"max_penetration", s.max_penetration},
                 {"inverted_elements", s.inverted_elements},
                 {"warnings", s.warnings},
                 {"profile", profile_json(s.profile)}};
    if (options.preconditioner == Preconditioner::multigrid || s.preconditioner_builds > 0)
      step["preconditioner_builds"] = s.preconditioner_builds;
    if (options.dynamics) step["time"] = s.time;
    if (options.contact.self) {
      step["self_contacts"] = s.self_contacts;
      step["max_self_penetration"] = s.max_self_penetration;
      if (options.contact.self_method == SelfContactMethod::barrier) {
        step["self_contact_pairs"] = s.self_contact_pairs;
        step["min_self_distance"] = s.min_self_distance;
        step["self_contact_seconds"] = s.self_contact_seconds;
      }
    }
    const size_t k = j["steps"].size();
    if (k < shapes.size() && shapes[k].shape.defined) {
      const StepShape& sh = shapes[k].shape;
      step["volume_ratio"] = sh.volume_ratio;
      step["min_j"] = sh.min_j;
      step["rigid_fit_rms"] = sh.rigid_fit_rms;
      step["rigid_fit_rms_relative"] = sh.rigid_fit_rms_relative;
    } else if (std::isfinite(s.min_j)) {
      step["min_j"] = s.min_j;
    }
    j["steps"].push_back(step);
  }
  j["wall_seconds"] = r.seconds;
  j["profile"] = profile_json(r.profile);
  j["device_memory_bytes"] = r.device_memory_bytes;
  j["final_residual"] = r.final_residual_norm;
  j["tolerance"] = r.tolerance;  // the absolute residual norm Newton stopped at
  j["converged"] = r.converged;
  j["volume_ratio"] = r.volume_ratio;
  j["min_j"] = r.min_j;
  j["max_j"] = r.max_j;
  j["inverted_elements"] = r.inverted_elements;
  j["warnings"] = r.warnings;
  j["history"] = history_json(r.history);
  return j;
}

// Per step, the force and torque every constraint set exerts on the body,
// the torque about the set's current centroid (fields.h).
json reactions_json(const std::vector<Reaction>& reactions) {
  json out = json::array();
  for (const Reaction& r : reactions)
    out.push_back({{"name", r.name}, {"force", r.force}, {"torque", r.torque}, {"about", r.about}});
  return out;
}

// The regions of a scene file: name, material, small-strain E and nu, and
// element count.
json regions_json(const MaterialMap& materials) {
  json out = json::array();
  for (size_t k = 1; k < materials.materials.size(); ++k) {
    const Material& m = materials.materials[k];
    const LameParameters l = m.lame();
    out.push_back({{"name", materials.names[k]},
                   {"material", m.description()},
                   {"youngs_modulus", l.mu * (3 * l.lambda + 2 * l.mu) / (l.lambda + l.mu)},
                   {"poisson_ratio", l.lambda / (2 * (l.lambda + l.mu))},
                   {"elements", std::count(materials.element_material.begin(), materials.element_material.end(),
                                           static_cast<int32_t>(k))}});
  }
  return out;
}

// "output.check_intersections": each step's or frame's count.
void add_intersections_json(json& records, const std::vector<SelfIntersections>& counts) {
  for (size_t i = 0; i < counts.size() && i < records.size(); ++i) {
    records[i]["surface_intersections"] = counts[i].intersecting_pairs;
    records[i]["surface_degenerate_triangles"] = counts[i].degenerate_triangles;
    json pairs = json::array();
    for (const auto& p : counts[i].first_pairs) pairs.push_back({p[0], p[1]});
    records[i]["surface_intersection_pairs"] = pairs;
  }
}

json load_steps_json(const SceneFile& file, const SceneRun& run) {
  const SolveResult& r = run.result;
  const Material& material = file.material;
  json j = summary_json(file.scene, run.options, r, run.steps);
  for (const std::string& w : run.warnings) j["warnings"].push_back(w);
  // Self-contact off: what the detector measured after each step.
  for (size_t i = 0; i < run.steps.size() && i < j["steps"].size(); ++i) {
    if (!run.steps[i].self_contact_measured) continue;
    j["steps"][i]["unresolved_self_contacts"] = run.steps[i].unresolved_self_contacts;
    j["steps"][i]["max_self_penetration"] = run.steps[i].max_self_penetration;
  }
  j["tolerance"] = r.tolerance;
  j["model"] = to_string(material.model);
  j["material"] = material.description();
  j["alpha"] = material.alpha_mu;
  j["alpha_lambda"] = material.alpha_lambda;
  if (material.lambda_model) j["lambda_model"] = to_string(*material.lambda_model);
  if (!file.materials.uniform()) j["regions"] = regions_json(file.materials);
  for (size_t i = 0; i < run.steps.size() && i < j["steps"].size(); ++i)
    if (run.steps[i].reactions) j["steps"][i]["reactions"] = reactions_json(*run.steps[i].reactions);
  add_intersections_json(j["steps"], run.surface_intersections);
  return j;
}

json frames_json(const SceneFile& file, const SceneRun& run) {
  const Scene& scene = file.scene;
  const SolveOptions& options = run.options;
  double seconds = 0.0;
  SolveProfile profile;
  size_t device_memory = 0;
  for (const FrameRecord& r : run.frames) {
    seconds += r.seconds;
    profile += r.profile;
    device_memory = std::max(device_memory, r.device_memory_bytes);
  }
  json j;
  j["scene"] = scene.name;
  j["element_type"] = to_string(scene.mesh.type);
  j["elements"] = scene.mesh.element_count();
  j["dofs"] = 3 * scene.mesh.vertex_count();
  j["device"] = run.device.platform + " / " + run.device.name;
  j["precision"] = to_string(options.precision);
  if (!run.frames.empty()) {  // every frame runs on the same engine: the last frame's
    j["kernel_specialization"] = run.frames.back().kernel_specialization;
    add_solver_json(j, options, run.frames.back());
  }
  j["load_steps_per_frame"] = options.load_steps;
  j["converged"] = run.converged;
  j["warnings"] = run.warnings;
  j["seconds"] = seconds;
  j["profile"] = profile_json(profile);      // summed over the frames
  j["device_memory_bytes"] = device_memory;  // the largest frame's
  j["frames"] = json::array();
  for (const FrameRecord& r : run.frames) {
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
                           {"warnings", r.warnings},
                           {"reactions", reactions_json(r.reactions)},
                           {"history", history_json(r.history)}});
    const size_t k = j["frames"].size() - 1;
    if (options.contact.self && options.contact.self_method == SelfContactMethod::barrier) {
      j["frames"][k]["self_contact_pairs"] = r.self_contact_pairs;
      j["frames"][k]["min_self_distance"] = r.min_self_distance;
      j["frames"][k]["self_contact_seconds"] = r.self_contact_seconds;
    }
    // A character's: the simulated surface against its skinned one.
    if (k < run.skin_deviation.size()) {
      j["frames"][k]["lbs_max_distance"] = run.skin_deviation[k].max_distance;
      j["frames"][k]["lbs_mean_distance"] = run.skin_deviation[k].mean_distance;
    }
  }
  add_intersections_json(j["frames"], run.surface_intersections);
  return j;
}

// The set-up: the lattice's pieces ("embed") and each bone's captured
// lattice vertices ("rig").
void add_setup_json(json& j, const SceneFile& file) {
  if (file.embedded) {
    json pieces = json::array();
    for (const LatticePiece& p : file.embedded->pieces) {
      json piece = {{"cells", p.elements.size()},
                    {"vertices", p.vertices},
                    {"min", p.lo},
                    {"max", p.hi},
                    {"held", to_string(p.hold)},
                    {"held_by", p.held_by},
                    {"outcome", p.outcome.empty() ? "kept" : p.outcome}};
      if (p.outcome == "attached") {
        piece["added_cells"] = p.added_cells;
        piece["joined_through"] = p.joined_through;
      }
      if (!p.nearest_bone.empty())
        piece["nearest_bone"] = {{"name", p.nearest_bone}, {"distance", p.nearest_bone_distance}};
      pieces.push_back(piece);
    }
    j["lattice_pieces"] = {{"rule", to_string(file.embedded->piece_rule)},
                           {"found", std::max<size_t>(1, file.embedded->pieces.size())},
                           {"now", file.embedded->voxels.components},
                           {"pieces", pieces},
                           {"warnings", file.embedded->piece_warnings}};
  }
  if (file.character) {
    const SceneFile::CharacterSection& c = *file.character;
    const auto [lo, hi] = character_bounds(c.character);
    j["character"] = {{"file", c.character.file},
                      {"vertices", c.character.surface.vertex_count()},
                      {"joints", c.character.joints.size()},
                      {"bounding_box", {{"min", lo}, {"max", hi}}},
                      {"cell", c.rig.cell},
                      {"resolution", c.resolution.value_or(0)},  // 0: "cell" given
                      {"vertices_outside", c.rig.vertices_outside},
                      {"max_outside_distance", c.rig.max_outside_distance},
                      {"warnings", character_repairs(c)},
                      {"surface_warnings", c.rig.voxels.warnings}};
  }
  if (file.rig) {
    json bones = json::array();
    for (const Bone& bone : file.rig->bones) {
      size_t vertices = 0;
      for (const ConstraintSet& set : file.scene.constraints)
        if (set.name == bone.name) vertices = set.vertices.size();
      bones.push_back({{"name", bone.name}, {"vertices", vertices}});
    }
    j["bones"] = bones;
  }
}

}  // namespace

std::vector<std::string> scene_setup_report(const SceneFile& file) {
  std::vector<std::string> lines;
  if (file.embedded) {
    const auto& pieces = file.embedded->pieces;
    std::ostringstream s;
    if (pieces.size() < 2) {
      s << "lattice: 1 piece";
      lines.push_back(s.str());
    } else {
      s << "lattice: " << pieces.size() << " pieces (embed.pieces " << to_string(file.embedded->piece_rule) << "), now "
        << file.embedded->voxels.components;
      lines.push_back(s.str());
      for (size_t p = 0; p < pieces.size(); ++p) {
        std::ostringstream l;
        l << "  piece " << p + 1 << ": " << pieces[p].elements.size() << " cells, ";
        switch (pieces[p].hold) {
          case PieceHold::constraint:
            l << "held by constraint set '" << pieces[p].held_by << "'";
            break;
          case PieceHold::obstacle:
            l << "held by " << pieces[p].held_by << " at rest";
            break;
          case PieceHold::inertia:
            l << "held by its inertia only";
            break;
          case PieceHold::largest:
            l << "the body (nothing holds any piece)";
            break;
          case PieceHold::none:
            l << "held by nothing";
            break;
        }
        if (pieces[p].outcome == "attached")
          l << ", attached (cells added: " << pieces[p].added_cells << ", "
            << (pieces[p].joined_through == "surface" ? "along the surface"
                                                      : "straight line: no path along the surface")
            << ")";
        if (pieces[p].outcome == "dropped") l << ", dropped";
        if (!pieces[p].nearest_bone.empty())
          l << "; nearest bone '" << pieces[p].nearest_bone << "' at " << pieces[p].nearest_bone_distance;
        lines.push_back(l.str());
      }
    }
    for (const std::string& w : file.embedded->piece_warnings) lines.push_back("warning: " + w);
  }
  if (file.character) {
    const SceneFile::CharacterSection& c = *file.character;
    const auto [lo, hi] = character_bounds(c.character);
    std::ostringstream l;
    l << "character " << c.character.file << ": " << c.character.surface.vertex_count() << " vertices, "
      << c.character.joints.size() << " joints; bind pose " << hi[0] - lo[0] << " x " << hi[1] - lo[1] << " x "
      << hi[2] - lo[2] << " from (" << lo[0] << ", " << lo[1] << ", " << lo[2] << "); cell " << c.rig.cell;
    if (c.resolution) l << " (" << *c.resolution << " cells along the longest side)";
    lines.push_back(l.str());
    for (const std::string& w : character_repairs(c)) lines.push_back("warning: " + w);
  }
  if (file.rig)
    for (const Bone& bone : file.rig->bones) {
      size_t vertices = 0;
      for (const ConstraintSet& set : file.scene.constraints)
        if (set.name == bone.name) vertices = set.vertices.size();
      lines.push_back("bone '" + bone.name + "': " + std::to_string(vertices) + " lattice vertices");
    }
  return lines;
}

std::string surface_obj_path(const std::string& prefix, const std::string& scene, int index) {
  char number[16];
  std::snprintf(number, sizeof number, "_%04d.obj", index);
  if (!prefix.empty() && (prefix.back() == '/' || std::filesystem::is_directory(prefix)))
    return (std::filesystem::path(prefix) / (scene + number)).string();
  return prefix + number;
}

SceneVtuSeries::SceneVtuSeries(std::string folder, const SceneFile& file, const SolveOptions& options)
    : folder_(std::move(folder)), file_(&file), options_(options) {
  std::filesystem::create_directories(folder_);
  // Obstacles are drawn to the rest bounding box's diagonal either side of
  // its centre (obstacle_surface.h).
  const Mesh& mesh = file.scene.mesh;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = v == 0 ? mesh.positions(v, k) : std::min(lo[k], mesh.positions(v, k));
      hi[k] = v == 0 ? mesh.positions(v, k) : std::max(hi[k], mesh.positions(v, k));
    }
  middle_ = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  extent_ = std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

SceneStepWriter SceneVtuSeries::writer() {
  return [this](int index, double time, const Points& x, const Points& surface) {
    const SceneFile& file = *file_;
    const std::string& name = file.scene.name;
    const std::string lattice = numbered(name, index);
    write_step_vtu(folder_ + "/" + lattice, file.scene.mesh, file.materials, x, warnings_);
    written_.push_back({time, lattice, 0});
    if (file.rig) {
      if (file.embedded) {  // part 1: the embedded surface
        const TriangleSurface& skin = file.embedded->surface;
        std::vector<double> displacement(surface.xyz().size());
        const double *now = surface.data(), *rest = skin.positions.data();
        for (size_t i = 0; i < displacement.size(); ++i) displacement[i] = now[i] - rest[i];
        const std::string skin_file = numbered(name + "_surface", index);
        write_surface_vtu(folder_ + "/" + skin_file, skin, surface, {{"displacement", 3, displacement}});
        written_.push_back({time, skin_file, 1});
      }
      // part 2: the bones where the frame puts them
      const std::string bones_file = numbered(name + "_bones", index);
      const std::vector<Bone>& bones = file.rig->bones;
      write_bone_mesh_vtu(folder_ + "/" + bones_file,
                          bone_mesh(bones, bone_transforms_at(bones, file.rig->animation, std::max(index, 0))));
      written_.push_back({time, bones_file, 2});
    } else if (!options_.obstacles.empty()) {  // part 1: the obstacles where the solver places them
      const std::string obstacles = numbered(name + "_obstacles", index);
      const double t = static_cast<double>(index) / options_.load_steps;
      write_surface_vtu(folder_ + "/" + obstacles, scene_io::obstacle_surface(options_.obstacles, t, middle_, extent_));
      written_.push_back({time, obstacles, 1});
    }
  };
}

void SceneVtuSeries::finish() { write_pvd_parts(folder_ + "/" + file_->scene.name + ".pvd", written_); }

SceneStepWriter surface_obj_writer(const std::string& prefix, const SceneFile& file) {
  if (!file.embedded) throw Error("scene " + file.scene.name + ": an OBJ surface output needs \"embed\"");
  return [prefix, &file](int index, double, const Points&, const Points& surface) {
    const std::string obj = surface_obj_path(prefix, file.scene.name, index);
    create_parent(obj);
    write_obj(obj, file.embedded->surface, surface);
  };
}

namespace {

// The resolved configuration (snh/configuration.h): per setting its value
// and the reason for it, in the resolver's order.
json resolved_json(const ResolvedConfiguration& config) {
  json j = json::object();
  for (const ResolvedSetting& s : config.settings) j[s.name] = {{"value", s.value}, {"reason", s.reason}};
  return j;
}

}  // namespace

void write_scene_json(const std::string& path, const SceneFile& file, const SceneRun& run) {
  create_parent(path);
  std::ofstream out(path);
  if (!out) throw Error("cannot write " + path);
  json j = file.rig ? frames_json(file, run) : load_steps_json(file, run);
  add_setup_json(j, file);
  j["resolved"] = resolved_json(run.resolved);
  out << j.dump(2) << '\n';
}

}  // namespace snh
