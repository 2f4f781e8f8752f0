// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/speed_limit.h"

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace mirage::estimation {
namespace {

constexpr BlockKey kPos0(blocks::kPosition, 0);
constexpr BlockKey kVel0(blocks::kVelocity, 0);
constexpr BlockKey kVel1(blocks::kVelocity, 1);

// Two agents, so the test also sees that only the named agent's velocity moves.
State TwoAgents(const Eigen::Vector2d& v0_mps, const Eigen::Vector2d& v1_mps) {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kPosition, 1);
  layout.Append(blocks::kVelocity, 1);
  Eigen::VectorXd mean(8);
  mean << 1.0, 2.0, v0_mps, 3.0, 4.0, v1_mps;
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(8, 8) * 0.01;
  P(0, 2) = P(2, 0) = 0.004;  // position-velocity correlation, which W = I must not use
  return State(layout, mean, P, 0.0);
}

TEST(SpeedLimit, ScalesAFasterVelocityOntoTheLimitKeepingItsDirection) {
  State state = TwoAgents({3.0, -4.0}, {2.0, 2.0});  // 5 m/s
  const Eigen::MatrixXd P_before = state.covariance();
  EXPECT_TRUE(LimitSpeed(state, 0, 1.5));
  const Eigen::VectorXd v = state.Mean(kVel0);
  EXPECT_NEAR(v.norm(), 1.5, 1e-12);
  EXPECT_NEAR(v(0), 0.9, 1e-12);
  EXPECT_NEAR(v(1), -1.2, 1e-12);
  // Nothing else moves: the position, the other agent, the covariance.
  EXPECT_EQ(state.Mean(kPos0), Eigen::Vector2d(1.0, 2.0));
  EXPECT_EQ(state.Mean(kVel1), Eigen::Vector2d(2.0, 2.0));
  EXPECT_EQ(state.covariance(), P_before);
}

TEST(SpeedLimit, LeavesAVelocityWithinTheLimitAlone) {
  State state = TwoAgents({0.3, 0.4}, {0.0, 0.0});
  EXPECT_FALSE(LimitSpeed(state, 0, 0.5));  // exactly at the limit
  EXPECT_EQ(state.Mean(kVel0), Eigen::Vector2d(0.3, 0.4));
  EXPECT_FALSE(LimitSpeed(state, 0, 1.5));
  EXPECT_EQ(state.Mean(kVel0), Eigen::Vector2d(0.3, 0.4));
}

TEST(SpeedLimit, ActsOnTheNamedAgentOnly) {
  State state = TwoAgents({0.1, 0.0}, {0.0, 6.0});
  EXPECT_TRUE(LimitSpeed(state, 1, 2.0));
  EXPECT_EQ(state.Mean(kVel0), Eigen::Vector2d(0.1, 0.0));
  EXPECT_NEAR(state.Mean(kVel1)(1), 2.0, 1e-12);
  EXPECT_NEAR(state.Mean(kVel1)(0), 0.0, 1e-12);
}

TEST(SpeedLimit, ZeroOrNegativeDisablesIt) {
  State state = TwoAgents({30.0, 40.0}, {0.0, 0.0});
  EXPECT_FALSE(LimitSpeed(state, 0, 0.0));
  EXPECT_FALSE(LimitSpeed(state, 0, -1.0));
  EXPECT_EQ(state.Mean(kVel0), Eigen::Vector2d(30.0, 40.0));
}

}  // namespace
}  // namespace mirage::estimation
