// SPDX-License-Identifier: MIT
#include "mirage/eval/ospa.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::eval {
namespace {

constexpr double kTol = 1e-12;

TEST(Ospa, BothEmptyIsZeroAndOneEmptyIsTheCutoff) {
  const std::vector<Vec2> none;
  const std::vector<Vec2> one{Vec2(1.0, 2.0)};
  EXPECT_NEAR(Ospa(none, none, 0.5).distance_m, 0.0, kTol);
  EXPECT_NEAR(Ospa(one, none, 0.5).distance_m, 0.5, kTol);
  EXPECT_NEAR(Ospa(none, one, 0.5).distance_m, 0.5, kTol);
}

TEST(Ospa, OnePairIsItsDistanceAndAssignsIt) {
  const std::vector<Vec2> x{Vec2(0.0, 0.0)};
  const std::vector<Vec2> y{Vec2(0.3, 0.4)};  // 0.5 m apart
  const auto r = Ospa(x, y, 1.0);
  EXPECT_NEAR(r.distance_m, 0.5, kTol);
  EXPECT_NEAR(r.localization_m, 0.5, kTol);
  EXPECT_NEAR(r.cardinality_m, 0.0, kTol);
  ASSERT_EQ(r.assignment.size(), 1u);
  EXPECT_EQ(r.assignment[0], 0);
}

TEST(Ospa, DistancesSaturateAtTheCutoffAndLeaveThePairUnmatched) {
  const std::vector<Vec2> x{Vec2(0.0, 0.0)};
  const std::vector<Vec2> y{Vec2(3.0, 4.0)};
  const auto r = Ospa(x, y, 0.5);
  EXPECT_NEAR(r.distance_m, 0.5, kTol);
  EXPECT_EQ(r.assignment[0], -1);
}

TEST(Ospa, CardinalityErrorCostsTheCutoffPerMissingPoint) {
  // {0} vs {0.1, 10}: the best pair costs 0.1, the extra point c = 1; n = 2, p = 1 -> 0.55.
  const std::vector<Vec2> x{Vec2(0.0, 0.0)};
  const std::vector<Vec2> y{Vec2(0.1, 0.0), Vec2(10.0, 0.0)};
  const auto r = Ospa(x, y, 1.0);
  EXPECT_NEAR(r.distance_m, 0.55, kTol);
  EXPECT_NEAR(r.localization_m, 0.05, kTol);
  EXPECT_NEAR(r.cardinality_m, 0.5, kTol);
  EXPECT_EQ(r.assignment[0], 0);
}

TEST(Ospa, IsInvariantToPermutationAndFindsTheOptimalAssignment) {
  // Greedy would pair x0 with y0 (0.1) and leave x1-y1 at 0.9; the optimum is 0.2 + 0.2.
  const std::vector<Vec2> x{Vec2(0.0, 0.0), Vec2(1.0, 0.0)};
  const std::vector<Vec2> y{Vec2(0.1, 0.0), Vec2(-0.2, 0.0)};
  const std::vector<Vec2> x_swapped{x[1], x[0]};
  const auto r = Ospa(x, y, 5.0);
  EXPECT_NEAR(r.distance_m, Ospa(x_swapped, y, 5.0).distance_m, kTol);
  // Pairs: x0-y1 (0.2) and x1-y0 (0.9): 1.1 / 2 = 0.55; the other pairing x0-y0 (0.1), x1-y1 (1.2) = 0.65.
  EXPECT_NEAR(r.distance_m, 0.55, kTol);
  EXPECT_EQ(r.assignment[0], 1);
  EXPECT_EQ(r.assignment[1], 0);
}

TEST(Ospa, OrderTwoIsTheRootMeanSquare) {
  const std::vector<Vec2> x{Vec2(0.0, 0.0), Vec2(5.0, 0.0)};
  const std::vector<Vec2> y{Vec2(0.3, 0.0), Vec2(5.0, 0.4)};
  EXPECT_NEAR(Ospa(x, y, 1.0, 2.0).distance_m, std::sqrt((0.09 + 0.16) / 2.0), kTol);
}

}  // namespace
}  // namespace mirage::eval
