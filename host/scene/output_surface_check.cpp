#include "scene/output_surface_check.h"

#include <cmath>

#include "snh/outcomes.h"

namespace snh::scene_io {

OutputSurfaceCheck::OutputSurfaceCheck(const SceneFile& file, const Mesh& mesh) : file_(&file), mesh_(&mesh) {
  if (file.embedded) {
    const WeldedSurface welded = weld_vertices(file.embedded->surface, 0.0);
    triangles_ = welded.surface.triangles;
    source_.assign(welded.surface.vertex_count(), -1);
    for (size_t i = 0; i < welded.vertex_of.size(); ++i)
      if (source_[size_t(welded.vertex_of[i])] < 0) source_[size_t(welded.vertex_of[i])] = int32_t(i);
  } else {
    MeshBoundary boundary = boundary_surface(mesh);
    triangles_ = std::move(boundary.surface.triangles);
    source_ = std::move(boundary.vertices);
  }
}

SelfIntersections OutputSurfaceCheck::count(const Points& x, const Points& surface) const {
  Points embedded;
  const Points* from = &x;
  if (file_->embedded) {
    if (surface.empty()) embedded = embedded_positions(file_->embedded->embedding, *mesh_, x);
    from = surface.empty() ? &embedded : &surface;
  }
  Points positions(source_.size());
  for (size_t i = 0; i < source_.size(); ++i)
    for (int d = 0; d < 3; ++d) positions(i, d) = (*from)(size_t(source_[i]), d);
  for (double v : positions.xyz())
    if (!std::isfinite(v)) {
      // Not countable: reported as damage, never as clean.
      SelfIntersections damaged;
      damaged.triangles = triangles_.size() / 3;
      damaged.degenerate_triangles = damaged.triangles;
      return damaged;
    }
  return count_self_intersections(positions, triangles_);
}

std::string OutputSurfaceCheck::warning(const SelfIntersections& count) {
  if (count.clean()) return "";
  std::string w =
      warning_text(ResultWarning::surface_intersections,
                   std::to_string(count.intersecting_pairs) + " intersecting triangle pairs of the output surface");
  if (!count.first_pairs.empty())
    w += " (first: triangles " + std::to_string(count.first_pairs[0][0]) + " and " +
         std::to_string(count.first_pairs[0][1]) + ")";
  if (count.degenerate_triangles > 0)
    w += ", " + std::to_string(count.degenerate_triangles) + " degenerate or non-finite triangles not counted";
  return w;
}

}  // namespace snh::scene_io
