// SPDX-License-Identifier: MIT
// The robust position fix from pairwise differences tdoa_m = |p - a_j| - |p - a_i|: exact
// recovery without noise; with Gaussian noise the error agrees with the returned covariance (each
// fix within 4 sigma of it, and the mean squared Mahalanobis distance near its 3 degrees of
// freedom); a quarter of the rows replaced by gross outliers is left out and not counted as
// inliers; too few rows, too few anchors, non-finite input, a non-positive sigma and anchors on one
// line (the tag's angle round the line is undetermined) give no fix.
#include "mirage/estimation/init/tdoa_position_fix.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

// Eight anchors in a 7 m x 7 m x 3 m room, alternately low (0.2 m) and high (2.5 m), as a Loco
// Positioning system is set up (examples/uwb_tdoa_3d.yaml).
const std::vector<Vec3> kRoom{Vec3(0.3, 0.3, 0.2), Vec3(3.5, 0.2, 2.5), Vec3(6.7, 0.3, 0.2), Vec3(6.8, 3.5, 2.5),
                              Vec3(6.7, 6.7, 0.2), Vec3(3.5, 6.8, 2.5), Vec3(0.3, 6.7, 0.2), Vec3(0.2, 3.5, 2.5)};
const Vec3 kTag(2.3, 4.1, 1.1);

// The true difference of anchors i and j at p (the convention of tdoa.h).
double TrueTdoa(const Vec3& p_m, const Vec3& a_i_m, const Vec3& a_j_m) { return (p_m - a_j_m).norm() - (p_m - a_i_m).norm(); }

// `count` rows of random pairs (i uniform, j uniform among the others) at p, with Gaussian noise
// of sigma_m.
std::vector<TdoaRow> RandomRows(const std::vector<Vec3>& anchors_m, const Vec3& p_m, int count, double sigma_m,
                                core::Rng& rng) {
  std::vector<TdoaRow> rows;
  const auto n = static_cast<std::uint64_t>(anchors_m.size());
  for (int k = 0; k < count; ++k) {
    const auto i = static_cast<int>(rng.UniformInt(n));
    auto j = static_cast<int>(rng.UniformInt(n - 1));
    if (j >= i) ++j;
    const Vec3& a_i = anchors_m[static_cast<std::size_t>(i)];
    const Vec3& a_j = anchors_m[static_cast<std::size_t>(j)];
    rows.push_back({a_i, a_j, i, j, TrueTdoa(p_m, a_i, a_j) + sigma_m * rng.Normal()});
  }
  return rows;
}

double SquaredMahalanobis(const TdoaPositionFix& fix, const Vec3& truth_m) {
  const Vec3 e = fix.fix.position_m - truth_m;
  return e.dot(fix.fix.covariance_m2.ldlt().solve(e));
}

TEST(FixPositionFromTdoas, RecoversTheTagExactlyWithoutNoise) {
  core::Rng rng(11);
  // Several tags in the room, low and high, near a wall and in the middle.
  for (const Vec3& tag : {kTag, Vec3(3.5, 3.5, 1.5), Vec3(6.0, 1.0, 0.4), Vec3(1.0, 6.2, 2.2)}) {
    SCOPED_TRACE(tag.transpose());
    const auto rows = RandomRows(kRoom, tag, 20, 0.0, rng);

    const auto fix = FixPositionFromTdoas(rows, 0.15);

    ASSERT_TRUE(fix.has_value());
    EXPECT_LT((fix->fix.position_m - tag).norm(), 1e-6) << fix->fix.position_m.transpose();
    EXPECT_EQ(fix->inliers, 20);
    EXPECT_GE(fix->anchors, 4);
    EXPECT_LT(fix->fix.rms_m, 1e-6);
  }
}

TEST(FixPositionFromTdoas, TheErrorLiesWithinAFewSigmaOfTheCovariance) {
  constexpr double kSigma_m = 0.15;
  for (const std::uint64_t seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    SCOPED_TRACE(seed);
    core::Rng rng(seed);
    const auto rows = RandomRows(kRoom, kTag, 40, kSigma_m, rng);

    const auto fix = FixPositionFromTdoas(rows, kSigma_m);

    ASSERT_TRUE(fix.has_value());
    EXPECT_LT(SquaredMahalanobis(*fix, kTag), 16.0) << fix->fix.position_m.transpose();
    EXPECT_GE(fix->inliers, 37);
    // The covariance is sigma^2 (J^T J)^-1: symmetric, positive, and of the noise's scale (40
    // rows of 0.15 m: a few centimetres per axis, not metres, not millimetres).
    EXPECT_LT((fix->fix.covariance_m2 - fix->fix.covariance_m2.transpose()).norm(), 1e-12);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(fix->fix.covariance_m2);
    EXPECT_GT(eigen.eigenvalues()(0), 0.0);
    EXPECT_GT(std::sqrt(eigen.eigenvalues()(2)), 0.01);
    EXPECT_LT(std::sqrt(eigen.eigenvalues()(2)), 0.5);
    EXPECT_NEAR(fix->fix.rms_m, kSigma_m, 0.5 * kSigma_m);
  }
}

TEST(FixPositionFromTdoas, TheMeanSquaredMahalanobisDistanceIsNearItsThreeDegreesOfFreedom) {
  constexpr double kSigma_m = 0.15;
  constexpr int kSeeds = 200;
  core::Rng rng(2024);
  double sum = 0.0;
  int fixes = 0;
  for (int s = 0; s < kSeeds; ++s) {
    const auto rows = RandomRows(kRoom, kTag, 40, kSigma_m, rng);
    const auto fix = FixPositionFromTdoas(rows, kSigma_m);
    if (!fix) continue;
    ++fixes;
    sum += SquaredMahalanobis(*fix, kTag);
  }
  ASSERT_EQ(fixes, kSeeds);
  const double mean = sum / fixes;
  EXPECT_GE(mean, 2.0);
  EXPECT_LE(mean, 4.5);
}

TEST(FixPositionFromTdoas, LeavesOutAQuarterOfTheRowsReplacedByGrossOutliers) {
  constexpr double kSigma_m = 0.15;
  for (const std::uint64_t seed : {21u, 22u, 23u, 24u, 25u}) {
    SCOPED_TRACE(seed);
    core::Rng rng(seed);
    auto rows = RandomRows(kRoom, kTag, 40, kSigma_m, rng);
    for (std::size_t k = 0; k < rows.size(); k += 4) rows[k].tdoa_m = rng.Uniform(-10.0, 10.0);  // 10 of 40
    // The rows a fix at the truth explains (the good ones and any outlier that happens to land
    // within 3 sigma of the true difference).
    int explained = 0, good = 0;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const double residual_m = rows[k].tdoa_m - TrueTdoa(kTag, rows[k].anchor_i_m, rows[k].anchor_j_m);
      if (std::abs(residual_m) <= 3.0 * kSigma_m) ++explained;
      if (k % 4 != 0) ++good;
    }
    ASSERT_EQ(good, 30);

    const auto fix = FixPositionFromTdoas(rows, kSigma_m);

    ASSERT_TRUE(fix.has_value());
    EXPECT_LT((fix->fix.position_m - kTag).norm(), 0.3) << fix->fix.position_m.transpose();
    EXPECT_NEAR(fix->inliers, explained, 2);
    EXPECT_GE(fix->inliers, 28);
    EXPECT_LE(fix->inliers, 33);  // not the outliers: at most a few land inside 3 sigma by chance
    EXPECT_NEAR(fix->fix.rms_m, kSigma_m, 0.5 * kSigma_m);
  }
}

TEST(FixPositionFromTdoas, GivesNoFixForFewerThanFiveRows) {
  core::Rng rng(3);
  const auto rows = RandomRows(kRoom, kTag, 5, 0.0, rng);
  ASSERT_TRUE(FixPositionFromTdoas(rows, 0.15).has_value()) << "five noise-free rows no longer fix: the case tests nothing";

  const std::vector<TdoaRow> four(rows.begin(), rows.begin() + 4);
  EXPECT_FALSE(FixPositionFromTdoas(four, 0.15).has_value());
  EXPECT_FALSE(FixPositionFromTdoas(std::vector<TdoaRow>(), 0.15).has_value());
}

TEST(FixPositionFromTdoas, GivesNoFixForRowsSpanningOnlyThreeAnchors) {
  core::Rng rng(4);
  const std::vector<Vec3> three(kRoom.begin(), kRoom.begin() + 3);
  const auto rows = RandomRows(three, kTag, 30, 0.0, rng);
  EXPECT_FALSE(FixPositionFromTdoas(rows, 0.15).has_value());
}

TEST(FixPositionFromTdoas, GivesNoFixForNonFiniteInputOrANonPositiveSigma) {
  core::Rng rng(5);
  const auto rows = RandomRows(kRoom, kTag, 20, 0.0, rng);
  ASSERT_TRUE(FixPositionFromTdoas(rows, 0.15).has_value());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  auto bad_tdoa = rows;
  bad_tdoa[7].tdoa_m = nan;
  auto bad_anchor_i = rows;
  bad_anchor_i[3].anchor_i_m.y() = inf;
  auto bad_anchor_j = rows;
  bad_anchor_j[12].anchor_j_m.z() = nan;

  EXPECT_FALSE(FixPositionFromTdoas(bad_tdoa, 0.15).has_value());
  EXPECT_FALSE(FixPositionFromTdoas(bad_anchor_i, 0.15).has_value());
  EXPECT_FALSE(FixPositionFromTdoas(bad_anchor_j, 0.15).has_value());
  EXPECT_FALSE(FixPositionFromTdoas(rows, 0.0).has_value());
  EXPECT_FALSE(FixPositionFromTdoas(rows, -0.15).has_value());
  EXPECT_FALSE(FixPositionFromTdoas(rows, nan).has_value());
}

// Anchors on one line: every gradient u_j - u_i lies in the plane through the line and the tag,
// so the tag's angle round the line is undetermined (any rotation of it about the line gives the
// same differences).
TEST(FixPositionFromTdoas, GivesNoFixForCollinearAnchors) {
  std::vector<Vec3> line;
  for (int k = 0; k < 8; ++k) line.push_back(Vec3(0.5 + 0.9 * k, 0.3, 2.5));
  core::Rng rng(6);
  const auto rows = RandomRows(line, kTag, 30, 0.0, rng);
  EXPECT_FALSE(FixPositionFromTdoas(rows, 0.15).has_value());
}

// Anchors all at one height (on the ceiling) with the tag below: determined up to the mirror
// image in the anchors' plane, so the fix is the tag or its mirror image.
// All anchors on one ceiling: in their plane every gradient u_j - u_i lacks the normal component,
// so starts in the plane (the centroid, the anchors pulled towards it) never leave it; the starts
// off the plane find the tag and its mirror, and the mirror rule keeps the one below.
TEST(FixPositionFromTdoas, FixesTheTagBelowCoplanarCeilingAnchorsNotItsMirror) {
  std::vector<Vec3> ceiling;
  for (const auto& a : kRoom) ceiling.push_back(Vec3(a.x(), a.y(), 2.5));
  core::Rng rng(7);
  const auto rows = RandomRows(ceiling, kTag, 30, 0.0, rng);
  const Vec3 mirror(kTag.x(), kTag.y(), 2.0 * 2.5 - kTag.z());

  const auto fix = FixPositionFromTdoas(rows, 0.15);

  ASSERT_TRUE(fix.has_value());
  // Both are exact; the one below the anchors (a ceiling-mounted system's side) is kept.
  EXPECT_LT((fix->fix.position_m - kTag).norm(), 1e-6) << fix->fix.position_m.transpose() << " (mirror "
                                                      << mirror.transpose() << ")";
}

}  // namespace
}  // namespace mirage::estimation

