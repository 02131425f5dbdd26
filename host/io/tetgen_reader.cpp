// TetGen .node/.ele pairs: points numbered consecutively from 0 or 1 (the
// first point's number sets the base, as TetGen does), 4-node tetrahedra.
// '#' starts a comment. TetGen's orientation is not relied on: the builder
// turns mirrored tetrahedra over.
#include <sstream>

#include "io/readers.h"
#include "snh/error.h"

namespace snh::io {
namespace {

std::vector<std::string_view> next(Scanner& s, const std::string& what, uint64_t& line) {
  std::string_view text;
  if (!s.next_line(text, line, '#')) fail(s.path(), line_at(s.line()), "the file ends where " + what + " was expected");
  return split(text);
}

int64_t to_int(const Scanner& s, std::string_view t, const std::string& what, uint64_t line) {
  int64_t v = 0;
  if (!parse_int(t, v)) fail(s.path(), line_at(line), "expected " + what + " (an integer), found " + quote(t));
  return v;
}

}  // namespace

Mesh read_tetgen(const std::string& node_path, const std::string& node_data, const std::string& ele_path,
                 const std::string& ele_data, const MeshReadOptions& options) {
  MeshBuilder builder(ele_path, node_path);
  builder.options = options;
  Scanner s(node_path, node_data);
  uint64_t line = 0;
  auto t = next(s, "the .node header (points, dimension, attributes, markers)", line);
  if (t.size() != 4 && t.size() != 3 && t.size() != 2)
    fail(node_path, line_at(line),
         "the header has " + std::to_string(t.size()) +
             " values, expected 4 (points, dimension, attributes, boundary markers)");
  const int64_t points = to_int(s, t[0], "the number of points", line);
  const int64_t dimension = to_int(s, t[1], "the dimension", line);
  const int64_t attributes = t.size() > 2 ? to_int(s, t[2], "the number of attributes", line) : 0;
  const int64_t markers = t.size() > 3 ? to_int(s, t[3], "the boundary marker flag", line) : 0;
  if (points <= 0 || static_cast<uint64_t>(points) > node_data.size())
    fail(node_path, line_at(line),
         "the number of points is " + std::to_string(points) +
             (points == 0 ? " (points kept in a .poly file are not supported)" : ""));
  if (dimension != 3) fail(node_path, line_at(line), "dimension " + std::to_string(dimension) + " is not 3");
  if (attributes < 0 || attributes > 1000)
    fail(node_path, line_at(line), "the number of attributes is " + std::to_string(attributes));
  if (markers != 0 && markers != 1)
    fail(node_path, line_at(line), "the boundary marker flag is " + std::to_string(markers) + ", not 0 or 1");
  const size_t values = static_cast<size_t>(4 + attributes + markers);
  int64_t base = 0;
  std::vector<double> xyz;
  for (int64_t i = 0; i < points; ++i) {
    t = next(s, "point " + std::to_string(i + 1) + " of " + std::to_string(points), line);
    if (t.size() != values) {
      std::ostringstream m;
      m << "point line " << i + 1 << " of " << points << " has " << t.size() << " values, expected " << values
        << " (number, x, y, z, " << attributes << " attributes, " << markers << " markers)";
      fail(node_path, line_at(line), m.str());
    }
    const int64_t number = to_int(s, t[0], "a point number", line);
    if (i == 0) {
      if (number != 0 && number != 1)
        fail(node_path, line_at(line), "the first point is numbered " + std::to_string(number) + ", not 0 or 1");
      base = number;
    } else if (number != base + i) {
      std::ostringstream m;
      m << "point numbers must be consecutive: expected " << base + i << ", found " << number;
      fail(node_path, line_at(line), m.str());
    }
    double p[3];
    for (int d = 0; d < 3; ++d)
      if (!parse_double(t[1 + d], p[d]))
        fail(node_path, line_at(line), "expected a coordinate (a number), found " + quote(t[1 + d]));
    builder.add_vertex(number, p, line_at(line));
  }

  Scanner e(ele_path, ele_data);
  t = next(e, "the .ele header (tetrahedra, nodes per tetrahedron, region attribute)", line);
  if (t.size() != 3 && t.size() != 2)
    fail(ele_path, line_at(line),
         "the header has " + std::to_string(t.size()) +
             " values, expected 3 (tetrahedra, nodes per tetrahedron, region attribute)");
  const int64_t tets = to_int(e, t[0], "the number of tetrahedra", line);
  const int64_t per = to_int(e, t[1], "the nodes per tetrahedron", line);
  const int64_t region = t.size() > 2 ? to_int(e, t[2], "the region attribute flag", line) : 0;
  if (tets < 0 || static_cast<uint64_t>(tets) > ele_data.size())
    fail(ele_path, line_at(line), "the number of tetrahedra is " + std::to_string(tets));
  if (per != 4)
    fail(ele_path, line_at(line), std::to_string(per) + " nodes per tetrahedron are not supported (only 4)");
  if (region != 0 && region != 1)
    fail(ele_path, line_at(line), "the region attribute flag is " + std::to_string(region) + ", not 0 or 1");
  for (int64_t i = 0; i < tets; ++i) {
    t = next(e, "tetrahedron " + std::to_string(i + 1) + " of " + std::to_string(tets), line);
    if (t.size() != static_cast<size_t>(5 + region)) {
      std::ostringstream m;
      m << "tetrahedron line " << i + 1 << " of " << tets << " has " << t.size() << " values, expected " << 5 + region;
      fail(ele_path, line_at(line), m.str());
    }
    const int64_t number = to_int(e, t[0], "a tetrahedron number", line);
    int32_t v[4];
    for (int a = 0; a < 4; ++a) {
      const int64_t n = to_int(e, t[1 + a], "a point number", line);
      if (n < base || n - base >= points) {
        std::ostringstream m;
        m << "tetrahedron " << number << " refers to point " << n << ", which " << node_path
          << " does not define (points " << base << " to " << base + points - 1 << ")";
        fail(ele_path, line_at(line), m.str());
      }
      v[a] = static_cast<int32_t>(n - base);
    }
    builder.add_element(ElementType::tet4, number, v, line_at(line));
  }
  return builder.finish();
}

}  // namespace snh::io
