// Internals shared by the surface readers (surface.h): a builder that collects
// vertices and polygons with where each came from, fans polygons into
// triangles and checks indices, and the per-format readers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/readers.h"
#include "snh/surface.h"

namespace snh::io {

class SurfaceBuilder {
 public:
  explicit SurfaceBuilder(const std::string& path) : path_(path) {}

  // Appends a vertex; throws for a non-finite coordinate. Returns its index.
  int32_t add_vertex(const double xyz[3], Location where);
  size_t vertex_count() const { return surface_.vertex_count(); }

  // Appends a polygon of 0-based vertex indices as the triangles of a fan
  // from its first corner. Throws naming `where` for fewer than 3 corners,
  // an index out of range or a corner repeated (a degenerate triangle would
  // break the surface's edge checks).
  void add_polygon(const int64_t* corners, size_t count, Location where);

  // Throws when the file held no triangles.
  TriangleSurface finish();

 private:
  const std::string& path_;
  TriangleSurface surface_;
};

// The readers, on a file's whole contents.
TriangleSurface read_obj(const std::string& path, const std::string& data);
TriangleSurface read_ply(const std::string& path, const std::string& data);
TriangleSurface read_stl(const std::string& path, const std::string& data);

}  // namespace snh::io
