// VTK XML unstructured grids (.vtu): DataArrays in ascii, inline base64
// ("binary") or appended (raw or base64) form, uncompressed. Reads what
// write_vtu writes, and what ParaView and meshio write without compression.
// The Piece's PointData and CellData arrays become the mesh's point and cell
// arrays (cell arrays keep the entries of the volume cells only).
#include <cstring>
#include <map>
#include <sstream>

#include "io/readers.h"
#include "snh/error.h"

namespace snh::io {
namespace {

struct Tag {
  std::string name;  // "/Piece" for a closing tag
  std::map<std::string, std::string> attributes;
  bool self_closing = false;
  uint64_t line = 0;
  size_t end = 0;  // just past '>'
};

struct Array {
  bool present = false;
  std::string type, format, name;
  int64_t components = 1;
  uint64_t offset = 0;        // appended
  size_t begin = 0, end = 0;  // inline content
  uint64_t line = 0;
};

class VtuReader {
 public:
  VtuReader(const std::string& path, const std::string& data, const MeshReadOptions& options)
      : path_(path), data_(data), s_(path, data), builder_(path) {
    builder_.set_element_noun("cell");
    builder_.options = options;
  }

  Mesh read() {
    bool in_points = false, in_cells = false, in_piece = false, seen_file = false, seen_piece = false;
    bool in_point_data = false, in_cell_data = false;
    int64_t points = -1, cells = -1;
    Array* open_array = nullptr;
    Array ignored;
    for (;;) {
      Tag tag;
      if (!next_tag(tag)) break;
      if (tag.name == "VTKFile") {
        seen_file = true;
        const std::string type = attribute(tag, "type");
        if (type != "UnstructuredGrid")
          fail(path_, line_at(tag.line), "the VTKFile type is " + quote(type) + ", not UnstructuredGrid");
        const std::string order = attribute(tag, "byte_order", "LittleEndian");
        if (order != "LittleEndian" && order != "BigEndian")
          fail(path_, line_at(tag.line), "unknown byte_order " + quote(order));
        const uint16_t probe = 1;
        unsigned char first;
        std::memcpy(&first, &probe, 1);
        swap_ = (order == "BigEndian") == (first == 1);
        const std::string header = attribute(tag, "header_type", "UInt32");
        if (header != "UInt32" && header != "UInt64")
          fail(path_, line_at(tag.line), "unknown header_type " + quote(header));
        header64_ = header == "UInt64";
        compressor_ = attribute(tag, "compressor", "");
      } else if (tag.name == "Piece") {
        if (!seen_file) fail(path_, line_at(tag.line), "a Piece outside a VTKFile element");
        if (seen_piece) fail(path_, line_at(tag.line), "a second Piece (only single-piece files are supported)");
        seen_piece = in_piece = true;
        piece_line_ = tag.line;
        points = count_attribute(tag, "NumberOfPoints");
        cells = count_attribute(tag, "NumberOfCells");
      } else if (tag.name == "/Piece") {
        in_piece = false;
      } else if (tag.name == "Points" && in_piece) {
        in_points = !tag.self_closing;
      } else if (tag.name == "/Points") {
        in_points = false;
      } else if (tag.name == "Cells" && in_piece) {
        in_cells = !tag.self_closing;
      } else if (tag.name == "/Cells") {
        in_cells = false;
      } else if (tag.name == "PointData" && in_piece) {
        in_point_data = !tag.self_closing;
      } else if (tag.name == "/PointData") {
        in_point_data = false;
      } else if (tag.name == "CellData" && in_piece) {
        in_cell_data = !tag.self_closing;
      } else if (tag.name == "/CellData") {
        in_cell_data = false;
      } else if (tag.name == "DataArray") {
        Array a;
        a.present = true;
        a.type = attribute(tag, "type");
        a.name = attribute(tag, "Name", "");
        a.format = attribute(tag, "format", "ascii");
        a.line = tag.line;
        a.components = count_attribute(tag, "NumberOfComponents", 1);
        if (a.format == "appended") {
          int64_t offset = count_attribute(tag, "offset");
          a.offset = static_cast<uint64_t>(offset);
        } else if (a.format != "ascii" && a.format != "binary") {
          fail(path_, line_at(tag.line), "unknown DataArray format " + quote(a.format));
        }
        a.begin = a.end = tag.end;
        open_array = &ignored;
        if (in_points && !points_.present) {
          points_ = a;
          open_array = &points_;
        } else if (in_cells && (a.name == "connectivity" || a.name == "offsets" || a.name == "types")) {
          Array& slot = a.name == "connectivity" ? connectivity_ : (a.name == "offsets" ? offsets_ : types_);
          if (slot.present) fail(path_, line_at(tag.line), "a second " + quote(a.name) + " array");
          slot = a;
          open_array = &slot;
        } else if (in_point_data || in_cell_data) {
          std::vector<Array>& list = in_point_data ? point_data_ : cell_data_;
          list.push_back(a);
          open_array = &list.back();  // arrays do not nest: valid until the next push
        }
        if (tag.self_closing) open_array = nullptr;
      } else if (tag.name == "/DataArray") {
        if (open_array) open_array->end = tag_start_;
        open_array = nullptr;
      } else if (tag.name == "AppendedData") {
        const std::string encoding = attribute(tag, "encoding", "raw");
        if (encoding != "raw" && encoding != "base64")
          fail(path_, line_at(tag.line), "unknown AppendedData encoding " + quote(encoding));
        appended_base64_ = encoding == "base64";
        const size_t underscore = data_.find('_', tag.end);
        if (underscore == std::string::npos)
          fail(path_, line_at(tag.line), "AppendedData has no '_' marking the start of its data");
        appended_ = underscore + 1;
        break;  // raw data follows; no more tags are read
      }
    }
    if (!seen_file) fail(path_, "not a VTK XML file: no VTKFile element");
    if (!seen_piece) fail(path_, "the file has no Piece element");
    if (!points_.present) fail(path_, line_at(piece_line_), "the Piece has no Points DataArray");
    if (!connectivity_.present || !offsets_.present || !types_.present)
      fail(path_, line_at(piece_line_), "the Piece's Cells lack a connectivity, offsets or types DataArray");
    if (points_.components != 3)
      fail(path_, line_at(points_.line),
           "the Points array has " + std::to_string(points_.components) + " components, not 3");

    std::vector<double> xyz;
    decode(points_, 3 * static_cast<uint64_t>(points), &xyz, nullptr, "the Points array");
    for (int64_t i = 0; i < points; ++i) builder_.add_vertex(i, xyz.data() + 3 * i, line_at(points_.line));
    std::vector<int64_t> offsets, types, connectivity;
    decode(offsets_, static_cast<uint64_t>(cells), nullptr, &offsets, "the offsets array");
    decode(types_, static_cast<uint64_t>(cells), nullptr, &types, "the types array");
    decode(connectivity_, UINT64_MAX, nullptr, &connectivity, "the connectivity array");
    int64_t start = 0;
    std::vector<char> kept(static_cast<size_t>(cells), 0);
    for (int64_t c = 0; c < cells; ++c) {
      const int64_t end = offsets[c];
      if (end < start || end > static_cast<int64_t>(connectivity.size())) {
        std::ostringstream m;
        m << "cell " << c << " ends at offset " << end << ", out of order or beyond the " << connectivity.size()
          << " connectivity entries";
        fail(path_, line_at(offsets_.line), m.str());
      }
      kept[static_cast<size_t>(c)] = add_vtk_cell(builder_, path_, c, types[c], connectivity.data() + start,
                                                  end - start, builder_.vertex_count(), line_at(connectivity_.line));
      start = end;
    }
    for (const Array& a : point_data_)
      add_point_array(builder_, path_, line_at(a.line), data_array(a, static_cast<uint64_t>(points), "PointData"),
                      builder_.vertex_count());
    for (const Array& a : cell_data_)
      add_cell_array(builder_, path_, line_at(a.line), data_array(a, static_cast<uint64_t>(cells), "CellData"), kept);
    return builder_.finish();
  }

 private:
  std::string attribute(const Tag& tag, const std::string& name) {
    const auto it = tag.attributes.find(name);
    if (it == tag.attributes.end())
      fail(path_, line_at(tag.line), "the " + tag.name + " element has no " + name + " attribute");
    return it->second;
  }
  std::string attribute(const Tag& tag, const std::string& name, const std::string& fallback) {
    const auto it = tag.attributes.find(name);
    return it == tag.attributes.end() ? fallback : it->second;
  }
  // XML's five predefined entities (array names written by write_vtu); any
  // other '&' is kept as it is.
  static std::string unescape(const std::string& text) {
    static const std::pair<const char*, char> kEntities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size(); ++i) {
      bool replaced = false;
      if (text[i] == '&')
        for (const auto& [entity, c] : kEntities)
          if (text.compare(i, std::char_traits<char>::length(entity), entity) == 0) {
            out += c;
            i += std::char_traits<char>::length(entity) - 1;
            replaced = true;
            break;
          }
      if (!replaced) out += text[i];
    }
    return out;
  }
  int64_t count_attribute(const Tag& tag, const std::string& name, int64_t fallback = -1) {
    const auto it = tag.attributes.find(name);
    if (it == tag.attributes.end() && fallback >= 0) return fallback;
    const std::string text = attribute(tag, name);
    int64_t v = 0;
    if (!parse_int(text, v) || v < 0 || static_cast<uint64_t>(v) > data_.size())
      fail(path_, line_at(tag.line),
           "the " + tag.name + " attribute " + name + "=" + quote(text) + " is not a count this file can hold");
    return v;
  }

  // The next element tag, skipping text, comments, declarations.
  bool next_tag(Tag& tag) {
    for (;;) {
      const size_t lt = data_.find('<', s_.pos());
      if (lt == std::string::npos) return false;
      s_.seek(lt);
      tag_start_ = lt;
      tag.line = s_.line();
      if (data_.compare(lt, 4, "<!--") == 0) {
        const size_t end = data_.find("-->", lt);
        if (end == std::string::npos) fail(path_, line_at(tag.line), "an XML comment is not closed");
        s_.seek(end + 3);
        continue;
      }
      if (lt + 1 < data_.size() && (data_[lt + 1] == '?' || data_[lt + 1] == '!')) {
        const size_t end = data_.find('>', lt);
        if (end == std::string::npos) fail(path_, line_at(tag.line), "an XML declaration is not closed");
        s_.seek(end + 1);
        continue;
      }
      size_t i = lt + 1;
      auto name_char = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
               c == ':' || c == '.' || c == '/';
      };
      while (i < data_.size() && name_char(data_[i])) ++i;
      tag.name = data_.substr(lt + 1, i - lt - 1);
      if (tag.name.empty() || tag.name == "/") fail(path_, line_at(tag.line), "malformed XML: '<' starts no element");
      tag.attributes.clear();
      for (;;) {
        while (i < data_.size() && (data_[i] == ' ' || data_[i] == '\t' || data_[i] == '\n' || data_[i] == '\r')) ++i;
        if (i >= data_.size())
          fail(path_, line_at(tag.line), "malformed XML: the <" + tag.name + "> tag is not closed");
        if (data_[i] == '>') {
          tag.self_closing = false;
          ++i;
          break;
        }
        if (data_[i] == '/' && i + 1 < data_.size() && data_[i + 1] == '>') {
          tag.self_closing = true;
          i += 2;
          break;
        }
        const size_t name_start = i;
        while (i < data_.size() && name_char(data_[i]) && data_[i] != '/') ++i;
        const std::string name = data_.substr(name_start, i - name_start);
        if (name.empty() || i >= data_.size() || data_[i] != '=' || i + 1 >= data_.size() ||
            (data_[i + 1] != '"' && data_[i + 1] != '\''))
          fail(path_, line_at(tag.line), "malformed XML attribute in the <" + tag.name + "> tag");
        const char q = data_[i + 1];
        const size_t close = data_.find(q, i + 2);
        if (close == std::string::npos)
          fail(path_, line_at(tag.line), "malformed XML: an attribute of <" + tag.name + "> is not closed");
        tag.attributes[name] = unescape(data_.substr(i + 2, close - i - 2));
        i = close + 1;
      }
      s_.seek(i);
      tag.end = i;
      return true;
    }
  }

  static int type_size(const std::string& type) {
    if (type == "Int8" || type == "UInt8") return 1;
    if (type == "Int16" || type == "UInt16") return 2;
    if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
    if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
    return 0;
  }

  // Base64 to bytes; '=' padding may end any 4-character group (VTK encodes
  // the header and the data separately). Stops once `limit` bytes are out.
  std::string base64(size_t begin, size_t end, uint64_t limit, Location where, size_t* consumed = nullptr) {
    std::string out;
    uint32_t group = 0;
    int bits = 0, chars = 0;
    size_t i = begin;
    for (; i < end && out.size() < limit; ++i) {
      const char c = data_[i];
      int v;
      if (c >= 'A' && c <= 'Z')
        v = c - 'A';
      else if (c >= 'a' && c <= 'z')
        v = c - 'a' + 26;
      else if (c >= '0' && c <= '9')
        v = c - '0' + 52;
      else if (c == '+')
        v = 62;
      else if (c == '/')
        v = 63;
      else if (c == '=') {
        ++chars;
        if (chars == 4) chars = 0, bits = 0, group = 0;
        continue;
      } else if (c == ' ' || c == '\n' || c == '\r' || c == '\t') {
        continue;
      } else {
        fail(path_, where, "invalid base64 character " + quote(std::string_view(&data_[i], 1)));
      }
      group = (group << 6) | static_cast<uint32_t>(v);
      bits += 6;
      chars = (chars + 1) % 4;
      if (bits >= 8) {
        bits -= 8;
        out += static_cast<char>((group >> bits) & 0xff);
      }
      if (chars == 0) bits = 0, group = 0;
    }
    if (consumed) *consumed = i;
    return out;
  }

  // Values of an array: `expected` of them (UINT64_MAX: whatever it holds).
  void decode(const Array& a, uint64_t expected, std::vector<double>* reals, std::vector<int64_t>* ints,
              const std::string& what) {
    const int size = type_size(a.type);
    const Location where = line_at(a.line);
    if (size == 0) fail(path_, where, what + " has unsupported type " + quote(a.type));
    const bool is_float = a.type[0] == 'F';
    const bool is_unsigned = a.type[0] == 'U';
    std::vector<double> r;
    std::vector<int64_t> k;
    if (a.format == "ascii") {
      Scanner t(path_, data_);
      t.seek(a.begin);
      for (uint64_t i = 0; i < expected; ++i) {
        std::string_view token = t.token();
        // The last value may touch the closing tag: "... 4</DataArray>".
        const size_t start = static_cast<size_t>(token.data() - data_.data());
        if (t.pos() > a.end && start < a.end) token = token.substr(0, a.end - start);
        if (start >= a.end || token.empty()) {
          if (expected == UINT64_MAX) break;
          std::ostringstream m;
          m << what << " holds " << i << " values, but " << expected << " are needed";
          fail(path_, where, m.str());
        }
        double x = 0;
        int64_t n = 0;
        if (ints && !parse_int(token, n))
          fail(path_, line_at(t.token_line()), what + ": " + quote(token) + " is not an integer");
        if (!ints && !parse_double(token, x))
          fail(path_, line_at(t.token_line()), what + ": " + quote(token) + " is not a number");
        if (reals) r.push_back(x);
        if (ints) k.push_back(n);
      }
    } else {
      if (!compressor_.empty())
        fail(path_, where, what + " is compressed (" + compressor_ + "); only uncompressed data is supported");
      std::string bytes;
      Location at = where;
      const int header = header64_ ? 8 : 4;
      if (a.format == "binary") {
        bytes = base64(a.begin, a.end, UINT64_MAX, where);
      } else {
        if (appended_ == std::string::npos) fail(path_, where, what + " is appended, but the file has no AppendedData");
        const uint64_t start = appended_ + a.offset;
        at = byte_at(start);
        if (start > data_.size()) fail(path_, at, what + ": its offset lies beyond the end of the file");
        if (appended_base64_) {
          size_t used = 0;
          bytes = base64(start, data_.size(), static_cast<uint64_t>(header), at, &used);
          if (bytes.size() >= static_cast<size_t>(header)) {
            uint64_t n = read_header(bytes, header);
            if (n > data_.size()) fail(path_, at, what + ": its byte count exceeds the file");
            bytes += base64(used, data_.size(), n + static_cast<uint64_t>(header) - bytes.size(), at);
          }
        } else {
          bytes = data_.substr(start, std::min<uint64_t>(data_.size() - start, UINT64_MAX));
        }
      }
      if (bytes.size() < static_cast<size_t>(header)) fail(path_, at, what + ": the data ends inside its header");
      const uint64_t n = read_header(bytes, header);
      if (n > bytes.size() - header) {
        std::ostringstream m;
        m << what << " announces " << n << " bytes, but only " << bytes.size() - header << " follow (truncated?)";
        fail(path_, at, m.str());
      }
      if (n % static_cast<uint64_t>(size) != 0)
        fail(path_, at, what + ": its byte count " + std::to_string(n) + " is not a multiple of its value size");
      const uint64_t count = n / static_cast<uint64_t>(size);
      if (expected != UINT64_MAX && count < expected) {
        std::ostringstream m;
        m << what << " holds " << count << " values, but " << expected << " are needed";
        fail(path_, at, m.str());
      }
      const uint64_t take = expected == UINT64_MAX ? count : expected;
      for (uint64_t i = 0; i < take; ++i) {
        unsigned char b[8];
        std::memcpy(b, bytes.data() + header + i * static_cast<uint64_t>(size), static_cast<size_t>(size));
        if (swap_) std::reverse(b, b + size);
        double x = 0;
        int64_t v = 0;
        if (is_float) {
          if (size == 4) {
            float f;
            std::memcpy(&f, b, 4);
            x = f;
          } else {
            std::memcpy(&x, b, 8);
          }
          if (ints) {
            if (!(x >= -9.2e18 && x <= 9.2e18) || x != static_cast<double>(static_cast<int64_t>(x)))
              fail(path_, at, what + " holds a non-integer value");
            v = static_cast<int64_t>(x);
          }
        } else {
          switch (size) {
            case 1:
              v = is_unsigned ? int64_t(*reinterpret_cast<uint8_t*>(b)) : int64_t(static_cast<int8_t>(b[0]));
              break;
            case 2: {
              uint16_t u;
              std::memcpy(&u, b, 2);
              v = is_unsigned ? int64_t(u) : int64_t(static_cast<int16_t>(u));
              break;
            }
            case 4: {
              uint32_t u;
              std::memcpy(&u, b, 4);
              v = is_unsigned ? int64_t(u) : int64_t(static_cast<int32_t>(u));
              break;
            }
            default: {
              uint64_t u;
              std::memcpy(&u, b, 8);
              v = static_cast<int64_t>(u);
              if (is_unsigned && v < 0) fail(path_, at, what + " holds a value out of range");
            }
          }
          x = static_cast<double>(v);
        }
        if (reals) r.push_back(x);
        if (ints) k.push_back(v);
      }
    }
    if (reals) *reals = std::move(r);
    if (ints) *ints = std::move(k);
  }

  // A PointData or CellData array of `tuples` tuples.
  MeshArray data_array(const Array& a, uint64_t tuples, const char* section) {
    MeshArray out{a.name, static_cast<int>(a.components), {}};
    const std::string what = std::string(section) + " array " + quote(a.name);
    if (a.name.empty()) fail(path_, line_at(a.line), std::string("a ") + section + " DataArray has no Name");
    if (a.components < 1 || a.components > 64)
      fail(path_, line_at(a.line), what + " has " + std::to_string(a.components) + " components");
    decode(a, UINT64_MAX, &out.values, nullptr, what);
    if (out.values.size() != tuples * static_cast<uint64_t>(a.components)) {
      std::ostringstream m;
      m << what << " holds " << out.values.size() << " values, but " << tuples << " tuples of " << a.components
        << " components need " << tuples * static_cast<uint64_t>(a.components);
      fail(path_, line_at(a.line), m.str());
    }
    return out;
  }

  uint64_t read_header(const std::string& bytes, int header) const {
    unsigned char b[8];
    std::memcpy(b, bytes.data(), static_cast<size_t>(header));
    if (swap_) std::reverse(b, b + header);
    if (header == 8) {
      uint64_t n;
      std::memcpy(&n, b, 8);
      return n;
    }
    uint32_t n;
    std::memcpy(&n, b, 4);
    return n;
  }

  const std::string& path_;
  const std::string& data_;
  Scanner s_;
  MeshBuilder builder_;
  bool swap_ = false, header64_ = false, appended_base64_ = false;
  std::string compressor_;
  size_t appended_ = std::string::npos;
  size_t tag_start_ = 0;
  uint64_t piece_line_ = 0;
  Array points_, connectivity_, offsets_, types_;
  std::vector<Array> point_data_, cell_data_;
};

}  // namespace

Mesh read_vtu(const std::string& path, const std::string& data, const MeshReadOptions& options) {
  return VtuReader(path, data, options).read();
}

}  // namespace snh::io
