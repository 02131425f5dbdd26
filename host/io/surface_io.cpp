// read_surface: dispatch by extension and the builder the surface readers
// share; write_obj.
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <locale>
#include <sstream>

#include "io/readers.h"
#include "io/surface_readers.h"
#include "snh/error.h"
#include "snh/surface.h"

namespace snh {
namespace io {

int32_t SurfaceBuilder::add_vertex(const double xyz[3], Location where) {
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(xyz[d])) {
      std::ostringstream s;
      s << "vertex " << vertex_count() + 1 << " has a non-finite coordinate ("
        << "xyz"[d] << " = " << xyz[d] << ")";
      fail(path_, where, s.str());
    }
  if (vertex_count() >= static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    fail(path_, where, "more vertices than 32-bit indices can address");
  surface_.positions.push_back({xyz[0], xyz[1], xyz[2]});
  return static_cast<int32_t>(vertex_count() - 1);
}

void SurfaceBuilder::add_polygon(const int64_t* corners, size_t count, Location where) {
  if (count < 3) {
    std::ostringstream s;
    s << "a face needs at least 3 corners, this one has " << count;
    fail(path_, where, s.str());
  }
  const int64_t vertices = static_cast<int64_t>(vertex_count());
  for (size_t a = 0; a < count; ++a) {
    if (corners[a] < 0 || corners[a] >= vertices) {
      std::ostringstream s;
      s << "a face refers to vertex " << corners[a] << " (0-based), but " << vertices << " vertices in the file";
      fail(path_, where, s.str());
    }
    for (size_t b = 0; b < a; ++b)
      if (corners[b] == corners[a]) {
        std::ostringstream s;
        s << "a face uses vertex " << corners[a] << " (0-based) twice (corners " << b + 1 << " and " << a + 1
          << "): a degenerate face";
        fail(path_, where, s.str());
      }
  }
  if (surface_.triangle_count() + count - 2 > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    fail(path_, where, "more triangles than 32-bit indices can address");
  for (size_t a = 1; a + 1 < count; ++a) {
    surface_.triangles.push_back(static_cast<int32_t>(corners[0]));
    surface_.triangles.push_back(static_cast<int32_t>(corners[a]));
    surface_.triangles.push_back(static_cast<int32_t>(corners[a + 1]));
  }
}

TriangleSurface SurfaceBuilder::finish() {
  if (surface_.triangle_count() == 0) fail(path_, "the file holds no faces");
  return std::move(surface_);
}

}  // namespace io

TriangleSurface read_surface(const std::string& path) {
  const std::string ext = io::lowercase_extension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".stl")
    throw Error(path + ": unknown surface format '" + ext + "' (expected .obj, .ply or .stl)");
  const std::string data = io::read_file(path);
  if (ext == ".obj") return io::read_obj(path, data);
  if (ext == ".ply") return io::read_ply(path, data);
  return io::read_stl(path, data);
}

void write_obj(const std::string& path, const TriangleSurface& surface, const Points& x) {
  const Points& p = x.empty() ? surface.positions : x;
  if (p.size() != surface.vertex_count()) {
    std::ostringstream s;
    s << "write_obj " << path << ": the positions have " << p.xyz().size() << " values, but the surface has "
      << surface.vertex_count() << " vertices (" << surface.positions.xyz().size() << " values expected)";
    throw Error(s.str());
  }
  for (size_t i = 0; i < surface.triangles.size(); ++i)
    if (surface.triangles[i] < 0 || static_cast<size_t>(surface.triangles[i]) >= surface.vertex_count()) {
      std::ostringstream s;
      s << "write_obj " << path << ": triangle " << i / 3 << " refers to vertex " << surface.triangles[i]
        << ", but the surface has " << surface.vertex_count() << " vertices";
      throw Error(s.str());
    }
  std::ofstream file(path, std::ios::out | std::ios::trunc);
  if (!file) throw Error("write_obj " + path + ": the file cannot be opened for writing (does its directory exist?)");
  file.imbue(std::locale::classic());
  file << std::setprecision(std::numeric_limits<double>::max_digits10);
  file << "# snh surface: " << surface.vertex_count() << " vertices, " << surface.triangle_count() << " triangles\n";
  for (size_t v = 0; v < surface.vertex_count(); ++v)
    file << "v " << p(v, 0) << ' ' << p(v, 1) << ' ' << p(v, 2) << '\n';
  for (size_t t = 0; t < surface.triangle_count(); ++t)
    file << "f " << surface.triangles[3 * t] + 1 << ' ' << surface.triangles[3 * t + 1] + 1 << ' '
         << surface.triangles[3 * t + 2] + 1 << '\n';
  file.flush();
  if (!file) throw Error("write_obj " + path + ": writing failed part way");
  file.close();
  if (file.fail()) throw Error("write_obj " + path + ": closing failed");
}

}  // namespace snh
