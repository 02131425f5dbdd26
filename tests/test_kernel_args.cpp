// Kernel arguments bound as one list per launch (device/kernel_args.h): a
// list that disagrees with the kernel's own parameter count, one argument
// short or one too many, throws naming the kernel; a complete one binds.
#include <gtest/gtest.h>

#include <string>

#include "device/kernel_args.h"
#include "device/material_args.h"
#include "snh/error.h"
#include "support/device_test_support.h"

namespace snh::test {
namespace {

// The error's message, or "" when `bind` does not throw snh::Error.
template <typename F>
std::string error_of(F bind) {
  try {
    bind();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(KernelArgs, CompleteListBinds) {
  device::OpenClContext& cl = device_for(Precision::double_);
  device::Kernel k = cl.kernel("reduce.cl", "", "snh_partial_minima");
  device::Buffer values = cl.buffer(CL_MEM_READ_WRITE, 64 * sizeof(double));
  device::Buffer partial = cl.buffer(CL_MEM_READ_WRITE, 64 * sizeof(double));
  EXPECT_EQ(device::kernel_arg_count(k.get()), 3u);
  EXPECT_EQ(device::kernel_name(k.get()), "snh_partial_minima");
  device::KernelArgs args(k.get());
  args.add(values.get()).add(64).add(partial.get());
  EXPECT_EQ(args.bind(), k.get());
}

TEST(KernelArgs, MissingArgumentThrowsNamingTheKernel) {
  device::OpenClContext& cl = device_for(Precision::double_);
  device::Kernel k = cl.kernel("reduce.cl", "", "snh_partial_minima");
  device::Buffer values = cl.buffer(CL_MEM_READ_WRITE, 64 * sizeof(double));
  const std::string message = error_of([&] { device::KernelArgs(k.get()).add(values.get()).add(64).bind(); });
  EXPECT_NE(message.find("snh_partial_minima"), std::string::npos) << message;
  EXPECT_NE(message.find("takes 3 arguments, 2 bound"), std::string::npos) << message;
}

TEST(KernelArgs, ExtraArgumentThrowsNamingTheKernel) {
  device::OpenClContext& cl = device_for(Precision::double_);
  device::Kernel k = cl.kernel("reduce.cl", "", "snh_partial_minima");
  device::Buffer values = cl.buffer(CL_MEM_READ_WRITE, 64 * sizeof(double));
  const std::string message = error_of(
      [&] { device::KernelArgs(k.get()).add(values.get()).add(64).add(values.get()).add(values.get()).bind(); });
  EXPECT_NE(message.find("snh_partial_minima"), std::string::npos) << message;
  EXPECT_NE(message.find("takes 3 arguments, 4 bound"), std::string::npos) << message;
}

// The parameter lists that build switches change: fem.cl's gather gains u
// and the mode, then the inertia's two buffers, with SNH_INERTIA; the
// elastic list bound to the inertia build throws.
TEST(KernelArgs, ConditionalParameterListsAreChecked) {
  device::OpenClContext& cl = device_for(Precision::double_);
  const Material material = StableNeoHookean::from_youngs_modulus(1.0, 0.45, Barrier::off);
  const std::string elastic = "-DSNH_HEX8=1 " + device::material_defines(material) + " -DSNH_UNIFORM_REST=1";
  device::Kernel plain = cl.kernel("fem.cl", elastic, "snh_gather_vectors");
  device::Kernel inertia = cl.kernel("fem.cl", elastic + " -DSNH_INERTIA=1", "snh_gather_vectors");
  const cl_uint count = device::kernel_arg_count(plain.get());
  EXPECT_EQ(device::kernel_arg_count(inertia.get()), count + 4);
  device::Buffer b = cl.buffer(CL_MEM_READ_WRITE, 64 * sizeof(double));
  const auto elastic_list = [&](cl_kernel k) {
    device::KernelArgs args(k);
    args.add(b.get()).add(b.get()).add(b.get()).add(b.get()).add(b.get()).add(0).add(1.0).add(8).add(b.get());
    return args;
  };
  EXPECT_EQ(elastic_list(plain.get()).bind(), plain.get());
  const std::string message = error_of([&] { elastic_list(inertia.get()).bind(); });
  EXPECT_NE(message.find("snh_gather_vectors"), std::string::npos) << message;
  device::KernelArgs full = elastic_list(inertia.get());
  full.add(b.get()).add(0).add(b.get()).add(b.get());
  EXPECT_EQ(full.bind(), inertia.get());
}

}  // namespace
}  // namespace snh::test
