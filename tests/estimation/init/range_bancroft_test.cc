// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/range_bancroft.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

std::vector<double> Ranges(const std::vector<Vec2>& positions, const Vec2& q) {
  std::vector<double> r;
  for (const auto& p : positions) r.push_back((q - p).norm());
  return r;
}

double Closest(const BancroftPair& pair, const Vec2& q) {
  return std::min((pair.positions_m[0] - q).norm(), (pair.positions_m[1] - q).norm());
}

TEST(RangeBancroft, RecoversAPointFromPositionsAroundACorner) {
  const std::vector<Vec2> positions{Vec2(1.0, 1.0), Vec2(1.0, 1.5), Vec2(1.0, 2.0), Vec2(1.5, 2.0), Vec2(2.0, 2.0)};
  const Vec2 va(-3.0, 4.0);
  const auto pair = RangeBancroft(positions, Ranges(positions, va));
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->solutions, 1);
  EXPECT_LT((pair->positions_m[0] - va).norm(), 1e-6);
}

TEST(RangeBancroft, CollinearPositionsGiveThePointAndItsMirrorImage) {
  // A straight walk along y = 2 (no point at the origin on purpose avoided: see the next test).
  std::vector<Vec2> positions;
  for (int i = 0; i < 10; ++i) positions.push_back(Vec2(0.5 + 0.05 * i, 2.0));
  const Vec2 va(1.0, 6.0);
  const Vec2 mirror(1.0, -2.0);
  const auto pair = RangeBancroft(positions, Ranges(positions, va));
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->solutions, 2);
  EXPECT_LT(Closest(*pair, va), 1e-6);
  EXPECT_LT(Closest(*pair, mirror), 1e-6);
}

TEST(RangeBancroft, WorksForAPathThroughTheOrigin) {
  // The digest's pitfall for the lambda = |q|^2 form: a straight path through the origin.
  std::vector<Vec2> positions;
  for (int i = -5; i <= 5; ++i) positions.push_back(Vec2(0.05 * i, 0.05 * i));
  const Vec2 va(2.0, -1.0);
  const auto pair = RangeBancroft(positions, Ranges(positions, va));
  ASSERT_TRUE(pair);
  EXPECT_LT(Closest(*pair, va), 1e-6);
  EXPECT_LT(Closest(*pair, Vec2(-1.0, 2.0)), 1e-6);  // mirror about y = x
}

TEST(RangeBancroft, CentimetreNoiseOnAnLShapedPathGivesDecimetres) {
  core::Rng rng(7, 0);
  std::vector<Vec2> positions;
  for (int i = 0; i < 10; ++i) positions.push_back(Vec2(1.0, 1.0 + 0.05 * i));
  for (int i = 1; i <= 10; ++i) positions.push_back(Vec2(1.0 + 0.05 * i, 1.45));
  const Vec2 va(-4.0, 3.0);
  auto ranges = Ranges(positions, va);
  for (auto& r : ranges) r += rng.Normal(0.0, 0.01);
  const auto pair = RangeBancroft(positions, ranges);
  ASSERT_TRUE(pair);
  EXPECT_LT(Closest(*pair, va), 0.10);
}

TEST(RangeBancroft, DegenerateInputGivesNothing) {
  const std::vector<Vec2> same{Vec2(1.0, 1.0), Vec2(1.0, 1.0), Vec2(1.0, 1.0)};
  EXPECT_FALSE(RangeBancroft(same, std::vector<double>{1.0, 1.0, 1.0}));
  const std::vector<Vec2> two{Vec2(0.0, 0.0), Vec2(1.0, 0.0)};
  EXPECT_FALSE(RangeBancroft(two, std::vector<double>{1.0, 1.0}));
  const std::vector<Vec2> three{Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(0.0, 1.0)};
  EXPECT_FALSE(RangeBancroft(three, std::vector<double>{1.0, NAN, 1.0}));
  EXPECT_FALSE(RangeBancroft(three, std::vector<double>{1.0, 1.0}));
}

}  // namespace
}  // namespace mirage::estimation
