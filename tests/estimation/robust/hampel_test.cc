// SPDX-License-Identifier: MIT
// Hampel's tanh weight (Bordoy Eq. 5.24): the MAD of known samples, the clipping point from the
// residuals and its floor, continuity at a and at b, monotone decrease, and the default's meaning
// for Gaussian residuals.
#include "mirage/estimation/robust/hampel.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

TEST(Median, TakesTheMiddleValueOrTheMeanOfTheTwoMiddleOnes) {
  EXPECT_DOUBLE_EQ(Median(std::vector<double>{5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(Median(std::vector<double>{4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(Median(std::vector<double>{7.0}), 7.0);
  EXPECT_DOUBLE_EQ(Median(std::vector<double>{}), 0.0);
}

TEST(Mad, IsTheMedianAbsoluteDeviationAboutTheMedian) {
  // Median 3; deviations {2, 1, 0, 1, 97}, whose median is 1: the gross value does not count.
  EXPECT_DOUBLE_EQ(Mad(std::vector<double>{1.0, 2.0, 3.0, 4.0, 100.0}), 1.0);
  // Median 2.5; deviations {1.5, 0.5, 0.5, 1.5} -> 1.0.
  EXPECT_DOUBLE_EQ(Mad(std::vector<double>{4.0, 1.0, 3.0, 2.0}), 1.0);
  // Shift invariant, scales with the data.
  EXPECT_DOUBLE_EQ(Mad(std::vector<double>{-10.0, -8.0, -6.0, -4.0, 188.0}), 2.0);  // 2 x first set - 12
  EXPECT_DOUBLE_EQ(Mad(std::vector<double>{}), 0.0);
}

TEST(Mad, EstimatesTheStandardDeviationOfGaussianSamplesWhenScaled) {
  core::Rng rng(11);
  std::vector<double> samples(20001);
  for (double& s : samples) s = rng.Normal(3.0, 2.0);
  EXPECT_NEAR(1.4826 * Mad(samples), 2.0, 0.05);
}

TEST(HampelFromClippingPoint, SolvesTheContinuityEquationForD) {
  for (const double a : {0.05, 0.5, 1.0, 2.0, 7.0}) {
    for (const double ratio : {1.5, 4.0, 10.0}) {
      const HampelParameters p = HampelFromClippingPoint(a, ratio);
      EXPECT_DOUBLE_EQ(p.a, a);
      EXPECT_DOUBLE_EQ(p.b, ratio * a);
      EXPECT_NEAR(p.d * std::tanh(0.5 * p.d * (p.b - p.a)), a, 1e-13 * a) << "a = " << a << ", b/a = " << ratio;
    }
  }
}

TEST(HampelWeight, IsContinuousAtTheClippingPointAndVanishesAtTheRejectionPoint) {
  for (const double a : {0.3, 1.0, 2.0, 5.0}) {
    const HampelParameters p = HampelFromClippingPoint(a, 4.0);
    EXPECT_EQ(HampelWeight(a, p), 1.0);
    EXPECT_NEAR(HampelWeight(a * (1.0 + 1e-9), p), 1.0, 1e-7);
    EXPECT_NEAR(HampelWeight(-a * (1.0 + 1e-9), p), 1.0, 1e-7);
    EXPECT_NEAR(HampelWeight(p.b * (1.0 - 1e-9), p), 0.0, 1e-7);
    EXPECT_EQ(HampelWeight(p.b, p), 0.0);
    EXPECT_EQ(HampelWeight(p.b * (1.0 + 1e-9), p), 0.0);
    EXPECT_EQ(HampelWeight(-50.0 * p.b, p), 0.0);
  }
}

TEST(HampelWeight, DecreasesMonotonicallyAndIsEven) {
  const HampelParameters p = HampelFromClippingPoint(2.0, 4.0);
  double previous = 1.0;
  int strictly_decreasing = 0;
  for (double r = 0.0; r <= 10.0; r += 0.01) {
    const double w = HampelWeight(r, p);
    EXPECT_LE(w, previous + 1e-15) << "r = " << r;
    EXPECT_GE(w, 0.0);
    EXPECT_DOUBLE_EQ(w, HampelWeight(-r, p));
    if (w < previous) ++strictly_decreasing;
    previous = w;
  }
  // Strictly decreasing over the whole middle branch (2, 8]: about 600 steps.
  EXPECT_GT(strictly_decreasing, 590);
}

TEST(HampelWeight, HalvesAtFourSigmaWithThetaOneHalf) {
  // theta = 0.5 on unit-variance residuals: a = 2, b = 8, d ~= 2, w(4) = 2 tanh(4) / 4 ~= 0.5.
  const HampelParameters p = HampelFromClippingPoint(1.0 / 0.5, HampelOptions{}.b_over_a);
  EXPECT_NEAR(HampelWeight(4.0, p), 0.4997, 1e-4);
  EXPECT_NEAR(HampelWeight(6.0, p), 2.0 * std::tanh(2.0) / 6.0, 1e-4);
}

TEST(HampelFromResiduals, SetsTheClippingPointFromTheMad) {
  // MAD of {-1, 0, 1} is 1: a = 1.4826 / theta.
  HampelOptions options;
  options.theta = 0.5;
  options.min_a = 0.1;
  const HampelParameters p = HampelFromResiduals(std::vector<double>{-1.0, 0.0, 1.0}, options);
  EXPECT_DOUBLE_EQ(p.a, 1.4826 / 0.5);
  EXPECT_DOUBLE_EQ(p.b, 4.0 * p.a);
}

TEST(HampelFromResiduals, PutsTheClippingPointNearTwoSigmaForGaussianResiduals) {
  core::Rng rng(5);
  std::vector<double> r(4001);
  for (double& x : r) x = rng.Normal(0.0, 3.0);
  const HampelParameters p = HampelFromResiduals(r, HampelOptions{.theta = 0.5, .b_over_a = 4.0, .min_a = 0.1});
  EXPECT_NEAR(p.a, 6.0, 0.3);
}

TEST(HampelFromResiduals, FloorsTheClippingPointWhenMostResidualsFitExactly) {
  // More than half the residuals are 0, so the MAD is 0.
  const std::vector<double> r{0.0, 0.0, 0.0, 0.0, 3.0, -2.0, 40.0};
  ASSERT_EQ(Mad(r), 0.0);
  const HampelParameters p = HampelFromResiduals(r, HampelOptions{});
  EXPECT_DOUBLE_EQ(p.a, HampelOptions{}.min_a);
  EXPECT_DOUBLE_EQ(HampelWeight(0.0, p), 1.0);
  EXPECT_GT(HampelWeight(3.0, p), 0.0);    // inside (a, b] = (1, 4]
  EXPECT_EQ(HampelWeight(40.0, p), 0.0);  // beyond b
  EXPECT_DOUBLE_EQ(HampelFromResiduals(std::vector<double>{}, HampelOptions{}).a, HampelOptions{}.min_a);
}

TEST(HampelOptions, DefaultsAreValidAndBadValuesAreReported) {
  EXPECT_TRUE(Validate(HampelOptions{}).empty());
  EXPECT_FALSE(Validate(HampelOptions{.theta = 0.0}).empty());
  EXPECT_FALSE(Validate(HampelOptions{.b_over_a = 1.0}).empty());
  EXPECT_FALSE(Validate(HampelOptions{.min_a = 0.0}).empty());
}

}  // namespace
}  // namespace mirage::estimation
