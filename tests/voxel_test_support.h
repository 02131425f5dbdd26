// Voxelizations made by hand for the embedding and rig tests: a box lattice
// whose cells a predicate keeps, with its grid (origin, cell, element_cell)
// as snh::voxelize describes it.
#pragma once

#include <array>
#include <functional>

#include "snh/mesh.h"
#include "snh/surface.h"

namespace snh::test {

inline Voxelization box_voxelization(int nx, int ny, int nz, double h, std::array<double, 3> origin,
                                     const std::function<bool(int, int, int)>& keep = {}) {
  const Mesh box = make_box_lattice(nx, ny, nz, h, origin);
  Voxelization v;
  v.cell = h;
  v.origin = origin;
  v.dims = {nx, ny, nz};
  v.lattice = box;
  v.lattice.elements.clear();
  // make_box_lattice's elements run over i fastest, then j, then k.
  size_t e = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++e)
        if (!keep || keep(i, j, k)) {
          v.lattice.elements.insert(v.lattice.elements.end(), box.elements.begin() + 8 * e,
                                    box.elements.begin() + 8 * (e + 1));
          v.element_cell.push_back({i, j, k});
        }
  return v;
}

}  // namespace snh::test
