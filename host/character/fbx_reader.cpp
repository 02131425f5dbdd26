// Reading a skinned FBX character through ufbx (fbx_reader.h). ufbx's types
// stay in this file.
//
// The file is loaded as stored: no target axes or unit (ufbx converts
// nothing unless asked), so control points and matrices are in the file's
// own units and axes, and positions in each mesh's geometry space, as
// Blender's FBX importer keeps its mesh vertices.
#include "character/fbx_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "character/clip_selection.h"
#include "character/reader_messages.h"
#include "snh/error.h"
#include "third_party/ufbx/ufbx.h"

namespace snh::detail {
namespace {

std::string text(const ufbx_string& s) { return std::string(s.data, s.length); }

// ufbx_matrix is an affine 3x4 matrix stored by columns; Matrix4 is 4x4 by
// rows.
Matrix4 to_matrix4(const ufbx_matrix& m) {
  return {m.m00, m.m01, m.m02, m.m03, m.m10, m.m11, m.m12, m.m13, m.m20, m.m21, m.m22, m.m23, 0.0, 0.0, 0.0, 1.0};
}

bool finite(const Matrix4& m) {
  return std::all_of(m.begin(), m.end(), [](double v) { return std::isfinite(v); });
}

bool close(const Matrix4& a, const Matrix4& b) {
  for (int k = 0; k < 16; ++k)
    if (std::abs(a[k] - b[k]) > 1e-6 * (1.0 + std::abs(b[k]))) return false;
  return true;
}

std::string ufbx_text(const ufbx_error& e) {
  std::string s = text(e.description);
  if (e.info_length > 0) s += ": " + std::string(e.info, e.info_length);
  return s;
}

struct SceneFree {
  void operator()(ufbx_scene* s) const { ufbx_free_scene(s); }
};
using ScenePtr = std::unique_ptr<ufbx_scene, SceneFree>;

// What ufbx may allocate while loading a file of `bytes` bytes, in each of
// its two allocators: an array's header gives its element count, and ufbx
// allocates that much before it reads (or inflates) the data, so a few
// corrupt bytes asked for gigabytes. Deflate expands at most 1032-fold; a
// real file stays far below this, a corrupt count is refused.
size_t fbx_memory_limit(uintmax_t bytes) {
  constexpr size_t kFloor = size_t(256) << 20;
  if (bytes > (SIZE_MAX - kFloor) / 1100) return SIZE_MAX;
  return kFloor + static_cast<size_t>(bytes) * 1100;
}

// A joint: a bone node, or a cluster whose bone node is missing (by name).
struct JointSource {
  const ufbx_node* node = nullptr;
  std::string name;
  Matrix4 geometry_to_bone;
};

// The scene as the file stores it (nothing converted), ufbx's allocations
// bounded by fbx_memory_limit.
ScenePtr load_fbx(const std::string& path) {
  ufbx_load_opts load{};
  // Clusters whose bone node is missing stay in their skin (held at their
  // bind pose: order_joints, read_clip) instead of being dropped with their
  // weights.
  load.connect_broken_elements = true;
  std::error_code size_error;
  const uintmax_t bytes = std::filesystem::file_size(path, size_error);
  load.temp_allocator.memory_limit = load.result_allocator.memory_limit = fbx_memory_limit(size_error ? 0 : bytes);
  ufbx_error error{};
  ScenePtr scene(ufbx_load_file(path.c_str(), &load, &error));
  if (!scene)
    fail(path, "cannot read the file (ufbx: " + ufbx_text(error) + ")" +
                   (error.type == UFBX_ERROR_MEMORY_LIMIT
                        ? ": it needs more than " + std::to_string(load.temp_allocator.memory_limit >> 20) +
                              " MiB (an array's element count is likely corrupt)"
                        : ""));
  return scene;
}

// What find_skinned_meshes gives.
struct SkinnedMeshes {
  std::vector<const ufbx_mesh*> meshes;
  std::vector<std::string> mesh_names;
  Matrix4 world_to_mesh{};
};

// The skinned meshes, their names for messages and the space they share.
SkinnedMeshes find_skinned_meshes(const std::string& path, const ufbx_scene& scene) {
  SkinnedMeshes out;
  std::vector<const ufbx_mesh*>& meshes = out.meshes;
  std::vector<std::string>& mesh_names = out.mesh_names;
  Matrix4 mesh_to_world{};
  for (size_t m = 0; m < scene.meshes.count; ++m) {
    const ufbx_mesh* mesh = scene.meshes.data[m];
    if (mesh->skin_deformers.count == 0) continue;
    const std::string name = "mesh " + std::to_string(m) + (mesh->name.length ? " '" + text(mesh->name) + "'" : "");
    if (mesh->instances.count == 0) fail(path, name + ": no node places it in the scene");
    const Matrix4 placed = to_matrix4(mesh->instances.data[0]->geometry_to_world);
    if (!finite(placed)) fail(path, name + ": its node's transform is not finite");
    if (meshes.empty())
      mesh_to_world = placed;
    else if (!close(placed, mesh_to_world))
      fail(path, name + " is placed differently from " + mesh_names[0] +
                     " (the skinned meshes' control points must share one space)");
    meshes.push_back(mesh);
    mesh_names.push_back(name);
  }
  if (meshes.empty()) fail(path, "no skinned mesh (no mesh has a skin deformer)");
  try {
    out.world_to_mesh = inverse_matrix4(mesh_to_world);
  } catch (const Error&) {
    fail(path, mesh_names[0] + ": its node's transform is singular");
  }
  return out;
}

// The joints' sources, and the joints' order (read_joint_sources, then
// order_joints).
struct FbxJoints {
  std::vector<JointSource> sources;
  std::map<const ufbx_node*, size_t> source_of_node;
  std::map<std::string, size_t> source_of_missing;
  std::map<const ufbx_skin_cluster*, size_t> source_of_cluster;
  std::vector<size_t> order;         // the sources in joint order
  std::vector<int> joint_of_source;  // index in Character::joints
};

// Joints: the clusters' bone nodes (a cluster without one by its name),
// one bind matrix per joint.
void read_joint_sources(const std::string& path, const std::vector<const ufbx_mesh*>& meshes, FbxJoints& joints) {
  std::vector<JointSource>& sources = joints.sources;
  for (size_t m = 0; m < meshes.size(); ++m)
    for (size_t d = 0; d < meshes[m]->skin_deformers.count; ++d) {
      const ufbx_skin_deformer* skin = meshes[m]->skin_deformers.data[d];
      for (size_t k = 0; k < skin->clusters.count; ++k) {
        const ufbx_skin_cluster* cluster = skin->clusters.data[k];
        const ufbx_node* node = cluster->bone_node;
        const std::string name = text(node ? node->name : cluster->name);
        const Matrix4 bind = to_matrix4(cluster->geometry_to_bone);
        if (!finite(bind)) fail(path, "joint '" + name + "': its bind matrix (geometry to bone) is not finite");
        size_t source = sources.size();
        if (node) {
          source = joints.source_of_node.emplace(node, source).first->second;
        } else {
          source = joints.source_of_missing.emplace(name, source).first->second;
        }
        if (source == sources.size())
          sources.push_back({node, name, bind});
        else if (!close(bind, sources[source].geometry_to_bone))
          fail(path, "joint '" + name + "': meshes give it different bind matrices");
        joints.source_of_cluster[cluster] = source;
      }
    }
}

// Joint order: bone nodes depth first from the root (parents before
// children), then the clusters without a bone node. Fills c.joints.
void order_joints(const std::string& path, const ufbx_scene& scene, FbxJoints& joints, Character& c) {
  const std::vector<JointSource>& sources = joints.sources;
  std::vector<size_t>& order = joints.order;
  joints.joint_of_source.assign(sources.size(), -1);
  std::map<const ufbx_node*, int> joint_of_node;
  std::vector<const ufbx_node*> stack{scene.root_node};
  while (!stack.empty()) {
    const ufbx_node* n = stack.back();
    stack.pop_back();
    const auto it = joints.source_of_node.find(n);
    if (it != joints.source_of_node.end()) order.push_back(it->second);
    for (size_t k = n->children.count; k-- > 0;) stack.push_back(n->children.data[k]);
  }
  for (const auto& [name, s] : joints.source_of_missing) order.push_back(s);
  std::sort(order.begin() + static_cast<std::ptrdiff_t>(order.size() - joints.source_of_missing.size()), order.end());
  if (order.size() != sources.size()) fail(path, "a skin cluster's bone node is not in the scene's hierarchy");
  std::vector<std::string> held;
  for (size_t s : order) {
    const JointSource& src = sources[s];
    Joint j;
    j.name = src.name;
    j.inverse_bind = src.geometry_to_bone;
    if (src.node)
      for (const ufbx_node* p = src.node->parent; p; p = p->parent) {
        const auto it = joint_of_node.find(p);
        if (it != joint_of_node.end()) {
          j.parent = it->second;
          break;
        }
      }
    else
      held.push_back("'" + src.name + "'");
    Matrix4 bind;
    try {
      bind = inverse_matrix4(j.inverse_bind);
    } catch (const Error&) {
      fail(path, "joint '" + src.name + "': its bind matrix (geometry to bone) is singular");
    }
    j.rest_position = {bind[3], bind[7], bind[11]};
    joints.joint_of_source[s] = static_cast<int>(c.joints.size());
    if (src.node) joint_of_node[src.node] = joints.joint_of_source[s];
    c.joints.push_back(j);
  }
  if (!held.empty()) {
    std::string list;
    for (size_t k = 0; k < held.size(); ++k) list += (k ? ", " : "") + held[k];
    c.warnings.push_back(std::to_string(held.size()) + (held.size() == 1 ? " joint has" : " joints have") +
                         " no bone node in the file and " + (held.size() == 1 ? "is" : "are") +
                         " held at the bind pose: " + list);
  }
}

// The skin: every skinned mesh's control points, its polygons as
// triangles, and the raw weights per control point. Fills c.surface and
// c.weights.
void read_skin(const std::string& path, const SkinnedMeshes& skinned, const FbxJoints& joints, Character& c) {
  const std::vector<const ufbx_mesh*>& meshes = skinned.meshes;
  const std::vector<std::string>& mesh_names = skinned.mesh_names;
  std::vector<std::vector<std::pair<int32_t, double>>> rows;
  std::vector<uint32_t> corners;
  for (size_t m = 0; m < meshes.size(); ++m) {
    const ufbx_mesh* mesh = meshes[m];
    const int32_t base = static_cast<int32_t>(c.surface.vertex_count());
    for (size_t v = 0; v < mesh->vertices.count; ++v) {
      const ufbx_vec3& p = mesh->vertices.data[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fail(path, mesh_names[m] + ": vertex " + std::to_string(v) + " has a non-finite position");
      c.surface.positions.push_back({p.x, p.y, p.z});
    }
    corners.resize(3 * std::max<size_t>(mesh->max_face_triangles, 1));
    for (size_t f = 0; f < mesh->faces.count; ++f) {
      const ufbx_face face = mesh->faces.data[f];
      if (face.num_indices < 3) continue;  // points and lines
      const uint32_t n = ufbx_triangulate_face(corners.data(), corners.size(), mesh, face);
      for (uint32_t k = 0; k < 3 * n; ++k)
        c.surface.triangles.push_back(base + static_cast<int32_t>(mesh->vertex_indices.data[corners[k]]));
    }
    rows.resize(c.surface.vertex_count());
    for (size_t d = 0; d < mesh->skin_deformers.count; ++d) {
      const ufbx_skin_deformer* skin = mesh->skin_deformers.data[d];
      const size_t count = std::min(skin->vertices.count, mesh->vertices.count);
      for (size_t v = 0; v < count; ++v) {
        const ufbx_skin_vertex& sv = skin->vertices.data[v];
        for (uint32_t k = 0; k < sv.num_weights; ++k) {
          const ufbx_skin_weight& w = skin->weights.data[sv.weight_begin + k];
          const int32_t j = joints.joint_of_source[joints.source_of_cluster.at(skin->clusters.data[w.cluster_index])];
          if (!std::isfinite(w.weight) || w.weight < 0.0)
            fail(path, mesh_names[m] + ": vertex " + std::to_string(v) + " has weight " + number(w.weight) +
                           " for joint '" + c.joints[j].name + "'");
          if (w.weight == 0.0) continue;
          auto& row = rows[static_cast<size_t>(base) + v];
          const auto same = std::find_if(row.begin(), row.end(), [&](const auto& jw) { return jw.first == j; });
          if (same != row.end())
            same->second += w.weight;  // two clusters of one bone
          else
            row.push_back({j, w.weight});
        }
      }
    }
  }
  if (c.surface.triangle_count() == 0) fail(path, "the skinned meshes have no triangles");
  for (auto& row : rows) {
    std::sort(row.begin(), row.end());
    for (const auto& [j, w] : row) {
      c.weights.joint.push_back(j);
      c.weights.weight.push_back(w);
    }
    c.weights.offset.push_back(static_cast<int32_t>(c.weights.joint.size()));
  }
}

// The clip: an anim stack. Fills c.clip_names and gives the index options
// select, or -1 for none (refused where options.require_clip).
int select_clip(const std::string& path, const ufbx_scene& scene, const CharacterReadOptions& options, Character& c) {
  for (size_t a = 0; a < scene.anim_stacks.count; ++a) c.clip_names.push_back(text(scene.anim_stacks.data[a]->name));
  return detail::select_clip(path, c.clip_names, options);
}

// Anim stack `clip`: its frame range checked, then each frame's skinning
// matrices from the scene ufbx evaluates at that time.
void read_clip(const std::string& path, const ufbx_scene& scene, const CharacterReadOptions& options, int clip,
               const SkinnedMeshes& skinned, const FbxJoints& joints, Character& c) {
  const ufbx_anim_stack* anim_stack = scene.anim_stacks.data[clip];
  const std::string clip_name = "clip '" + c.clip_names[clip] + "'";
  const double duration = anim_stack->time_end - anim_stack->time_begin;
  if (!std::isfinite(anim_stack->time_begin) || !std::isfinite(duration) || duration < 0.0)
    fail(path, clip_name + ": its duration is not finite");
  const int last = detail::begin_clip(path, clip_name, duration, clip, options, c);
  Matrix4 identity{};
  for (int k = 0; k < 4; ++k) identity[5 * k] = 1.0;
  ufbx_evaluate_opts evaluate{};
  ufbx_error error{};
  for (int f = options.first_frame; f <= last; ++f) {
    const double seconds = f / options.fps;
    const ScenePtr posed(
        ufbx_evaluate_scene(&scene, anim_stack->anim, anim_stack->time_begin + seconds, &evaluate, &error));
    if (!posed)
      fail(path, clip_name + ": frame " + std::to_string(f) + " cannot be evaluated (ufbx: " + ufbx_text(error) + ")");
    std::vector<Matrix4> skinning;
    for (const Joint& j : c.joints) {
      const JointSource& src = joints.sources[joints.order[skinning.size()]];
      if (!src.node) {
        skinning.push_back(identity);
        continue;
      }
      const ufbx_node* node = posed->nodes.data[src.node->typed_id];
      const Matrix4 m =
          multiply_matrix4(multiply_matrix4(skinned.world_to_mesh, to_matrix4(node->node_to_world)), j.inverse_bind);
      if (!finite(m))
        fail(path, clip_name + ": joint '" + j.name + "' at frame " + std::to_string(f) + " is not finite");
      skinning.push_back(m);
    }
    c.clip.times.push_back(seconds);
    c.clip.skinning.push_back(std::move(skinning));
  }
}

}  // namespace

Character read_fbx_character(const std::string& path, const CharacterReadOptions& options) {
  if (!(options.fps > 0.0) || !std::isfinite(options.fps)) fail(path, "fps must be > 0, got " + number(options.fps));
  if (options.first_frame < 0) fail(path, "the first frame must be >= 0, got " + std::to_string(options.first_frame));
  const ScenePtr scene = load_fbx(path);

  Character c;
  c.file = path;
  // What ufbx repaired while loading (broken indices and the like).
  for (size_t w = 0; w < scene->metadata.warnings.count; ++w) {
    const ufbx_warning& warning = scene->metadata.warnings.data[w];
    c.warnings.push_back("ufbx: " + text(warning.description) +
                         (warning.count > 1 ? " (" + std::to_string(warning.count) + " times)" : ""));
  }
  const SkinnedMeshes skinned = find_skinned_meshes(path, *scene);
  FbxJoints joints;
  read_joint_sources(path, skinned.meshes, joints);
  order_joints(path, *scene, joints, c);
  read_skin(path, skinned, joints, c);
  const int clip = select_clip(path, *scene, options, c);
  if (clip < 0) return c;
  read_clip(path, *scene, options, clip, skinned, joints, c);
  return c;
}

}  // namespace snh::detail
