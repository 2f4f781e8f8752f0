// SPDX-License-Identifier: MIT
#include "mirage/estimation/meas/va_range.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

// Central differences of the range with respect to the agent and to the VA position.
struct NumericJacobians {
  Eigen::RowVector2d J_range_p;
  Eigen::RowVector2d J_range_va;
};

double RangeOrNan(const Vec2& p, const Vec2& a) {
  const auto prediction = PredictVaRange(p, a);
  return prediction ? prediction->range_m : std::nan("");
}

NumericJacobians CentralDifferences(const Vec2& p, const Vec2& a, double step_m) {
  NumericJacobians out;
  for (int k = 0; k < 2; ++k) {
    const Vec2 e = step_m * Vec2::Unit(k);
    out.J_range_p(k) = (RangeOrNan(p + e, a) - RangeOrNan(p - e, a)) / (2.0 * step_m);
    out.J_range_va(k) = (RangeOrNan(p, a + e) - RangeOrNan(p, a - e)) / (2.0 * step_m);
  }
  return out;
}

// The analytic Jacobians agree with central differences. The truncation error of a central
// difference is about h^2 |f'''| / 6 with |f'''| ~ 1/r^2, the round-off about eps r / h; with
// h = 1e-4 r they are ~2e-9 and ~2e-12, so the tolerance 1e-6 leaves margin while a wrong sign,
// a swapped component or a missing 1/r still fails by O(1).
void ExpectJacobiansMatch(const Vec2& p, const Vec2& a) {
  const auto prediction = PredictVaRange(p, a);
  ASSERT_TRUE(prediction.has_value()) << "p = " << p.transpose() << ", a = " << a.transpose();
  const double r = (p - a).norm();
  const NumericJacobians numeric = CentralDifferences(p, a, 1e-4 * r);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(prediction->J_range_p(k), numeric.J_range_p(k), 1e-6) << "p = " << p.transpose() << ", a = "
                                                                      << a.transpose();
    EXPECT_NEAR(prediction->J_range_va(k), numeric.J_range_va(k), 1e-6) << "p = " << p.transpose() << ", a = "
                                                                        << a.transpose();
  }
}

TEST(PredictVaRange, GivesTheDistanceAndTheUnitDirectionOnA345Triangle) {
  // p - a = (3, 4): range 5, J_p = (3, 4) / 5, J_va = -J_p.
  const auto prediction = PredictVaRange(Vec2(4.0, 5.0), Vec2(1.0, 1.0));

  ASSERT_TRUE(prediction.has_value());
  EXPECT_DOUBLE_EQ(prediction->range_m, 5.0);
  EXPECT_DOUBLE_EQ(prediction->J_range_p(0), 0.6);
  EXPECT_DOUBLE_EQ(prediction->J_range_p(1), 0.8);
  EXPECT_DOUBLE_EQ(prediction->J_range_va(0), -0.6);
  EXPECT_DOUBLE_EQ(prediction->J_range_va(1), -0.8);
}

TEST(PredictVaRange, HandlesAVaMirroredBehindAWall) {
  // Anchor (1, 1.5) mirrored at the wall x = 0 gives the VA (-1, 1.5); agent (2, -2.5):
  // p - a = (3, -4), range 5, J_p = (0.6, -0.8).
  const auto prediction = PredictVaRange(Vec2(2.0, -2.5), Vec2(-1.0, 1.5));

  ASSERT_TRUE(prediction.has_value());
  EXPECT_DOUBLE_EQ(prediction->range_m, 5.0);
  EXPECT_DOUBLE_EQ(prediction->J_range_p(0), 0.6);
  EXPECT_DOUBLE_EQ(prediction->J_range_p(1), -0.8);
}

TEST(PredictVaRange, JacobiansMatchCentralDifferencesAtAGenericPoint) {
  ExpectJacobiansMatch(Vec2(2.3, -0.7), Vec2(-3.1, 4.4));
}

TEST(PredictVaRange, JacobiansMatchCentralDifferencesAtSeededRandomPoints) {
  core::Rng rng(20140220);
  for (int i = 0; i < 200; ++i) {
    const Vec2 p = testing::UniformVec2(rng, Vec2(-10.0, -10.0), Vec2(10.0, 10.0));
    const Vec2 a = testing::UniformVec2(rng, Vec2(-30.0, -30.0), Vec2(30.0, 30.0));
    ExpectJacobiansMatch(p, a);
  }
}

TEST(PredictVaRange, JacobiansMatchCentralDifferencesOneCentimetreFromTheVa) {
  // Near-degenerate: 1 cm from the VA, in 16 directions including the axes.
  const Vec2 a(1.25, -0.5);
  for (int i = 0; i < 16; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / 16.0;
    const Vec2 p = a + 0.01 * Vec2(std::cos(angle), std::sin(angle));
    ExpectJacobiansMatch(p, a);
  }
}

TEST(PredictVaRange, JacobiansMatchCentralDifferencesJustAboveTheDegenerateLimit) {
  // 2 mm apart, twice kMinVaRange_m; the differencing step (1e-4 r = 0.2 um) stays outside the limit.
  ExpectJacobiansMatch(Vec2(0.0012, 0.0016), Vec2(0.0, 0.0));
}

TEST(PredictVaRange, JacobiansAreUnitVectorsAndOpposite) {
  core::Rng rng(7);
  for (int i = 0; i < 50; ++i) {
    const Vec2 p = testing::UniformVec2(rng, Vec2(-5.0, -5.0), Vec2(5.0, 5.0));
    const Vec2 a = testing::UniformVec2(rng, Vec2(-5.0, -5.0), Vec2(5.0, 5.0));
    const auto prediction = PredictVaRange(p, a);
    ASSERT_TRUE(prediction.has_value());

    EXPECT_NEAR(prediction->J_range_p.norm(), 1.0, 1e-14);
    EXPECT_EQ(prediction->J_range_va, -prediction->J_range_p);
    EXPECT_NEAR(prediction->range_m, std::hypot(p.x() - a.x(), p.y() - a.y()), 1e-12);
  }
}

TEST(PredictVaRange, ReturnsNothingBelowTheMinimumRange) {
  EXPECT_FALSE(PredictVaRange(Vec2(3.0, 4.0), Vec2(3.0, 4.0)).has_value());
  EXPECT_FALSE(PredictVaRange(Vec2(0.0, 0.0), Vec2(0.00059, 0.00079)).has_value());  // 0.986 mm
  EXPECT_FALSE(PredictVaRange(Vec2(0.5, 0.5), Vec2(0.5 + 0.9 * kMinVaRange_m, 0.5)).has_value());
}

TEST(PredictVaRange, ReturnsAPredictionJustAboveTheMinimumRange) {
  const auto prediction = PredictVaRange(Vec2(0.5, 0.5), Vec2(0.5, 0.5 - 1.1 * kMinVaRange_m));

  ASSERT_TRUE(prediction.has_value());
  EXPECT_NEAR(prediction->range_m, 1.1e-3, 1e-15);
  EXPECT_NEAR(prediction->J_range_p(0), 0.0, 1e-12);
  EXPECT_NEAR(prediction->J_range_p(1), 1.0, 1e-12);
}

}  // namespace
}  // namespace mirage::estimation
