// SPDX-License-Identifier: MIT
#include "mirage/eval/position_error_bound.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace mirage::eval {
namespace {

constexpr double kTol = 1e-12;

TEST(PositionErrorBound, OfTwoOrthogonalRangesIsSigmaTimesRootOfSummedInverseSinrs) {
  // Agent (1, 2); VA (6, 2) gives u = (-1, 0), VA (1, -1) gives u = (0, 1). J = diag(s1, s2) / sigma^2,
  // so PEB = sigma sqrt(1/s1 + 1/s2) = 0.1 sqrt(1/2 + 1/8) = 0.1 sqrt(0.625).
  const std::vector<RangeInformation> ranges{{Vec2(6, 2), 2.0}, {Vec2(1, -1), 8.0}};

  const auto peb = PositionErrorBound(Vec2(1, 2), ranges, 0.1);

  ASSERT_TRUE(peb.has_value());
  EXPECT_NEAR(*peb, 0.1 * std::sqrt(0.625), kTol);
}

TEST(PositionErrorBound, DoesNotDependOnTheDistanceToTheVas) {
  // Same directions as above with the VAs 100x farther away.
  const std::vector<RangeInformation> ranges{{Vec2(501, 2), 2.0}, {Vec2(1, -298), 8.0}};

  const auto peb = PositionErrorBound(Vec2(1, 2), ranges, 0.1);

  ASSERT_TRUE(peb.has_value());
  EXPECT_NEAR(*peb, 0.1 * std::sqrt(0.625), kTol);
}

TEST(PositionErrorBound, MatchesAHandComputedThreeRangeCase) {
  // Agent (2, 3), sigma = 1:
  //   VA (-2, 3):  u1 = (1, 0),       SINR 1 -> [[1, 0], [0, 0]]
  //   VA (-1, -1): u2 = (3, 4) / 5,   SINR 2 -> 2 [[0.36, 0.48], [0.48, 0.64]]
  //   VA (2, 1):   u3 = (0, 1),       SINR 3 -> [[0, 0], [0, 3]]
  // J = [[1.72, 0.96], [0.96, 4.28]], det = 7.3616 - 0.9216 = 6.44, trace(J^-1) = 6 / 6.44,
  // PEB = sqrt(6 / 6.44) = 0.965240...
  const std::vector<RangeInformation> ranges{{Vec2(-2, 3), 1.0}, {Vec2(-1, -1), 2.0}, {Vec2(2, 1), 3.0}};

  const auto peb = PositionErrorBound(Vec2(2, 3), ranges, 1.0);

  ASSERT_TRUE(peb.has_value());
  EXPECT_NEAR(*peb, std::sqrt(6.0 / 6.44), kTol);
}

TEST(PositionErrorBound, MatchesASymmetricThreeRangeCase) {
  // Agent (0, 0); VAs (1, 0), (0, 1), (2, 2) with SINRs 1, 1, 2:
  // J sigma^2 = [[1, 0], [0, 0]] + [[0, 0], [0, 1]] + 2 [[1/2, 1/2], [1/2, 1/2]] = [[2, 1], [1, 2]],
  // trace(J^-1) = sigma^2 * 4 / 3, PEB = 0.05 sqrt(4/3).
  const std::vector<RangeInformation> ranges{{Vec2(1, 0), 1.0}, {Vec2(0, 1), 1.0}, {Vec2(2, 2), 2.0}};

  const auto peb = PositionErrorBound(Vec2(0, 0), ranges, 0.05);

  ASSERT_TRUE(peb.has_value());
  EXPECT_NEAR(*peb, 0.05 * std::sqrt(4.0 / 3.0), kTol);
}

TEST(PositionErrorBound, ScalesAsOneOverRootSinr) {
  // Multiplying every SINR by 4 quarters J^-1 and halves the PEB; dividing by 9 triples it.
  const Vec2 agent(2, 3);
  std::vector<RangeInformation> ranges{{Vec2(-2, 3), 1.0}, {Vec2(-1, -1), 2.0}, {Vec2(2, 1), 3.0}};
  const double base = PositionErrorBound(agent, ranges, 0.07).value();
  auto scaled = [&](double factor) {
    std::vector<RangeInformation> r = ranges;
    for (auto& x : r) x.sinr *= factor;
    return PositionErrorBound(agent, r, 0.07).value();
  };

  EXPECT_NEAR(scaled(4.0), base / 2.0, kTol);
  EXPECT_NEAR(scaled(1.0 / 9.0), 3.0 * base, kTol);
}

TEST(PositionErrorBound, ScalesLinearlyWithTheRangeSigma) {
  const std::vector<RangeInformation> ranges{{Vec2(6, 2), 2.0}, {Vec2(1, -1), 8.0}};

  const double a = PositionErrorBound(Vec2(1, 2), ranges, 0.1).value();
  const double b = PositionErrorBound(Vec2(1, 2), ranges, 0.3).value();

  EXPECT_NEAR(b, 3.0 * a, kTol);
}

TEST(PositionErrorBound, IsUndefinedForOneRange) {
  const std::vector<RangeInformation> ranges{{Vec2(3, 4), 10.0}};

  EXPECT_FALSE(PositionErrorBound(Vec2(0, 0), ranges, 0.1).has_value());
}

TEST(PositionErrorBound, IsUndefinedForNoRanges) {
  EXPECT_FALSE(PositionErrorBound(Vec2(0, 0), std::vector<RangeInformation>{}, 0.1).has_value());
}

TEST(PositionErrorBound, IsUndefinedForCollinearRanges) {
  // VAs on both sides along the x axis, and on both sides and one side along (3, 4) / 5: all
  // information lies along one direction.
  const std::vector<RangeInformation> axis{{Vec2(2, 0), 1.0}, {Vec2(-3, 0), 4.0}};
  const std::vector<RangeInformation> diagonal{{Vec2(3, 4), 1.0}, {Vec2(-6, -8), 2.0}, {Vec2(6, 8), 5.0}};

  EXPECT_FALSE(PositionErrorBound(Vec2(0, 0), axis, 0.1).has_value());
  EXPECT_FALSE(PositionErrorBound(Vec2(0, 0), diagonal, 0.1).has_value());
}

TEST(PositionErrorBound, IgnoresRangesWithoutSinr) {
  // The second direction carries SINR 0, so it adds no information.
  const std::vector<RangeInformation> ranges{{Vec2(6, 2), 2.0}, {Vec2(1, -1), 0.0}};

  EXPECT_FALSE(PositionErrorBound(Vec2(1, 2), ranges, 0.1).has_value());
}

TEST(PositionErrorBound, SkipsAVaThatCoincidesWithTheAgent) {
  // The orthogonal pair plus a VA at the agent itself (no direction): same PEB as the pair.
  const std::vector<RangeInformation> ranges{{Vec2(6, 2), 2.0}, {Vec2(1, 2), 100.0}, {Vec2(1, -1), 8.0}};

  const auto peb = PositionErrorBound(Vec2(1, 2), ranges, 0.1);

  ASSERT_TRUE(peb.has_value());
  EXPECT_NEAR(*peb, 0.1 * std::sqrt(0.625), kTol);
}

TEST(PositionErrorBound, StaysDefinedForVeryUnequalButIndependentSinrs) {
  // Orthogonal ranges with SINRs 1e4 and 1e-3: PEB = sqrt(1e-4 + 1e3) (sigma = 1), ~31.6 m.
  const std::vector<RangeInformation> ranges{{Vec2(5, 0), 1e4}, {Vec2(0, 5), 1e-3}};

  const auto peb = PositionErrorBound(Vec2(0, 0), ranges, 1.0);

  ASSERT_TRUE(peb.has_value());
  EXPECT_NEAR(*peb, std::sqrt(1e-4 + 1e3), 1e-9);
}

}  // namespace
}  // namespace mirage::eval
