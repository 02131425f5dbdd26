// "output.check_intersections": the exact self-intersection count
// (snh/surface_intersections.h) of a scene's output surface at the end of
// each step or frame. The output surface is the embedded surface with "embed"
// (its vertices that share a rest position welded into one, so that a seam
// of the artist's file is not a touch), else the boundary of the mesh.
#pragma once

#include <string>
#include <vector>

#include "snh/scene.h"
#include "snh/surface_intersections.h"

namespace snh::scene_io {

class OutputSurfaceCheck {
 public:
  OutputSurfaceCheck(const SceneFile& file, const Mesh& mesh);
  // x: the lattice's positions; surface: the embedded surface's (one per
  // vertex of file.embedded->surface), or empty to compute them from x.
  SelfIntersections count(const Points& x, const Points& surface = {}) const;
  // The warning for a count that is not clean ("surface_intersections: ..."),
  // empty for a clean one.
  static std::string warning(const SelfIntersections& count);

 private:
  const SceneFile* file_;
  const Mesh* mesh_;
  std::vector<int32_t> triangles_;
  // Per output-surface vertex: the lattice vertex (no "embed") or the
  // embedded surface's vertex whose position it takes.
  std::vector<int32_t> source_;
};

}  // namespace snh::scene_io
