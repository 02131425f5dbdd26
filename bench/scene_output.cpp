#include "scene_output.h"

#include <iostream>

#include "snh/error.h"
#include "snh/fields.h"
#include "snh/io.h"

namespace snh::bench {

void write_step_vtu(const std::string& path, const Mesh& mesh, const MaterialMap& materials,
                    const std::vector<double>& x) {
  std::vector<double> displacement(x.size());
  for (size_t i = 0; i < x.size(); ++i) displacement[i] = x[i] - mesh.positions[i];
  std::vector<VtuCellField> cell_fields;
  try {
    cell_fields = element_fields_for_vtu(compute_element_fields(mesh, materials, x), materials);
  } catch (const Error& e) {
    std::cerr << "warning: " << path << " has no element fields: " << e.what() << '\n';
  }
  write_vtu(path, mesh, x, {{"displacement", 3, displacement}}, cell_fields);
}

}  // namespace snh::bench
