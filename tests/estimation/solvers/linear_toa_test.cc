// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/linear_toa.h"

#include <cmath>
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

TEST(LinearToa, IsExactOnNoiseFreeRandomGeometries) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    core::Rng rng(seed);
    const auto receivers = RandomReceivers(rng, 5 + static_cast<int>(seed % 4));
    const Vec3 sender = testing::UniformVec3(rng, Vec3(1.0, 1.0, 0.0), Vec3(9.0, 7.0, 2.5));
    const double offset = rng.Uniform(-100.0, 100.0);
    std::vector<double> sigmas;
    for (std::size_t i = 0; i < receivers.size(); ++i) sigmas.push_back(rng.Uniform(0.01, 0.3));
    const auto rho = Values(receivers, sender, offset);

    for (const bool weighted : {false, true}) {
      const std::span<const double> s = weighted ? std::span<const double>(sigmas) : std::span<const double>();
      const SolverFix toa = SolveLinearToa(receivers, rho, s, std::nullopt);
      ASSERT_EQ(toa.status, SolverStatus::kOk) << "seed " << seed;
      EXPECT_LT((toa.position_m - sender).norm(), 1e-6) << "seed " << seed;
      EXPECT_NEAR(toa.offset_m, offset, 1e-6);
      EXPECT_TRUE(toa.converged);

      const SolverFix known = SolveLinearToa(receivers, rho, s, sender.z());
      ASSERT_EQ(known.status, SolverStatus::kOk);
      EXPECT_LT((known.position_m - sender).norm(), 1e-6);
      EXPECT_EQ(known.position_m.z(), sender.z());

      const auto ranges = Values(receivers, sender, 0.0);
      const SolverFix range = SolveLinearRanges(receivers, ranges, s, std::nullopt);
      ASSERT_EQ(range.status, SolverStatus::kOk);
      EXPECT_LT((range.position_m - sender).norm(), 1e-6);
      EXPECT_FALSE(range.offset_estimated);
      const SolverFix range_known = SolveLinearRanges(receivers, ranges, s, sender.z());
      ASSERT_EQ(range_known.status, SolverStatus::kOk);
      EXPECT_LT((range_known.position_m - sender).norm(), 1e-6);
    }
  }
}

TEST(LinearToa, CoplanarReceiversNeedAKnownHeight) {
  const std::vector<Vec3> receivers{Vec3(0.0, 0.0, 3.0), Vec3(6.0, 0.5, 3.0), Vec3(5.5, 5.0, 3.0), Vec3(0.5, 4.0, 3.0),
                                    Vec3(3.0, 2.0, 3.0)};
  const Vec3 sender(2.0, 1.5, 1.2);
  const auto rho = Values(receivers, sender, 3.0);
  EXPECT_EQ(SolveLinearToa(receivers, rho, {}, std::nullopt).status, SolverStatus::kDegenerateGeometry);
  const SolverFix fix = SolveLinearToa(receivers, rho, {}, 1.2);
  ASSERT_EQ(fix.status, SolverStatus::kOk);
  EXPECT_LT((fix.position_m - sender).norm(), 1e-6);
  EXPECT_NEAR(fix.offset_m, 3.0, 1e-6);
}

TEST(LinearToa, TooFewReceiversAreReported) {
  core::Rng rng(3);
  const auto receivers = RandomReceivers(rng, 4);
  const std::vector<double> rho{1.0, 2.0, 3.0, 4.0};
  EXPECT_EQ(SolveLinearToa(receivers, rho, {}, std::nullopt).status, SolverStatus::kTooFewRows);  // 5 unknowns
  EXPECT_EQ(SolveLinearRanges(std::span(receivers).first(3), std::span(rho).first(3), {}, std::nullopt).status,
            SolverStatus::kTooFewRows);
  EXPECT_EQ(SolveLinearToa(receivers, std::span(rho).first(3), {}, std::nullopt).status, SolverStatus::kInvalidInput);
}

TEST(LinearToa, ARowWithALargeSigmaBarelyMovesTheWeightedFix) {
  core::Rng rng(11);
  const auto receivers = RandomReceivers(rng, 7);
  const Vec3 sender(4.0, 3.0, 1.0);
  auto rho = Values(receivers, sender, 2.0);
  rho[3] += 1.5;  // an NLOS excess on receiver 3
  std::vector<double> sigmas(receivers.size(), 0.01);
  sigmas[3] = 100.0;

  const double unweighted = (SolveLinearToa(receivers, rho, {}, std::nullopt).position_m - sender).norm();
  const double weighted = (SolveLinearToa(receivers, rho, sigmas, std::nullopt).position_m - sender).norm();

  EXPECT_GT(unweighted, 0.05);
  EXPECT_LT(weighted, 1e-3);
}

}  // namespace
}  // namespace mirage::estimation
