// A character's surface per frame as binary PLY (snh/character.h).
#include <cstring>
#include <fstream>

#include "snh/character.h"
#include "snh/error.h"

namespace snh {

void write_surface_ply(const std::string& path, const TriangleSurface& surface, const Points& x) {
  const Points& p = x.empty() ? surface.positions : x;
  if (p.size() != surface.vertex_count())
    throw Error(path + ": " + std::to_string(p.size()) + " positions for a surface of " +
                std::to_string(surface.vertex_count()) + " vertices");
  std::string b = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(surface.vertex_count()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(surface.triangle_count()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&](const void* v, size_t n) {
    // Little-endian hosts only write their bytes as they are; others swap.
    const unsigned char* c = static_cast<const unsigned char*>(v);
    const uint32_t one = 1;
    const bool little = *reinterpret_cast<const unsigned char*>(&one) == 1;
    for (size_t i = 0; i < n; ++i) b.push_back(static_cast<char>(c[little ? i : n - 1 - i]));
  };
  for (double v : p.xyz()) {
    const float f = static_cast<float>(v);
    put(&f, 4);
  }
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    b.push_back(3);
    for (int k = 0; k < 3; ++k) put(&surface.triangles[3 * t + k], 4);
  }
  std::ofstream out(path, std::ios::binary);
  out.write(b.data(), static_cast<std::streamsize>(b.size()));
  if (!out) throw Error(path + ": cannot write the surface");
}

}  // namespace snh
