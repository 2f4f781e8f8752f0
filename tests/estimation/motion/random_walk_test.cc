// SPDX-License-Identifier: MIT
// The random walk: each listed block's covariance grows by sigma^2 dt I, means and every other
// entry stay; it composes with the constant-velocity model over one dt.
#include "mirage/estimation/motion/random_walk.h"

#include <gtest/gtest.h>

#include "mirage/estimation/motion/constant_velocity.h"

namespace mirage::estimation {
namespace {

State AgentAndTwoVas() {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kVirtualAnchor, 1);
  layout.Append(blocks::kVirtualAnchor, 2);
  Eigen::VectorXd mean(8);
  mean << 0, 0, 1, 0, 5, 5, -3, 2;
  Eigen::MatrixXd P = 0.01 * Eigen::MatrixXd::Identity(8, 8);
  P(4, 0) = P(0, 4) = 0.002;
  return State(layout, mean, P, 1.0);
}

TEST(RandomWalk, GrowsOnlyTheListedBlocksBySigmaSquaredDt) {
  State state = AgentAndTwoVas();
  const State before = state;
  const RandomWalk walk(0.1, {BlockKey(blocks::kVirtualAnchor, 2)});

  Propagate(state, 3.0, {&walk});  // dt = 2 s: + 0.01 * 2 = 0.02 on VA 2's diagonal

  Eigen::MatrixXd expected = before.covariance();
  expected(6, 6) += 0.02;
  expected(7, 7) += 0.02;
  EXPECT_TRUE(state.covariance().isApprox(expected, 1e-15));
  EXPECT_EQ(state.mean(), before.mean());
  EXPECT_DOUBLE_EQ(state.t_s(), 3.0);
}

TEST(RandomWalk, SharesOneDtWithTheAgentsMotionModel) {
  // Both models see dt = 2 s although the chain stamps the time only once, after both.
  State state = AgentAndTwoVas();
  const ConstantVelocity motion(ConstantVelocityOptions{1.0});
  const RandomWalk walk(0.1, {BlockKey(blocks::kVirtualAnchor, 1)});

  Propagate(state, 3.0, {&motion, &walk});

  EXPECT_NEAR(state.covariance()(4, 4), 0.01 + 0.02, 1e-15);
  EXPECT_NEAR(state.Mean(BlockKey(blocks::kPosition, 0))(0), 2.0, 1e-15);  // v = 1 m/s for 2 s
}

TEST(RandomWalk, ZeroSigmaOrZeroDtChangesNothing) {
  State state = AgentAndTwoVas();
  const State before = state;
  const RandomWalk off(0.0, {BlockKey(blocks::kVirtualAnchor, 1)});
  Propagate(state, 2.0, {&off});
  const RandomWalk walk(0.1, {BlockKey(blocks::kVirtualAnchor, 1)});
  Propagate(state, 2.0, {&walk});
  EXPECT_EQ(state.covariance(), before.covariance());
}

}  // namespace
}  // namespace mirage::estimation
