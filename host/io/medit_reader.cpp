// Medit ASCII .mesh (MeshVersionFormatted 1 or 2, Dimension 3): Vertices,
// Tetrahedra and Hexahedra, 1-based indices, each entry ending with a
// reference number. Other 0D-2D keywords are skipped; other volume elements
// are rejected. Medit's own orientation convention is not relied on: the
// builder turns mirrored elements over. The reference numbers of
// tetrahedra and hexahedra become volume groups, those of triangles and
// quadrilaterals surface groups and those of edges curve groups, each named
// by its number (as gmsh writes them, the elementary entity tags).
// Reference 0 is Medit's "none": entries with it are in no group.
#include <limits>
#include <map>
#include <sstream>

#include "io/readers.h"
#include "snh/error.h"

namespace snh::io {
namespace {

struct Keyword {
  const char* name;
  int values;  // per entry
  int kind;    // 0 skip, 1 vertices, 2 tetrahedra, 3 hexahedra, 4 unsupported volume,
               // 5 edges, 6 triangles, 7 quadrilaterals
};

// Entry sizes, including the trailing reference where the format has one.
constexpr Keyword kKeywords[] = {
    {"Vertices", 4, 1},
    {"Tetrahedra", 5, 2},
    {"Hexahedra", 9, 3},
    {"Edges", 3, 5},
    {"Triangles", 4, 6},
    {"Quadrilaterals", 5, 7},
    {"Corners", 1, 0},
    {"RequiredVertices", 1, 0},
    {"Ridges", 1, 0},
    {"RequiredEdges", 1, 0},
    {"RequiredTriangles", 1, 0},
    {"RequiredQuadrilaterals", 1, 0},
    {"Normals", 3, 0},
    {"NormalAtVertices", 2, 0},
    {"Tangents", 3, 0},
    {"TangentAtVertices", 2, 0},
    {"TangentAtEdges", 3, 0},
    {"EdgesP2", 4, 0},
    {"TrianglesP2", 7, 0},
    {"QuadrilateralsQ2", 10, 0},
    {"Prisms", 7, 4},
    {"Pyramids", 6, 4},
    {"TetrahedraP2", 11, 4},
    {"HexahedraQ2", 28, 4},
    {"RequiredTetrahedra", 1, 0},
    {"RequiredHexahedra", 1, 0},
};

class MeditReader {
 public:
  MeditReader(const std::string& path, const std::string& data, const MeshReadOptions& options)
      : path_(path), s_(path, data), builder_(path) {
    builder_.options = options;
  }

  Mesh read() {
    bool have_version = false, have_dimension = false;
    for (;;) {
      const std::string_view key = s_.token('#');
      if (key.empty()) break;
      const uint64_t line = s_.token_line();
      if (iequals(key, "End")) break;
      if (iequals(key, "MeshVersionFormatted")) {
        const int64_t v = s_.integer("the mesh version", '#');
        if (v != 1 && v != 2)
          fail(path_, line_at(s_.token_line()),
               "MeshVersionFormatted " + std::to_string(v) + " is not supported (1 or 2)");
        have_version = true;
        continue;
      }
      if (!have_version)
        fail(path_, line_at(line), "not a Medit mesh: expected MeshVersionFormatted first, found " + quote(key));
      if (iequals(key, "Dimension")) {
        const int64_t d = s_.integer("the dimension", '#');
        if (d != 3) fail(path_, line_at(s_.token_line()), "Dimension " + std::to_string(d) + " is not supported (3)");
        have_dimension = true;
        continue;
      }
      if (iequals(key, "Identifier") || iequals(key, "Geometry")) {
        s_.rest_of_line();
        continue;
      }
      const Keyword* k = nullptr;
      for (const Keyword& c : kKeywords)
        if (iequals(key, c.name)) k = &c;
      if (!k) fail(path_, line_at(line), "unknown keyword " + quote(key) + " (its data cannot be skipped)");
      if (!have_dimension && k->kind != 0)
        fail(path_, line_at(line), std::string(k->name) + " comes before the Dimension keyword");
      const int64_t n = s_.integer(std::string("the number of ") + k->name, '#');
      if (n < 0 || static_cast<uint64_t>(n) > s_.remaining())
        fail(path_, line_at(s_.token_line()),
             std::string("the number of ") + k->name + " is " + std::to_string(n) + ", which the file cannot hold");
      if (k->kind == 4 && n > 0) {
        std::ostringstream m;
        m << "the file has " << n << " " << k->name << ", an unsupported element type (only Tetrahedra and "
          << "Hexahedra are supported)";
        fail(path_, line_at(line), m.str());
      }
      if (k->kind == 1 && builder_.vertex_count() > 0) fail(path_, line_at(line), "a second Vertices section");
      if (k->kind >= 2 && k->kind != 4 && builder_.vertex_count() == 0 && n > 0)
        fail(path_, line_at(line), std::string(k->name) + " come before any Vertices");
      for (int64_t i = 0; i < n; ++i) entry(*k, i + 1, n);
    }
    if (!have_version) fail(path_, "not a Medit mesh: no MeshVersionFormatted keyword");
    for (auto& [key, group] : groups_) builder_.groups.push_back(std::move(group));
    return builder_.finish();
  }

 private:
  void entry(const Keyword& k, int64_t number, int64_t n) {
    const std::string what = std::string(k.name) + " entry " + std::to_string(number) + " of " + std::to_string(n);
    if (k.kind == 1) {
      double xyz[3];
      for (int d = 0; d < 3; ++d) xyz[d] = s_.real("coordinate " + std::string(1, "xyz"[d]) + " of " + what, '#');
      const uint64_t line = s_.token_line();
      s_.integer("the reference of " + what, '#');
      builder_.add_vertex(number, xyz, line_at(line));
      return;
    }
    if (k.kind == 2 || k.kind == 3 || k.kind >= 5) {
      const int nodes = k.values - 1;
      int32_t v[8];
      uint64_t line = 0;
      for (int a = 0; a < nodes; ++a) {
        const int64_t index = s_.integer("vertex " + std::to_string(a + 1) + " of " + what, '#');
        if (a == 0) line = s_.token_line();
        if (index < 1 || static_cast<uint64_t>(index) > builder_.vertex_count()) {
          std::ostringstream m;
          static const char* const kNouns[8] = {"", "",     "tetrahedron", "hexahedron",
                                                "", "edge", "triangle",    "quadrilateral"};
          m << kNouns[k.kind] << " " << number << " refers to vertex " << index << ", but the file has "
            << builder_.vertex_count() << " Vertices (numbered from 1)";
          fail(path_, line_at(s_.token_line()), m.str());
        }
        v[a] = static_cast<int32_t>(index - 1);
      }
      const int64_t reference = s_.integer("the reference of " + what, '#');
      if (reference < std::numeric_limits<int>::min() || reference > std::numeric_limits<int>::max())
        fail(path_, line_at(s_.token_line()), "the reference of " + what + " is out of range");
      const int dimension = k.kind == 5 ? 1 : (k.kind >= 6 ? 2 : 3);
      if (reference == 0) {  // Medit's "no reference": no group
        if (dimension == 3)
          builder_.add_element(k.kind == 2 ? ElementType::tet4 : ElementType::hex8, number, v, line_at(line));
        return;
      }
      MeshGroup& group = groups_[{dimension, reference}];
      group.name = std::to_string(reference);
      group.tag = static_cast<int>(reference);
      group.dimension = dimension;
      if (dimension == 3) {
        group.elements.push_back(static_cast<int32_t>(builder_.element_count()));
        builder_.add_element(k.kind == 2 ? ElementType::tet4 : ElementType::hex8, number, v, line_at(line));
      } else {
        group.vertices.insert(group.vertices.end(), v, v + nodes);
      }
      return;
    }
    for (int i = 0; i < k.values; ++i) s_.real("value " + std::to_string(i + 1) + " of " + what, '#');
  }

  const std::string& path_;
  Scanner s_;
  MeshBuilder builder_;
  std::map<std::pair<int, int64_t>, MeshGroup> groups_;  // by (dimension, reference)
};

}  // namespace

Mesh read_medit(const std::string& path, const std::string& data, const MeshReadOptions& options) {
  return MeditReader(path, data, options).read();
}

}  // namespace snh::io
