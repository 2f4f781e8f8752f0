// SPDX-License-Identifier: MIT
// Against the bound (Bordoy 2020 Sec. 8.1, issue 26 "RMSE / CRLB <= 1.2 for line-of-sight-only
// fixes"): the TOA NLLS with the emission time unknown is efficient on line-of-sight stamps. In the
// ch. 5 hall (ten ceiling microphones at two heights), at sigma = 0.044 ms, its 3-D RMSE over 400
// noisy emissions at each of three sender positions is within 0.85-1.2 times the CRLB of the
// pseudo-range model (eval/dop.h, kPseudoRange: position and emission offset unknown).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/estimation/solvers/toa_nlls.h"
#include "mirage/eval/dop.h"

namespace mirage::estimation {
namespace {

TEST(ToaNllsEfficiency, LineOfSightFixesReachTheCramerRaoBound) {
  const std::vector<Vec3> mics{Vec3(1.5, 1.5, 4.851),  Vec3(7.5, 1.2, 4.824), Vec3(13.5, 1.5, 4.879),
                               Vec3(1.2, 5.5, 4.835),  Vec3(13.8, 5.5, 4.862), Vec3(1.5, 9.5, 4.844),
                               Vec3(13.5, 9.5, 4.870), Vec3(5.0, 4.0, 3.40),   Vec3(10.0, 7.0, 3.40),
                               Vec3(7.5, 9.8, 3.40)};
  const double sigma_m = 343.0 * 0.044e-3;
  const std::vector<double> sigmas(mics.size(), sigma_m);
  core::Rng rng(2026);
  for (const Vec3& sender : {Vec3(4.0, 3.0, 1.3), Vec3(9.0, 6.0, 1.0), Vec3(12.5, 9.0, 1.6)}) {
    eval::DopInput input;
    input.sender_m = sender;
    input.receivers_m = mics;
    input.sigma_m = {sigma_m};
    input.model = eval::DopModel::kPseudoRange;
    const eval::DopResult bound = eval::ComputeDop(input);
    ASSERT_FALSE(bound.degenerate);
    const double crlb_m = std::sqrt(bound.position_crlb_m2.trace());
    constexpr int kTrials = 400;
    double sum_sq = 0.0;
    for (int trial = 0; trial < kTrials; ++trial) {
      const double offset_m = rng.Uniform(-5.0, 5.0);
      std::vector<double> rho;
      for (const auto& m : mics) rho.push_back((sender - m).norm() + offset_m + rng.Normal(0.0, sigma_m));
      // Started 0.5 m off: the test is about efficiency, not the basin of convergence.
      const SolverFix fix = SolveToaNlls(mics, rho, sigmas, sender + Vec3(0.4, -0.3, 0.2), offset_m + 0.3, NllsOptions{});
      ASSERT_TRUE(fix.converged);
      sum_sq += (fix.position_m - sender).squaredNorm();
    }
    const double ratio = std::sqrt(sum_sq / kTrials) / crlb_m;
    SCOPED_TRACE(testing::Message() << "sender " << sender.transpose() << ": CRLB " << crlb_m << " m");
    EXPECT_LE(ratio, 1.2);
    EXPECT_GE(ratio, 0.85);
  }
}

}  // namespace
}  // namespace mirage::estimation
