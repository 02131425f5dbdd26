// Reading a skinned character through assimp (snh/character.h). assimp's
// types stay in this file; FBX files go to the ufbx reader (fbx_reader.h)
// and both end in finish_character (weights, weld).
//
// The importer runs with aiProcess_Triangulate alone: no step that joins,
// splits or reorders vertices, so the surface keeps the file's vertex list
// (seams included) and the weld for the simulation is our own. assimp's
// Collada loader splits vertices per polygon corner; those are collapsed
// onto the file's <vertices> (collada_vertices.h).
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <unordered_map>

#include "character/clip_selection.h"
#include "character/collada_vertices.h"
#include "character/fbx_reader.h"
#include "character/reader_messages.h"
#include "character/skin_weights.h"
#include "snh/character.h"
#include "snh/error.h"

namespace snh {
namespace {

using detail::fail;
using detail::number;

Matrix4 to_matrix4(const aiMatrix4x4& m) {
  return {m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4};
}

double determinant3(const Matrix4& m) {  // of the upper-left 3x3 block
  return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) + m[2] * (m[4] * m[9] - m[5] * m[8]);
}

bool finite(const Matrix4& m) {
  return std::all_of(m.begin(), m.end(), [](double v) { return std::isfinite(v); });
}

// A key's value between keys: linear (positions, scales) or spherical
// (rotations) interpolation at the fraction of the way from key i to i+1,
// as assimp's own evaluators do; before the first key the first, after the
// last the last.
template <class Key>
size_t key_before(const Key* keys, unsigned count, double ticks, double& fraction) {
  fraction = 0.0;
  if (ticks <= keys[0].mTime) return 0;
  if (ticks >= keys[count - 1].mTime) return count - 1;
  size_t i = 0;
  while (i + 1 < count && keys[i + 1].mTime <= ticks) ++i;
  const double span = keys[i + 1].mTime - keys[i].mTime;
  fraction = span > 0.0 ? (ticks - keys[i].mTime) / span : 0.0;
  return i;
}

std::array<double, 3> sample_vector(const aiVectorKey* keys, unsigned count, double ticks,
                                    const std::array<double, 3>& fallback, bool step) {
  if (count == 0) return fallback;
  double f = 0.0;
  const size_t i = key_before(keys, count, ticks, f);
  if (step) f = 0.0;
  const aiVector3D& a = keys[i].mValue;
  if (f == 0.0) return {a.x, a.y, a.z};
  const aiVector3D& b = keys[i + 1].mValue;
  return {a.x + f * (double(b.x) - a.x), a.y + f * (double(b.y) - a.y), a.z + f * (double(b.z) - a.z)};
}

std::array<double, 4> sample_rotation(const aiQuatKey* keys, unsigned count, double ticks,
                                      const std::array<double, 4>& fallback, bool step) {
  if (count == 0) return fallback;
  double f = 0.0;
  const size_t i = key_before(keys, count, ticks, f);
  if (step) f = 0.0;
  const aiQuaternion& qa = keys[i].mValue;
  std::array<double, 4> a{qa.w, qa.x, qa.y, qa.z};
  if (f != 0.0) {
    const aiQuaternion& qb = keys[i + 1].mValue;
    std::array<double, 4> b{qb.w, qb.x, qb.y, qb.z};
    double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (c < 0.0) {  // the shorter arc
      c = -c;
      for (double& v : b) v = -v;
    }
    double s0 = 1.0 - f, s1 = f;
    if (1.0 - c > 1e-9) {
      const double omega = std::acos(std::min(c, 1.0)), so = std::sin(omega);
      s0 = std::sin((1.0 - f) * omega) / so;
      s1 = std::sin(f * omega) / so;
    }
    for (int k = 0; k < 4; ++k) a[k] = s0 * a[k] + s1 * b[k];
  }
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3]);
  for (double& v : a) v /= n;
  return a;
}

// A node's rest transform as translation, rotation and scale.
void decompose(const aiMatrix4x4& m, std::array<double, 3>& t, std::array<double, 4>& q, std::array<double, 3>& s) {
  aiVector3D ts, ss;
  aiQuaternion qs;
  m.Decompose(ss, qs, ts);
  t = {ts.x, ts.y, ts.z};
  q = {qs.w, qs.x, qs.y, qs.z};
  s = {ss.x, ss.y, ss.z};
}

// Whether `path` names a glTF file (.gltf, or binary .glb) by its extension.
bool is_gltf_path(const std::string& path) {
  std::string ext = path.size() >= 5 ? path.substr(path.size() - 5) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext == ".gltf" || ext.substr(1) == ".glb";
}

// A .gltf's JSON, or a .glb's first chunk's; discarded (is_discarded())
// for another format or what does not parse.
nlohmann::json gltf_json(const std::string& path) {
  if (!is_gltf_path(path)) return nlohmann::json(nlohmann::json::value_t::discarded);
  std::string ext = path.substr(path.size() - 5);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  std::ifstream in(path, std::ios::binary);
  std::string text(std::istreambuf_iterator<char>(in), {});
  if (ext != ".gltf") {  // glb: 12-byte header, then chunk 0 (length, "JSON", data)
    if (text.size() < 20 || text.compare(0, 4, "glTF") != 0 || text.compare(16, 4, "JSON") != 0)
      return nlohmann::json(nlohmann::json::value_t::discarded);
    uint32_t length = 0;
    for (int i = 0; i < 4; ++i) length |= uint32_t(static_cast<unsigned char>(text[12 + i])) << (8 * i);
    text = text.substr(20, length);
  }
  return nlohmann::json::parse(text, nullptr, false);
}

// What assimp 5.2 does not check before it reads a glTF file: a skin
// without inverseBindMatrices (identity matrices by the specification)
// makes it dereference a null accessor (a crash). Its JSON reader also
// takes text that is not UTF-8, where a mangled key hides the same skin
// from a check that cannot parse the file, so JSON that does not parse is
// refused too. snh::Error naming the file and the skin.
void check_gltf_for_assimp(const std::string& path) {
  if (!is_gltf_path(path)) return;
  const nlohmann::json doc = gltf_json(path);
  if (doc.is_discarded()) fail(path, "is not glTF: its JSON does not parse (glTF's JSON is UTF-8 text, RFC 8259)");
  if (!doc.is_object() || !doc.contains("skins") || !doc["skins"].is_array()) return;
  for (size_t k = 0; k < doc["skins"].size(); ++k) {
    const nlohmann::json& skin = doc["skins"][k];
    if (!skin.is_object() || !skin.contains("inverseBindMatrices"))
      fail(path, "skin " + std::to_string(k) +
                     " has no inverseBindMatrices (assimp 5.2 cannot read such a skin; write the identity "
                     "matrices explicitly)");
  }
}

// The channels of glTF animation `clip` whose sampler is STEP, as (node
// name, 0 translation | 1 rotation | 2 scale): assimp 5.2 does not pass the
// interpolation on. Read from the file's JSON (.gltf, or a .glb's first
// chunk); nodes without a name are left linear. Nothing for other formats, nor for
// JSON of unexpected types (assimp read the file all the same).
std::set<std::pair<std::string, int>> gltf_step_channels(const std::string& path, int clip) {
  std::set<std::pair<std::string, int>> out;
  const nlohmann::json doc = gltf_json(path);
  try {
    if (doc.is_discarded() || !doc.contains("animations") || !doc["animations"].is_array() ||
        clip >= static_cast<int>(doc["animations"].size()) || !doc.contains("nodes"))
      return out;
    const nlohmann::json& a = doc["animations"][clip];
    if (!a.contains("channels") || !a.contains("samplers")) return out;
    for (const nlohmann::json& ch : a["channels"]) {
      const size_t sampler = ch.value("sampler", size_t(0));
      if (sampler >= a["samplers"].size() || a["samplers"][sampler].value("interpolation", "LINEAR") != "STEP")
        continue;
      if (!ch.contains("target") || !ch["target"].contains("node")) continue;
      const size_t node = ch["target"]["node"].get<size_t>();
      const std::string p = ch["target"].value("path", "");
      if (node >= doc["nodes"].size() || !doc["nodes"][node].contains("name")) continue;
      const int kind = p == "translation" ? 0 : p == "rotation" ? 1 : p == "scale" ? 2 : -1;
      if (kind >= 0) out.insert({doc["nodes"][node]["name"].get<std::string>(), kind});
    }
  } catch (const nlohmann::json::exception&) {
    return {};
  }
  return out;
}

void weld(Character& c, double distance) {
  const size_t n = c.surface.vertex_count();
  const double h = distance;
  std::unordered_map<unsigned long long, std::vector<int32_t>> grid;
  // Clamped before the conversion (a weld distance far below the
  // coordinates' size, e.g. 1e-9 of a zero diagonal).
  const auto cell = [&](double v) {
    const double t = std::floor(v / h);
    return t >= 0x1p62 ? (1LL << 62) : t <= -0x1p62 ? -(1LL << 62) : static_cast<long long>(t);
  };
  const auto key = [](long long i, long long j, long long k) {  // unsigned: wraps
    return (static_cast<unsigned long long>(i) * 73856093ULL) ^ (static_cast<unsigned long long>(j) * 19349663ULL) ^
           (static_cast<unsigned long long>(k) * 83492791ULL);
  };
  c.welded_index.assign(n, -1);
  c.welded = TriangleSurface{};
  for (size_t v = 0; v < n; ++v) {
    const double* p = c.surface.positions.data() + 3 * v;
    const long long ci = cell(p[0]), cj = cell(p[1]), ck = cell(p[2]);
    int32_t found = -1;
    for (long long i = ci - 1; i <= ci + 1 && found < 0; ++i)
      for (long long j = cj - 1; j <= cj + 1 && found < 0; ++j)
        for (long long k = ck - 1; k <= ck + 1 && found < 0; ++k) {
          const auto it = grid.find(key(i, j, k));
          if (it == grid.end()) continue;
          for (int32_t w : it->second) {
            const double* q = c.welded.positions.data() + 3 * static_cast<size_t>(w);
            const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
            if (dx * dx + dy * dy + dz * dz <= h * h) {
              found = w;
              break;
            }
          }
        }
    if (found < 0) {
      found = static_cast<int32_t>(c.welded.vertex_count());
      c.welded.positions.push_back({p[0], p[1], p[2]});
      grid[key(ci, cj, ck)].push_back(found);
    }
    c.welded_index[v] = found;
  }
  for (size_t t = 0; t < c.surface.triangle_count(); ++t) {
    const int32_t a = c.welded_index[c.surface.triangles[3 * t]], b = c.welded_index[c.surface.triangles[3 * t + 1]],
                  d = c.welded_index[c.surface.triangles[3 * t + 2]];
    if (a == b || b == d || a == d) continue;  // collapsed by the weld
    c.welded.triangles.insert(c.welded.triangles.end(), {a, b, d});
  }
}

// The end every format's reading shares: the skin weights (raw, rows in
// any order) resolved by options.weights (detail::resolve_skin_weights:
// checked or normalized, unweighted vertices filled, rows sorted by joint),
// then the weld of the simulated surface.
void finish_character(Character& c, const CharacterReadOptions& options) {
  detail::resolve_skin_weights(c, options);

  // The weld of the simulated surface.
  double diagonal = 0.0;
  {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (size_t v = 0; v < c.surface.vertex_count(); ++v)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], c.surface.positions(v, d));
        hi[d] = std::max(hi[d], c.surface.positions(v, d));
      }
    for (int d = 0; d < 3; ++d) diagonal += (hi[d] - lo[d]) * (hi[d] - lo[d]);
    diagonal = std::sqrt(diagonal);
  }
  const double weld_distance = options.weld_distance.value_or(1e-9 * std::max(diagonal, 1e-300));
  weld(c, weld_distance);
}

bool has_extension(const std::string& path, const std::string& ext) {
  std::string tail = path.size() >= ext.size() ? path.substr(path.size() - ext.size()) : "";
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return tail == ext;
}

bool is_fbx(const std::string& path) { return has_extension(path, ".fbx"); }

// A scene's node hierarchy (read_hierarchy).
struct Hierarchy {
  std::map<std::string, const aiNode*> nodes;
  std::vector<const aiNode*> order;  // depth first, parents first
};

// Nodes by name, and each node's parent chain.
Hierarchy read_hierarchy(const aiScene* scene) {
  Hierarchy h;
  const std::function<void(const aiNode*)> visit = [&](const aiNode* n) {
    h.nodes.emplace(n->mName.C_Str(), n);
    h.order.push_back(n);
    for (unsigned i = 0; i < n->mNumChildren; ++i) visit(n->mChildren[i]);
  };
  visit(scene->mRootNode);
  return h;
}

// Joints: the nodes the skinned meshes' bones name, with their offset
// matrices (one per joint: meshes that share a joint must agree). Fills
// c.joints; gives each joint's index by name.
std::map<std::string, int> read_joints(const std::string& path, const aiScene* scene, const Hierarchy& h,
                                       Character& c) {
  std::map<std::string, Matrix4> offsets;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      const aiBone* bone = mesh->mBones[b];
      const std::string name = bone->mName.C_Str();
      const Matrix4 offset = to_matrix4(bone->mOffsetMatrix);
      if (!finite(offset)) fail(path, "joint '" + name + "': its inverse bind matrix is not finite");
      const auto [it, added] = offsets.emplace(name, offset);
      if (!added)
        for (int k = 0; k < 16; ++k)
          if (std::abs(it->second[k] - offset[k]) > 1e-6 * (1.0 + std::abs(offset[k])))
            fail(path, "joint '" + name + "': meshes give it different inverse bind matrices");
    }
  }
  if (offsets.empty()) fail(path, "no skinned mesh (no mesh has bones)");
  // Joints in hierarchy order, then those the weights name but the
  // hierarchy lacks (held at their bind pose, parentless).
  std::vector<const aiNode*> joint_nodes;
  std::set<std::string> listed;
  for (const aiNode* n : h.order)
    if (offsets.count(n->mName.C_Str()) && listed.insert(n->mName.C_Str()).second) joint_nodes.push_back(n);
  std::vector<std::string> missing;
  for (const auto& [name, offset] : offsets)
    if (!listed.count(name)) missing.push_back(name);
  std::map<std::string, int> joint_of;
  const auto add_joint = [&](const std::string& name, const aiNode* n) {
    Joint j;
    j.name = name;
    j.inverse_bind = offsets[name];
    for (const aiNode* p = n ? n->mParent : nullptr; p; p = p->mParent) {
      const auto it = joint_of.find(p->mName.C_Str());
      if (it != joint_of.end()) {
        j.parent = it->second;
        break;
      }
    }
    Matrix4 bind;
    try {
      bind = inverse_matrix4(j.inverse_bind);
    } catch (const Error&) {
      fail(path, "joint '" + name + "': its inverse bind matrix is singular");
    }
    j.rest_position = {bind[3], bind[7], bind[11]};
    joint_of[name] = static_cast<int>(c.joints.size());
    c.joints.push_back(j);
  };
  for (const aiNode* n : joint_nodes) add_joint(n->mName.C_Str(), n);
  for (const std::string& name : missing) add_joint(name, nullptr);
  if (!missing.empty()) {
    std::string names;
    for (size_t k = 0; k < missing.size() && k < 8; ++k) names += (k ? ", '" : "'") + missing[k] + "'";
    if (missing.size() > 8) names += ", ...";
    c.warnings.push_back("joints: " + std::to_string(missing.size()) +
                         " joint(s) named by skin weights have no node in the hierarchy (" + names +
                         "); held at their bind pose");
  }
  return joint_of;
}

// The skin: every mesh with bones, its vertices as given. Fills c.surface
// and c.weights (raw, as the file gives them).
void read_skin(const std::string& path, const aiScene* scene, const std::map<std::string, int>& joint_of,
               Character& c) {
  std::vector<std::vector<std::pair<int32_t, double>>> rows;
  std::vector<detail::ColladaCornerMesh> corner_meshes;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (mesh->mNumBones == 0) continue;
    const std::string mesh_name =
        "mesh " + std::to_string(m) + (mesh->mName.length ? " '" + std::string(mesh->mName.C_Str()) + "'" : "");
    const int32_t base = static_cast<int32_t>(c.surface.vertex_count());
    corner_meshes.push_back({mesh->mName.C_Str(), base, static_cast<int32_t>(mesh->mNumVertices)});
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fail(path, mesh_name + ": vertex " + std::to_string(v) + " has a non-finite position");
      c.surface.positions.push_back({p.x, p.y, p.z});
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines of a mixed mesh
      for (unsigned k = 0; k < 3; ++k) c.surface.triangles.push_back(base + static_cast<int32_t>(face.mIndices[k]));
    }
    rows.resize(c.surface.vertex_count());
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      const aiBone* bone = mesh->mBones[b];
      const int32_t j = joint_of.at(bone->mName.C_Str());
      for (unsigned k = 0; k < bone->mNumWeights; ++k) {
        const aiVertexWeight& w = bone->mWeights[k];
        if (w.mVertexId >= mesh->mNumVertices)
          fail(path, mesh_name + ": joint '" + c.joints[j].name + "' weighs vertex " + std::to_string(w.mVertexId) +
                         " of " + std::to_string(mesh->mNumVertices));
        if (!std::isfinite(w.mWeight) || w.mWeight < 0.0f)
          fail(path, mesh_name + ": vertex " + std::to_string(w.mVertexId) + " has weight " + number(w.mWeight) +
                         " for joint '" + c.joints[j].name + "'");
        if (w.mWeight > 0.0f) rows[base + w.mVertexId].push_back({j, w.mWeight});
      }
    }
  }
  if (has_extension(path, ".dae")) {
    // One vertex per <vertices> entry, as Blender and Maya import the file.
    const size_t corners = c.surface.vertex_count();
    const std::string why = detail::collapse_collada_corners(
        path, corner_meshes,
        [&](const std::string& name) {
          const auto it = joint_of.find(name);
          return it == joint_of.end() ? -1 : it->second;
        },
        c.surface, rows);
    if (!why.empty())
      c.warnings.push_back("Collada: the surface and its caches are per polygon corner (" + std::to_string(corners) +
                           " vertices, as assimp splits them), not the file's <vertices>: " + why);
  }
  if (c.surface.triangle_count() == 0) fail(path, "the skinned meshes have no triangles");
  for (const auto& row : rows) {
    for (const auto& [j, w] : row) {
      c.weights.joint.push_back(j);
      c.weights.weight.push_back(w);
    }
    c.weights.offset.push_back(static_cast<int32_t>(c.weights.joint.size()));
  }
}

// The clip: fills c.clip_names and gives the index options select, or -1
// for none (refused where options.require_clip).
int select_clip(const std::string& path, const aiScene* scene, const CharacterReadOptions& options, Character& c) {
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) c.clip_names.push_back(scene->mAnimations[a]->mName.C_Str());
  return detail::select_clip(path, c.clip_names, options);
}

// What a clip's frames are sampled from.
struct ClipAnimation {
  std::string name;  // "clip '<name>'", for messages
  double ticks_per_second = 25.0;
  std::map<std::string, const aiNodeAnim*> channels;  // by node name
  std::set<std::pair<std::string, int>> step;         // gltf_step_channels
  Matrix4 to_skin{};                                  // skin_space
};

// The clip's channels by node name, their keys checked.
std::map<std::string, const aiNodeAnim*> read_channels(const std::string& path, const aiAnimation* anim,
                                                       const std::string& clip_name, const Hierarchy& h) {
  std::map<std::string, const aiNodeAnim*> channels;
  for (unsigned ci = 0; ci < anim->mNumChannels; ++ci) {
    const aiNodeAnim* ch = anim->mChannels[ci];
    const std::string node = ch->mNodeName.C_Str();
    const auto bad = [&](const char* what, unsigned key) {
      fail(path, clip_name + ": node '" + node + "': " + what + " key " + std::to_string(key) + " is not finite");
    };
    for (unsigned i = 0; i < ch->mNumPositionKeys; ++i) {
      const auto& k = ch->mPositionKeys[i];
      if (!std::isfinite(k.mTime) || !std::isfinite(k.mValue.x) || !std::isfinite(k.mValue.y) ||
          !std::isfinite(k.mValue.z))
        bad("translation", i);
    }
    for (unsigned i = 0; i < ch->mNumRotationKeys; ++i) {
      const auto& k = ch->mRotationKeys[i];
      const double n2 = double(k.mValue.w) * k.mValue.w + double(k.mValue.x) * k.mValue.x +
                        double(k.mValue.y) * k.mValue.y + double(k.mValue.z) * k.mValue.z;
      if (!std::isfinite(k.mTime) || !std::isfinite(n2)) bad("rotation", i);
      if (!(n2 > 1e-12))
        fail(path, clip_name + ": node '" + node + "': rotation key " + std::to_string(i) + " is zero");
    }
    for (unsigned i = 0; i < ch->mNumScalingKeys; ++i) {
      const auto& k = ch->mScalingKeys[i];
      if (!std::isfinite(k.mTime) || !std::isfinite(k.mValue.x) || !std::isfinite(k.mValue.y) ||
          !std::isfinite(k.mValue.z))
        bad("scale", i);
    }
    if (!h.nodes.count(node)) fail(path, clip_name + ": animates node '" + node + "', which the scene does not have");
    channels[node] = ch;
  }
  return channels;
}

// The skin's own space. Where every joint's skinning matrix in the
// scene's static (unanimated) pose is one and the same M (a bind pose
// placed by the mesh's node, as Collada exporters write it), the frames
// are M^-1 S(t): the bind pose is the identity and the surface stays in the
// coordinates the file, and every importer, gives its vertices.
Matrix4 skin_space(const Hierarchy& h, const std::vector<Joint>& joints) {
  std::map<const aiNode*, Matrix4> world;
  Matrix4 to_skin = compose_trs({0, 0, 0}, {1, 0, 0, 0}, {1, 1, 1});
  for (const aiNode* n : h.order) {
    const Matrix4 local = to_matrix4(n->mTransformation);
    world[n] = n->mParent ? multiply_matrix4(world.at(n->mParent), local) : local;
  }
  std::vector<Matrix4> bind;
  for (const Joint& j : joints)
    if (h.nodes.count(j.name)) bind.push_back(multiply_matrix4(world.at(h.nodes.at(j.name)), j.inverse_bind));
  if (bind.empty()) return to_skin;  // no joint in the hierarchy: the file's coordinates
  bool same = true, identity = true;
  double scale = 1.0;
  for (double v : bind.front()) scale = std::max(scale, std::abs(v));
  for (const Matrix4& m : bind)
    for (int k = 0; k < 16; ++k) {
      if (std::abs(m[k] - bind.front()[k]) > 1e-5 * scale) same = false;
      if (std::abs(m[k] - to_skin[k]) > 1e-9 * scale) identity = false;
    }
  if (same && !identity && std::abs(determinant3(bind.front())) > 1e-12 * scale * scale * scale)
    to_skin = inverse_matrix4(bind.front());
  return to_skin;
}

// The skinning matrices of frames options.first_frame..last, into c.clip.
void sample_frames(const std::string& path, const CharacterReadOptions& options, int last, const Hierarchy& h,
                   const ClipAnimation& clip, Character& c) {
  std::map<const aiNode*, Matrix4> world;
  for (int f = options.first_frame; f <= last; ++f) {
    const double seconds = f / options.fps, ticks = seconds * clip.ticks_per_second;
    world.clear();
    for (const aiNode* n : h.order) {
      Matrix4 local = to_matrix4(n->mTransformation);
      const auto it = clip.channels.find(n->mName.C_Str());
      if (it != clip.channels.end()) {
        const aiNodeAnim* ch = it->second;
        std::array<double, 3> t, s;
        std::array<double, 4> q;
        decompose(n->mTransformation, t, q, s);  // a channel without keys of a kind keeps the node's own
        const std::string name = n->mName.C_Str();
        local =
            compose_trs(sample_vector(ch->mPositionKeys, ch->mNumPositionKeys, ticks, t, clip.step.count({name, 0})),
                        sample_rotation(ch->mRotationKeys, ch->mNumRotationKeys, ticks, q, clip.step.count({name, 1})),
                        sample_vector(ch->mScalingKeys, ch->mNumScalingKeys, ticks, s, clip.step.count({name, 2})));
      }
      world[n] = n->mParent ? multiply_matrix4(world.at(n->mParent), local) : local;
    }
    std::vector<Matrix4> skinning;
    for (const Joint& j : c.joints) {
      const auto node = h.nodes.find(j.name);
      if (node == h.nodes.end()) {  // not in the hierarchy: held at the bind pose
        skinning.push_back(compose_trs({0, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}));
        continue;
      }
      const Matrix4 m = multiply_matrix4(clip.to_skin, multiply_matrix4(world.at(node->second), j.inverse_bind));
      if (!finite(m))
        fail(path, clip.name + ": joint '" + j.name + "' at frame " + std::to_string(f) + " is not finite");
      skinning.push_back(m);
    }
    c.clip.times.push_back(seconds);
    c.clip.skinning.push_back(std::move(skinning));
  }
}

// Animation `clip`: its channels and frame range checked, then sampled.
void read_clip(const std::string& path, const aiScene* scene, const CharacterReadOptions& options, const Hierarchy& h,
               int clip, Character& c) {
  const aiAnimation* anim = scene->mAnimations[clip];
  ClipAnimation animation;
  animation.ticks_per_second = anim->mTicksPerSecond > 0.0 ? anim->mTicksPerSecond : 25.0;
  animation.name = "clip '" + c.clip_names[clip] + "'";
  const std::string& clip_name = animation.name;
  animation.channels = read_channels(path, anim, clip_name, h);
  const double duration = anim->mDuration / animation.ticks_per_second;
  if (!std::isfinite(duration) || duration < 0.0) fail(path, clip_name + ": its duration is not finite");
  const int last = detail::begin_clip(path, clip_name, duration, clip, options, c);
  // The clip index is the glTF animation's: assimp 5.2 imports them in order.
  animation.step = scene->mNumAnimations > 0 ? gltf_step_channels(path, clip) : std::set<std::pair<std::string, int>>{};
  animation.to_skin = skin_space(h, c.joints);
  sample_frames(path, options, last, h, animation, c);
}

}  // namespace

Character read_character(const std::string& path, const CharacterReadOptions& options) {
  if (is_fbx(path)) {
    Character c = detail::read_fbx_character(path, options);
    finish_character(c, options);
    return c;
  }
  if (!(options.fps > 0.0) || !std::isfinite(options.fps)) fail(path, "fps must be > 0, got " + number(options.fps));
  if (options.first_frame < 0) fail(path, "the first frame must be >= 0, got " + std::to_string(options.first_frame));
  // What assimp 5.2 would only assert on (an abort): checked first.
  if (has_extension(path, ".dae")) detail::check_collada_for_assimp(path);
  check_gltf_for_assimp(path);
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode)
    fail(path, std::string("cannot read the file (assimp: ") + importer.GetErrorString() + ")");

  Character c;
  c.file = path;
  const Hierarchy h = read_hierarchy(scene);
  const std::map<std::string, int> joint_of = read_joints(path, scene, h, c);
  read_skin(path, scene, joint_of, c);
  finish_character(c, options);
  const int clip = select_clip(path, scene, options, c);
  if (clip < 0) return c;
  read_clip(path, scene, options, h, clip, c);
  return c;
}

}  // namespace snh
