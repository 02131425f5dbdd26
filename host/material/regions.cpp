#include "snh/regions.h"

#include "snh/error.h"

namespace snh {

MaterialMap uniform_material(const Mesh& mesh, const Material& material) {
  MaterialMap map;
  map.materials = {material};
  map.names = {"base"};
  map.element_material.assign(mesh.element_count(), 0);
  return map;
}

MaterialMap make_material_map(const Mesh& mesh, const Material& base, const std::vector<MaterialRegion>& regions) {
  MaterialMap map = uniform_material(mesh, base);
  const size_t count = mesh.element_count();
  for (size_t k = 0; k < regions.size(); ++k) {
    const MaterialRegion& region = regions[k];
    if (region.elements.empty()) throw Error("material region '" + region.name + "' selects no element");
    const auto id = static_cast<int32_t>(k + 1);
    for (int32_t e : region.elements) {
      if (e < 0 || static_cast<size_t>(e) >= count)
        throw Error("material region '" + region.name + "' refers to element " + std::to_string(e) +
                    ", but the mesh has " + std::to_string(count) + " elements");
      int32_t& slot = map.element_material[static_cast<size_t>(e)];
      if (slot == id) continue;  // listed twice in the same region
      if (slot != 0)
        throw Error("element " + std::to_string(e) + " is in material regions '" + regions[slot - 1].name + "' and '" +
                    region.name + "'");
      slot = id;
    }
    map.materials.push_back(region.material);
    map.names.push_back(region.name);
  }
  return map;
}

void validate_material_map(const Mesh& mesh, const MaterialMap& map) {
  if (map.materials.empty()) throw Error("material map: no material (materials[0] is the base material)");
  if (map.names.size() != map.materials.size())
    throw Error("material map: " + std::to_string(map.names.size()) + " names for " +
                std::to_string(map.materials.size()) + " materials");
  if (map.element_material.size() != mesh.element_count())
    throw Error("material map: element_material has " + std::to_string(map.element_material.size()) +
                " entries, but the mesh has " + std::to_string(mesh.element_count()) + " elements");
  for (size_t e = 0; e < map.element_material.size(); ++e) {
    const int32_t k = map.element_material[e];
    if (k < 0 || static_cast<size_t>(k) >= map.materials.size())
      throw Error("material map: element " + std::to_string(e) + " has material " + std::to_string(k) +
                  ", but the map has " + std::to_string(map.materials.size()) + " materials");
  }
}

}  // namespace snh
