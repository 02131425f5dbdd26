#include "solver/model/point_lanes.h"

#include <string>

#include "snh/error.h"

namespace snh::solver {

template <typename Real>
PointLanes<Real>::PointLanes(ElementData<Real>& data, const device::MaterialArgs<Real>& material,
                             ProductVariants<Real>& products)
    : data_(data), material_(material), products_(products) {}

template <typename Real>
bool PointLanes<Real>::point_lanes_available() const {
  // tet4 lanes hold 8 elements, so they share one material; the lanes read
  // the value-major or point-major cache.
  return data_.cache_tile == 1 && (data_.nodes == 8 || !material_.per_element());
}

template <typename Real>
void PointLanes<Real>::set_point_lanes(bool on) {
  if (on && data_.cache_tile > 1)
    throw Error(
        "solver: the per-point lanes program reads the value-major or point-major cache, not the tiled one "
        "(PointDataLayout)");
  if (on && !point_lanes_available())
    throw Error("solver: per-point lanes of tet4 meshes need one material for the mesh (this map has regions)");
  data_.point_lanes = on;
  set_material_lanes(on ? default_material_lanes() : ElementData<Real>::kCacheLanes);
  products_.set_point_lanes(material_lanes_);
  diagonal_k_ = data_.point_kernel("snh_element_diagonal");
}

template <typename Real>
int PointLanes<Real>::default_material_lanes() const {
  // Two of the device's native vectors per lane vector where it has 8-wide
  // ones for Real (AVX-512 in double, AVX and up in float): the SVD's chains
  // of dependent square roots and divisions bound one vector's throughput,
  // and a second, independent one fills their latency (twice the elements
  // per work-item). 8 where hex8 elements carry their own material (a
  // work-item's material is one element's).
  const DeviceInfo& info = data_.cl.info();
  const unsigned native =
      sizeof(Real) == sizeof(double) ? info.native_vector_width_double : info.native_vector_width_float;
  return native >= 8 && !hex8_materials_per_element() ? 16 : ElementData<Real>::kCacheLanes;
}

template <typename Real>
void PointLanes<Real>::set_material_lanes(int lanes) {
  if (lanes != 8 && lanes != 16) throw Error("solver: material lanes are 8 or 16, not " + std::to_string(lanes));
  if (lanes == 16 && hex8_materials_per_element())
    throw Error(
        "solver: 16 material lanes hold two hex8 elements, so they need one material for the mesh (this map has "
        "regions)");
  material_lanes_ = data_.point_lanes ? lanes : 0;
  linearize_k_ = data_.point_kernel("snh_element_linearize", material_lanes_);
  products_.set_material_lanes(material_lanes_);
}

template class PointLanes<float>;
template class PointLanes<double>;

}  // namespace snh::solver
