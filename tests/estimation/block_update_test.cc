// SPDX-License-Identifier: MIT
#include "mirage/estimation/block_update.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/estimation/ekf_update.h"

namespace mirage::estimation {
namespace {

// Agent position (offset 0), velocity (2) and two VAs (4, 6), with a random dense covariance.
State RandomState(core::Rng& rng) {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kVirtualAnchor, 1);
  layout.Append(blocks::kVirtualAnchor, 2);
  Eigen::MatrixXd A(8, 8);
  Eigen::VectorXd x(8);
  for (int i = 0; i < 8; ++i) {
    x(i) = rng.Normal(0.0, 3.0);
    for (int j = 0; j < 8; ++j) A(i, j) = rng.Normal(0.0, 0.1);
  }
  const Eigen::MatrixXd P = A * A.transpose() + 1e-3 * Eigen::MatrixXd::Identity(8, 8);
  return State(layout, x, P, 0.0);
}

TEST(BlockUpdate, GivesEveryBlockOfTheFullUpdate) {
  core::Rng rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const State prior = RandomState(rng);
    const int m = 1 + trial % 4;  // 1-4 rows on the position block
    Eigen::MatrixXd H_b(m, 2);
    Eigen::VectorXd nu(m);
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, m);
    for (int r = 0; r < m; ++r) {
      H_b.row(r) << rng.Normal(), rng.Normal();
      nu(r) = rng.Normal(0.0, 0.3);
      R(r, r) = rng.Uniform(1e-4, 1e-2);
    }
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, 8);
    H.leftCols(2) = H_b;
    State full = prior;
    ASSERT_TRUE(EkfUpdate(full, H, nu, R, CovarianceForm::kStandard).applied);

    const auto update = BlockUpdate::Make(prior, 0, H_b, nu, R);
    ASSERT_TRUE(update.has_value());
    for (int v = 0; v < 8; v += 2) {
      EXPECT_LT((update->Mean(prior, v) - full.mean().segment<2>(v)).norm(), 1e-12) << "block " << v;
      for (int w = 0; w < 8; w += 2) {
        EXPECT_LT((update->Covariance(prior, v, w) - full.covariance().block<2, 2>(v, w)).norm(), 1e-12)
            << "blocks " << v << ", " << w;
      }
    }
  }
}

TEST(BlockUpdate, RejectsWhatEkfUpdateRejects) {
  core::Rng rng(3);
  const State prior = RandomState(rng);
  EXPECT_FALSE(BlockUpdate::Make(prior, 0, Eigen::MatrixXd(0, 2), Eigen::VectorXd(0), Eigen::MatrixXd(0, 0)));
  // S = H P H^T + R with H = 0 and R = -1: not positive definite.
  EXPECT_FALSE(BlockUpdate::Make(prior, 0, Eigen::MatrixXd::Zero(1, 2), Eigen::VectorXd::Zero(1),
                                 Eigen::MatrixXd::Constant(1, 1, -1.0)));
}

TEST(BlockUpdate, KeepsTheVarianceOfARangeToAVaThatMovesWithTheAgent) {
  // A VA promoted from the agent's position (Lafer Eq. 4.7-4.9): P_vv = P_pp + P_rls, P_pv = P_pp.
  // An update of the agent alone (a LOS range) cannot tell where the VA is relative to the agent,
  // so the variance of the range between them, J (P_pp + P_vv - 2 P_pv) J^T = J P_rls J^T, stays.
  // Mixing the agent's posterior with the VA's prior blocks makes it negative: the stage-2 bug
  // this class replaced in SlamTracker.
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVirtualAnchor, 1);
  const Eigen::Matrix2d P_pp = Eigen::Vector2d(0.04 * 0.04, 0.03 * 0.03).asDiagonal();
  const Eigen::Matrix2d P_rls = Eigen::Matrix2d::Identity() * 0.005 * 0.005;
  Eigen::MatrixXd P(4, 4);
  P << P_pp, P_pp, P_pp, P_pp + P_rls;
  Eigen::Vector4d x;
  x << 1.0, 2.0, 5.0, 2.0;  // the VA 4 m to the right: the range's Jacobian is along x
  const State prior(layout, x, P, 0.0);
  Eigen::MatrixXd H_b(1, 2);
  H_b << 1.0, 0.0;  // a LOS range along x, 1 cm std
  const auto update =
      BlockUpdate::Make(prior, 0, H_b, Eigen::VectorXd::Constant(1, 0.02), Eigen::MatrixXd::Constant(1, 1, 1e-4));
  ASSERT_TRUE(update.has_value());

  const Eigen::RowVector2d J_p(-1.0, 0.0);  // d|v - p| / dp
  const Eigen::RowVector2d J_v(1.0, 0.0);   // d|v - p| / dv
  auto range_variance = [&](const Eigen::Matrix2d& pp, const Eigen::Matrix2d& vv, const Eigen::Matrix2d& pv) {
    return (J_p * pp * J_p.transpose() + J_v * vv * J_v.transpose() + 2.0 * J_p * pv * J_v.transpose())(0, 0);
  };
  const double expected_m2 = (J_v * P_rls * J_v.transpose())(0, 0);
  const double joint_m2 = range_variance(update->Covariance(prior, 0, 0), update->Covariance(prior, 2, 2),
                                         update->Covariance(prior, 0, 2));
  EXPECT_NEAR(joint_m2, expected_m2, 1e-15);
  const double mixed_m2 = range_variance(update->Covariance(prior, 0, 0), P_pp + P_rls, P_pp);
  EXPECT_LT(mixed_m2, 0.0);
  // And the VA's mean moves with the agent's: the predicted range does not change.
  EXPECT_NEAR((update->Mean(prior, 2) - update->Mean(prior, 0)).norm(), 4.0, 1e-12);
}

}  // namespace
}  // namespace mirage::estimation
