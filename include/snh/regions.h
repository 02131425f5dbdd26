// Regions of a mesh with their own materials: flesh is muscle, fat and skin
// with different stiffness. A region is a set of elements and a material;
// elements in no region keep the base material.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "snh/material.h"
#include "snh/mesh.h"

namespace snh {

struct MaterialRegion {
  std::string name;
  std::vector<int32_t> elements;  // element indices into the mesh
  Material material;
};

// The material of every element: element e uses materials[element_material[e]].
// materials[0] is the base material (elements in no region); region k's
// material is materials[k + 1], even where two regions share a material.
struct MaterialMap {
  std::vector<Material> materials;
  std::vector<int32_t> element_material;  // one per element
  std::vector<std::string> names;         // "base", then the regions' names

  bool uniform() const { return materials.size() == 1; }
  const Material& of_element(size_t e) const { return materials[element_material[e]]; }
};

// One material for the whole mesh.
MaterialMap uniform_material(const Mesh& mesh, const Material& material);

// Throws snh::Error naming the region for: a region with no element, an
// element index out of range, an element in two regions (naming both).
MaterialMap make_material_map(const Mesh& mesh, const Material& base, const std::vector<MaterialRegion>& regions);

// Throws snh::Error naming the problem unless `map` fits `mesh`: at least one
// material, one name per material, one entry per element, every entry an
// index into `materials`.
void validate_material_map(const Mesh& mesh, const MaterialMap& map);

}  // namespace snh
