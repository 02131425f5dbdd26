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

}  // namespace snh
