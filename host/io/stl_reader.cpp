// STL surfaces, ASCII and binary. STL stores each facet's corners by value;
// corners with exactly equal coordinates are merged into one vertex (in the
// order first met) so that the surface is indexed and its edges can be
// checked. A file whose size is 84 + 50 n bytes, n being the count at byte
// 80, is binary (some binary files also start with "solid"); otherwise a file
// starting with "solid" is ASCII.
#include <cstdint>
#include <cstring>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/surface_readers.h"

namespace snh::io {
namespace {

struct CornerKey {
  uint64_t bits[3];
  bool operator==(const CornerKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (uint64_t b : k.bits) h = (h ^ b) * 0x100000001b3ull + (h >> 29);
    return static_cast<size_t>(h);
  }
};

class CornerMerger {
 public:
  explicit CornerMerger(SurfaceBuilder& builder) : builder_(builder) {}

  int64_t vertex(const double xyz[3], Location where) {
    CornerKey key{};
    for (int d = 0; d < 3; ++d) {
      const double v = xyz[d] + 0.0;  // -0 and +0 are the same corner
      std::memcpy(&key.bits[d], &v, sizeof v);
    }
    const auto found = index_.find(key);
    if (found != index_.end()) return found->second;
    const int32_t v = builder_.add_vertex(xyz, where);
    index_.emplace(key, v);
    return v;
  }

 private:
  SurfaceBuilder& builder_;
  std::unordered_map<CornerKey, int32_t, CornerHash> index_;
};

bool host_is_little_endian() {
  const uint16_t one = 1;
  unsigned char byte;
  std::memcpy(&byte, &one, 1);
  return byte == 1;
}

TriangleSurface read_binary(const std::string& path, const std::string& data, uint32_t count) {
  Scanner scan(path, data);
  SurfaceBuilder builder(path);
  CornerMerger merger(builder);
  const bool swap = !host_is_little_endian();
  scan.seek(84);
  for (uint32_t f = 0; f < count; ++f) {
    const Location where = byte_at(scan.pos());
    for (int k = 0; k < 3; ++k) scan.binary<float>(swap, "a facet normal");
    int64_t corners[3];
    for (int64_t& corner : corners) {
      double xyz[3];
      for (double& x : xyz) x = scan.binary<float>(swap, "a facet corner");
      corner = merger.vertex(xyz, where);
    }
    scan.binary<uint16_t>(swap, "a facet's attribute bytes");
    builder.add_polygon(corners, 3, where);
  }
  return builder.finish();
}

TriangleSurface read_ascii(const std::string& path, const std::string& data) {
  Scanner scan(path, data);
  SurfaceBuilder builder(path);
  CornerMerger merger(builder);
  std::vector<int64_t> corners;
  for (;;) {
    const std::string_view start = scan.token();
    if (start.empty()) break;
    if (start != "solid")
      fail(path, line_at(scan.token_line()), "expected 'solid' (a new solid) or the end, found " + quote(start));
    scan.rest_of_line();  // the solid's name
    for (;;) {
      const std::string_view t = scan.token();
      const Location where = line_at(scan.token_line());
      if (t == "endsolid") {
        scan.rest_of_line();
        break;
      }
      if (t.empty()) fail(path, where, "the file ends inside a solid (no 'endsolid')");
      if (t != "facet") fail(path, where, "expected 'facet' or 'endsolid', found " + quote(t));
      scan.expect("normal", "after 'facet'");
      for (int k = 0; k < 3; ++k) scan.real("a facet normal component");
      scan.expect("outer", "to start the facet's corners");
      scan.expect("loop", "after 'outer'");
      corners.clear();
      for (;;) {
        const std::string_view v = scan.token();
        if (v == "endloop") break;
        if (v != "vertex")
          fail(path, line_at(scan.token_line()),
               "expected 'vertex x y z' or 'endloop', found " + (v.empty() ? std::string("the end") : quote(v)));
        const Location at = line_at(scan.token_line());
        double xyz[3];
        for (double& x : xyz) x = scan.real("a vertex coordinate");
        corners.push_back(merger.vertex(xyz, at));
      }
      scan.expect("endfacet", "after 'endloop'");
      builder.add_polygon(corners.data(), corners.size(), where);
    }
  }
  return builder.finish();
}

}  // namespace

TriangleSurface read_stl(const std::string& path, const std::string& data) {
  if (data.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, 4);
    if (!host_is_little_endian()) count = __builtin_bswap32(count);
    if (84 + 50 * uint64_t(count) == data.size()) return read_binary(path, data, count);
  }
  const size_t first = data.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && data.compare(first, 5, "solid") == 0) return read_ascii(path, data);
  if (data.size() < 84)
    fail(path,
         "not an STL file: it does not start with 'solid' (ASCII) and is shorter than a binary header (84 bytes)");
  uint32_t count = 0;
  std::memcpy(&count, data.data() + 80, 4);
  if (!host_is_little_endian()) count = __builtin_bswap32(count);
  fail(path, byte_at(80),
       "a binary STL of " + std::to_string(count) + " facets must be " + std::to_string(84 + 50 * uint64_t(count)) +
           " bytes, but the file has " + std::to_string(data.size()) + " (truncated or not STL)");
}

}  // namespace snh::io
