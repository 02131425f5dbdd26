#include "scene/obstacle_surface.h"

#include <cmath>

namespace snh::scene_io {
namespace {

using Vec = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

Vec add(const Vec& a, const Vec& b, double s = 1.0) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec unit(const Vec& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

// Two unit vectors completing n to a right-handed orthonormal frame (u, v, n).
void frame(const Vec& n, Vec& u, Vec& v) {
  const Vec helper = std::abs(n[0]) < 0.9 ? Vec{1, 0, 0} : Vec{0, 1, 0};
  u = unit(cross(helper, n));
  v = cross(n, u);
}

int32_t push(TriangleSurface& s, const Vec& x) {
  s.positions.push_back(x);
  return static_cast<int32_t>(s.vertex_count() - 1);
}

void triangle(TriangleSurface& s, int32_t a, int32_t b, int32_t c) { s.triangles.insert(s.triangles.end(), {a, b, c}); }

}  // namespace

TriangleSurface obstacle_surface(const std::vector<Obstacle>& obstacles, double t, const Vec& center, double extent) {
  TriangleSurface s;
  const int around = 48;
  for (const Obstacle& o : obstacles) {
    Vec point = o.point, direction = o.direction;
    if (o.motion) {
      const RigidTransform m = o.motion(t);
      point = m.apply(o.point);
      for (int r = 0; r < 3; ++r)
        direction[r] = m.rotation[3 * r] * o.direction[0] + m.rotation[3 * r + 1] * o.direction[1] +
                       m.rotation[3 * r + 2] * o.direction[2];
    }
    if (o.type == ObstacleType::plane) {
      const Vec n = unit(direction);
      Vec u, v;
      frame(n, u, v);
      const Vec c = add(center, n, -dot(add(center, point, -1.0), n));  // center projected on the plane
      const int32_t a = push(s, add(add(c, u, -extent), v, -extent)), b = push(s, add(add(c, u, extent), v, -extent)),
                    d = push(s, add(add(c, u, extent), v, extent)), e = push(s, add(add(c, u, -extent), v, extent));
      triangle(s, a, b, d);
      triangle(s, a, d, e);
    } else if (o.type == ObstacleType::cylinder) {
      const Vec axis = unit(direction);
      Vec u, v;
      frame(axis, u, v);
      const Vec c = add(point, axis, dot(add(center, point, -1.0), axis));  // center projected on the axis
      const int32_t first = static_cast<int32_t>(s.vertex_count());
      for (int k = 0; k < around; ++k) {
        const double phi = 2 * kPi * k / around;
        const Vec radial =
            add(Vec{o.radius * std::cos(phi) * u[0], o.radius * std::cos(phi) * u[1], o.radius * std::cos(phi) * u[2]},
                v, o.radius * std::sin(phi));
        push(s, add(add(c, radial), axis, -extent));
        push(s, add(add(c, radial), axis, extent));
      }
      for (int k = 0; k < around; ++k) {
        const int32_t a = first + 2 * k, b = first + 2 * ((k + 1) % around);
        triangle(s, a, b, b + 1);
        triangle(s, a, b + 1, a + 1);
      }
    } else {
      const int rings = around / 2;
      const int32_t first = static_cast<int32_t>(s.vertex_count());
      for (int i = 0; i <= rings; ++i) {
        const double theta = kPi * i / rings;
        for (int k = 0; k < around; ++k) {
          const double phi = 2 * kPi * k / around;
          push(s, {point[0] + o.radius * std::sin(theta) * std::cos(phi),
                   point[1] + o.radius * std::sin(theta) * std::sin(phi), point[2] + o.radius * std::cos(theta)});
        }
      }
      for (int i = 0; i < rings; ++i)
        for (int k = 0; k < around; ++k) {
          const int32_t a = first + i * around + k, b = first + i * around + (k + 1) % around;
          triangle(s, a, a + around, b + around);
          triangle(s, a, b + around, b);
        }
    }
  }
  return s;
}

}  // namespace snh::scene_io
