// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/closed_form_tdoa_2d.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

std::array<double, 3> PseudoRanges(const std::array<Vec3, 3>& receivers, const Vec3& sender, double offset) {
  return {(sender - receivers[0]).norm() + offset, (sender - receivers[1]).norm() + offset,
          (sender - receivers[2]).norm() + offset};
}

// Every returned root must reproduce both differences and have r_0 = |S - M_0|.
void ExpectRootsFitTheDifferences(const TdoaRoots2d& roots, const std::array<Vec3, 3>& receivers,
                                  const std::array<double, 3>& rho) {
  for (int k = 0; k < roots.count; ++k) {
    const Vec3& s = roots.positions_m[static_cast<std::size_t>(k)];
    const double r0 = (s - receivers[0]).norm();
    EXPECT_NEAR(roots.reference_range_m[static_cast<std::size_t>(k)], r0, 1e-7) << "root " << k;
    EXPECT_NEAR((s - receivers[1]).norm() - r0, rho[1] - rho[0], 1e-7) << "root " << k;
    EXPECT_NEAR((s - receivers[2]).norm() - r0, rho[2] - rho[0], 1e-7) << "root " << k;
  }
}

TEST(ClosedFormTdoa2d, RootsContainTheTruthOnRandomGeometries) {
  int two_root_cases = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    core::Rng rng(seed);
    std::array<Vec3, 3> receivers;
    for (auto& m : receivers) m = testing::UniformVec3(rng, Vec3(0.0, 0.0, 0.3), Vec3(10.0, 8.0, 3.0));
    const Vec3 sender = testing::UniformVec3(rng, Vec3(-5.0, -5.0, 0.0), Vec3(15.0, 13.0, 2.0));
    const double offset = rng.Uniform(-50.0, 50.0);
    const auto rho = PseudoRanges(receivers, sender, offset);

    const TdoaRoots2d roots = SolveTdoa2dFromPseudoRanges(receivers, rho, sender.z());

    ASSERT_EQ(roots.status, SolverStatus::kOk) << "seed " << seed;
    ASSERT_GE(roots.count, 1);
    double best = std::numeric_limits<double>::infinity();
    int best_k = 0;
    for (int k = 0; k < roots.count; ++k) {
      const double error = (roots.positions_m[static_cast<std::size_t>(k)] - sender).norm();
      if (error < best) {
        best = error;
        best_k = k;
      }
      EXPECT_EQ(roots.positions_m[static_cast<std::size_t>(k)].z(), sender.z());
    }
    EXPECT_LT(best, 1e-6) << "seed " << seed;
    // The emission offset follows from the true root: b = rho_0 - r_0.
    EXPECT_NEAR(rho[0] - roots.reference_range_m[static_cast<std::size_t>(best_k)], offset, 1e-6);
    ExpectRootsFitTheDifferences(roots, receivers, rho);
    if (roots.count == 2) {
      ++two_root_cases;
      EXPECT_LE(roots.reference_range_m[0], roots.reference_range_m[1]);
      EXPECT_GT((roots.positions_m[0] - roots.positions_m[1]).norm(), 1e-6);
    }
  }
  // Senders outside the receivers' triangle give the two-solution case; it must be exercised.
  EXPECT_GT(two_root_cases, 10);
}

TEST(ClosedFormTdoa2d, BothRootsOfAnAmbiguousGeometryAreReturned) {
  // Sender far outside the triangle, on the side of receiver 0: both hyperbola branches cross twice.
  const std::array<Vec3, 3> receivers{Vec3(0.0, 0.0, 2.5), Vec3(4.0, 0.0, 2.5), Vec3(0.0, 3.0, 2.0)};
  const Vec3 sender(-6.0, -5.0, 1.2);
  const auto rho = PseudoRanges(receivers, sender, 0.0);

  const TdoaRoots2d roots = SolveTdoa2dFromPseudoRanges(receivers, rho, 1.2);

  ASSERT_EQ(roots.count, 2);
  const double e0 = (roots.positions_m[0] - sender).norm();
  const double e1 = (roots.positions_m[1] - sender).norm();
  EXPECT_LT(std::min(e0, e1), 1e-8);
  EXPECT_GT(std::max(e0, e1), 0.1);
  ExpectRootsFitTheDifferences(roots, receivers, rho);
}

TEST(ClosedFormTdoa2d, DifferencesAndPseudoRangesGiveTheSameRoots) {
  const std::array<Vec3, 3> receivers{Vec3(1.0, 1.0, 2.0), Vec3(6.0, 1.5, 2.7), Vec3(3.0, 5.0, 0.4)};
  const Vec3 sender(3.0, 2.5, 1.0);
  const auto rho = PseudoRanges(receivers, sender, 17.0);

  const TdoaRoots2d a = SolveTdoa2dFromPseudoRanges(receivers, rho, 1.0);
  const TdoaRoots2d b = SolveTdoa2d(receivers, {rho[1] - rho[0], rho[2] - rho[0]}, 1.0);

  ASSERT_EQ(a.count, b.count);
  ASSERT_GE(a.count, 1);
  for (int k = 0; k < a.count; ++k) {
    EXPECT_LT((a.positions_m[static_cast<std::size_t>(k)] - b.positions_m[static_cast<std::size_t>(k)]).norm(), 1e-12);
  }
}

TEST(ClosedFormTdoa2d, FlagsReceiversCollinearInThePlane) {
  // On one line in xy although at different heights: x, y are not linear in r_0.
  const std::array<Vec3, 3> line{Vec3(0.0, 0.0, 2.5), Vec3(2.0, 1.0, 1.0), Vec3(4.0, 2.0, 3.0)};
  const TdoaRoots2d roots = SolveTdoa2d(line, {0.3, -0.2}, 1.0);
  EXPECT_EQ(roots.status, SolverStatus::kCollinearReceivers);
  EXPECT_EQ(roots.count, 0);
  EXPECT_TRUE(IsDegenerate(roots.status));
  // Two receivers on one vertical.
  const std::array<Vec3, 3> stacked{Vec3(1.0, 1.0, 0.5), Vec3(1.0, 1.0, 2.5), Vec3(4.0, 2.0, 3.0)};
  EXPECT_EQ(SolveTdoa2d(stacked, {0.3, -0.2}, 1.0).status, SolverStatus::kCollinearReceivers);
}

TEST(ClosedFormTdoa2d, DifferencesLongerThanTheBaselineHaveNoRoot) {
  // |d_1| > |M_1 - M_0| violates the geometric bound (Eq. 5.5): no sender can produce it.
  const std::array<Vec3, 3> receivers{Vec3(0.0, 0.0, 2.5), Vec3(3.0, 0.0, 2.5), Vec3(0.0, 3.0, 2.5)};
  const TdoaRoots2d roots = SolveTdoa2d(receivers, {3.5, 0.0}, 1.0);
  EXPECT_EQ(roots.status, SolverStatus::kNoAdmissibleRoot);
  EXPECT_EQ(roots.count, 0);
}

TEST(ClosedFormTdoa2d, RejectsNonFiniteInput) {
  const std::array<Vec3, 3> receivers{Vec3(0.0, 0.0, 2.5), Vec3(3.0, 0.0, 2.5), Vec3(0.0, 3.0, 2.5)};
  EXPECT_EQ(SolveTdoa2d(receivers, {std::nan(""), 0.0}, 1.0).status, SolverStatus::kInvalidInput);
  EXPECT_EQ(SolveTdoa2d(receivers, {0.1, 0.0}, std::numeric_limits<double>::infinity()).status,
            SolverStatus::kInvalidInput);
}

}  // namespace
}  // namespace mirage::estimation
