// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/closed_form_toa_3d.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

std::vector<double> Values(const std::vector<Vec3>& receivers, const Vec3& sender, double offset) {
  std::vector<double> out;
  for (const Vec3& m : receivers) out.push_back((sender - m).norm() + offset);
  return out;
}

std::vector<Vec3> RandomReceivers(core::Rng& rng, int n) {
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) out.push_back(testing::UniformVec3(rng, Vec3(0.0, 0.0, 0.3), Vec3(10.0, 8.0, 3.0)));
  return out;
}

// The root nearest the truth: its index and position error.
std::pair<int, double> Nearest(const ToaRoots3d& roots, const Vec3& truth) {
  int best = -1;
  double error = std::numeric_limits<double>::infinity();
  for (int k = 0; k < roots.count; ++k) {
    const double e = (roots.fixes[static_cast<std::size_t>(k)].position_m - truth).norm();
    if (e < error) {
      error = e;
      best = k;
    }
  }
  return {best, error};
}

TEST(ClosedFormToa3d, FourReceiversRecoverSenderAndOffsetAmongTheRoots) {
  int two_root_cases = 0;
  for (std::uint64_t seed = 1; seed <= 100; ++seed) {
    core::Rng rng(seed);
    const auto receivers = RandomReceivers(rng, 4);
    const Vec3 sender = testing::UniformVec3(rng, Vec3(-3.0, -3.0, 0.0), Vec3(13.0, 11.0, 2.5));
    const double offset = rng.Uniform(-30.0, 30.0);
    const auto rho = Values(receivers, sender, offset);

    const ToaRoots3d roots = SolveToa3dClosedForm(receivers, rho);

    ASSERT_EQ(roots.status, SolverStatus::kOk) << "seed " << seed;
    const auto [k, error] = Nearest(roots, sender);
    ASSERT_GE(k, 0);
    EXPECT_LT(error, 1e-6) << "seed " << seed;
    EXPECT_NEAR(roots.fixes[static_cast<std::size_t>(k)].offset_m, offset, 1e-6);
    EXPECT_TRUE(roots.fixes[static_cast<std::size_t>(k)].offset_estimated);
    // Both roots of 4 receivers are exact fits (the 4-station two-solution ambiguity).
    for (int j = 0; j < roots.count; ++j) EXPECT_LT(roots.fixes[static_cast<std::size_t>(j)].rms_m, 1e-6);
    if (roots.count == 2) ++two_root_cases;
  }
  EXPECT_GT(two_root_cases, 0);
}

TEST(ClosedFormToa3d, FiveOrMoreReceiversGiveTheUniqueExactRoot) {
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    core::Rng rng(seed, 1);
    const auto receivers = RandomReceivers(rng, 5 + static_cast<int>(seed % 4));
    const Vec3 sender = testing::UniformVec3(rng, Vec3(1.0, 1.0, 0.0), Vec3(9.0, 7.0, 2.5));
    const double offset = rng.Uniform(-30.0, 30.0);

    const ToaRoots3d roots = SolveToa3dClosedForm(receivers, Values(receivers, sender, offset));

    ASSERT_EQ(roots.status, SolverStatus::kOk) << "seed " << seed;
    ASSERT_EQ(roots.count, 1);
    EXPECT_LT((roots.fixes[0].position_m - sender).norm(), 1e-6) << "seed " << seed;
    EXPECT_NEAR(roots.fixes[0].offset_m, offset, 1e-6);
    EXPECT_TRUE(std::isfinite(roots.fixes[0].dop));
  }
}

TEST(ClosedFormToa3d, CoplanarReceiversReturnTheSenderAndItsMirrorAboutTheirPlane) {
  // Ceiling mount at 3 m: the height above or below the ceiling fits alike.
  const std::vector<Vec3> receivers{Vec3(0.0, 0.0, 3.0), Vec3(6.0, 0.5, 3.0), Vec3(5.5, 5.0, 3.0), Vec3(0.5, 4.0, 3.0),
                                    Vec3(3.0, 2.0, 3.0)};
  const Vec3 sender(2.0, 1.5, 1.2);
  const Vec3 mirror(2.0, 1.5, 4.8);

  const ToaRoots3d roots = SolveToa3dClosedForm(receivers, Values(receivers, sender, 4.0));

  EXPECT_EQ(roots.status, SolverStatus::kCoplanarHeightMirror);
  EXPECT_EQ(Describe(roots.status), "coplanar receivers: height mirror");
  ASSERT_EQ(roots.count, 2);
  EXPECT_LT((roots.fixes[0].position_m - sender).norm(), 1e-6);  // lower z first
  EXPECT_LT((roots.fixes[1].position_m - mirror).norm(), 1e-6);
  for (const SolverFix& fix : roots.fixes) {
    EXPECT_NEAR(fix.offset_m, 4.0, 1e-6);
    EXPECT_TRUE(fix.degenerate());
    EXPECT_EQ(fix.reason(), "coplanar receivers: height mirror");
  }
}

TEST(ClosedFormToa3d, TiltedCoplanarReceiversMirrorAboutTheirOwnPlane) {
  // Four receivers on the plane x + z = 4, four is the minimum with the offset unknown.
  const std::vector<Vec3> receivers{Vec3(1.0, 0.0, 3.0), Vec3(3.0, 1.0, 1.0), Vec3(2.0, 5.0, 2.0), Vec3(0.5, 3.0, 3.5)};
  const Vec3 sender(0.5, 2.0, 1.0);  // x + z = 1.5: 2.5 / sqrt(2) below the plane
  const Vec3 n = Vec3(1.0, 0.0, 1.0).normalized();
  const Vec3 mirror = sender + 2.0 * ((4.0 - sender.x() - sender.z()) / std::sqrt(2.0)) * n;

  const ToaRoots3d roots = SolveToa3dClosedForm(receivers, Values(receivers, sender, -2.0));

  ASSERT_EQ(roots.status, SolverStatus::kCoplanarHeightMirror);
  ASSERT_EQ(roots.count, 2);
  const auto [k, error] = Nearest(roots, sender);
  EXPECT_LT(error, 1e-6);
  EXPECT_LT((roots.fixes[static_cast<std::size_t>(1 - k)].position_m - mirror).norm(), 1e-6);
}

TEST(ClosedFormToa3d, RangesAreExactWithFourReceiversAndMirroredWithThreeCoplanar) {
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    core::Rng rng(seed, 2);
    const auto receivers = RandomReceivers(rng, 4);
    const Vec3 sender = testing::UniformVec3(rng, Vec3(1.0, 1.0, 0.0), Vec3(9.0, 7.0, 2.5));
    const ToaRoots3d roots = SolveRange3dClosedForm(receivers, Values(receivers, sender, 0.0));
    ASSERT_EQ(roots.status, SolverStatus::kOk);
    ASSERT_EQ(roots.count, 1);
    EXPECT_LT((roots.fixes[0].position_m - sender).norm(), 1e-6) << "seed " << seed;
    EXPECT_FALSE(roots.fixes[0].offset_estimated);
  }
  const std::vector<Vec3> three{Vec3(0.0, 0.0, 2.5), Vec3(5.0, 0.0, 2.0), Vec3(1.0, 4.0, 3.0)};
  const Vec3 sender(2.0, 1.0, 0.8);
  const ToaRoots3d roots = SolveRange3dClosedForm(three, Values(three, sender, 0.0));
  EXPECT_EQ(roots.status, SolverStatus::kCoplanarHeightMirror);
  ASSERT_EQ(roots.count, 2);
  EXPECT_LT(Nearest(roots, sender).second, 1e-6);
  // The mirror root fits the ranges as well.
  EXPECT_LT(roots.fixes[0].rms_m, 1e-6);
  EXPECT_LT(roots.fixes[1].rms_m, 1e-6);
}

TEST(ClosedFormToa3d, TooFewOrCollinearReceiversGiveNoRoot) {
  const std::vector<Vec3> three{Vec3(0.0, 0.0, 2.5), Vec3(5.0, 0.0, 2.0), Vec3(1.0, 4.0, 3.0)};
  const std::vector<double> rho{3.0, 4.0, 5.0};
  EXPECT_EQ(SolveToa3dClosedForm(three, rho).status, SolverStatus::kTooFewRows);
  EXPECT_EQ(SolveRange3dClosedForm(std::span(three).first(2), std::span(rho).first(2)).status,
            SolverStatus::kTooFewRows);
  const std::vector<Vec3> line{Vec3(0.0, 0.0, 1.0), Vec3(1.0, 1.0, 1.5), Vec3(2.0, 2.0, 2.0), Vec3(4.0, 4.0, 3.0)};
  const ToaRoots3d roots = SolveToa3dClosedForm(line, std::vector<double>{3.0, 3.0, 3.5, 4.0});
  EXPECT_EQ(roots.status, SolverStatus::kCollinearReceivers);
  EXPECT_EQ(roots.count, 0);
  EXPECT_EQ(SolveToa3dClosedForm(three, std::vector<double>{1.0, 2.0}).status, SolverStatus::kInvalidInput);
}

TEST(ClosedFormToa3d, SenderOnTheAxisOfACircularArrayIsDegenerate) {
  // All pseudo-ranges equal: the offset and the height trade off exactly.
  std::vector<Vec3> receivers;
  for (int i = 0; i < 6; ++i) {
    const double a = 2.0 * M_PI * i / 6.0;
    receivers.emplace_back(3.0 + 2.0 * std::cos(a), 3.0 + 2.0 * std::sin(a), 3.0);
  }
  const ToaRoots3d roots = SolveToa3dClosedForm(receivers, Values(receivers, Vec3(3.0, 3.0, 1.0), 0.5));
  EXPECT_EQ(roots.status, SolverStatus::kDegenerateGeometry);
  EXPECT_EQ(roots.count, 0);
}

TEST(ClosedFormToa3d, RootsNeedingNegativeRangesAreNotAdmissible) {
  // Pseudo-ranges of a sender whose emission offset exceeds every arrival: no causal sender.
  const std::vector<Vec3> receivers{Vec3(0.0, 0.0, 3.0), Vec3(6.0, 0.5, 2.0), Vec3(5.5, 5.0, 3.0), Vec3(0.5, 4.0, 1.0),
                                    Vec3(3.0, 2.0, 0.5)};
  const Vec3 sender(2.0, 1.5, 1.2);
  auto rho = Values(receivers, sender, 0.0);
  for (double& r : rho) r = -r;  // time reversed: |S - M_i| = b - rho_i
  const ToaRoots3d roots = SolveToa3dClosedForm(receivers, rho);
  EXPECT_EQ(roots.status, SolverStatus::kNoAdmissibleRoot);
  EXPECT_EQ(roots.count, 0);
}

}  // namespace
}  // namespace mirage::estimation
