// Internals shared by the mesh readers (mesh_io.h): a scanner over a file's
// bytes that knows its line, error messages that name the file and the line
// or byte offset, and a builder that collects vertices and elements with
// where each came from, then fixes orientation and checks the mesh.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "snh/mesh.h"
#include "snh/mesh_io.h"

namespace snh::io {

// Where something is in a file: a 1-based line, or a byte offset in binary data.
struct Location {
  uint64_t value = 0;
  bool binary = false;
};

inline Location line_at(uint64_t line) { return {line, false}; }
inline Location byte_at(uint64_t offset) { return {offset, true}; }

// "mesh.msh:17" or "mesh.msh (byte 1234)".
std::string describe(const std::string& path, Location where);

// Throws snh::Error "<path>:<line>: <what>" (or with the byte offset).
[[noreturn]] void fail(const std::string& path, Location where, const std::string& what);
// Throws snh::Error "<path>: <what>".
[[noreturn]] void fail(const std::string& path, const std::string& what);

// A token for an error message: quoted, shortened, non-printable bytes escaped.
std::string quote(std::string_view token);

// Whole-token number parsing, independent of the locale. Doubles accept
// "nan"/"inf" (the builder rejects them with a location).
bool parse_int(std::string_view text, int64_t& value);
bool parse_double(std::string_view text, double& value);

// Case-insensitive ASCII comparison.
bool iequals(std::string_view a, std::string_view b);

// Splits a line into whitespace-separated tokens.
std::vector<std::string_view> split(std::string_view line);

// A cursor over a file's bytes that counts lines as it moves (newlines inside
// binary data included, so the line numbers match an editor's).
class Scanner {
 public:
  Scanner(const std::string& path, const std::string& data) : path_(path), data_(data) {}

  const std::string& path() const { return path_; }
  const std::string& data() const { return data_; }
  size_t pos() const { return pos_; }
  uint64_t line() const { return line_; }
  bool at_end() const { return pos_ >= data_.size(); }
  size_t remaining() const { return data_.size() - pos_; }

  // Skips whitespace, and from `comment` (when not 0) to the line end.
  void skip_space(char comment = 0);
  // The next whitespace-separated token (empty at the end of the file);
  // token_line() is its line.
  std::string_view token(char comment = 0);
  uint64_t token_line() const { return token_line_; }
  // The rest of the current line without its line break, moving past it.
  std::string_view rest_of_line();
  // The next line that is not blank (and not only a comment when `comment`
  // is set, which is also cut from the line); false at the end of the file.
  bool next_line(std::string_view& text, uint64_t& line, char comment = 0);
  // Moves n bytes on (at most to the end), counting the lines passed.
  void advance(size_t n);
  void seek(size_t pos);

  // Tokens read as numbers; a missing or malformed one throws naming `what`.
  int64_t integer(const std::string& what, char comment = 0);
  double real(const std::string& what, char comment = 0);
  // Throws unless the next token is `keyword` (case-sensitive).
  void expect(std::string_view keyword, const std::string& context, char comment = 0);

  // Binary values at the cursor; `swap` reverses their bytes. Throws naming
  // `what` and the byte offset when the file ends first.
  template <class T>
  T binary(bool swap, const char* what);
  // Throws when fewer than `bytes` remain.
  void need(uint64_t bytes, const std::string& what) const;

  [[noreturn]] void fail_here(const std::string& what) const;

 private:
  const std::string& path_;
  const std::string& data_;
  size_t pos_ = 0;
  uint64_t line_ = 1;
  uint64_t token_line_ = 0;
};

// Collects a mesh as a reader finds it, with the file's own vertex and
// element numbers and locations for error messages.
class MeshBuilder {
 public:
  explicit MeshBuilder(const std::string& path) : path_(path), vertex_path_(path) {}
  // Vertices from one file, elements from another (TetGen).
  MeshBuilder(const std::string& path, const std::string& vertex_path) : path_(path), vertex_path_(vertex_path) {}

  // Appends a vertex; throws for a non-finite coordinate. Returns its index.
  int32_t add_vertex(int64_t file_id, const double xyz[3], Location where);
  size_t vertex_count() const { return positions_.size() / 3; }

  // Appends an element of 0-based vertex indices (checked against the
  // vertices added so far by the caller). Throws when its type differs from
  // the elements before it.
  void add_element(ElementType type, int64_t file_id, const int32_t* nodes, Location where);
  size_t element_count() const { return ids_.size(); }
  // What the file calls its elements in messages ("element", "cell").
  void set_element_noun(const std::string& noun) { noun_ = noun; }

  // Groups and arrays as the reader finds them. Group element indices and
  // cell-array entries follow the elements added (the file's volume cells,
  // in order); finish() sorts each group's lists, removes repeats and gives
  // volume groups the vertices of their elements.
  std::vector<MeshGroup> groups;
  std::vector<MeshArray> point_arrays, cell_arrays;

  // What read_mesh was asked to accept (coincident vertices).
  MeshReadOptions options;

  // Checks for no elements, repeated nodes, duplicate vertices (unless
  // options allow them), fixes mirrored elements, rejects degenerate ones,
  // and validates the mesh.
  Mesh finish();

 private:
  const std::string& path_;
  const std::string& vertex_path_;
  std::vector<double> positions_;
  std::vector<int64_t> vertex_ids_;
  std::vector<Location> vertex_where_;
  bool typed_ = false;
  ElementType type_ = ElementType::tet4;
  std::vector<int32_t> elements_;
  std::vector<int64_t> ids_;
  std::vector<Location> where_;
  std::string noun_ = "element";

  static std::string place(Location where);  // "line 8" or "byte 1234"
};

const char* element_noun(ElementType type);  // "tetrahedron" / "hexahedron"

// VTK cell types shared by the legacy and XML readers: appends the cells
// (tetra, hexahedron, voxel) to the builder, skips cells of lower dimension
// and throws for other volume cells. `where` gives each cell's location.
// Returns whether the cell became an element.
bool add_vtk_cell(MeshBuilder& builder, const std::string& path, int64_t cell, int64_t vtk_type, const int64_t* nodes,
                  int64_t count, size_t vertices, Location where);

template <class T>
T Scanner::binary(bool swap, const char* what) {
  need(sizeof(T), what);
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, data_.data() + pos_, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  advance(sizeof(T));
  return value;
}

// Checks that a data array read from a file has one tuple per point or cell
// and a name not used before among `existing`, then appends it (cell arrays:
// only the entries of cells that became elements, `kept[c]`).
void add_point_array(MeshBuilder& builder, const std::string& path, Location where, MeshArray array, size_t points);
void add_cell_array(MeshBuilder& builder, const std::string& path, Location where, MeshArray array,
                    const std::vector<char>& kept);

// The readers, on a file's whole contents.
Mesh read_gmsh(const std::string& path, const std::string& data, const MeshReadOptions& options = {});
Mesh read_vtk_legacy(const std::string& path, const std::string& data, const MeshReadOptions& options = {});
Mesh read_vtu(const std::string& path, const std::string& data, const MeshReadOptions& options = {});
Mesh read_medit(const std::string& path, const std::string& data, const MeshReadOptions& options = {});
Mesh read_tetgen(const std::string& node_path, const std::string& node_data, const std::string& ele_path,
                 const std::string& ele_data, const MeshReadOptions& options = {});

// A file's whole contents; throws naming the path when it cannot be read.
std::string read_file(const std::string& path);

// The file name's extension with its dot, in lower case ("" for none).
std::string lowercase_extension(const std::string& path);

}  // namespace snh::io
