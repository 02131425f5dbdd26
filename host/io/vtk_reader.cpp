// VTK legacy .vtk unstructured grids, ASCII and BINARY (big-endian), with
// the classic CELLS layout (count, then indices) or the 5.x OFFSETS and
// CONNECTIVITY arrays; and the VTK cell types both VTK readers share.
// POINT_DATA and CELL_DATA attributes (SCALARS, COLOR_SCALARS, VECTORS,
// NORMALS, TEXTURE_COORDINATES, TENSORS, FIELD arrays) become the mesh's
// point and cell arrays; lookup tables are skipped.
#include <cmath>
#include <sstream>

#include "io/readers.h"
#include "snh/error.h"

namespace snh::io {

namespace {

const char* vtk_cell_name(int64_t type) {
  switch (type) {
    case 13:
      return "wedge";
    case 14:
      return "pyramid";
    case 15:
      return "pentagonal prism";
    case 16:
      return "hexagonal prism";
    case 24:
      return "quadratic tetra";
    case 25:
      return "quadratic hexahedron";
    case 26:
      return "quadratic wedge";
    case 27:
      return "quadratic pyramid";
    case 29:
      return "triquadratic hexahedron";
    case 42:
      return "polyhedron";
    default:
      return "a volume or unknown cell";
  }
}

bool lower_dimensional(int64_t type) {
  switch (type) {
    case 1:
    case 2:
    case 3:
    case 4:
    case 5:
    case 6:
    case 7:
    case 8:
    case 9:  // vertex .. quad
    case 21:
    case 22:
    case 23:
    case 28:
    case 30:
    case 34:
    case 35:
    case 36:  // quadratic 1D/2D
    case 68:
    case 69:
    case 70:
    case 75:
    case 76:
    case 77:  // Lagrange, Bezier 1D/2D
      return true;
    default:
      return false;
  }
}

}  // namespace

bool add_vtk_cell(MeshBuilder& builder, const std::string& path, int64_t cell, int64_t vtk_type, const int64_t* nodes,
                  int64_t count, size_t vertices, Location where) {
  if (lower_dimensional(vtk_type)) return false;
  if (vtk_type != 10 && vtk_type != 11 && vtk_type != 12) {
    std::ostringstream m;
    m << "cell " << cell << " has unsupported VTK cell type " << vtk_type << " (" << vtk_cell_name(vtk_type)
      << "); only tetra (10), hexahedron (12) and voxel (11) are supported";
    fail(path, where, m.str());
  }
  const int64_t expected = vtk_type == 10 ? 4 : 8;
  if (count != expected) {
    std::ostringstream m;
    m << "cell " << cell << " (VTK type " << vtk_type << ") has " << count << " points, expected " << expected;
    fail(path, where, m.str());
  }
  int32_t v[8];
  for (int64_t a = 0; a < count; ++a) {
    if (nodes[a] < 0 || static_cast<uint64_t>(nodes[a]) >= vertices) {
      std::ostringstream m;
      m << "cell " << cell << " refers to point " << nodes[a] << ", but the file has " << vertices
        << " points (numbered from 0)";
      fail(path, where, m.str());
    }
    v[a] = static_cast<int32_t>(nodes[a]);
  }
  if (vtk_type == 11) {  // voxel: lattice order to hexahedron order
    std::swap(v[2], v[3]);
    std::swap(v[6], v[7]);
  }
  builder.add_element(vtk_type == 10 ? ElementType::tet4 : ElementType::hex8, cell, v, where);
  return true;
}

namespace {

class VtkLegacyReader {
 public:
  VtkLegacyReader(const std::string& path, const std::string& data, const MeshReadOptions& options)
      : path_(path), s_(path, data), builder_(path) {
    builder_.set_element_noun("cell");
    builder_.options = options;
  }

  Mesh read() {
    const std::string_view header = s_.rest_of_line();
    const std::string_view magic = "# vtk DataFile Version";
    if (header.substr(0, magic.size()) != magic)
      fail(path_, line_at(1),
           "not a VTK legacy file: the first line is " + quote(header) + ", not '" + std::string(magic) + " x.y'");
    {
      const auto t = split(header.substr(magic.size()));
      int64_t major = 0;
      const std::string_view v = t.empty() ? std::string_view() : t[0].substr(0, t[0].find('.'));
      if (!parse_int(v, major)) fail(path_, line_at(1), "the version is missing or malformed");
      version5_ = major >= 5;
    }
    s_.rest_of_line();  // title
    const std::string_view format = s_.token();
    if (iequals(format, "binary")) {
      binary_ = true;
    } else if (!iequals(format, "ascii")) {
      fail(path_, line_at(s_.token_line()), "expected ASCII or BINARY on line 3, found " + quote(format));
    }
    s_.rest_of_line();
    const std::string_view dataset = s_.token();
    const std::string_view kind = s_.token();
    if (!iequals(dataset, "dataset") || !iequals(kind, "unstructured_grid"))
      fail(path_, line_at(s_.token_line()),
           "expected DATASET UNSTRUCTURED_GRID, found " + quote(std::string(dataset) + " " + std::string(kind)));
    s_.rest_of_line();

    bool points = false, cells = false, types = false;
    for (;;) {
      const std::string_view key = s_.token();
      const uint64_t line = s_.token_line();
      if (key.empty()) break;
      if (iequals(key, "points")) {
        if (points) fail(path_, line_at(line), "a second POINTS section");
        read_points(line);
        points = true;
      } else if (iequals(key, "cells")) {
        if (cells) fail(path_, line_at(line), "a second CELLS section");
        read_cells(line);
        cells = true;
      } else if (iequals(key, "cell_types")) {
        if (types) fail(path_, line_at(line), "a second CELL_TYPES section");
        const int64_t n = count("the CELL_TYPES count", line);
        s_.rest_of_line();
        read_array(n, "int", nullptr, &types_, &type_where_, "a cell type");
        types = true;
      } else if (iequals(key, "metadata")) {
        skip_metadata();
      } else if (iequals(key, "field") && data_ == Data::none) {
        skip_field(line);
      } else if (iequals(key, "point_data") || iequals(key, "cell_data")) {
        const bool point = iequals(key, "point_data");
        if (point ? !points : !cells)
          fail(path_, line_at(line),
               std::string(point ? "POINT_DATA comes before POINTS" : "CELL_DATA comes before CELLS"));
        bool& seen = point ? seen_point_data_ : seen_cell_data_;
        if (seen)
          fail(path_, line_at(line), "a second " + std::string(point ? "POINT_DATA" : "CELL_DATA") + " section");
        seen = true;
        // Not bounded by the bytes left: a section may hold no arrays.
        const int64_t n = s_.integer(point ? "the POINT_DATA count" : "the CELL_DATA count");
        const size_t expected = point ? builder_.vertex_count() : cell_count_;
        if (n < 0 || static_cast<uint64_t>(n) != expected) {
          std::ostringstream m;
          m << (point ? "POINT_DATA" : "CELL_DATA") << " is for " << n << " " << (point ? "points" : "cells")
            << ", but the file has " << expected;
          fail(path_, line_at(line), m.str());
        }
        s_.rest_of_line();
        data_ = point ? Data::point : Data::cell;
        tuples_ = n;
      } else if (data_ != Data::none) {
        read_attribute(key, line);
      } else {
        fail(path_, line_at(line), "unexpected keyword " + quote(key) + " in an unstructured grid");
      }
    }
    if (!points) fail(path_, "the file has no POINTS section");
    if (!cells) fail(path_, "the file has no CELLS section");
    if (!types) fail(path_, "the file has no CELL_TYPES section");
    if (types_.size() != cell_count_) {
      std::ostringstream m;
      m << "CELL_TYPES has " << types_.size() << " entries, but CELLS has " << cell_count_ << " cells";
      fail(path_, type_where_.empty() ? line_at(s_.line()) : type_where_.front(), m.str());
    }
    std::vector<char> kept(cell_count_, 0);
    for (size_t c = 0; c < cell_count_; ++c)
      kept[c] = add_vtk_cell(builder_, path_, static_cast<int64_t>(c), types_[c], connectivity_.data() + cell_start_[c],
                             static_cast<int64_t>(cell_start_[c + 1] - cell_start_[c]), builder_.vertex_count(),
                             cell_where_[c]);
    for (auto& [array, where, point] : arrays_) {
      if (point)
        add_point_array(builder_, path_, where, std::move(array), builder_.vertex_count());
      else
        add_cell_array(builder_, path_, where, std::move(array), kept);
    }
    return builder_.finish();
  }

 private:
  enum class Data { none, point, cell };

  // Legacy names encode spaces and other bytes as %XX.
  static std::string decode_name(std::string_view name) {
    std::string out;
    for (size_t i = 0; i < name.size(); ++i) {
      int64_t byte = 0;
      if (name[i] == '%' && i + 2 < name.size() && parse_hex(name.substr(i + 1, 2), byte)) {
        out += static_cast<char>(byte);
        i += 2;
      } else {
        out += name[i];
      }
    }
    return out;
  }
  static bool parse_hex(std::string_view two, int64_t& value) {
    value = 0;
    for (char c : two) {
      const int d = (c >= '0' && c <= '9')   ? c - '0'
                    : (c >= 'a' && c <= 'f') ? c - 'a' + 10
                    : (c >= 'A' && c <= 'F') ? c - 'A' + 10
                                             : -1;
      if (d < 0) return false;
      value = 16 * value + d;
    }
    return true;
  }

  void skip_metadata() {
    // Up to the first blank line.
    std::string_view text;
    s_.rest_of_line();
    while (!s_.at_end() && !(text = s_.rest_of_line()).empty()) {
    }
  }

  std::string array_name(const char* what) {
    const std::string_view name = s_.token();
    if (name.empty())
      fail(path_, line_at(s_.token_line()), std::string("the file ends where the name of ") + what + " was expected");
    return decode_name(name);
  }

  // A data type token, lower-cased.
  std::string data_type() {
    const std::string_view t = s_.token();
    std::string type(t);
    for (char& c : type)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return type;
  }

  // One attribute of the current POINT_DATA or CELL_DATA section.
  void read_attribute(std::string_view key, uint64_t line) {
    const bool point = data_ == Data::point;
    const std::string kind = point ? "point" : "cell";
    auto add = [&](std::string name, int64_t components, const std::string& type, const std::string& what) {
      if (components < 1 || components > 64)
        fail(path_, line_at(line), what + " " + quote(name) + " has " + std::to_string(components) + " components");
      if (tuples_ > static_cast<int64_t>(s_.remaining()) / components)
        fail(path_, line_at(line), what + " " + quote(name) + " is larger than the file");
      MeshArray a{std::move(name), static_cast<int>(components), {}};
      read_array(tuples_ * components, type, &a.values, nullptr, nullptr, "a value of " + what + " " + quote(a.name));
      arrays_.push_back({std::move(a), line_at(line), point});
    };
    if (iequals(key, "scalars")) {
      std::string name = array_name("a SCALARS array");
      const std::string type = data_type();
      int64_t components = 1;
      const std::string_view rest = s_.rest_of_line();
      const auto extra = split(rest);
      if (extra.size() > 1 || (extra.size() == 1 && !parse_int(extra[0], components)))
        fail(path_, line_at(line),
             "SCALARS " + quote(name) + ": expected an optional component count, found " + quote(rest));
      if (!binary_) s_.skip_space();  // binary values may start with a space byte
      if (s_.data().compare(s_.pos(), 12, "LOOKUP_TABLE") == 0) {
        s_.token();
        s_.rest_of_line();
      }
      add(std::move(name), components, type, kind + " SCALARS");
    } else if (iequals(key, "vectors") || iequals(key, "normals")) {
      std::string name = array_name("a VECTORS array");
      const std::string type = data_type();
      s_.rest_of_line();
      add(std::move(name), 3, type, kind + " " + std::string(key));
    } else if (iequals(key, "tensors") || iequals(key, "tensors6")) {
      std::string name = array_name("a TENSORS array");
      const std::string type = data_type();
      s_.rest_of_line();
      add(std::move(name), iequals(key, "tensors") ? 9 : 6, type, kind + " " + std::string(key));
    } else if (iequals(key, "texture_coordinates")) {
      std::string name = array_name("a TEXTURE_COORDINATES array");
      const int64_t dimension = s_.integer("the TEXTURE_COORDINATES dimension");
      const std::string type = data_type();
      s_.rest_of_line();
      add(std::move(name), dimension, type, kind + " TEXTURE_COORDINATES");
    } else if (iequals(key, "color_scalars")) {
      std::string name = array_name("a COLOR_SCALARS array");
      const int64_t components = s_.integer("the COLOR_SCALARS value count");
      s_.rest_of_line();
      const size_t before = arrays_.size();
      add(std::move(name), components, binary_ ? "unsigned_char" : "float", kind + " COLOR_SCALARS");
      if (binary_ && arrays_.size() > before)
        for (double& v : arrays_.back().array.values) v /= 255.0;
    } else if (iequals(key, "lookup_table")) {
      array_name("a LOOKUP_TABLE");
      const int64_t n = count("the LOOKUP_TABLE size", line);
      s_.rest_of_line();
      std::vector<double> ignored;
      read_array(4 * n, binary_ ? "unsigned_char" : "float", &ignored, nullptr, nullptr, "a LOOKUP_TABLE value");
    } else if (iequals(key, "field")) {
      s_.token();  // the field's name
      const int64_t arrays = count("the FIELD array count", line);
      s_.rest_of_line();
      for (int64_t i = 0; i < arrays; ++i) {
        s_.skip_space();
        if (s_.data().compare(s_.pos(), 8, "METADATA") == 0) {
          s_.token();
          skip_metadata();
        }
        std::string name = array_name("a FIELD array");
        const uint64_t at = s_.token_line();
        const int64_t components = count("a FIELD array's component count", at);
        const int64_t tuples = count("a FIELD array's tuple count", at);
        const std::string type = data_type();
        s_.rest_of_line();
        if (tuples != tuples_) {
          std::ostringstream m;
          m << "FIELD array " << quote(name) << " has " << tuples << " tuples, but its "
            << (point ? "POINT_DATA" : "CELL_DATA") << " section is for " << tuples_ << " " << kind << "s";
          fail(path_, line_at(at), m.str());
        }
        line = at;
        add(std::move(name), components, type, kind + " FIELD array");
      }
    } else {
      fail(path_, line_at(line),
           "unexpected keyword " + quote(key) + " in " + (point ? "POINT_DATA" : "CELL_DATA") +
               " (expected SCALARS, VECTORS, NORMALS, TENSORS, TEXTURE_COORDINATES, "
               "COLOR_SCALARS, LOOKUP_TABLE or FIELD)");
    }
  }

  int64_t count(const std::string& what, uint64_t line) {
    const int64_t n = s_.integer(what);
    if (n < 0 || static_cast<uint64_t>(n) > s_.remaining())
      fail(path_, line_at(line),
           what + " is " + std::to_string(n) + (n < 0 ? ", which is negative" : ", more than the file holds"));
    return n;
  }

  static int type_size(std::string_view type) {
    if (type == "float" || type == "int" || type == "unsigned_int" || type == "vtktypeint32" || type == "vtktypeuint32")
      return 4;
    if (type == "double" || type == "long" || type == "unsigned_long" || type == "vtktypeint64" ||
        type == "vtktypeuint64" || type == "vtkidtype")
      return 8;
    if (type == "short" || type == "unsigned_short") return 2;
    if (type == "char" || type == "unsigned_char" || type == "bit") return 1;
    return 0;
  }

  // n values of `type`, as reals or integers, with each value's location.
  void read_array(int64_t n, std::string_view type, std::vector<double>* reals, std::vector<int64_t>* ints,
                  std::vector<Location>* where, const std::string& what) {
    const int size = type_size(type);
    if (size == 0 || type == "bit") fail(path_, line_at(s_.line()), "unsupported data type " + quote(type));
    if (binary_) s_.need(static_cast<uint64_t>(n) * static_cast<uint64_t>(size), std::to_string(n) + " values");
    const size_t reserve = static_cast<size_t>(std::min<uint64_t>(static_cast<uint64_t>(n), s_.remaining()));
    if (reals) reals->reserve(reserve);
    if (ints) ints->reserve(reserve);
    if (where) where->reserve(reserve);
    const bool is_float = type == "float" || type == "double";
    const bool is_unsigned = type.substr(0, 8) == "unsigned" || type == "vtktypeuint32" || type == "vtktypeuint64";
    for (int64_t i = 0; i < n; ++i) {
      double r = 0.0;
      int64_t k = 0;
      Location at;
      if (binary_) {
        at = byte_at(s_.pos());
        if (is_float) {
          r = size == 4 ? s_.binary<float>(true, what.c_str()) : s_.binary<double>(true, what.c_str());
          if (ints) {
            if (!(r >= -9.2e18 && r <= 9.2e18) || r != std::floor(r)) fail(path_, at, what + " is not an integer");
            k = static_cast<int64_t>(r);
          }
        } else {
          switch (size) {
            case 1:
              k = is_unsigned ? s_.binary<uint8_t>(true, what.c_str()) : s_.binary<int8_t>(true, what.c_str());
              break;
            case 2:
              k = is_unsigned ? s_.binary<uint16_t>(true, what.c_str()) : s_.binary<int16_t>(true, what.c_str());
              break;
            case 4:
              k = is_unsigned ? s_.binary<uint32_t>(true, what.c_str()) : s_.binary<int32_t>(true, what.c_str());
              break;
            default: {
              const uint64_t u = s_.binary<uint64_t>(true, what.c_str());
              k = static_cast<int64_t>(u);
              if (is_unsigned && k < 0) fail(path_, at, what + " is out of range");
            }
          }
          r = static_cast<double>(k);
        }
      } else {
        const std::string_view t = s_.token();
        at = line_at(s_.token_line());
        if (t.empty()) fail(path_, at, "the file ends where " + what + " was expected (does the count match?)");
        if (ints) {
          if (!parse_int(t, k)) fail(path_, at, "expected " + what + " (an integer), found " + quote(t));
        } else if (!parse_double(t, r)) {
          fail(path_, at, "expected " + what + " (a number), found " + quote(t));
        }
      }
      if (reals) reals->push_back(r);
      if (ints) ints->push_back(k);
      if (where) where->push_back(at);
    }
  }

  void read_points(uint64_t line) {
    const int64_t n = count("the POINTS count", line);
    const std::string_view type = s_.token();
    if (type != "float" && type != "double" && !(type_size(type) != 0 && !binary_))
      fail(path_, line_at(s_.token_line()), "unsupported POINTS data type " + quote(type));
    s_.rest_of_line();
    std::vector<double> xyz;
    std::vector<Location> where;
    read_array(3 * n, type, &xyz, nullptr, &where, "a point coordinate");
    for (int64_t i = 0; i < n; ++i) builder_.add_vertex(i, xyz.data() + 3 * i, where[3 * i]);
  }

  void read_cells(uint64_t line) {
    const int64_t a = count("the CELLS count", line);
    const int64_t b = count("the CELLS size", line);
    s_.rest_of_line();
    std::vector<int64_t> values;
    std::vector<Location> where;
    cell_start_.clear();
    if (version5_) {
      // CELLS offsets connectivity; OFFSETS type ...; CONNECTIVITY type ...
      std::vector<int64_t> offsets;
      std::vector<Location> offset_where;
      s_.expect("OFFSETS", "after CELLS");
      std::string type(s_.token());
      s_.rest_of_line();
      read_array(a, type, nullptr, &offsets, &offset_where, "a cell offset");
      s_.expect("CONNECTIVITY", "after the cell offsets");
      type = std::string(s_.token());
      s_.rest_of_line();
      read_array(b, type, nullptr, &connectivity_, &where, "a cell point index");
      if (a == 0) fail(path_, line_at(line), "CELLS has no offsets (at least one, 0, is needed)");
      for (int64_t i = 0; i < a; ++i) {
        const int64_t o = offsets[i];
        if ((i == 0 && o != 0) || (i > 0 && o < offsets[i - 1]) || o > b) {
          std::ostringstream m;
          m << "cell offset " << i << " is " << o << ", out of order or beyond the " << b << " connectivity entries";
          fail(path_, offset_where[i], m.str());
        }
        cell_start_.push_back(static_cast<size_t>(o));
      }
      if (offsets.back() != b) {
        std::ostringstream m;
        m << "the last cell offset is " << offsets.back() << ", but CONNECTIVITY has " << b << " entries";
        fail(path_, offset_where.back(), m.str());
      }
      cell_count_ = static_cast<size_t>(a - 1);
      for (size_t c = 0; c < cell_count_; ++c)
        cell_where_.push_back(cell_start_[c] < where.size() ? where[cell_start_[c]] : offset_where[c]);
    } else {
      read_array(b, binary_ ? "int" : "vtktypeint64", nullptr, &values, &where, "a CELLS entry");
      size_t k = 0;
      for (int64_t c = 0; c < a; ++c) {
        if (k >= values.size()) {
          std::ostringstream m;
          m << "CELLS announces " << a << " cells in " << b << " values, but the values end after cell " << c;
          fail(path_, line_at(line), m.str());
        }
        const int64_t n = values[k];
        if (n < 0 || static_cast<uint64_t>(n) >= values.size() - k) {
          std::ostringstream m;
          m << "cell " << c << " has " << n << " points, more than the CELLS size leaves";
          fail(path_, where[k], m.str());
        }
        cell_where_.push_back(where[k]);
        cell_start_.push_back(connectivity_.size());
        connectivity_.insert(connectivity_.end(), values.begin() + static_cast<std::ptrdiff_t>(k + 1),
                             values.begin() + static_cast<std::ptrdiff_t>(k + 1 + n));
        k += static_cast<size_t>(n) + 1;
      }
      if (k != values.size()) {
        std::ostringstream m;
        m << "CELLS size is " << b << ", but its " << a << " cells use " << k << " values";
        fail(path_, line_at(line), m.str());
      }
      cell_start_.push_back(connectivity_.size());
      cell_count_ = static_cast<size_t>(a);
    }
  }

  void skip_field(uint64_t line) {
    s_.token();  // name
    const int64_t arrays = count("the FIELD array count", line);
    s_.rest_of_line();
    for (int64_t i = 0; i < arrays; ++i) {
      s_.token();  // array name
      const uint64_t at = s_.token_line();
      const int64_t components = count("a FIELD array's component count", at);
      const int64_t tuples = count("a FIELD array's tuple count", at);
      const std::string type(s_.token());
      s_.rest_of_line();
      if (components > 0 && tuples > static_cast<int64_t>(s_.remaining()) / components)
        fail(path_, line_at(at), "a FIELD array larger than the file");
      std::vector<double> ignored;
      read_array(components * tuples, type, &ignored, nullptr, nullptr, "a FIELD value");
    }
  }

  const std::string& path_;
  Scanner s_;
  MeshBuilder builder_;
  bool binary_ = false, version5_ = false;
  std::vector<int64_t> connectivity_, types_;
  std::vector<size_t> cell_start_;  // cell c: [cell_start_[c], cell_start_[c + 1])
  std::vector<Location> cell_where_, type_where_;
  size_t cell_count_ = 0;
  Data data_ = Data::none;  // the POINT_DATA or CELL_DATA section being read
  int64_t tuples_ = 0;
  bool seen_point_data_ = false, seen_cell_data_ = false;
  struct PendingArray {
    MeshArray array;
    Location where;
    bool point;
  };
  std::vector<PendingArray> arrays_;  // added once the cells are known
};

}  // namespace

Mesh read_vtk_legacy(const std::string& path, const std::string& data, const MeshReadOptions& options) {
  return VtkLegacyReader(path, data, options).read();
}

}  // namespace snh::io
