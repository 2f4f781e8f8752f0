// SPDX-License-Identifier: MIT
// Rigid alignment (Bordoy 2020 Eq. 3.49-3.52): a track rotated and shifted into another frame is
// mapped back exactly (3-D and planar, where only the rotation about the vertical and a horizontal
// shift are estimated), a mirror image yields a rotation rather than a reflection, and too few
// pairs give no alignment.
#include "mirage/eval/rigid_alignment.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::eval {
namespace {

std::vector<Vec3> Track(core::Rng& rng, int n, bool planar) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    // Drawn z first (tests/rng_vectors.h: the order the recorded numbers come from).
    const double z_m = planar ? 1.2 : rng.Uniform(0.5, 2.0);
    const Vec2 xy_m = testing::UniformVec2(rng, Vec2(0.0, 0.0), Vec2(8.0, 6.0));
    out.emplace_back(xy_m.x(), xy_m.y(), z_m);
  }
  return out;
}

TEST(AlignRigid, RecoversARotationAndShiftIn3d) {
  core::Rng rng(3);
  const auto estimate = Track(rng, 40, false);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.6, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  const Vec3 t(2.0, -1.0, 0.3);
  std::vector<Vec3> reference;
  for (const auto& h : estimate) reference.push_back(R * h + t);
  const auto a = AlignRigid(reference, estimate, false);
  ASSERT_TRUE(a.has_value());
  EXPECT_LT((a->rotation - R).norm(), 1e-9);
  EXPECT_NEAR(a->AngleRad(), 0.6, 1e-9);
  for (std::size_t i = 0; i < estimate.size(); ++i) EXPECT_LT((a->Apply(estimate[i]) - reference[i]).norm(), 1e-9);
}

TEST(AlignRigid, PlanarRotatesAboutTheVerticalAndKeepsTheHeights) {
  core::Rng rng(4);
  const auto estimate = Track(rng, 30, true);
  const double angle = 40.0 * std::numbers::pi / 180.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
  std::vector<Vec3> reference;
  for (const auto& h : estimate) {
    Vec3 g = R * h + Vec3(-3.0, 1.5, 0.0);
    g.z() = 1.5;  // the reference's height differs: a planar alignment leaves it alone
    const Vec2 noise_m = 0.01 * testing::NormalVec2(rng);
    reference.push_back(g + Vec3(noise_m.x(), noise_m.y(), 0.0));
  }
  const auto a = AlignRigid(reference, estimate, true);
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(a->AngleRad(), angle, 0.01);
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const Vec3 aligned = a->Apply(estimate[i]);
    EXPECT_LT((aligned - reference[i]).head<2>().norm(), 0.05);
    EXPECT_DOUBLE_EQ(aligned.z(), estimate[i].z());
  }
}

TEST(AlignRigid, AMirrorImageYieldsARotationNotAReflection) {
  core::Rng rng(5);
  const auto estimate = Track(rng, 20, false);
  std::vector<Vec3> reference;
  for (const auto& h : estimate) reference.emplace_back(h.x(), -h.y(), h.z());  // mirrored in y = 0
  const auto a = AlignRigid(reference, estimate, false);
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR(a->rotation.determinant(), 1.0, 1e-9);
  EXPECT_LT((a->rotation * a->rotation.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-9);
  // The nearest rotation: no other proper rotation (e.g. the flip of another axis) fits better.
  const auto residual = [&](const Eigen::Matrix3d& R) {
    double sum = 0.0;
    for (std::size_t i = 0; i < estimate.size(); ++i) sum += (R * (estimate[i] - a->from_m) + a->to_m - reference[i]).squaredNorm();
    return sum;
  };
  const double best = residual(a->rotation);
  for (const Eigen::Matrix3d& other : {Eigen::Matrix3d(Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal()),
                                       Eigen::Matrix3d(Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal()),
                                       Eigen::Matrix3d(Eigen::Vector3d(-1.0, 1.0, -1.0).asDiagonal())}) {
    EXPECT_LE(best, residual(a->rotation * other) + 1e-9);
  }
}

TEST(AlignRigid, TooFewOrUnpairedPointsGiveNone) {
  const std::vector<Vec3> two = {Vec3(0.0, 0.0, 1.0), Vec3(1.0, 0.0, 1.0)};
  const std::vector<Vec3> one = {Vec3(0.0, 0.0, 1.0)};
  EXPECT_FALSE(AlignRigid(two, two, false).has_value());
  EXPECT_TRUE(AlignRigid(two, two, true).has_value());
  EXPECT_FALSE(AlignRigid(one, one, true).has_value());
  EXPECT_FALSE(AlignRigid(two, one, true).has_value());
}

}  // namespace
}  // namespace mirage::eval
