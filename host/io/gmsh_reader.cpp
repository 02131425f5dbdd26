// Gmsh .msh 2.2 and 4.1, ASCII and binary. Gmsh numbers first-order
// hexahedron nodes as VTK does; tetrahedra may come either way round and are
// turned over by the builder. Point, line and surface elements become no
// mesh elements; their vertices make the physical groups of dimension 0..2.
//
// Physical groups: in 2.2 an element's first tag is its physical group (0:
// none), and gmsh writes an element once per group it belongs to, under a
// new number; the copies of a volume element become one element. In 4.1 the
// $Entities section lists each entity's physical groups and every element
// block names its entity. $PhysicalNames names groups by (dimension, tag).
#include <array>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

#include "io/readers.h"
#include "snh/error.h"

namespace snh::io {
namespace {

struct GmshType {
  int nodes;      // 0: unknown type
  int dimension;  // 0..3
  const char* name;
};

// Element types of the Gmsh file format (gmsh's GmshDefines.h), up to 31
// plus the common higher-order hexahedra.
GmshType gmsh_type(int64_t type) {
  switch (type) {
    case 1:
      return {2, 1, "2-node line"};
    case 2:
      return {3, 2, "3-node triangle"};
    case 3:
      return {4, 2, "4-node quadrangle"};
    case 4:
      return {4, 3, "4-node tetrahedron"};
    case 5:
      return {8, 3, "8-node hexahedron"};
    case 6:
      return {6, 3, "6-node prism"};
    case 7:
      return {5, 3, "5-node pyramid"};
    case 8:
      return {3, 1, "3-node line"};
    case 9:
      return {6, 2, "6-node triangle"};
    case 10:
      return {9, 2, "9-node quadrangle"};
    case 11:
      return {10, 3, "10-node tetrahedron"};
    case 12:
      return {27, 3, "27-node hexahedron"};
    case 13:
      return {18, 3, "18-node prism"};
    case 14:
      return {14, 3, "14-node pyramid"};
    case 15:
      return {1, 0, "point"};
    case 16:
      return {8, 2, "8-node quadrangle"};
    case 17:
      return {20, 3, "20-node hexahedron"};
    case 18:
      return {15, 3, "15-node prism"};
    case 19:
      return {13, 3, "13-node pyramid"};
    case 20:
      return {9, 2, "9-node triangle"};
    case 21:
      return {10, 2, "10-node triangle"};
    case 22:
      return {12, 2, "12-node triangle"};
    case 23:
      return {15, 2, "15-node triangle"};
    case 24:
      return {15, 2, "15-node triangle"};
    case 25:
      return {21, 2, "21-node triangle"};
    case 26:
      return {4, 1, "4-node line"};
    case 27:
      return {5, 1, "5-node line"};
    case 28:
      return {6, 1, "6-node line"};
    case 29:
      return {20, 3, "20-node tetrahedron"};
    case 30:
      return {35, 3, "35-node tetrahedron"};
    case 31:
      return {56, 3, "56-node tetrahedron"};
    case 92:
      return {64, 3, "64-node hexahedron"};
    case 93:
      return {125, 3, "125-node hexahedron"};
    default:
      return {0, 0, ""};
  }
}

struct NodesKey {
  std::array<int32_t, 8> v{};
  bool operator==(const NodesKey& o) const { return v == o.v; }
};

struct NodesHash {
  size_t operator()(const NodesKey& k) const {
    uint64_t h = 0xcbf29ce484222325ull;
    for (int32_t x : k.v) h = (h ^ static_cast<uint32_t>(x)) * 0x100000001b3ull;
    return static_cast<size_t>(h);
  }
};

using GroupKey = std::pair<int, int64_t>;  // (dimension, physical tag)

const char* const kEntityKinds[4] = {"point", "curve", "surface", "volume"};

std::string group_words(const GroupKey& key) {
  return std::string("physical ") + kEntityKinds[key.first] + " " + std::to_string(key.second);
}

class GmshReader {
 public:
  GmshReader(const std::string& path, const std::string& data, const MeshReadOptions& options)
      : path_(path), s_(path, data), builder_(path) {
    builder_.options = options;
  }

  Mesh read() {
    const std::string_view first = s_.token();
    if (first != "$MeshFormat")
      fail(path_, line_at(s_.token_line()),
           "not a Gmsh mesh: expected $MeshFormat at the start, found " + quote(first));
    read_format();
    bool have_nodes = false, have_elements = false;
    for (;;) {
      const std::string_view section = s_.token();
      if (section.empty()) break;
      const uint64_t line = s_.token_line();
      if (section == "$Nodes") {
        if (have_nodes) fail(path_, line_at(line), "a second $Nodes section (only one is supported)");
        have_nodes = true;
        s_.rest_of_line();
        version4_ ? read_nodes4() : read_nodes2();
        s_.expect("$EndNodes", "after the nodes (does the node count match?)");
      } else if (section == "$Elements") {
        if (!have_nodes) fail(path_, line_at(line), "the $Elements section comes before any $Nodes section");
        if (have_elements) fail(path_, line_at(line), "a second $Elements section (only one is supported)");
        have_elements = true;
        s_.rest_of_line();
        version4_ ? read_elements4() : read_elements2();
        s_.expect("$EndElements", "after the elements (does the element count match?)");
      } else if (section == "$PhysicalNames") {
        if (have_names_) fail(path_, line_at(line), "a second $PhysicalNames section");
        have_names_ = true;
        s_.rest_of_line();
        read_physical_names();
        s_.expect("$EndPhysicalNames", "after the physical names (does their count match?)");
      } else if (section == "$Entities" && version4_) {
        if (have_entities_) fail(path_, line_at(line), "a second $Entities section");
        if (have_elements)
          fail(path_, line_at(line), "the $Entities section comes after $Elements (gmsh writes it before $Nodes)");
        have_entities_ = true;
        s_.rest_of_line();
        read_entities();
        s_.expect("$EndEntities", "after the entities (do their counts match?)");
      } else if (section.size() > 1 && section[0] == '$' && section.substr(0, 4) != "$End") {
        // Skipped: $NodeData, $ElementData, $PartitionedEntities, ...
        const std::string end = "$End" + std::string(section.substr(1));
        const size_t found = s_.data().find(end, s_.pos());
        if (found == std::string::npos)
          fail(path_, line_at(line), "section " + quote(section) + " has no " + end + " (is the file truncated?)");
        s_.seek(found + end.size());
      } else {
        fail(path_, line_at(line), "expected a section such as $Nodes or $Elements, found " + quote(section));
      }
    }
    if (!have_nodes) fail(path_, "the file has no $Nodes section");
    if (!have_elements) fail(path_, "the file has no $Elements section");
    for (const auto& [key, named] : names_) {
      const auto it = groups_.find(key);
      if (it == groups_.end())
        fail(path_, named.where,
             "$PhysicalNames names " + group_words(key) + " " + quote(named.name) + ", but no " +
                 (version4_ ? "entity" : "element") + " belongs to it");
      it->second.name = named.name;
    }
    for (auto& [key, group] : groups_) builder_.groups.push_back(std::move(group));
    return builder_.finish();
  }

 private:
  void read_format() {
    const std::string_view version = s_.token();
    const uint64_t line = s_.token_line();
    if (version == "2.2" || version == "2.1" || version == "2" || version == "2.0") {
      version4_ = false;
    } else if (version == "4.1") {
      version4_ = true;
    } else {
      fail(path_, line_at(line),
           "Gmsh format version " + quote(version) + " is not supported (2.2 and 4.1 are; gmsh -format msh22/msh41)");
    }
    const int64_t file_type = s_.integer("the file type (0 ASCII, 1 binary)");
    const int64_t data_size = s_.integer("the data size");
    if (file_type != 0 && file_type != 1)
      fail(path_, line_at(s_.token_line()), "file type " + std::to_string(file_type) + " is neither 0 nor 1");
    if (data_size != 8)
      fail(path_, line_at(s_.token_line()),
           "data size " + std::to_string(data_size) + " is not supported (8-byte doubles and size_t are)");
    binary_ = file_type == 1;
    s_.rest_of_line();
    if (binary_) {
      const size_t at = s_.pos();
      const int32_t one = s_.binary<int32_t>(false, "the endianness marker");
      if (one == 1) {
        swap_ = false;
      } else if (one == 0x01000000) {
        swap_ = true;
      } else {
        fail(path_, byte_at(at), "the binary endianness marker is " + std::to_string(one) + ", not 1");
      }
    }
    s_.expect("$EndMeshFormat", "after the format line");
  }

  Location here() const { return binary_ ? byte_at(s_.pos()) : line_at(s_.line()); }

  // A count from a header, checked to be non-negative and at most `limit`.
  int64_t count(int64_t value, const std::string& what, Location where, int64_t limit) {
    if (value < 0 || value > limit) {
      std::ostringstream m;
      m << what << " is " << value << (value < 0 ? ", which is negative" : ", more than the file can hold");
      fail(path_, where, m.str());
    }
    return value;
  }

  std::vector<std::string_view> line_tokens(const std::string& what, uint64_t& line) {
    std::string_view text;
    if (!s_.next_line(text, line)) fail(path_, line_at(s_.line()), "the file ends where " + what + " was expected");
    return split(text);
  }

  int64_t int_token(std::string_view t, const std::string& what, uint64_t line) {
    int64_t v = 0;
    if (!parse_int(t, v)) fail(path_, line_at(line), "expected " + what + " (an integer), found " + quote(t));
    return v;
  }

  double real_token(std::string_view t, const std::string& what, uint64_t line) {
    double v = 0;
    if (!parse_double(t, v)) fail(path_, line_at(line), "expected " + what + " (a number), found " + quote(t));
    return v;
  }

  void add_node(int64_t tag, const double xyz[3], Location where) {
    const auto [it, inserted] = index_.emplace(tag, static_cast<int32_t>(builder_.vertex_count()));
    if (!inserted) {
      std::ostringstream m;
      m << "node " << tag << " is defined twice";
      fail(path_, where, m.str());
    }
    builder_.add_vertex(tag, xyz, where);
  }

  int32_t vertex_of(int64_t element, int64_t node, Location where) {
    const auto it = index_.find(node);
    if (it == index_.end()) {
      std::ostringstream m;
      m << "element " << element << " refers to node " << node << ", which the $Nodes section does not define";
      fail(path_, where, m.str());
    }
    return it->second;
  }

  MeshGroup& group(int dimension, int64_t physical, Location where) {
    if (physical < std::numeric_limits<int>::min() || physical > std::numeric_limits<int>::max())
      fail(path_, where, "physical tag " + std::to_string(physical) + " is out of range");
    MeshGroup& g = groups_[{dimension, physical}];
    g.tag = static_cast<int>(physical);
    g.dimension = dimension;
    return g;
  }

  // Node tags of an element to vertex indices, then the element (volume
  // elements of our types) or only its vertices in its physical groups
  // (lower dimensions).
  void add_element(int64_t tag, int64_t type, const int64_t* nodes, Location where,
                   const std::vector<int64_t>& physicals) {
    const GmshType t = gmsh_type(type);
    if (t.dimension < 3) {
      if (physicals.empty()) return;
      for (int a = 0; a < t.nodes; ++a) {
        const int32_t v = vertex_of(tag, nodes[a], where);
        for (int64_t p : physicals) group(t.dimension, p, where).vertices.push_back(v);
      }
      return;
    }
    if (type != 4 && type != 5) {
      std::ostringstream m;
      m << "element " << tag << " has unsupported type " << type << " (" << t.name
        << "); only 4-node tetrahedra (type 4) and 8-node hexahedra (type 5) are supported";
      fail(path_, where, m.str());
    }
    NodesKey key;
    for (int a = 0; a < t.nodes; ++a) key.v[a] = vertex_of(tag, nodes[a], where);
    int32_t element = static_cast<int32_t>(builder_.element_count());
    if (!version4_ && !physicals.empty()) {
      // A 2.2 copy of an element already read, written for another group.
      const auto [it, inserted] = copies_.emplace(key, element);
      if (!inserted) element = it->second;
    }
    if (element == static_cast<int32_t>(builder_.element_count()))
      builder_.add_element(type == 4 ? ElementType::tet4 : ElementType::hex8, tag, key.v.data(), where);
    for (int64_t p : physicals) group(3, p, where).elements.push_back(element);
  }

  void known_type(int64_t type, const std::string& who, Location where) {
    if (gmsh_type(type).nodes == 0) fail(path_, where, who + " has unknown element type " + std::to_string(type));
  }

  // ---- 2.2 ----

  void read_nodes2() {
    uint64_t line = 0;
    auto header = line_tokens("the node count", line);
    if (header.size() != 1) fail(path_, line_at(line), "expected the node count alone on the line");
    const int64_t n = count(int_token(header[0], "the node count", line), "the node count", line_at(line),
                            static_cast<int64_t>(s_.remaining()));
    for (int64_t i = 0; i < n; ++i) {
      if (binary_) {
        const Location where = here();
        s_.need(28, "node " + std::to_string(i + 1) + " of " + std::to_string(n));
        const int64_t tag = s_.binary<int32_t>(swap_, "a node tag");
        double xyz[3];
        for (double& x : xyz) x = s_.binary<double>(swap_, "a coordinate");
        add_node(tag, xyz, where);
      } else {
        auto t = line_tokens("node " + std::to_string(i + 1) + " of " + std::to_string(n), line);
        if (t.size() != 4) {
          std::ostringstream m;
          m << "node line " << i + 1 << " of " << n << " has " << t.size()
            << " values, expected 4 (tag x y z); does the node count match?";
          fail(path_, line_at(line), m.str());
        }
        const int64_t tag = int_token(t[0], "a node tag", line);
        double xyz[3];
        for (int d = 0; d < 3; ++d) xyz[d] = real_token(t[d + 1], "a coordinate", line);
        add_node(tag, xyz, line_at(line));
      }
    }
  }

  void read_elements2() {
    uint64_t line = 0;
    auto header = line_tokens("the element count", line);
    if (header.size() != 1) fail(path_, line_at(line), "expected the element count alone on the line");
    const int64_t n = count(int_token(header[0], "the element count", line), "the element count", line_at(line),
                            static_cast<int64_t>(s_.remaining()));
    int64_t read = 0;
    std::vector<int64_t> nodes, physicals;
    while (read < n) {
      if (binary_) {
        const Location block = here();
        const int64_t type = s_.binary<int32_t>(swap_, "an element block header");
        const int64_t in_block = s_.binary<int32_t>(swap_, "an element block header");
        const int64_t tags = s_.binary<int32_t>(swap_, "an element block header");
        known_type(type, "an element block", block);
        if (in_block <= 0 || in_block > n - read) {
          std::ostringstream m;
          m << "an element block of " << in_block << " elements, but " << n - read << " of the " << n
            << " elements remain";
          fail(path_, block, m.str());
        }
        if (tags < 0 || tags > 1000) fail(path_, block, "an element block with " + std::to_string(tags) + " tags");
        const int64_t per = 1 + tags + gmsh_type(type).nodes;
        s_.need(static_cast<uint64_t>(in_block) * static_cast<uint64_t>(per) * 4,
                "a block of " + std::to_string(in_block) + " elements");
        nodes.resize(static_cast<size_t>(gmsh_type(type).nodes));
        for (int64_t e = 0; e < in_block; ++e) {
          const Location where = here();
          const int64_t tag = s_.binary<int32_t>(swap_, "an element tag");
          physicals.clear();
          for (int64_t k = 0; k < tags; ++k) {
            const int64_t value = s_.binary<int32_t>(swap_, "an element tag");
            if (k == 0 && value != 0) physicals.push_back(value);
          }
          for (int64_t& v : nodes) v = s_.binary<int32_t>(swap_, "an element node");
          add_element(tag, type, nodes.data(), where, physicals);
        }
        read += in_block;
      } else {
        auto t = line_tokens("element " + std::to_string(read + 1) + " of " + std::to_string(n), line);
        if (t.size() < 3) {
          std::ostringstream m;
          m << "element line " << read + 1 << " of " << n << " has " << t.size()
            << " values, too few for tag, type and tag count; does the element count match?";
          fail(path_, line_at(line), m.str());
        }
        const int64_t tag = int_token(t[0], "an element tag", line);
        const int64_t type = int_token(t[1], "an element type", line);
        const int64_t tags = int_token(t[2], "the number of tags", line);
        known_type(type, "element " + std::to_string(tag), line_at(line));
        const int nn = gmsh_type(type).nodes;
        if (tags < 0 || static_cast<int64_t>(t.size()) != 3 + tags + nn) {
          std::ostringstream m;
          m << "element " << tag << " (" << gmsh_type(type).name << ") has " << t.size() << " values, expected "
            << 3 + std::max<int64_t>(tags, 0) + nn << " (tag, type, " << tags << " tags, " << nn << " nodes)";
          fail(path_, line_at(line), m.str());
        }
        nodes.resize(static_cast<size_t>(nn));
        for (int a = 0; a < nn; ++a) nodes[a] = int_token(t[3 + tags + a], "a node tag", line);
        physicals.clear();
        if (tags > 0) {
          const int64_t physical = int_token(t[3], "a physical tag", line);
          if (physical != 0) physicals.push_back(physical);
        }
        add_element(tag, type, nodes.data(), line_at(line), physicals);
        ++read;
      }
    }
  }

  // ---- 4.1 ----

  // Four header counts (ASCII line or binary size_t).
  void header4(int64_t values[4], const char* what) {
    if (binary_) {
      for (int i = 0; i < 4; ++i) {
        const uint64_t v = s_.binary<uint64_t>(swap_, what);
        values[i] = v > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) ? -1 : static_cast<int64_t>(v);
      }
    } else {
      uint64_t line = 0;
      auto t = line_tokens(what, line);
      if (t.size() != 4)
        fail(path_, line_at(line), std::string("expected 4 values in ") + what + ", found " + std::to_string(t.size()));
      for (int i = 0; i < 4; ++i) values[i] = int_token(t[i], what, line);
    }
  }

  // Entity block header: dim, tag, a third int, then a count.
  void block4(int64_t values[4], const char* what, Location& where) {
    where = here();
    if (binary_) {
      for (int i = 0; i < 3; ++i) values[i] = s_.binary<int32_t>(swap_, what);
      const uint64_t v = s_.binary<uint64_t>(swap_, what);
      values[3] = v > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) ? -1 : static_cast<int64_t>(v);
    } else {
      uint64_t line = 0;
      auto t = line_tokens(what, line);
      where = line_at(line);
      if (t.size() != 4)
        fail(path_, where, std::string("expected 4 values in ") + what + ", found " + std::to_string(t.size()));
      for (int i = 0; i < 4; ++i) values[i] = int_token(t[i], what, line);
    }
  }

  void read_nodes4() {
    int64_t h[4];
    const Location at = here();
    header4(h, "the $Nodes header");
    const int64_t limit = static_cast<int64_t>(s_.remaining());
    const int64_t blocks = count(h[0], "the number of node blocks", at, limit);
    const int64_t total = count(h[1], "the node count", at, limit);
    int64_t read = 0;
    std::vector<int64_t> tags;
    std::vector<Location> where;
    for (int64_t b = 0; b < blocks; ++b) {
      int64_t bh[4];
      Location block;
      block4(bh, "a node block header", block);
      const int64_t dim = bh[0], parametric = bh[2];
      const int64_t n = count(bh[3], "the node count of a block", block, total - read);
      if (dim < 0 || dim > 3) fail(path_, block, "a node block of entity dimension " + std::to_string(dim));
      if (parametric != 0 && parametric != 1)
        fail(path_, block, "a node block with parametric flag " + std::to_string(parametric));
      const int64_t values = 3 + (parametric ? dim : 0);
      tags.resize(static_cast<size_t>(n));
      where.resize(static_cast<size_t>(n));
      if (binary_) s_.need(static_cast<uint64_t>(n) * (8 + 8 * values), "a block of " + std::to_string(n) + " nodes");
      for (int64_t i = 0; i < n; ++i) {
        if (binary_) {
          where[i] = here();
          const uint64_t tag = s_.binary<uint64_t>(swap_, "a node tag");
          tags[i] = tag > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) ? -1 : static_cast<int64_t>(tag);
        } else {
          uint64_t line = 0;
          auto t = line_tokens("a node tag", line);
          if (t.size() != 1)
            fail(path_, line_at(line), "expected a node tag alone on the line (does the count match?)");
          tags[i] = int_token(t[0], "a node tag", line);
        }
        if (tags[i] < 0) fail(path_, binary_ ? where[i] : line_at(s_.line() - 1), "a negative node tag");
      }
      for (int64_t i = 0; i < n; ++i) {
        double xyz[3];
        Location loc;
        if (binary_) {
          loc = here();
          for (double& x : xyz) x = s_.binary<double>(swap_, "a coordinate");
          for (int64_t k = 3; k < values; ++k) s_.binary<double>(swap_, "a parametric coordinate");
        } else {
          uint64_t line = 0;
          auto t = line_tokens("the coordinates of node " + std::to_string(tags[i]), line);
          loc = line_at(line);
          if (static_cast<int64_t>(t.size()) != values) {
            std::ostringstream m;
            m << "node " << tags[i] << " has " << t.size() << " coordinates, expected " << values;
            fail(path_, loc, m.str());
          }
          for (int d = 0; d < 3; ++d) xyz[d] = real_token(t[d], "a coordinate", line);
        }
        add_node(tags[i], xyz, loc);
      }
      read += n;
    }
    if (read != total) {
      std::ostringstream m;
      m << "the $Nodes header announces " << total << " nodes, but its blocks hold " << read;
      fail(path_, at, m.str());
    }
  }

  void read_elements4() {
    int64_t h[4];
    const Location at = here();
    header4(h, "the $Elements header");
    const int64_t limit = static_cast<int64_t>(s_.remaining());
    const int64_t blocks = count(h[0], "the number of element blocks", at, limit);
    const int64_t total = count(h[1], "the element count", at, limit);
    int64_t read = 0;
    std::vector<int64_t> nodes;
    for (int64_t b = 0; b < blocks; ++b) {
      int64_t bh[4];
      Location block;
      block4(bh, "an element block header", block);
      const int64_t type = bh[2];
      const int64_t n = count(bh[3], "the element count of a block", block, total - read);
      known_type(type, "an element block", block);
      const std::vector<int64_t>& physicals = block_physicals(bh[0], bh[1], block);
      const int nn = gmsh_type(type).nodes;
      nodes.resize(static_cast<size_t>(nn));
      if (binary_)
        s_.need(static_cast<uint64_t>(n) * (8 + 8 * static_cast<uint64_t>(nn)),
                "a block of " + std::to_string(n) + " elements");
      for (int64_t e = 0; e < n; ++e) {
        int64_t tag = 0;
        Location where;
        if (binary_) {
          where = here();
          const uint64_t t = s_.binary<uint64_t>(swap_, "an element tag");
          tag = t > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) ? -1 : static_cast<int64_t>(t);
          for (int64_t& v : nodes) {
            const uint64_t x = s_.binary<uint64_t>(swap_, "an element node");
            v = x > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()) ? -1 : static_cast<int64_t>(x);
          }
        } else {
          uint64_t line = 0;
          auto t = line_tokens("an element", line);
          where = line_at(line);
          tag = int_token(t[0], "an element tag", line);
          if (static_cast<int64_t>(t.size()) != 1 + nn) {
            std::ostringstream m;
            m << "element " << tag << " (" << gmsh_type(type).name << ") has " << t.size() - 1 << " nodes, expected "
              << nn << " (does the block's element count match?)";
            fail(path_, where, m.str());
          }
          for (int a = 0; a < nn; ++a) nodes[a] = int_token(t[1 + a], "a node tag", line);
        }
        add_element(tag, type, nodes.data(), where, physicals);
      }
      read += n;
    }
    if (read != total) {
      std::ostringstream m;
      m << "the $Elements header announces " << total << " elements, but its blocks hold " << read;
      fail(path_, at, m.str());
    }
  }

  // ---- Physical groups ----

  // "dim tag \"name\"" lines, ASCII in binary files too.
  void read_physical_names() {
    uint64_t line = 0;
    auto header = line_tokens("the physical name count", line);
    if (header.size() != 1) fail(path_, line_at(line), "expected the physical name count alone on the line");
    const int64_t n = count(int_token(header[0], "the physical name count", line), "the physical name count",
                            line_at(line), static_cast<int64_t>(s_.remaining()));
    for (int64_t i = 0; i < n; ++i) {
      std::string_view text;
      if (!s_.next_line(text, line))
        fail(path_, line_at(s_.line()), "the file ends where physical name " + std::to_string(i + 1) + " was expected");
      const auto t = split(text);
      if (t.size() < 3 || t[0].substr(0, 4) == "$End") {
        std::ostringstream m;
        m << "physical name " << i + 1 << " of " << n
          << " should read: dimension tag \"name\" (does the count match?), found " << quote(text);
        fail(path_, line_at(line), m.str());
      }
      const int64_t dimension = int_token(t[0], "the dimension of a physical group", line);
      const int64_t tag = int_token(t[1], "the tag of a physical group", line);
      if (dimension < 0 || dimension > 3)
        fail(path_, line_at(line),
             "physical group " + std::to_string(tag) + " has dimension " + std::to_string(dimension) + ", not 0 to 3");
      const size_t open = text.find('"', static_cast<size_t>(t[2].data() - text.data()));
      const size_t close = text.rfind('"');
      if (t[2][0] != '"' || close == open || text.find_first_not_of(" \t\r", close + 1) != std::string_view::npos)
        fail(path_, line_at(line), "the name of physical group " + std::to_string(tag) + " is not in double quotes");
      const GroupKey key{static_cast<int>(dimension), tag};
      const auto [it, inserted] =
          names_.emplace(key, PhysicalName{std::string(text.substr(open + 1, close - open - 1)), line_at(line)});
      if (!inserted)
        fail(path_, line_at(line),
             group_words(key) + " is named twice (first " + quote(it->second.name) + ", line " +
                 std::to_string(it->second.where.value) + ")");
    }
  }

  // 4.1 $Entities: each point, curve, surface and volume with its physical
  // tags (bounding boxes and bounding entities are skipped).
  void read_entities() {
    int64_t h[4];
    const Location at = here();
    header4(h, "the $Entities header");
    const int64_t limit = static_cast<int64_t>(s_.remaining());
    for (int dimension = 0; dimension < 4; ++dimension) {
      const int64_t n = count(h[dimension], "an entity count", at, limit);
      for (int64_t i = 0; i < n; ++i) {
        Location where = here();
        int64_t tag = 0;
        std::vector<int64_t> physicals;
        const int reals = dimension == 0 ? 3 : 6;
        if (binary_) {
          tag = s_.binary<int32_t>(swap_, "an entity tag");
          for (int k = 0; k < reals; ++k) s_.binary<double>(swap_, "an entity's coordinates");
          const uint64_t np = s_.binary<uint64_t>(swap_, "an entity's physical tag count");
          if (np > s_.remaining() / 4) fail(path_, where, "an entity's physical tag count is larger than the file");
          for (uint64_t k = 0; k < np; ++k) physicals.push_back(s_.binary<int32_t>(swap_, "a physical tag"));
          if (dimension > 0) {
            const uint64_t nb = s_.binary<uint64_t>(swap_, "an entity's bounding entity count");
            if (nb > s_.remaining() / 4)
              fail(path_, where, "an entity's bounding entity count is larger than the file");
            s_.advance(nb * 4);
          }
        } else {
          uint64_t line = 0;
          const std::string what = std::string("a ") + kEntityKinds[dimension] + " entity";
          const auto t = line_tokens(what, line);
          where = line_at(line);
          // tag, coordinates, physical count and tags, then (curves and
          // above) the bounding count and tags.
          const auto check_size = [&](size_t at_least, bool exact) {
            if (exact ? t.size() != at_least : t.size() < at_least) {
              std::ostringstream m;
              m << what << " has " << t.size() << " values, " << (exact ? "expected " : "too few for ") << at_least
                << " (do the $Entities counts match?)";
              fail(path_, where, m.str());
            }
          };
          size_t k = static_cast<size_t>(reals) + 2;
          check_size(k, false);
          tag = int_token(t[0], "an entity tag", line);
          for (int r = 1; r <= reals; ++r) real_token(t[r], "an entity coordinate", line);
          const int64_t np = int_token(t[k - 1], "a physical tag count", line);
          if (np < 0 || np > static_cast<int64_t>(t.size())) fail(path_, where, what + " has a bad physical tag count");
          check_size(k + static_cast<size_t>(np) + (dimension > 0 ? 1 : 0), false);
          for (int64_t p = 0; p < np; ++p) physicals.push_back(int_token(t[k++], "a physical tag", line));
          if (dimension > 0) {
            const int64_t nb = int_token(t[k++], "a bounding entity count", line);
            if (nb < 0 || nb > static_cast<int64_t>(t.size())) fail(path_, where, what + " has a bad bounding count");
            k += static_cast<size_t>(nb);
          }
          check_size(k, true);
        }
        for (int64_t p : physicals) group(dimension, p, where);
        const auto [it, inserted] = entities_.emplace(GroupKey{dimension, tag}, std::move(physicals));
        if (!inserted)
          fail(path_, where,
               "entity " + std::to_string(tag) + " of dimension " + std::to_string(dimension) + " is defined twice");
      }
    }
  }

  // The physical groups of the entity a 4.1 element block belongs to (none
  // when the file has no $Entities).
  const std::vector<int64_t>& block_physicals(int64_t dimension, int64_t entity, Location where) {
    static const std::vector<int64_t> none;
    if (!have_entities_) return none;
    const auto it = entities_.find({static_cast<int>(dimension), entity});
    if (it == entities_.end() || dimension < 0 || dimension > 3) {
      std::ostringstream m;
      m << "an element block belongs to entity " << entity << " of dimension " << dimension
        << ", which the $Entities section does not define";
      fail(path_, where, m.str());
    }
    return it->second;
  }

  struct PhysicalName {
    std::string name;
    Location where;
  };

  const std::string& path_;
  Scanner s_;
  MeshBuilder builder_;
  bool version4_ = false, binary_ = false, swap_ = false;
  bool have_names_ = false, have_entities_ = false;
  std::unordered_map<int64_t, int32_t> index_;
  std::map<GroupKey, PhysicalName> names_;
  std::map<GroupKey, MeshGroup> groups_;
  std::map<GroupKey, std::vector<int64_t>> entities_;
  std::unordered_map<NodesKey, int32_t, NodesHash> copies_;  // 2.2: element by its vertices
};

}  // namespace

Mesh read_gmsh(const std::string& path, const std::string& data, const MeshReadOptions& options) {
  return GmshReader(path, data, options).read();
}

}  // namespace snh::io
