// The material's part of a kernel build and launch, in the order of
// kernels/materials/kernel_args.h (MATERIAL_ARGS): its build switches and its
// kernel arguments. Shared by the engine's and the probe's kernels.
#pragma once

#include <CL/cl.h>

#include <string>
#include <vector>

#include "device/kernel_args.h"
#include "device/kernel_config.h"
#include "device/opencl_context.h"
#include "snh/material.h"
#include "snh/regions.h"

namespace snh::device {

// How much of the material a kernel build fixes:
//   specialized   model, barrier, alpha/mixing path and lambda model at build time
//                 (the engine's default: only what the scene uses is compiled);
//   runtime       one kernel for every material, all of it read at run time;
//   all_terms     specialized to the model, but always through the alpha/mixing
//                 parts (as a kernel that carries every term would compute).
// The last two are the baselines of `snh-gpu-bench specialization`.
enum class MaterialKernel { specialized, runtime, all_terms };

// The material's fields of a kernel build (model, barrier, alpha/mixing
// path, lambda model; or the run-time material), and their switches.
KernelConfig material_config(const Material& material, MaterialKernel build = MaterialKernel::specialized);
std::string material_defines(const Material& material, MaterialKernel build = MaterialKernel::specialized);

// The switches for a map. A uniform map: those of its one material, nothing
// more. Otherwise -DSNH_REGIONS=1 (materials per element from a table) with,
// when every material shares model, barrier, alpha/mixing path and lambda model,
// the specialized switches of the first one; else the run-time material
// (-DSNH_GENERAL_KERNEL=1).
KernelConfig material_config(const MaterialMap& map, MaterialKernel build = MaterialKernel::specialized);
std::string material_defines(const MaterialMap& map, MaterialKernel build = MaterialKernel::specialized);

// Whether two materials build the same specialized kernels (model, barrier,
// alpha/mixing path, lambda model), so that only their parameters differ.
bool same_specialization(const Material& a, const Material& b);

// The table of an SNH_REGIONS build: SNH_MATERIAL_RECORD reals per material
// of the map (kernels/materials/material_record.h).
template <typename Real>
std::vector<Real> material_table(const MaterialMap& map);

// Adds MATERIAL_ARGS of a uniform build to a kernel's argument list.
template <typename Real>
KernelArgs& add_material_args(KernelArgs& args, const Material& material);
// The same from index `first`; returns the index after them.
template <typename Real>
cl_uint set_material_args(cl_kernel kernel, cl_uint first, const Material& material);

// The material arguments of a map's kernels, ready to set: the scalars of a
// uniform map's material, or the table and per-element index buffers of an
// SNH_REGIONS build, uploaded once.
template <typename Real>
class MaterialArgs {
 public:
  MaterialArgs(OpenClContext& cl, const MaterialMap& map, MaterialKernel build);

  const KernelConfig& config() const { return config_; }
  std::string defines() const { return config_.defines(); }
  bool per_element() const { return static_cast<bool>(table_); }
  // Adds MATERIAL_ARGS to a kernel's argument list.
  KernelArgs& add_to(KernelArgs& args) const;
  // Device memory of the table and per-element indices (0 for a uniform map).
  size_t memory_bytes() const {
    return OpenClContext::bytes(table_.get()) + OpenClContext::bytes(element_material_.get());
  }

 private:
  KernelConfig config_;
  Material uniform_;
  Buffer table_, element_material_;
};

}  // namespace snh::device
