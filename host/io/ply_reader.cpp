// PLY surfaces (ASCII, binary little and big endian): the `vertex` element's
// x, y and z properties (any numeric type) and the `face` element's
// `vertex_indices` (or `vertex_index`) list, 0-based. Other properties and
// elements are read past and ignored.
#include <cstring>
#include <string_view>
#include <vector>

#include "io/surface_readers.h"

namespace snh::io {
namespace {

enum class Type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool parse_type(std::string_view name, Type& type) {
  static const struct {
    const char* a;
    const char* b;
    Type type;
  } names[] = {{"char", "int8", Type::int8},        {"uchar", "uint8", Type::uint8},
               {"short", "int16", Type::int16},     {"ushort", "uint16", Type::uint16},
               {"int", "int32", Type::int32},       {"uint", "uint32", Type::uint32},
               {"float", "float32", Type::float32}, {"double", "float64", Type::float64}};
  for (const auto& n : names)
    if (name == n.a || name == n.b) {
      type = n.type;
      return true;
    }
  return false;
}

bool is_integer(Type t) { return t != Type::float32 && t != Type::float64; }

struct Property {
  std::string name;
  Type type = Type::float32;
  bool list = false;
  Type count_type = Type::uint8;
};

struct Element {
  std::string name;
  int64_t count = 0;
  uint64_t line = 0;
  std::vector<Property> properties;
};

enum class Format { ascii, little, big };

bool host_is_big_endian() {
  const uint16_t one = 1;
  unsigned char byte;
  std::memcpy(&byte, &one, 1);
  return byte == 0;
}

class Body {
 public:
  Body(Scanner& scan, Format format) : scan_(scan), format_(format) {
    swap_ = format != Format::ascii && ((format == Format::big) != host_is_big_endian());
  }

  double real(Type type, const std::string& what) {
    if (format_ == Format::ascii) return is_integer(type) ? double(scan_.integer(what)) : scan_.real(what);
    return binary(type, what.c_str());
  }

  int64_t integer(Type type, const std::string& what) {
    if (!is_integer(type)) {
      const Location where = here();
      fail(scan_.path(), where, what + " has a floating-point type; an integer type is expected");
    }
    if (format_ == Format::ascii) return scan_.integer(what);
    return static_cast<int64_t>(binary(type, what.c_str()));
  }

  Location here() {
    if (format_ != Format::ascii) return byte_at(scan_.pos());
    scan_.skip_space();
    return line_at(scan_.line());
  }

 private:
  double binary(Type type, const char* what) {
    switch (type) {
      case Type::int8:
        return scan_.binary<int8_t>(swap_, what);
      case Type::uint8:
        return scan_.binary<uint8_t>(swap_, what);
      case Type::int16:
        return scan_.binary<int16_t>(swap_, what);
      case Type::uint16:
        return scan_.binary<uint16_t>(swap_, what);
      case Type::int32:
        return scan_.binary<int32_t>(swap_, what);
      case Type::uint32:
        return scan_.binary<uint32_t>(swap_, what);
      case Type::float32:
        return scan_.binary<float>(swap_, what);
      case Type::float64:
        return scan_.binary<double>(swap_, what);
    }
    return 0.0;
  }

  Scanner& scan_;
  Format format_;
  bool swap_ = false;
};

}  // namespace

TriangleSurface read_ply(const std::string& path, const std::string& data) {
  Scanner scan(path, data);
  std::string_view text;
  uint64_t line = 0;
  if (!scan.next_line(text, line) || split(text) != std::vector<std::string_view>{"ply"})
    fail(path, line_at(1), "not a PLY file (the first line must be 'ply')");

  bool have_format = false;
  Format format = Format::ascii;
  std::vector<Element> elements;
  for (;;) {
    if (!scan.next_line(text, line)) fail(path, line_at(scan.line()), "the header ends without 'end_header'");
    const std::vector<std::string_view> t = split(text);
    if (t[0] == "end_header") break;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() != 3 || t[2] != "1.0")
        fail(path, line_at(line), "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (t[1] == "ascii")
        format = Format::ascii;
      else if (t[1] == "binary_little_endian")
        format = Format::little;
      else if (t[1] == "binary_big_endian")
        format = Format::big;
      else
        fail(path, line_at(line), "unknown PLY format " + quote(t[1]));
      have_format = true;
    } else if (t[0] == "element") {
      Element e;
      if (t.size() != 3 || !parse_int(t[2], e.count) || e.count < 0)
        fail(path, line_at(line), "expected 'element NAME COUNT' with a count >= 0");
      e.name = std::string(t[1]);
      e.line = line;
      elements.push_back(e);
    } else if (t[0] == "property") {
      if (elements.empty()) fail(path, line_at(line), "a property before any element");
      Property p;
      if (t.size() == 5 && t[1] == "list") {
        p.list = true;
        if (!parse_type(t[2], p.count_type) || !is_integer(p.count_type))
          fail(path, line_at(line), "a list's count type must be an integer type, found " + quote(t[2]));
        if (!parse_type(t[3], p.type)) fail(path, line_at(line), "unknown property type " + quote(t[3]));
        p.name = std::string(t[4]);
      } else if (t.size() == 3) {
        if (!parse_type(t[1], p.type)) fail(path, line_at(line), "unknown property type " + quote(t[1]));
        p.name = std::string(t[2]);
      } else {
        fail(path, line_at(line), "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      elements.back().properties.push_back(p);
    } else {
      fail(path, line_at(line), "unknown header line " + quote(text));
    }
  }
  if (!have_format) fail(path, line_at(line), "the header has no 'format' line");

  SurfaceBuilder builder(path);
  std::vector<int64_t> corners, offsets{0};
  std::vector<Location> face_where;
  bool have_vertices = false, have_faces = false;
  Body body(scan, format);
  for (const Element& e : elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face";
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
    for (size_t i = 0; i < e.properties.size(); ++i) {
      const Property& p = e.properties[i];
      if (vertex && !p.list && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z')
        xyz[p.name[0] - 'x'] = static_cast<int>(i);
      if (face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = static_cast<int>(i);
    }
    if (vertex) {
      for (int d = 0; d < 3; ++d)
        if (xyz[d] < 0)
          fail(path, line_at(e.line), std::string("the vertex element has no scalar property '") + "xyz"[d] + "'");
      have_vertices = true;
    }
    if (face) {
      if (indices < 0) fail(path, line_at(e.line), "the face element has no 'vertex_indices' list");
      have_faces = true;
    }
    for (int64_t n = 0; n < e.count; ++n) {
      const Location where = body.here();
      const std::string who = e.name + " " + std::to_string(n);
      double position[3] = {0.0, 0.0, 0.0};
      for (size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        const std::string what = who + "'s " + p.name;
        if (p.list) {
          const int64_t count = body.integer(p.count_type, what + " count");
          if (count < 0) fail(path, where, what + " has a negative count");
          for (int64_t k = 0; k < count; ++k) {
            if (face && static_cast<int>(i) == indices)
              corners.push_back(body.integer(p.type, what));
            else
              body.real(p.type, what);
          }
        } else {
          const double value = body.real(p.type, what);
          for (int d = 0; d < 3; ++d)
            if (vertex && static_cast<int>(i) == xyz[d]) position[d] = value;
        }
      }
      if (vertex) builder.add_vertex(position, where);
      if (face) {
        offsets.push_back(static_cast<int64_t>(corners.size()));
        face_where.push_back(where);
      }
    }
  }
  if (!have_vertices) fail(path, "the header declares no vertex element");
  if (!have_faces) fail(path, "the header declares no face element");
  if (format == Format::ascii) {
    scan.skip_space();
    if (!scan.at_end()) fail(path, line_at(scan.line()), "unexpected data after the last element");
  } else if (!scan.at_end()) {
    fail(path, byte_at(scan.pos()), "unexpected data after the last element");
  }
  // Faces are added after all vertices so that a file listing faces first still reads.
  for (size_t f = 0; f + 1 < offsets.size(); ++f)
    builder.add_polygon(corners.data() + offsets[f], static_cast<size_t>(offsets[f + 1] - offsets[f]), face_where[f]);
  return builder.finish();
}

}  // namespace snh::io
