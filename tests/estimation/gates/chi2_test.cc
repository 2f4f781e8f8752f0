// SPDX-License-Identifier: MIT
#include "mirage/estimation/gates/chi2.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mirage::estimation {
namespace {

TEST(Chi2Cdf, MatchesTabulatedValues) {
  // Standard tables: the 99.73 % point of 1 dof is 9 (3 sigma); 95 % points 3.841, 5.991, 7.815,
  // 9.488, 11.070 for 1..5 dof.
  EXPECT_NEAR(Chi2Cdf(9.0, 1), 0.9973002039, 1e-9);
  EXPECT_NEAR(Chi2Cdf(3.841458821, 1), 0.95, 1e-9);
  EXPECT_NEAR(Chi2Cdf(5.991464547, 2), 0.95, 1e-9);
  EXPECT_NEAR(Chi2Cdf(7.814727903, 3), 0.95, 1e-9);
  EXPECT_NEAR(Chi2Cdf(9.487729037, 4), 0.95, 1e-9);
  EXPECT_NEAR(Chi2Cdf(11.07049769, 5), 0.95, 1e-9);
  EXPECT_EQ(Chi2Cdf(0.0, 3), 0.0);
  EXPECT_EQ(Chi2Cdf(-1.0, 2), 0.0);
}

TEST(Chi2Quantile, InvertsTheCdf) {
  for (int dof = 1; dof <= 6; ++dof) {
    for (const double p : {0.1, 0.5, 0.95, 0.9973}) {
      EXPECT_NEAR(Chi2Cdf(Chi2Quantile(p, dof), dof), p, 1e-10) << dof << " dof, p " << p;
    }
  }
  EXPECT_EQ(Chi2Quantile(0.0, 3), 0.0);
}

TEST(Chi2ThresholdLike1Dof, CarriesThreeSigmaToThreeDimensions) {
  // The 99.73 % point of 3 dof is 14.16 (tables).
  EXPECT_NEAR(Chi2ThresholdLike1Dof(9.0, 3), 14.156, 1e-3);
  EXPECT_NEAR(Chi2ThresholdLike1Dof(9.0, 1), 9.0, 1e-9);
  EXPECT_NEAR(Chi2ThresholdLike1Dof(9.0, 2), -2.0 * std::log(1.0 - 0.9973002039), 1e-6);
}

}  // namespace
}  // namespace mirage::estimation
