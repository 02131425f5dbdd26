// read_mesh: dispatch by extension, and what the readers share: the scanner,
// number parsing, error messages, and the builder that fixes orientation and
// checks the mesh a reader found.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "io/readers.h"
#include "snh/error.h"
#include "snh/mesh_io.h"

namespace snh {
namespace io {

std::string describe(const std::string& path, Location where) {
  if (where.binary) return path + " (byte " + std::to_string(where.value) + ")";
  return path + ":" + std::to_string(where.value);
}

void fail(const std::string& path, Location where, const std::string& what) {
  throw Error(describe(path, where) + ": " + what);
}

void fail(const std::string& path, const std::string& what) { throw Error(path + ": " + what); }

std::string quote(std::string_view token) {
  std::string out = "'";
  const size_t shown = std::min<size_t>(token.size(), 40);
  for (size_t i = 0; i < shown; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (shown < token.size()) out += "...";
  return out + "'";
}

bool parse_int(std::string_view text, int64_t& value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

bool parse_double(std::string_view text, double& value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  if (text.empty() || text[0] == '+') return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // Overflow reads as infinity (rejected later with its location);
    // underflow as zero.
    // from_chars does not say which; the exponent's sign does.
    const bool negative = text[0] == '-';
    const size_t e = text.find_first_of("eE");
    const bool huge = e == std::string_view::npos || (e + 1 < text.size() && text[e + 1] != '-');
    value = huge ? (negative ? -HUGE_VAL : HUGE_VAL) : 0.0;
    return end == text.data() + text.size();
  }
  return ec == std::errc() && end == text.data() + text.size();
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
}  // namespace

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

void Scanner::advance(size_t n) {
  const size_t end = std::min(data_.size(), pos_ + std::min(n, data_.size()));
  line_ += static_cast<uint64_t>(std::count(data_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                            data_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
  pos_ = end;
}

void Scanner::seek(size_t pos) {
  if (pos >= pos_) {
    advance(pos - pos_);
  } else {
    pos_ = 0;
    line_ = 1;
    advance(pos);
  }
}

void Scanner::skip_space(char comment) {
  while (pos_ < data_.size()) {
    const char c = data_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_space(c)) {
      ++pos_;
    } else if (comment != 0 && c == comment) {
      while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

std::string_view Scanner::token(char comment) {
  skip_space(comment);
  token_line_ = line_;
  const size_t start = pos_;
  while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
  return std::string_view(data_).substr(start, pos_ - start);
}

std::string_view Scanner::rest_of_line() {
  const size_t start = pos_;
  while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  std::string_view text = std::string_view(data_).substr(start, pos_ - start);
  if (pos_ < data_.size()) {
    ++pos_;
    ++line_;
  }
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  return text;
}

bool Scanner::next_line(std::string_view& text, uint64_t& line, char comment) {
  while (pos_ < data_.size()) {
    line = line_;
    text = rest_of_line();
    if (comment != 0) {
      const size_t c = text.find(comment);
      if (c != std::string_view::npos) text = text.substr(0, c);
    }
    for (char c : text)
      if (!is_space(c)) return true;
  }
  return false;
}

int64_t Scanner::integer(const std::string& what, char comment) {
  const std::string_view t = token(comment);
  if (t.empty()) fail(path_, line_at(token_line_), "the file ends where " + what + " was expected");
  int64_t value = 0;
  if (!parse_int(t, value)) fail(path_, line_at(token_line_), "expected " + what + " (an integer), found " + quote(t));
  return value;
}

double Scanner::real(const std::string& what, char comment) {
  const std::string_view t = token(comment);
  if (t.empty()) fail(path_, line_at(token_line_), "the file ends where " + what + " was expected");
  double value = 0.0;
  if (!parse_double(t, value)) fail(path_, line_at(token_line_), "expected " + what + " (a number), found " + quote(t));
  return value;
}

void Scanner::expect(std::string_view keyword, const std::string& context, char comment) {
  const std::string_view t = token(comment);
  if (t.empty())
    fail(path_, line_at(token_line_), "the file ends where " + std::string(keyword) + " was expected " + context);
  if (t != keyword)
    fail(path_, line_at(token_line_), "expected " + std::string(keyword) + " " + context + ", found " + quote(t));
}

void Scanner::need(uint64_t bytes, const std::string& what) const {
  if (bytes > remaining()) {
    std::ostringstream s;
    s << "the file is truncated: " << what << " needs " << bytes << " bytes, but only " << remaining() << " remain";
    fail(path_, byte_at(pos_), s.str());
  }
}

void Scanner::fail_here(const std::string& what) const { fail(path_, line_at(line_), what); }

const char* element_noun(ElementType type) { return type == ElementType::hex8 ? "hexahedron" : "tetrahedron"; }

int32_t MeshBuilder::add_vertex(int64_t file_id, const double xyz[3], Location where) {
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(xyz[d])) {
      std::ostringstream s;
      s << "vertex " << file_id << " has a non-finite coordinate ("
        << "xyz"[d] << " = " << xyz[d] << ")";
      fail(vertex_path_, where, s.str());
    }
  if (vertex_count() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    fail(vertex_path_, where, "more vertices than 32-bit indices can address");
  positions_.insert(positions_.end(), xyz, xyz + 3);
  vertex_ids_.push_back(file_id);
  vertex_where_.push_back(where);
  return static_cast<int32_t>(vertex_count() - 1);
}

void MeshBuilder::add_element(ElementType type, int64_t file_id, const int32_t* nodes, Location where) {
  if (!typed_) {
    typed_ = true;
    type_ = type;
  } else if (type != type_) {
    std::ostringstream s;
    s << noun_ << " " << file_id << " is a " << element_noun(type) << ", but " << noun_ << " " << ids_.front() << " ("
      << place(where_.front()) << ") is a " << element_noun(type_) << "; a mesh must hold one element type ("
      << element_type_name(type_) << " or " << element_type_name(type) << ")";
    fail(path_, where, s.str());
  }
  if (ids_.size() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    fail(path_, where, "more elements than 32-bit indices can address");
  elements_.insert(elements_.end(), nodes, nodes + nodes_per_element(type));
  ids_.push_back(file_id);
  where_.push_back(where);
}

std::string MeshBuilder::place(Location where) {
  return (where.binary ? "byte " : "line ") + std::to_string(where.value);
}

namespace {

double det3(const double a[3], const double b[3], const double c[3]) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

struct CoordinateKey {
  uint64_t bits[3];
  bool operator==(const CoordinateKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct CoordinateHash {
  size_t operator()(const CoordinateKey& k) const {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (uint64_t b : k.bits) h = (h ^ b) * 0x100000001b3ull + (h >> 29);
    return static_cast<size_t>(h);
  }
};

// Corner signs of the hex8 nodes in VTK order.
constexpr double kSigns[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

}  // namespace

Mesh MeshBuilder::finish() {
  if (vertex_count() == 0) fail(vertex_path_, "the file defines no vertices");
  if (!typed_) fail(path_, "the file holds no tetrahedra or 8-node hexahedra (only lower-dimensional elements)");
  const int n = nodes_per_element(type_);
  const size_t count = ids_.size();

  for (size_t e = 0; e < count; ++e) {
    const int32_t* v = elements_.data() + n * e;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < a; ++b)
        if (v[a] == v[b]) {
          std::ostringstream s;
          s << noun_ << " " << ids_[e] << " uses vertex " << vertex_ids_[v[a]] << " twice (nodes " << b << " and " << a
            << ")";
          fail(path_, where_[e], s.str());
        }
  }

  if (!options.allow_coincident_vertices) {
    std::unordered_map<CoordinateKey, int32_t, CoordinateHash> seen;
    seen.reserve(vertex_count());
    for (size_t i = 0; i < vertex_count(); ++i) {
      CoordinateKey key;
      for (int d = 0; d < 3; ++d) {
        const double x = positions_[3 * i + d] == 0.0 ? 0.0 : positions_[3 * i + d];  // -0 is 0
        std::memcpy(&key.bits[d], &x, sizeof x);
      }
      const auto [it, inserted] = seen.emplace(key, static_cast<int32_t>(i));
      if (!inserted) {
        const size_t j = static_cast<size_t>(it->second);
        std::ostringstream s;
        s.precision(17);
        s << "vertex " << vertex_ids_[i] << " duplicates vertex " << vertex_ids_[j] << " (" << place(vertex_where_[j])
          << "): both are at (" << positions_[3 * i] + 0.0 << ", " << positions_[3 * i + 1] + 0.0 << ", "
          << positions_[3 * i + 2] + 0.0
          << ") (a mesh whose vertices were not merged falls apart; a lattice kept open across thin gaps, as "
             "voxelize makes, has them on purpose: MeshReadOptions::allow_coincident_vertices)";
        fail(vertex_path_, vertex_where_[i], s.str());
      }
    }
  }

  // Orientation: mirrored elements (the file's convention, or the mesher's
  // choice) are turned over; degenerate and tangled ones are rejected.
  const double g = 1.0 / std::sqrt(3.0);
  for (size_t e = 0; e < count; ++e) {
    int32_t* v = elements_.data() + n * e;
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) lo[d] = hi[d] = positions_[3 * v[0] + d];
    for (int a = 1; a < n; ++a)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], positions_[3 * v[a] + d]);
        hi[d] = std::max(hi[d], positions_[3 * v[a] + d]);
      }
    const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const double tolerance = 1e-12 * size * size * size;
    if (type_ == ElementType::tet4) {
      double edge[3][3];
      for (int r = 0; r < 3; ++r)
        for (int d = 0; d < 3; ++d) edge[r][d] = positions_[3 * v[r + 1] + d] - positions_[3 * v[0] + d];
      const double det = det3(edge[0], edge[1], edge[2]);
      if (!(std::abs(det) > tolerance) || !std::isfinite(det)) {
        std::ostringstream s;
        s << noun_ << " " << ids_[e] << " (tetrahedron) has zero volume: its four vertices are coplanar";
        fail(path_, where_[e], s.str());
      }
      if (det < 0.0) std::swap(v[1], v[2]);
    } else {
      int positive = 0, negative = 0;
      for (int q = 0; q < 8; ++q) {
        const double xi[3] = {g * kSigns[q][0], g * kSigns[q][1], g * kSigns[q][2]};
        double j[3][3] = {};  // j[r] = dX/dxi_r
        for (int a = 0; a < 8; ++a) {
          const double* s = kSigns[a];
          const double f[3] = {1 + s[0] * xi[0], 1 + s[1] * xi[1], 1 + s[2] * xi[2]};
          const double dn[3] = {0.125 * s[0] * f[1] * f[2], 0.125 * f[0] * s[1] * f[2], 0.125 * f[0] * f[1] * s[2]};
          for (int r = 0; r < 3; ++r)
            for (int d = 0; d < 3; ++d) j[r][d] += dn[r] * positions_[3 * v[a] + d];
        }
        const double det = det3(j[0], j[1], j[2]) * 8.0;  // reference cube volume 8
        if (det > tolerance) ++positive;
        if (det < -tolerance) ++negative;
      }
      if (negative == 8) {
        for (int a = 0; a < 4; ++a) std::swap(v[a], v[a + 4]);
      } else if (positive != 8) {
        std::ostringstream s;
        s << noun_ << " " << ids_[e] << " (hexahedron) ";
        if (positive == 0 && negative == 0)
          s << "has zero volume";
        else
          s << "is degenerate or tangled: its volume is positive at " << positive << " of its 8 quadrature points, "
            << "negative at " << negative << " (are its nodes in VTK_HEXAHEDRON order?)";
        fail(path_, where_[e], s.str());
      }
    }
  }

  for (MeshGroup& group : groups) {
    std::vector<int32_t>& in = group.elements;
    std::sort(in.begin(), in.end());
    in.erase(std::unique(in.begin(), in.end()), in.end());
    std::vector<int32_t>& v = group.vertices;
    for (int32_t e : in) v.insert(v.end(), &elements_[n * e], &elements_[n * e] + n);
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }

  Mesh mesh;
  mesh.type = type_;
  mesh.positions = Points::from_xyz(std::move(positions_));
  mesh.elements = std::move(elements_);
  mesh.groups = std::move(groups);
  mesh.point_arrays = std::move(point_arrays);
  mesh.cell_arrays = std::move(cell_arrays);
  try {
    validate_mesh(mesh);
  } catch (const Error& e) {
    fail(path_, e.what());
  }
  return mesh;
}

namespace {

void add_array(std::vector<MeshArray>& arrays, const std::string& path, Location where, MeshArray array, size_t tuples,
               const char* kind) {
  for (const MeshArray& a : arrays)
    if (a.name == array.name) fail(path, where, std::string("a second ") + kind + " array named " + quote(a.name));
  if (array.components < 1 || array.values.size() != tuples * static_cast<size_t>(array.components)) {
    std::ostringstream s;
    s << kind << " array " << quote(array.name) << " has " << array.values.size() << " values, but " << tuples << " "
      << kind << "s of " << array.components << " components need " << tuples * static_cast<size_t>(array.components);
    fail(path, where, s.str());
  }
  arrays.push_back(std::move(array));
}

}  // namespace

void add_point_array(MeshBuilder& builder, const std::string& path, Location where, MeshArray array, size_t points) {
  add_array(builder.point_arrays, path, where, std::move(array), points, "point");
}

void add_cell_array(MeshBuilder& builder, const std::string& path, Location where, MeshArray array,
                    const std::vector<char>& kept) {
  add_array(builder.cell_arrays, path, where, array, kept.size(), "cell");
  MeshArray& added = builder.cell_arrays.back();
  const size_t c = static_cast<size_t>(added.components);
  size_t out = 0;
  for (size_t cell = 0; cell < kept.size(); ++cell)
    if (kept[cell]) {
      std::copy(added.values.begin() + static_cast<std::ptrdiff_t>(c * cell),
                added.values.begin() + static_cast<std::ptrdiff_t>(c * (cell + 1)),
                added.values.begin() + static_cast<std::ptrdiff_t>(c * out));
      ++out;
    }
  added.values.resize(c * out);
}

std::string read_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error("cannot read " + path + " (the file cannot be opened; does it exist?)");
  std::ostringstream contents;
  contents << file.rdbuf();
  if (file.bad()) throw Error("cannot read " + path + " (reading failed part way)");
  return contents.str();
}

std::string lowercase_extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return ext;
}

}  // namespace io

Mesh read_mesh(const std::string& path, const MeshReadOptions& options) {
  const std::string ext = io::lowercase_extension(path);
  if (ext == ".msh") return io::read_gmsh(path, io::read_file(path), options);
  if (ext == ".vtk") return io::read_vtk_legacy(path, io::read_file(path), options);
  if (ext == ".vtu") return io::read_vtu(path, io::read_file(path), options);
  if (ext == ".mesh") return io::read_medit(path, io::read_file(path), options);
  if (ext == ".node" || ext == ".ele") {
    const std::string stem = path.substr(0, path.size() - ext.size());
    const std::string node = stem + ".node", ele = stem + ".ele";
    return io::read_tetgen(node, io::read_file(node), ele, io::read_file(ele), options);
  }
  throw Error(path + ": unknown mesh format '" + ext +
              "' (read_mesh reads .msh, .vtk, .vtu, .mesh, and TetGen .node/.ele pairs)");
}

}  // namespace snh
