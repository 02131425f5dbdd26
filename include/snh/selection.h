// Picking vertices (to constrain) and elements (to give a material) by where
// they are or by what the mesh file says about them: boxes, planes and
// spheres in rest coordinates, the file's groups (Gmsh physical groups,
// Medit references) and its point and cell arrays.
//
// Every selector returns indices sorted ascending, without repeats. An empty
// result is returned as is: the caller decides (the solver rejects an empty
// constraint set). Bad arguments (an inverted box, a zero normal, a negative
// radius) and a group or array the mesh does not have throw snh::Error; the
// latter lists the groups or arrays the mesh has.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "snh/mesh.h"

namespace snh {

// ---- Vertices ----

// Vertices with lo <= x <= hi in every coordinate (faces included).
std::vector<int32_t> vertices_in_box(const Mesh& mesh, const std::array<double, 3>& lo,
                                     const std::array<double, 3>& hi);

// Vertices within `tolerance` of the plane through `point` with normal
// `normal` (any length but zero): |(x - point) . normal / |normal|| <= tolerance.
std::vector<int32_t> vertices_on_plane(const Mesh& mesh, const std::array<double, 3>& point,
                                       const std::array<double, 3>& normal, double tolerance = 1e-9);

// Vertices with |x - center| <= radius.
std::vector<int32_t> vertices_in_sphere(const Mesh& mesh, const std::array<double, 3>& center, double radius);

// The vertices of the group named `name` (volume groups: their elements'
// vertices). `dimension` -1 accepts a group of any dimension; when several
// groups share the name (a surface and a volume group), say which.
std::vector<int32_t> vertices_in_group(const Mesh& mesh, const std::string& name, int dimension = -1);
// The same by the group's tag (Gmsh physical tag, Medit reference). Gmsh
// numbers each dimension separately, so a surface and a volume group often
// share a tag: give the dimension then.
std::vector<int32_t> vertices_in_group(const Mesh& mesh, int tag, int dimension = -1);

// Vertices whose value in the one-component point array `array` equals
// `value` exactly (integer ids stored as numbers compare exactly), or lies
// in [lo, hi].
std::vector<int32_t> vertices_with_value(const Mesh& mesh, const std::string& array, double value);
std::vector<int32_t> vertices_with_value_in(const Mesh& mesh, const std::string& array, double lo, double hi);

// ---- Elements ----
// An element's centroid is the mean of its vertices' rest positions (for a
// hex8, the image of the reference cube's centre).

std::vector<int32_t> elements_in_box(const Mesh& mesh, const std::array<double, 3>& lo,
                                     const std::array<double, 3>& hi);
std::vector<int32_t> elements_in_sphere(const Mesh& mesh, const std::array<double, 3>& center, double radius);

// The elements of the volume group (dimension 3) named `name`, or with tag
// `tag`. Naming a surface, curve or point group throws: it holds vertices,
// not elements.
std::vector<int32_t> elements_in_group(const Mesh& mesh, const std::string& name);
std::vector<int32_t> elements_in_group(const Mesh& mesh, int tag);

// Elements whose value in the one-component cell array `array` equals
// `value`, or lies in [lo, hi].
std::vector<int32_t> elements_with_value(const Mesh& mesh, const std::string& array, double value);
std::vector<int32_t> elements_with_value_in(const Mesh& mesh, const std::string& array, double lo, double hi);

}  // namespace snh
