// Bones from a character's skeleton and the pieces of its simulation
// (snh/character.h).
#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <set>
#include <sstream>
#include <string>

#include "character/reader_messages.h"
#include "snh/character.h"
#include "snh/error.h"
#include "snh/pieces.h"

namespace snh {
namespace {

using detail::number;

using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

// The squared distance from p to triangle abc (Ericson, Real-Time Collision
// Detection, 5.1.5: the closest point by Voronoi regions).
double point_triangle_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const auto at = [&](double v, double w) {
    const Vec3 q{a[0] + v * ab[0] + w * ac[0], a[1] + v * ab[1] + w * ac[1], a[2] + v * ab[2] + w * ac[2]};
    const Vec3 d = sub(p, q);
    return dot(d, d);
  };
  if (d1 <= 0 && d2 <= 0) return at(0, 0);
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(d1 / (d1 - d3), 0);
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  return at(vb * denom, vc * denom);
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Whether segment ab meets triangle (p, q, r) (Moeller and Trumbore 1997,
// the ray parameter kept in [0, 1]).
bool segment_meets_triangle(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 d = sub(b, a), e1 = sub(q, p), e2 = sub(r, p);
  const Vec3 h = cross(d, e2);
  const double det = dot(e1, h);
  if (std::abs(det) < 1e-300) return false;  // parallel: the sampled distances decide
  const Vec3 s = sub(a, p);
  const double u = dot(s, h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 qv = cross(s, e1);
  const double v = dot(d, qv) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = dot(e2, qv) / det;
  return t >= 0.0 && t <= 1.0;
}

// The distance from segment ab to the surface: 0 where it crosses a
// triangle, else the least distance from 65 points along it.
double segment_surface_distance(const Vec3& a, const Vec3& b, const TriangleSurface& s) {
  for (size_t k = 0; k < s.triangle_count(); ++k) {
    const auto v = [&](int c) {
      const size_t i = static_cast<size_t>(s.triangles[3 * k + c]);
      return Vec3{s.positions(i, 0), s.positions(i, 1), s.positions(i, 2)};
    };
    if (segment_meets_triangle(a, b, v(0), v(1), v(2))) return 0.0;
  }
  double best = 1e300;
  const int samples = 64;
  for (int i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) / samples;
    const Vec3 p{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
    for (size_t k = 0; k < s.triangle_count(); ++k) {
      const auto v = [&](int c) {
        const size_t vertex = static_cast<size_t>(s.triangles[3 * k + c]);
        return Vec3{s.positions(vertex, 0), s.positions(vertex, 1), s.positions(vertex, 2)};
      };
      best = std::min(best, point_triangle_distance2(p, v(0), v(1), v(2)));
    }
  }
  return std::sqrt(best);
}

// Names quoted and comma-separated, the first 8 and a count of the rest.
std::string name_list(const std::vector<std::string>& names) {
  std::string s;
  for (size_t k = 0; k < names.size() && k < 8; ++k) s += (k ? ", '" : "'") + names[k] + "'";
  if (names.size() > 8) s += " and " + std::to_string(names.size() - 8) + " more";
  return s;
}

bool excluded(const std::string& name, const std::vector<std::string>& patterns) {
  return std::any_of(patterns.begin(), patterns.end(),
                     [&](const std::string& p) { return p == name || fnmatch(p.c_str(), name.c_str(), 0) == 0; });
}

// Each point's skin weights: the inverse-distance average of the weights of
// its k nearest surface points (a point on one of them takes its weights).
SkinWeights carried_weights(const std::vector<double>& points, const std::vector<double>& from,
                            const SkinWeights& from_weights, size_t joints, int k) {
  const size_t n = points.size() / 3, m = from.size() / 3;
  SkinWeights out;
  std::vector<double> w(joints);
  std::vector<std::pair<double, size_t>> near;
  for (size_t v = 0; v < n; ++v) {
    near.clear();
    for (size_t s = 0; s < m; ++s) {
      double d2 = 0.0;
      for (int d = 0; d < 3; ++d) d2 += (points[3 * v + d] - from[3 * s + d]) * (points[3 * v + d] - from[3 * s + d]);
      near.push_back({d2, s});
    }
    const size_t count = std::min<size_t>(static_cast<size_t>(k), near.size());
    std::partial_sort(near.begin(), near.begin() + count, near.end());
    std::fill(w.begin(), w.end(), 0.0);
    double total = 0.0;
    for (size_t i = 0; i < count; ++i) {
      const double d = std::sqrt(near[i].first);
      const double inv = d > 0.0 ? 1.0 / d : 1e300;
      const size_t s = near[i].second;
      for (int32_t e = from_weights.offset[s]; e < from_weights.offset[s + 1]; ++e)
        w[from_weights.joint[e]] += inv * from_weights.weight[e];
      total += inv;
      if (d == 0.0) {  // exactly on a surface point: its weights alone
        std::fill(w.begin(), w.end(), 0.0);
        for (int32_t e = from_weights.offset[s]; e < from_weights.offset[s + 1]; ++e)
          w[from_weights.joint[e]] = from_weights.weight[e];
        total = 1.0;
        break;
      }
    }
    double sum = 0.0;
    for (double x : w) sum += x;
    for (size_t j = 0; j < joints; ++j)
      if (w[j] > 0.0) {
        out.joint.push_back(static_cast<int32_t>(j));
        out.weight.push_back(w[j] / sum);
      }
    (void)total;
    out.offset.push_back(static_cast<int32_t>(out.joint.size()));
  }
  return out;
}

}  // namespace

CharacterBones character_bones(const Character& character, const CharacterBoneOptions& options) {
  const std::string& file = character.file;
  if (!(options.radius_fraction > 0.0) || !std::isfinite(options.radius_fraction))
    throw Error(file + ": bones.radius_fraction must be > 0");
  if (!(options.leaf_fraction >= 0.0)) throw Error(file + ": bones.leaf_fraction must be >= 0");
  std::set<std::string> names;
  for (const Joint& j : character.joints) names.insert(j.name);
  for (const auto& [name, r] : options.radius) {
    if (!names.count(name)) throw Error(file + ": bones.radius: no joint named '" + name + "'");
    if (!(r > 0.0) || !std::isfinite(r)) throw Error(file + ": bones.radius." + name + " must be > 0");
  }
  for (const std::string& p : options.exclude)
    if (std::none_of(names.begin(), names.end(), [&](const std::string& n) { return excluded(n, {p}); }))
      throw Error(file + ": bones.exclude: '" + p + "' matches no joint");

  const size_t n = character.joints.size();
  std::vector<std::vector<int>> children(n);
  for (size_t j = 0; j < n; ++j)
    if (character.joints[j].parent >= 0) children[character.joints[j].parent].push_back(static_cast<int>(j));
  // Each joint's segment end: its child, the centroid of its children, or
  // (a leaf) the parent's direction continued.
  // How many skin vertices each joint weighs most, and how far along its
  // parent's direction the farthest of them lies from it (a leaf's reach).
  std::vector<int> dominant(n, 0);
  std::vector<double> reach(n, 0.0);
  const SkinWeights& w = character.weights;
  for (size_t v = 0; v < w.vertex_count(); ++v) {
    int best = -1;
    for (int32_t k = w.offset[v]; k < w.offset[v + 1]; ++k)
      if (best < 0 || w.weight[k] > w.weight[best]) best = k;
    if (best < 0 || static_cast<size_t>(w.joint[best]) >= n) continue;
    const size_t j = static_cast<size_t>(w.joint[best]);
    ++dominant[j];
    const int p = character.joints[j].parent;
    if (p < 0) continue;
    const Vec3& a = character.joints[j].rest_position;
    const Vec3 dir = sub(a, character.joints[p].rest_position);
    const double length = norm(dir);
    if (!(length > 0.0)) continue;
    const Vec3 x{character.surface.positions(v, 0), character.surface.positions(v, 1),
                 character.surface.positions(v, 2)};
    reach[j] = std::max(reach[j], dot(sub(x, a), dir) / length);
  }
  const auto end_of = [&](size_t j, Vec3& end) {
    const Vec3& a = character.joints[j].rest_position;
    if (!children[j].empty()) {
      end = {0, 0, 0};
      for (int c : children[j])
        for (int d = 0; d < 3; ++d)
          end[d] += character.joints[c].rest_position[d] / static_cast<double>(children[j].size());
      return true;
    }
    const int p = character.joints[j].parent;
    if (p < 0) return false;
    const Vec3 dir = sub(a, character.joints[p].rest_position);
    if (options.leaf_fraction > 0.0) {
      for (int d = 0; d < 3; ++d) end[d] = a[d] + options.leaf_fraction * dir[d];
      return true;
    }
    // From the skin it weighs most: three quarters of the way to the
    // farthest such vertex along the parent's direction.
    const double length = norm(dir);
    if (!options.leaf_from_skin || !(reach[j] > 0.0) || !(length > 0.0)) return false;
    for (int d = 0; d < 3; ++d) end[d] = a[d] + 0.75 * reach[j] * dir[d] / length;
    return true;
  };

  std::vector<std::string> unboned_leaves;  // leaves skipped although they weigh skin most

  CharacterBones out;
  std::vector<std::string> touching;  // bones whose segment touches the skin
  for (size_t j = 0; j < n; ++j) {
    const Joint& joint = character.joints[j];
    if (excluded(joint.name, options.exclude)) continue;
    Vec3 end;
    if (!end_of(j, end)) {
      if (children[j].empty() && dominant[j] > 0) unboned_leaves.push_back(joint.name);
      continue;
    }
    if (!(norm(sub(end, joint.rest_position)) > 0.0))
      throw Error(file + ": joint '" + joint.name + "': its segment to its child has zero length");
    Capsule capsule{joint.rest_position, end, 0.0};
    const auto given = options.radius.find(joint.name);
    if (given != options.radius.end()) {
      capsule.radius = given->second;
    } else {
      const double distance = segment_surface_distance(capsule.a, capsule.b, character.welded);
      capsule.radius = options.radius_fraction * distance;
      if (!(capsule.radius > 0.0)) {  // the segment touches or crosses the skin: a thin limb
        touching.push_back(joint.name);
        if (!(options.touching_radius > 0.0)) continue;
        capsule.radius = options.touching_radius;
      }
    }
    if (options.joint_clearance >= 0.0) {
      // Keep the capsule (caps included) clear of the flesh around both
      // ends: two rigid bones meeting at a joint would crush the elements
      // between them as the joint bends. Too short a segment for that
      // leaves a sphere at its middle.
      const Vec3 axis = sub(capsule.b, capsule.a);
      const double length = norm(axis);
      const double trim = std::min(options.joint_clearance * length + capsule.radius, 0.5 * length);
      const Vec3 a = capsule.a;
      for (int d = 0; d < 3; ++d) {
        capsule.a[d] = a[d] + axis[d] * trim / length;
        capsule.b[d] = a[d] + axis[d] * (length - trim) / length;
      }
    }
    out.bones.push_back({joint.name, capsule});
    out.joint.push_back(static_cast<int>(j));
  }
  if (!unboned_leaves.empty())
    out.warnings.push_back("bones: " + std::to_string(unboned_leaves.size()) +
                           " leaf joint(s) weigh skin vertices most but get no bone (" + name_list(unboned_leaves) +
                           "): with no parent, or none of that skin beyond the joint, they have no direction or "
                           "length, so their flesh follows its neighbours");
  if (!touching.empty())
    out.warnings.push_back(
        "bones: " + std::to_string(touching.size()) + " bone segment(s) touch or cross the skin (" +
        name_list(touching) + ")" +
        (options.touching_radius > 0.0 ? "; given the radius " + number(options.touching_radius) : "; left out") +
        " (bones.radius or bones.exclude decide otherwise)");
  if (out.bones.empty())
    throw Error(file + ": no bone left (every joint is excluded, a leaf, or touches the skin without a radius)");
  for (const Bone& b : out.bones) out.animation.bones.push_back(b.name);
  if (character.has_clip) {
    out.animation.times = character.clip.times;
    for (const auto& frame : character.clip.skinning) {
      std::vector<Matrix4> m;
      for (int j : out.joint) m.push_back(frame[j]);
      out.animation.transforms.push_back(std::move(m));
    }
  }
  return out;
}

namespace {

// Leaves out the bones that hold no lattice vertex (thinner than a cell,
// outside the lattice, or inside an earlier bone), with a warning.
void keep_bones_that_hold(const Character& character, CharacterRig& rig) {
  {
    std::vector<char> owned(rig.voxels.lattice.vertex_count(), 0);
    std::vector<std::string> empty;
    CharacterBones kept;
    kept.animation.times = rig.bones.animation.times;
    kept.animation.transforms.resize(rig.bones.animation.transforms.size());
    kept.warnings = rig.bones.warnings;
    for (size_t b = 0; b < rig.bones.bones.size(); ++b) {
      bool holds = false;
      for (size_t v = 0; v < owned.size(); ++v)
        if (!owned[v] && bone_contains(rig.bones.bones[b], rig.voxels.lattice.vertex(v))) {
          owned[v] = 1;
          holds = true;
        }
      if (!holds) {
        empty.push_back(rig.bones.bones[b].name);
        continue;
      }
      kept.bones.push_back(rig.bones.bones[b]);
      kept.joint.push_back(rig.bones.joint[b]);
      kept.animation.bones.push_back(rig.bones.animation.bones[b]);
      for (size_t f = 0; f < kept.animation.transforms.size(); ++f)
        kept.animation.transforms[f].push_back(rig.bones.animation.transforms[f][b]);
    }
    if (!empty.empty()) {
      if (kept.bones.empty())
        throw Error(character.file + ": bones: no bone holds a lattice vertex (" + name_list(empty) +
                    "): use a smaller cell");
      const std::string w = "bones: " + std::to_string(empty.size()) + " bone(s) hold no lattice vertex (" +
                            name_list(empty) + "; thinner than a cell, or outside the flesh) and are left out";
      kept.warnings.push_back(w);
      rig.warnings.push_back(w);
      rig.bones = std::move(kept);
    }
  }
}

}  // namespace

double character_cell(const Character& character, int resolution) {
  if (resolution < 1) throw Error(character.file + ": resolution must be >= 1 cell, got " + std::to_string(resolution));
  const std::vector<double>& x = character.surface.positions.xyz();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i + 2 < x.size(); i += 3)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], x[i + d]);
      hi[d] = std::max(hi[d], x[i + d]);
    }
  const double longest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (!(longest > 0.0) || !std::isfinite(longest))
    throw Error(character.file + ": the skin has no extent, so no cell can be chosen from a resolution");
  return longest / resolution;
}

CharacterRig prepare_character(const Character& character, double cell, const CharacterBoneOptions& bones,
                               const VoxelizeOptions& voxelize_options) {
  CharacterPrepareOptions options;
  options.bones = bones;
  options.voxelize = voxelize_options;
  return prepare_character(character, cell, options);
}

CharacterRig prepare_character(const Character& character, double cell, const CharacterPrepareOptions& options) {
  CharacterRig rig;
  rig.cell = cell;
  VoxelizeOptions voxelize_options = options.voxelize;
  if (voxelize_options.name == VoxelizeOptions{}.name) voxelize_options.name = character.file;
  try {
    rig.voxels = voxelize(character.welded, cell, voxelize_options);
  } catch (const Error& e) {
    throw Error(character.file + ": the welded skin surface: " + e.what());
  }
  rig.warnings = rig.voxels.warnings;

  CharacterBoneOptions bones = options.bones;
  if (!(bones.touching_radius > 0.0)) bones.touching_radius = options.touching_radius_cells * cell;
  rig.bones = character_bones(character, bones);
  for (const std::string& w : rig.bones.warnings) rig.warnings.push_back(w);
  keep_bones_that_hold(character, rig);

  // Pieces no bone holds: joined to the body (or as options.pieces says).
  Embedding welded_embedding = embed_carrying_all(rig.voxels, character.welded).embedding;
  try {
    rig.constraints = bone_constraints(rig.voxels.lattice, rig.bones.bones);
  } catch (const Error& e) {
    throw Error(character.file + ": bones: " + e.what());
  }
  {
    PieceOptions piece_options;
    piece_options.rule = options.pieces;
    piece_options.rule_name = "CharacterPrepareOptions::pieces (scene files: character.pieces)";
    PiecedLattice pieced;
    try {
      pieced = resolve_pieces(rig.voxels, welded_embedding, character.welded, rig.constraints, rig.bones.bones,
                              piece_options);
    } catch (const Error& e) {
      throw Error(character.file + ": " + e.what());
    }
    for (const std::string& w : pieced.warnings) rig.warnings.push_back(w);
    if (pieced.changed) {
      int cells = 0, added = 0, moved = 0;
      for (const LatticePiece& p : pieced.pieces)
        if (!p.outcome.empty()) {
          ++moved;
          cells += static_cast<int>(p.elements.size());
          added += p.added_cells;
        }
      std::ostringstream m;
      m << "lattice: " << moved << " of " << pieced.pieces.size() << " pieces (" << cells << " cells) hold no bone; "
        << (options.pieces == PieceRule::attach ? "attached to the nearest held piece (" : "dropped (") << added
        << " cells added)";
      rig.warnings.push_back(m.str());
      rig.voxels = std::move(pieced.voxels);
      rig.constraints = bone_constraints(rig.voxels.lattice, rig.bones.bones);  // the capsules on the new lattice
    }
    if (pieced.pieces.size() > 1) rig.pieces = std::move(pieced.pieces);
  }

  // Every surface vertex is carried; those beyond a cell from the lattice
  // (open sheets, thin flaps, loose points) to first order from their
  // nearest element, unless far from everything.
  const CarriedEmbedding welded = embed_carrying_all(rig.voxels, character.welded);
  double diagonal = 0.0;
  {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    const std::vector<double>& x = character.surface.positions.xyz();
    for (size_t i = 0; i + 2 < x.size(); i += 3)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], x[i + d]);
        hi[d] = std::max(hi[d], x[i + d]);
      }
    diagonal = norm(sub(hi, lo));
  }
  const double farthest = std::max(4.0 * cell, options.max_outside_fraction * diagonal);
  const size_t n = character.surface.vertex_count();
  rig.embedding.element.resize(n);
  rig.embedding.weights.resize(8 * n);
  size_t worst = 0;
  for (size_t v = 0; v < n; ++v) {
    const size_t w = static_cast<size_t>(character.welded_index[v]);
    rig.embedding.element[v] = welded.embedding.element[w];
    std::copy_n(welded.embedding.weights.begin() + 8 * w, 8, rig.embedding.weights.begin() + 8 * v);
    const double d = welded.distance[w];
    if (d > farthest) {
      std::ostringstream m;
      m << character.file << ": surface vertex " << v << " at (" << character.surface.positions(v, 0) << ", "
        << character.surface.positions(v, 1) << ", " << character.surface.positions(v, 2) << ") is " << d
        << " from the nearest lattice element, farther than " << farthest
        << " (4 cells, or a quarter of the skin's diagonal): geometry far from everything else cannot follow the "
           "flesh (a smaller cell fills thin parts)";
      throw Error(m.str());
    }
    if (d > cell) {
      ++rig.vertices_outside;
      if (d > rig.max_outside_distance) {
        rig.max_outside_distance = d;
        worst = v;
      }
    }
  }
  if (rig.vertices_outside > 0) {
    std::ostringstream m;
    m << "embedding: " << rig.vertices_outside << " of " << n
      << " surface vertices lie more than a cell outside the lattice (open sheets, parts thinner than a cell, loose "
         "points); each follows its nearest element, extended to first order; the farthest, vertex "
      << worst << ", is " << rig.max_outside_distance << " (" << rig.max_outside_distance / cell << " cells) away";
    rig.warnings.push_back(m.str());
  }

  // The welded vertices' weights (the first surface vertex of each).
  SkinWeights welded_weights;
  std::vector<int32_t> first(character.welded.vertex_count(), -1);
  for (size_t v = 0; v < n; ++v)
    if (first[character.welded_index[v]] < 0) first[character.welded_index[v]] = static_cast<int32_t>(v);
  for (int32_t v : first) {
    for (int32_t e = character.weights.offset[v]; e < character.weights.offset[v + 1]; ++e) {
      welded_weights.joint.push_back(character.weights.joint[e]);
      welded_weights.weight.push_back(character.weights.weight[e]);
    }
    welded_weights.offset.push_back(static_cast<int32_t>(welded_weights.joint.size()));
  }
  rig.lattice_weights = carried_weights(rig.voxels.lattice.positions.xyz(), character.welded.positions.xyz(),
                                        welded_weights, character.joints.size(), 4);
  return rig;
}

}  // namespace snh
