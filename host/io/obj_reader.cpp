// Wavefront OBJ surfaces: `v x y z` vertices (a fourth weight or vertex
// colours are ignored) and `f` faces whose corners are `v`, `v/vt`, `v//vn`
// or `v/vt/vn`, 1-based or negative (relative to the vertices read so far).
// Other statements (vt, vn, g, o, s, usemtl, mtllib, l, p) are skipped.
#include <string_view>
#include <vector>

#include "io/surface_readers.h"

namespace snh::io {

TriangleSurface read_obj(const std::string& path, const std::string& data) {
  Scanner scan(path, data);
  SurfaceBuilder builder(path);
  std::string_view text;
  uint64_t line = 0;
  std::vector<int64_t> corners;
  while (scan.next_line(text, line, '#')) {
    const std::vector<std::string_view> tokens = split(text);
    if (tokens[0] == "v") {
      if (tokens.size() < 4) fail(path, line_at(line), "a vertex needs 3 coordinates (v x y z)");
      double xyz[3];
      for (int d = 0; d < 3; ++d)
        if (!parse_double(tokens[1 + d], xyz[d]))
          fail(path, line_at(line),
               std::string("expected the vertex's ") + "xyz"[d] + " coordinate (a number), found " +
                   quote(tokens[1 + d]));
      builder.add_vertex(xyz, line_at(line));
    } else if (tokens[0] == "f") {
      corners.clear();
      for (size_t i = 1; i < tokens.size(); ++i) {
        const std::string_view vertex = tokens[i].substr(0, tokens[i].find('/'));
        int64_t index = 0;
        if (!parse_int(vertex, index) || index == 0)
          fail(path, line_at(line),
               "expected a face corner (a vertex number, 1-based or negative, before any '/'), found " +
                   quote(tokens[i]));
        const int64_t count = static_cast<int64_t>(builder.vertex_count());
        if (index > count || index < -count)
          fail(path, line_at(line),
               "face corner " + quote(tokens[i]) + " refers to vertex " + std::to_string(index) + ", but " +
                   std::to_string(count) + " vertices are defined before this line");
        corners.push_back(index > 0 ? index - 1 : count + index);
      }
      builder.add_polygon(corners.data(), corners.size(), line_at(line));
    }
  }
  return builder.finish();
}

}  // namespace snh::io
