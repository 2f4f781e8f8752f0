// SPDX-License-Identifier: MIT
// The innovation scale: no factor before kMinInnovations or while the mean NIS is at most 1, the
// mean over the last `window` innovations after, and close to 1 for seeded consistent
// innovations but the excess for a biased source.
#include "mirage/estimation/innovation_scale.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

TEST(InnovationScale, NeedsFiveInnovationsAndNeverShrinksTheVariance) {
  InnovationScale scale(20);
  for (int i = 0; i < 4; ++i) scale.Add(9.0);
  EXPECT_EQ(scale.Factor(), 1.0) << "four innovations are too few";
  scale.Add(9.0);
  EXPECT_DOUBLE_EQ(scale.Factor(), 9.0);
  InnovationScale small(20);
  for (int i = 0; i < 10; ++i) small.Add(0.2);
  EXPECT_EQ(small.Factor(), 1.0) << "a source better than its variance keeps it";
}

TEST(InnovationScale, AveragesOnlyTheLastWindow) {
  InnovationScale scale(5);
  for (int i = 0; i < 5; ++i) scale.Add(100.0);
  for (int i = 0; i < 5; ++i) scale.Add(3.0);
  EXPECT_DOUBLE_EQ(scale.Factor(), 3.0) << "the five old innovations have left the window";
  scale.Add(8.0);
  EXPECT_DOUBLE_EQ(scale.Factor(), (4 * 3.0 + 8.0) / 5.0);
}

TEST(InnovationScale, RejectsANisThatIsNotANonNegativeNumber) {
  // Without the check a NaN would make the window's mean NaN and the factor silently 1.
  InnovationScale scale(20);
  for (int i = 0; i < 10; ++i) scale.Add(9.0);
  EXPECT_THROW(scale.Add(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(scale.Add(std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(scale.Add(-1.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(scale.Factor(), 9.0) << "a rejected NIS is not recorded";
  InnovationScale off(0);
  EXPECT_THROW(off.Add(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument)
      << "checked even with the scaling off";
}

TEST(InnovationScale, WindowZeroIsOff) {
  InnovationScale off(0);
  for (int i = 0; i < 30; ++i) off.Add(50.0);
  EXPECT_EQ(off.Factor(), 1.0);
}

TEST(InnovationScale, SeparatesAConsistentFromABiasedSource) {
  // Innovations nu ~ N(b, 1) with S = 1: E[NIS] = 1 + b^2.
  core::Rng rng(7, 0);
  InnovationScale consistent(20), biased(20);
  double consistent_max = 0.0, biased_min = 1e9;
  for (int i = 0; i < 2000; ++i) {
    const double nu = rng.Normal();
    consistent.Add(nu * nu);
    biased.Add((nu + 3.0) * (nu + 3.0));
    if (i >= 20) {
      consistent_max = std::max(consistent_max, consistent.Factor());
      biased_min = std::min(biased_min, biased.Factor());
    }
  }
  // chi^2_20 / 20 exceeds 3 with probability 7e-6 per window; the biased source's mean NIS is
  // 1 + 3^2 = 10 with a std of 1.4 over 20 innovations.
  EXPECT_LT(consistent_max, 3.0);
  EXPECT_GT(biased_min, 3.0);
}

}  // namespace
}  // namespace mirage::estimation
