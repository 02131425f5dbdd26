// Vertex and element selectors (snh/selection.h).
#include "snh/selection.h"

#include <cmath>
#include <sstream>

#include "snh/error.h"

namespace snh {
namespace {

using Point = std::array<double, 3>;

void check_box(const Point& lo, const Point& hi, const char* who) {
  for (int d = 0; d < 3; ++d)
    if (!(lo[d] <= hi[d]) || !std::isfinite(lo[d]) || !std::isfinite(hi[d])) {
      std::ostringstream s;
      s << who << ": the box's "
        << "xyz"[d] << " range [" << lo[d] << ", " << hi[d] << "] is empty or not finite (min must be <= max)";
      throw Error(s.str());
    }
}

void check_sphere(const Point& center, double radius, const char* who) {
  if (!(radius >= 0.0) || !std::isfinite(radius) || !std::isfinite(center[0]) || !std::isfinite(center[1]) ||
      !std::isfinite(center[2])) {
    std::ostringstream s;
    s << who << ": the sphere needs a finite centre and a radius >= 0, got radius " << radius;
    throw Error(s.str());
  }
}

bool in_box(const Point& x, const Point& lo, const Point& hi) {
  return x[0] >= lo[0] && x[0] <= hi[0] && x[1] >= lo[1] && x[1] <= hi[1] && x[2] >= lo[2] && x[2] <= hi[2];
}

bool in_sphere(const Point& x, const Point& c, double r) {
  const double dx = x[0] - c[0], dy = x[1] - c[1], dz = x[2] - c[2];
  return dx * dx + dy * dy + dz * dz <= r * r;
}

Point centroid(const Mesh& mesh, size_t e) {
  const int n = nodes_per_element(mesh.type);
  Point c{0.0, 0.0, 0.0};
  for (int a = 0; a < n; ++a) {
    const int32_t v = mesh.elements[n * e + a];
    for (int d = 0; d < 3; ++d) c[d] += mesh.positions(v, d);
  }
  for (double& x : c) x /= n;
  return c;
}

template <class Keep>
std::vector<int32_t> vertices_where(const Mesh& mesh, Keep keep) {
  std::vector<int32_t> out;
  for (size_t v = 0; v < mesh.vertex_count(); ++v)
    if (keep(mesh.vertex(v))) out.push_back(static_cast<int32_t>(v));
  return out;
}

template <class Keep>
std::vector<int32_t> elements_where(const Mesh& mesh, Keep keep) {
  std::vector<int32_t> out;
  for (size_t e = 0; e < mesh.element_count(); ++e)
    if (keep(centroid(mesh, e))) out.push_back(static_cast<int32_t>(e));
  return out;
}

const char* dimension_word(int dimension) {
  static const char* const kWords[4] = {"point", "curve", "surface", "volume"};
  return dimension >= 0 && dimension < 4 ? kWords[dimension] : "unknown";
}

std::string describe(const MeshGroup& g) {
  std::ostringstream s;
  if (g.name.empty())
    s << "unnamed";
  else
    s << "'" << g.name << "'";
  s << " (" << dimension_word(g.dimension) << ", tag " << g.tag << ")";
  return s.str();
}

std::string describe_groups(const Mesh& mesh, int dimension) {
  std::string out;
  for (const MeshGroup& g : mesh.groups)
    if (dimension < 0 || g.dimension == dimension) out += (out.empty() ? "" : ", ") + describe(g);
  return out.empty() ? "none" : out;
}

// The one group `matches` picks among those of `dimension` (-1: any).
template <class Matches>
const MeshGroup& find_group(const Mesh& mesh, Matches matches, const std::string& wanted, int dimension,
                            const char* who) {
  std::vector<const MeshGroup*> found;
  for (const MeshGroup& g : mesh.groups)
    if (matches(g) && (dimension < 0 || g.dimension == dimension)) found.push_back(&g);
  if (found.size() == 1) return *found.front();
  std::ostringstream s;
  s << who << ": ";
  if (found.empty()) {
    s << "the mesh has no group " << wanted;
    if (dimension >= 0) s << " of dimension " << dimension;
    s << "; its groups: " << describe_groups(mesh, -1);
    if (mesh.groups.empty()) s << " (groups come from Gmsh physical groups and Medit references)";
  } else {
    s << found.size() << " groups match " << wanted << " (";
    for (size_t i = 0; i < found.size(); ++i) s << (i ? ", " : "") << describe(*found[i]);
    s << "); give the dimension";
  }
  throw Error(s.str());
}

const MeshArray& find_array(const std::vector<MeshArray>& arrays, const std::string& name, const char* kind,
                            const char* who) {
  for (const MeshArray& a : arrays)
    if (a.name == name) {
      if (a.components != 1) {
        std::ostringstream s;
        s << who << ": " << kind << " array '" << name << "' has " << a.components
          << " components; selecting by value needs a one-component array";
        throw Error(s.str());
      }
      return a;
    }
  std::ostringstream s;
  s << who << ": the mesh has no " << kind << " array '" << name << "'; its " << kind << " arrays: ";
  if (arrays.empty()) s << "none";
  for (size_t i = 0; i < arrays.size(); ++i)
    s << (i ? ", " : "") << "'" << arrays[i].name << "' (" << arrays[i].components << " component"
      << (arrays[i].components == 1 ? "" : "s") << ")";
  throw Error(s.str());
}

std::vector<int32_t> with_value_in(const MeshArray& a, double lo, double hi, const char* who) {
  if (!(lo <= hi)) {
    std::ostringstream s;
    s << who << ": the range [" << lo << ", " << hi << "] is empty";
    throw Error(s.str());
  }
  std::vector<int32_t> out;
  for (size_t i = 0; i < a.values.size(); ++i)
    if (a.values[i] >= lo && a.values[i] <= hi) out.push_back(static_cast<int32_t>(i));
  return out;
}

std::string quoted(const std::string& name) { return "'" + name + "'"; }

}  // namespace

std::vector<int32_t> vertices_in_box(const Mesh& mesh, const Point& lo, const Point& hi) {
  check_box(lo, hi, "vertices_in_box");
  return vertices_where(mesh, [&](const Point& x) { return in_box(x, lo, hi); });
}

std::vector<int32_t> vertices_on_plane(const Mesh& mesh, const Point& point, const Point& normal, double tolerance) {
  const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  if (!(length > 0.0) || !std::isfinite(length))
    throw Error("vertices_on_plane: the plane's normal must be finite and not zero");
  if (!(tolerance >= 0.0))
    throw Error("vertices_on_plane: the tolerance must be >= 0, got " + std::to_string(tolerance));
  const Point n{normal[0] / length, normal[1] / length, normal[2] / length};
  return vertices_where(mesh, [&](const Point& x) {
    return std::abs((x[0] - point[0]) * n[0] + (x[1] - point[1]) * n[1] + (x[2] - point[2]) * n[2]) <= tolerance;
  });
}

std::vector<int32_t> vertices_in_sphere(const Mesh& mesh, const Point& center, double radius) {
  check_sphere(center, radius, "vertices_in_sphere");
  return vertices_where(mesh, [&](const Point& x) { return in_sphere(x, center, radius); });
}

std::vector<int32_t> vertices_in_group(const Mesh& mesh, const std::string& name, int dimension) {
  return find_group(
             mesh, [&](const MeshGroup& g) { return g.name == name; }, quoted(name), dimension, "vertices_in_group")
      .vertices;
}

std::vector<int32_t> vertices_in_group(const Mesh& mesh, int tag, int dimension) {
  return find_group(
             mesh, [&](const MeshGroup& g) { return g.tag == tag; }, "with tag " + std::to_string(tag), dimension,
             "vertices_in_group")
      .vertices;
}

std::vector<int32_t> vertices_with_value(const Mesh& mesh, const std::string& array, double value) {
  return with_value_in(find_array(mesh.point_arrays, array, "point", "vertices_with_value"), value, value,
                       "vertices_with_value");
}

std::vector<int32_t> vertices_with_value_in(const Mesh& mesh, const std::string& array, double lo, double hi) {
  return with_value_in(find_array(mesh.point_arrays, array, "point", "vertices_with_value_in"), lo, hi,
                       "vertices_with_value_in");
}

std::vector<int32_t> elements_in_box(const Mesh& mesh, const Point& lo, const Point& hi) {
  check_box(lo, hi, "elements_in_box");
  return elements_where(mesh, [&](const Point& x) { return in_box(x, lo, hi); });
}

std::vector<int32_t> elements_in_sphere(const Mesh& mesh, const Point& center, double radius) {
  check_sphere(center, radius, "elements_in_sphere");
  return elements_where(mesh, [&](const Point& x) { return in_sphere(x, center, radius); });
}

namespace {

template <class Matches>
std::vector<int32_t> elements_of_volume_group(const Mesh& mesh, Matches matches, const std::string& wanted) {
  const char* who = "elements_in_group";
  bool lower = false;
  for (const MeshGroup& g : mesh.groups) lower = lower || (matches(g) && g.dimension != 3);
  bool volume = false;
  for (const MeshGroup& g : mesh.groups) volume = volume || (matches(g) && g.dimension == 3);
  if (lower && !volume) {
    std::ostringstream s;
    s << who << ": group " << wanted << " is not a volume group, so it holds vertices, not elements; the mesh's "
      << "volume groups: " << describe_groups(mesh, 3);
    throw Error(s.str());
  }
  return find_group(mesh, matches, wanted, 3, who).elements;
}

}  // namespace

std::vector<int32_t> elements_in_group(const Mesh& mesh, const std::string& name) {
  return elements_of_volume_group(
      mesh, [&](const MeshGroup& g) { return g.name == name; }, quoted(name));
}

std::vector<int32_t> elements_in_group(const Mesh& mesh, int tag) {
  return elements_of_volume_group(
      mesh, [&](const MeshGroup& g) { return g.tag == tag; }, "with tag " + std::to_string(tag));
}

std::vector<int32_t> elements_with_value(const Mesh& mesh, const std::string& array, double value) {
  return with_value_in(find_array(mesh.cell_arrays, array, "cell", "elements_with_value"), value, value,
                       "elements_with_value");
}

std::vector<int32_t> elements_with_value_in(const Mesh& mesh, const std::string& array, double lo, double hi) {
  return with_value_in(find_array(mesh.cell_arrays, array, "cell", "elements_with_value_in"), lo, hi,
                       "elements_with_value_in");
}

}  // namespace snh
