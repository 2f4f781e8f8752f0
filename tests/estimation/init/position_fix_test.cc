// SPDX-License-Identifier: MIT
// The multilateration fix: exact ranges give the point in 3-D (general anchors), in the plane at
// a known height, and below coplanar ceiling anchors (the mirror above them rejected); noisy
// ranges give a covariance the errors respect; degenerate geometry gives no fix.
#include "mirage/estimation/init/position_fix.h"

#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

std::vector<double> Ranges(const std::vector<Vec3>& anchors, const Vec3& p, double sigma = 0.0, core::Rng* rng = nullptr) {
  std::vector<double> out;
  for (const auto& a : anchors) out.push_back((p - a).norm() + (rng != nullptr ? rng->Normal(0.0, sigma) : 0.0));
  return out;
}

const std::vector<Vec3> kCeiling{Vec3(0, 0, 2.9), Vec3(6, 0, 2.9), Vec3(6, 5, 2.9), Vec3(0, 5, 2.9)};

TEST(FixPosition, FindsAPointBelowCoplanarCeilingAnchorsAndRejectsItsMirror) {
  const Vec3 tag(2.0, 3.5, 0.6);

  const auto fix = FixPosition(kCeiling, Ranges(kCeiling, tag), std::nullopt, 0.1);

  ASSERT_TRUE(fix.has_value());
  EXPECT_LT((fix->position_m - tag).norm(), 1e-6) << fix->position_m.transpose();
  EXPECT_TRUE(fix->mirror_rejected);
  EXPECT_LT(fix->rms_m, 1e-9);
}

TEST(FixPosition, SolvesGeneralAnchorsInThreeDimensions) {
  const std::vector<Vec3> anchors{Vec3(0, 0, 0.3), Vec3(7, 0, 2.5), Vec3(7, 7, 0.2), Vec3(0, 7, 2.4), Vec3(3, 3, 2.8)};
  const Vec3 tag(4.0, 2.0, 1.2);
  const auto fix = FixPosition(anchors, Ranges(anchors, tag), std::nullopt, 0.1);
  ASSERT_TRUE(fix.has_value());
  EXPECT_LT((fix->position_m - tag).norm(), 1e-6);
  EXPECT_FALSE(fix->mirror_rejected);
}

TEST(FixPosition, SolvesThePlaneAtAKnownHeight) {
  const std::vector<Vec3> anchors{Vec3(0, 0, 2.4), Vec3(6, 0, 2.4), Vec3(3, 5, 2.4)};
  const Vec3 tag(1.5, 2.0, 0.9);
  const auto fix = FixPosition(anchors, Ranges(anchors, tag), 0.9, 0.1);
  ASSERT_TRUE(fix.has_value());
  EXPECT_LT((fix->position_m - tag).norm(), 1e-6);
  EXPECT_EQ(fix->covariance_m2(2, 2), 0.0);
}

TEST(FixPosition, NoisyFixErrorsAgreeWithTheReportedCovariance) {
  // Mean NEES over 400 fixes of a 3-D position: chi^2(3) / 400 mean has sd 0.12 around 3.
  core::Rng rng(21);
  double nees = 0.0;
  const int trials = 400;
  for (int k = 0; k < trials; ++k) {
    const Vec3 tag = testing::UniformVec3(rng, Vec3(1, 1, 0.3), Vec3(5, 4, 1.8));
    const auto fix = FixPosition(kCeiling, Ranges(kCeiling, tag, 0.05, &rng), std::nullopt, 0.05);
    ASSERT_TRUE(fix.has_value());
    const Vec3 e = fix->position_m - tag;
    nees += e.dot(fix->covariance_m2.inverse() * e);
  }
  EXPECT_NEAR(nees / trials, 3.0, 0.5);
}

TEST(FixPosition, RefusesTooFewAnchorsCollinearAnchorsAndBadInput) {
  const std::vector<Vec3> line{Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(2, 0, 2), Vec3(3, 0, 2)};
  EXPECT_FALSE(FixPosition(line, Ranges(line, Vec3(1, 1, 0)), std::nullopt, 0.1).has_value());
  const std::vector<Vec3> two{Vec3(0, 0, 2), Vec3(4, 0, 2)};
  EXPECT_FALSE(FixPosition(two, std::vector<double>{2.0, 3.0}, 0.5, 0.1).has_value());
  EXPECT_FALSE(FixPosition(kCeiling, std::vector<double>{1.0, std::nan(""), 2.0, 3.0}, std::nullopt, 0.1).has_value());
  EXPECT_FALSE(FixPosition(kCeiling, std::vector<double>{1.0, 2.0}, std::nullopt, 0.1).has_value());
}

// Five ceiling anchors at 2.8 m to 3.0 m (near one plane) and 10 cm noise: a second solution
// near the mirror above them fits about as well, and in many draws better (46 of these 300 draws
// with the lower squared residuals winning). The floor-side one is taken while its residuals are
// consistent with the noise.
TEST(FixPosition, PrefersTheFloorSideBelowNearCoplanarAnchorsWithinTheNoise) {
  const std::vector<Vec3> ceiling{Vec3(0, 0, 2.8), Vec3(6, 0, 3.0), Vec3(6, 5, 2.85), Vec3(0, 5, 2.95),
                                  Vec3(3, 2.5, 3.0)};
  const Vec3 tag(2.0, 3.0, 1.0);
  core::Rng rng(5);
  int above = 0;
  const int draws = 300;
  for (int k = 0; k < draws; ++k) {
    const auto fix = FixPosition(ceiling, Ranges(ceiling, tag, 0.1, &rng), std::nullopt, 0.1);
    ASSERT_TRUE(fix.has_value());
    above += fix->position_m.z() > 2.9 ? 1 : 0;
  }
  EXPECT_LE(above, draws / 100) << "fixes above the anchors";
}

}  // namespace
}  // namespace mirage::estimation
