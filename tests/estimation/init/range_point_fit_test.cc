// SPDX-License-Identifier: MIT
// The batch point fit: recovers a point from noisy ranges over an L-shaped walk from either
// mirror start, keeps a wrong point's residuals large, rejects an outlier and another path's
// ranges that inflate the RMS (the gate is median-based), its covariance matches
// the spread of the estimates over seeded noise draws, and refuses degenerate input.
#include "mirage/estimation/init/range_point_fit.h"

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

// 40 positions 5 cm apart east, then 10 north (the L a walk with one corner makes).
std::vector<Vec2> LWalk() {
  std::vector<Vec2> p;
  for (int i = 0; i < 40; ++i) p.emplace_back(1.0 + 0.05 * i, 1.0);
  for (int i = 1; i <= 10; ++i) p.emplace_back(2.95, 1.0 + 0.05 * i);
  return p;
}

std::vector<double> Ranges(const std::vector<Vec2>& p, const Vec2& q, double sigma_m, core::Rng& rng) {
  std::vector<double> r;
  for (const auto& a : p) r.push_back((q - a).norm() + rng.Normal(0.0, sigma_m));
  return r;
}

TEST(RangePointFit, AfterATurnTheMirrorStartEndsFarWorse) {
  core::Rng rng(1, 0);
  const Vec2 q(2.5, 6.0);
  const auto p = LWalk();
  const auto r = Ranges(p, q, 0.01, rng);
  const auto right = FitPointToRanges(p, r, Vec2(2.4, 5.5));
  ASSERT_TRUE(right.has_value());
  EXPECT_LT((right->position_m - q).norm(), 0.05);
  EXPECT_LT(right->rms_m, 0.015);
  EXPECT_EQ(right->inliers, static_cast<int>(p.size()));
  // From the mirror image in the first leg's line y = 1 the fit stays in the mirror's basin,
  // which the 50 cm north no longer fits: the residual the promotion check compares.
  const auto mirror = FitPointToRanges(p, r, Vec2(2.5, -4.0));
  ASSERT_TRUE(mirror.has_value());
  EXPECT_GT((mirror->position_m - q).norm(), 5.0);
  EXPECT_GT(mirror->rms_m, 5.0 * right->rms_m);
}

TEST(RangePointFit, OnAStraightWalkTheMirrorFitsAsWell) {
  // Without the corner both mirror images explain the ranges: the ambiguity the promotion check
  // waits out.
  core::Rng rng(2, 0);
  const auto walk = LWalk();
  const std::vector<Vec2> p(walk.begin(), walk.begin() + 40);
  const Vec2 q(2.5, 6.0);
  const auto r = Ranges(p, q, 0.01, rng);
  const auto right = FitPointToRanges(p, r, Vec2(2.4, 5.5));
  const auto mirror = FitPointToRanges(p, r, Vec2(2.5, -4.0));
  ASSERT_TRUE(right && mirror);
  EXPECT_LT((mirror->position_m - Vec2(2.5, -4.0)).norm(), 0.2);
  EXPECT_NEAR(mirror->rms_m, right->rms_m, 0.002);
}

TEST(RangePointFit, LeavesOneOutlierOut) {
  core::Rng rng(3, 0);
  const auto p = LWalk();
  const Vec2 q(4.0, 5.0);
  auto r = Ranges(p, q, 0.01, rng);
  r[17] += 0.8;  // a range of another path
  const auto fit = FitPointToRanges(p, r, Vec2(3.8, 4.6));
  ASSERT_TRUE(fit.has_value());
  EXPECT_EQ(fit->inliers, static_cast<int>(p.size()) - 1);
  EXPECT_LT((fit->position_m - q).norm(), 0.05);
  EXPECT_LT(fit->rms_m, 0.015);
}

TEST(RangePointFit, LeavesOutAnotherPathsRangesThatInflateTheRms) {
  // One range in eight is another path's, 15-20 cm shorter (inside a candidate's 15 cm cut-off
  // of its hypothesis's predicted range, which may itself be a few cm off): a 2 cm core with a
  // 6-7 cm RMS. A gate of 3 x RMS (about 19 cm) keeps 3-6 of the 6 (300 seeds of this draw); the
  // median-based one keeps none in 78 % of them and at most 2 in 99 %. The first pass is fitted
  // to all ranges, so a few of them can still end near its gate.
  core::Rng rng(5, 0);
  const auto p = LWalk();
  const Vec2 q(4.0, 5.0);
  auto r = Ranges(p, q, 0.02, rng);
  int other = 0;
  double sum_m2 = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (i % 8 == 3) {
      r[i] -= rng.Uniform(0.15, 0.20);
      ++other;
    }
    const double e = r[i] - (q - p[i]).norm();
    sum_m2 += e * e;
  }
  ASSERT_GT(std::sqrt(sum_m2 / static_cast<double>(r.size())), 0.06) << "the case the RMS gate keeps";
  const auto fit = FitPointToRanges(p, r, Vec2(3.8, 4.6));
  ASSERT_TRUE(fit.has_value());
  EXPECT_LE(fit->inliers, static_cast<int>(p.size()) - other + 2);
  EXPECT_LT(fit->rms_m, 0.04) << "the 2 cm core's, not the 6 cm of all ranges";
  // Within 3.5 std of the fit's own covariance (a 0.2 % tail for a consistent one).
  const Vec2 d = fit->position_m - q;
  EXPECT_LT(std::sqrt(d.dot(fit->covariance_m2.inverse() * d)), 3.5);
}

TEST(RangePointFit, CovarianceMatchesTheSpreadOfTheEstimates) {
  const auto p = LWalk();
  const Vec2 q(2.5, 6.0);
  const double sigma_m = 0.03;  // above the covariance's floor of 2 cm
  core::Rng rng(4, 0);
  std::vector<Vec2> estimates;
  Eigen::Matrix2d predicted = Eigen::Matrix2d::Zero();
  const int trials = 400;
  for (int t = 0; t < trials; ++t) {
    const auto fit = FitPointToRanges(p, Ranges(p, q, sigma_m, rng), Vec2(2.4, 5.5));
    ASSERT_TRUE(fit.has_value());
    estimates.push_back(fit->position_m);
    predicted += fit->covariance_m2 / trials;
  }
  Vec2 mean = Vec2::Zero();
  for (const auto& e : estimates) mean += e / trials;
  Eigen::Matrix2d empirical = Eigen::Matrix2d::Zero();
  for (const auto& e : estimates) empirical += (e - mean) * (e - mean).transpose() / (trials - 1);
  // Traces within 25 % (400 draws give about 7 % standard error on a variance).
  EXPECT_NEAR(empirical.trace() / predicted.trace(), 1.0, 0.25);
}

TEST(RangePointFit, RefusesDegenerateInput) {
  const std::vector<Vec2> two{Vec2(0, 0), Vec2(1, 0)};
  EXPECT_FALSE(FitPointToRanges(two, std::vector<double>{1.0, 1.0}, Vec2(0.5, 1.0)).has_value());
  const std::vector<Vec2> three{Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)};
  EXPECT_FALSE(FitPointToRanges(three, std::vector<double>{1.0, NAN, 1.0}, Vec2(0.5, 1.0)).has_value());
  EXPECT_FALSE(FitPointToRanges(three, std::vector<double>{1.0, 1.0}, Vec2(0.5, 1.0)).has_value());
}

}  // namespace
}  // namespace mirage::estimation
