// The host's material model ids (snh::MaterialModel) and the kernels'
// (SNH_MODEL_* of kernels/materials/material.h) are one list: the host
// passes static_cast<int>(model) as SNH_MODEL, MATERIAL_ARGS and the
// SNH_REGIONS table's model entry (device/material_args.h), and the
// kernels branch on their own constants.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <string>

#include "snh/material.h"

namespace snh::test {
namespace kernel_side {
#define SNH_DOUBLE 1
#include "materials/material.h"
}  // namespace kernel_side
namespace {

constexpr int id(MaterialModel model) { return static_cast<int>(model); }

static_assert(id(MaterialModel::stable_neo_hookean) == SNH_MODEL_SNH);
static_assert(id(MaterialModel::fung) == SNH_MODEL_FUNG);
static_assert(id(MaterialModel::arruda_boyce) == SNH_MODEL_ARRUDA_BOYCE);
static_assert(id(MaterialModel::corotational) == SNH_MODEL_COROTATIONAL);
static_assert(id(MaterialModel::fixed_corotational) == SNH_MODEL_FIXED_COROTATIONAL);
static_assert(id(MaterialModel::stvk_kikuuwe) == SNH_MODEL_STVK_KIKUUWE);
static_assert(id(MaterialModel::neohookean) == SNH_MODEL_NEOHOOKEAN);

// Every kernel id names a host model, and the host's names round-trip: a
// model added on one side only shows up here.
TEST(MaterialIds, HostModelsMatchKernelModels) {
  const int kernel_ids[] = {SNH_MODEL_SNH,
                            SNH_MODEL_FUNG,
                            SNH_MODEL_ARRUDA_BOYCE,
                            SNH_MODEL_COROTATIONAL,
                            SNH_MODEL_FIXED_COROTATIONAL,
                            SNH_MODEL_STVK_KIKUUWE,
                            SNH_MODEL_NEOHOOKEAN};
  for (int k : kernel_ids) {
    const MaterialModel model = static_cast<MaterialModel>(k);
    const std::string name = to_string(model);
    EXPECT_NE(name, "?") << "kernel model id " << k << " has no host model";
    EXPECT_EQ(id(parse_material_model(name)), k) << name;
  }
  EXPECT_EQ(std::string(to_string(static_cast<MaterialModel>(SNH_MODEL_NEOHOOKEAN + 1))), "?")
      << "a host model past the kernels' last id";
}

}  // namespace
}  // namespace snh::test
