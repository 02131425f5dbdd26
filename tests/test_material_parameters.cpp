// E, nu -> Lame -> the energy's (mu, lambda) (sec. 3.4, Chen and Barbic 2024, Table 1),
// and clear errors outside the admissible range.
#include <gtest/gtest.h>

#include <cmath>

#include "snh/error.h"
#include "snh/material.h"

namespace snh {
namespace {

TEST(MaterialParameters, ReparameterizationWithBarrier) {
  const LameParameters lame = lame_from_youngs_modulus(1.0e5, 0.3);
  const StableNeoHookean m = StableNeoHookean::from_youngs_modulus(1.0e5, 0.3, Barrier::on);
  EXPECT_TRUE(m.barrier);
  EXPECT_NEAR(m.mu, 4.0 / 3.0 * lame.mu, 1e-9);
  EXPECT_NEAR(m.lambda, lame.lambda + 5.0 / 6.0 * lame.mu, 1e-9);
  EXPECT_NEAR(m.alpha(), 1.0 + 0.75 * m.mu / m.lambda, 1e-15);
  EXPECT_NEAR(m.poisson_ratio(), 0.3, 1e-14);
  EXPECT_NEAR(m.youngs_modulus(), 1.0e5, 1e-9);
}

TEST(MaterialParameters, ReparameterizationWithoutBarrier) {
  const LameParameters lame = lame_from_youngs_modulus(2.0, 0.45);
  const StableNeoHookean m = StableNeoHookean::from_youngs_modulus(2.0, 0.45, Barrier::off);
  EXPECT_FALSE(m.barrier);
  EXPECT_NEAR(m.mu, lame.mu, 1e-15);
  EXPECT_NEAR(m.lambda, lame.lambda + lame.mu, 1e-14);
  EXPECT_NEAR(m.alpha(), 1.0 + m.mu / m.lambda, 1e-15);
  EXPECT_NEAR(m.poisson_ratio(), 0.45, 1e-14);
}

TEST(MaterialParameters, AutomaticBarrierFollowsPaperAppendixD) {
  EXPECT_TRUE(StableNeoHookean::from_youngs_modulus(1.0, 0.39).barrier);
  EXPECT_FALSE(StableNeoHookean::from_youngs_modulus(1.0, 0.4).barrier);
  EXPECT_FALSE(StableNeoHookean::from_youngs_modulus(1.0, 0.49).barrier);
  EXPECT_EQ(parse_barrier("auto"), std::nullopt);  // unset: on below nu 0.4
  EXPECT_EQ(parse_barrier("on"), Barrier::on);
  EXPECT_THROW(parse_barrier("maybe"), Error);
}

void expect_error_mentioning(double e, double nu, Barrier b, const std::string& words) {
  try {
    StableNeoHookean::from_youngs_modulus(e, nu, b);
    ADD_FAILURE() << "no error for E = " << e << ", nu = " << nu;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
  }
}

TEST(MaterialParameters, RejectsOutOfRange) {
  expect_error_mentioning(0.0, 0.3, Barrier::on, "Young's modulus");
  expect_error_mentioning(-1.0, 0.3, Barrier::on, "Young's modulus");
  expect_error_mentioning(std::nan(""), 0.3, Barrier::on, "Young's modulus");
  expect_error_mentioning(1.0, 0.5, Barrier::on, "Poisson");
  expect_error_mentioning(1.0, 0.7, Barrier::on, "Poisson");
  expect_error_mentioning(1.0, -1.0, Barrier::on, "Poisson");
  expect_error_mentioning(1.0, -0.9, Barrier::on, "stable range");
  expect_error_mentioning(1.0, 0.3, Barrier::off, "barrier");
  EXPECT_NO_THROW(StableNeoHookean::from_youngs_modulus(1.0, -0.85, Barrier::on));
  EXPECT_THROW(StableNeoHookean::from_lame({-1.0, 1.0}), Error);
  EXPECT_THROW(StableNeoHookean::from_lame({1.0, -1.0}), Error);
}

}  // namespace
}  // namespace snh
