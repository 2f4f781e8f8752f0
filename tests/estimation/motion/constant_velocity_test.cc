// SPDX-License-Identifier: MIT
#include "mirage/estimation/motion/constant_velocity.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"
#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

constexpr BlockKey kPos0(blocks::kPosition, 0);
constexpr BlockKey kPos1(blocks::kPosition, 1);
constexpr BlockKey kVa4(blocks::kVirtualAnchor, 4);

// Moves only `agent` (2-D) to t_s.
void PropagateAgent(State& state, int agent, double t_s, const ConstantVelocityOptions& options) {
  const ConstantVelocity model(options, 2, std::vector<int>{agent});
  Propagate(state, t_s, {&model});
}

Eigen::MatrixXd RandomSpd(int n, std::uint64_t seed) {
  core::Rng rng(seed);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) a(i, j) = rng.Uniform(-1.0, 1.0);
  }
  return a * a.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
}

State AgentState(const Eigen::Vector4d& mean, const Eigen::Matrix4d& P, double t_s) {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  return State(layout, mean, P, t_s);
}

// F of Eq. (3.16) and the discrete white-noise-acceleration Q, written out independently.
Eigen::Matrix4d ExpectedF(double dt) {
  Eigen::Matrix4d F;
  F << 1, 0, dt, 0,  //
      0, 1, 0, dt,   //
      0, 0, 1, 0,    //
      0, 0, 0, 1;
  return F;
}

Eigen::Matrix4d ExpectedQ(double dt, double sigma_a) {
  const double q = sigma_a * sigma_a;
  const double a = q * std::pow(dt, 4) / 4.0, b = q * std::pow(dt, 3) / 2.0, c = q * dt * dt;
  Eigen::Matrix4d Q;
  Q << a, 0, b, 0,  //
      0, a, 0, b,   //
      b, 0, c, 0,   //
      0, b, 0, c;
  return Q;
}

TEST(ConstantVelocity, MovesThePositionByVelocityTimesDt) {
  // p = (1, 2), v = (0.5, -0.25), dt = 1.4 - 1.0 = 0.4: p+ = (1.2, 1.9), v unchanged.
  State state = AgentState(Eigen::Vector4d(1.0, 2.0, 0.5, -0.25), Eigen::Matrix4d::Identity(), 1.0);

  PropagateAgent(state, 0, 1.4, ConstantVelocityOptions{});

  EXPECT_NEAR(state.mean()(0), 1.2, 1e-14);
  EXPECT_NEAR(state.mean()(1), 1.9, 1e-14);
  EXPECT_DOUBLE_EQ(state.mean()(2), 0.5);
  EXPECT_DOUBLE_EQ(state.mean()(3), -0.25);
  EXPECT_DOUBLE_EQ(state.t_s(), 1.4);
}

TEST(ConstantVelocity, AddsTheWhiteNoiseAccelerationQPerAxis) {
  // P = 0, sigma_a = 2 (q = 4), dt = 0.5:
  //   Q_pp = 4 * 0.5^4 / 4 = 0.0625, Q_pv = 4 * 0.5^3 / 2 = 0.25, Q_vv = 4 * 0.5^2 = 1,
  //   with no coupling between the x and y axes.
  State state = AgentState(Eigen::Vector4d::Zero(), Eigen::Matrix4d::Zero(), 0.0);

  PropagateAgent(state, 0, 0.5, ConstantVelocityOptions{2.0});

  Eigen::Matrix4d expected;
  expected << 0.0625, 0, 0.25, 0,  //
      0, 0.0625, 0, 0.25,          //
      0.25, 0, 1, 0,               //
      0, 0.25, 0, 1;
  EXPECT_TRUE(state.covariance().isApprox(expected, 1e-14)) << state.covariance();
  EXPECT_DOUBLE_EQ(state.covariance()(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(state.covariance()(0, 3), 0.0);
}

TEST(ConstantVelocity, PropagatesAFullCovarianceAsFPFtPlusQ) {
  const Eigen::Matrix4d P0 = RandomSpd(4, 1);
  State state = AgentState(Eigen::Vector4d(0.3, -0.2, 1.0, 0.7), P0, 2.0);

  PropagateAgent(state, 0, 2.25, ConstantVelocityOptions{0.8});

  const Eigen::Matrix4d F = ExpectedF(0.25);
  const Eigen::Matrix4d expected = F * P0 * F.transpose() + ExpectedQ(0.25, 0.8);
  EXPECT_TRUE(state.covariance().isApprox(expected, 1e-13)) << state.covariance() << "\n\n" << expected;
}

TEST(ConstantVelocity, ZeroDtLeavesMeanAndCovarianceUnchanged) {
  const Eigen::Matrix4d P0 = RandomSpd(4, 2);
  State state = AgentState(Eigen::Vector4d(1, 2, 3, 4), P0, 5.0);

  PropagateAgent(state, 0, 5.0, ConstantVelocityOptions{3.0});

  EXPECT_EQ(state.covariance(), Eigen::MatrixXd(P0));
  EXPECT_EQ(state.mean(), Eigen::VectorXd(Eigen::Vector4d(1, 2, 3, 4)));
  EXPECT_DOUBLE_EQ(state.t_s(), 5.0);
}

TEST(ConstantVelocity, PropagatesCrossCovariancesOfBlocksAfterTheAgent) {
  // [pos0 | vel0 | va4]: the agent-VA cross-covariance becomes F P_agent,va (so pos-VA gains
  // dt * vel-VA), the VA block itself is untouched.
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kVirtualAnchor, 4);
  const Eigen::MatrixXd P0 = RandomSpd(6, 3);
  Eigen::VectorXd x0(6);
  x0 << 0, 0, 1, -1, 5, 6;
  State state(layout, x0, P0, 0.0);
  const double dt = 0.1;

  PropagateAgent(state, 0, dt, ConstantVelocityOptions{1.0});

  Eigen::MatrixXd F_full = Eigen::MatrixXd::Identity(6, 6);
  F_full.topLeftCorner(4, 4) = ExpectedF(dt);
  Eigen::MatrixXd Q_full = Eigen::MatrixXd::Zero(6, 6);
  Q_full.topLeftCorner(4, 4) = ExpectedQ(dt, 1.0);
  EXPECT_TRUE(state.covariance().isApprox(F_full * P0 * F_full.transpose() + Q_full, 1e-13));
  EXPECT_NEAR(state.covariance()(0, 4), P0(0, 4) + dt * P0(2, 4), 1e-14);
  EXPECT_NEAR(state.covariance()(5, 1), P0(5, 1) + dt * P0(5, 3), 1e-14);
  EXPECT_EQ(state.Covariance(kVa4), P0.bottomRightCorner(2, 2));
  EXPECT_EQ(state.Mean(kVa4), Eigen::VectorXd(Eigen::Vector2d(5, 6)));
  EXPECT_NEAR(state.mean()(0), 0.1, 1e-15);
  EXPECT_NEAR(state.mean()(1), -0.1, 1e-15);
}

TEST(ConstantVelocity, MovesOnlyTheRequestedAgent) {
  // [pos0 | vel0 | pos1 | vel1]: propagating agent 1 (offset 4) leaves agent 0's block alone but
  // updates the agent 0 - agent 1 cross-covariance.
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kPosition, 1);
  layout.Append(blocks::kVelocity, 1);
  const Eigen::MatrixXd P0 = RandomSpd(8, 4);
  Eigen::VectorXd x0(8);
  x0 << 1, 1, 9, 9, 2, 3, -1, 0.5;
  State state(layout, x0, P0, 0.0);

  PropagateAgent(state, 1, 2.0, ConstantVelocityOptions{0.5});

  Eigen::MatrixXd F_full = Eigen::MatrixXd::Identity(8, 8);
  F_full.bottomRightCorner(4, 4) = ExpectedF(2.0);
  Eigen::MatrixXd Q_full = Eigen::MatrixXd::Zero(8, 8);
  Q_full.bottomRightCorner(4, 4) = ExpectedQ(2.0, 0.5);
  EXPECT_TRUE(state.covariance().isApprox(F_full * P0 * F_full.transpose() + Q_full, 1e-13));
  EXPECT_EQ(state.covariance().topLeftCorner(4, 4), P0.topLeftCorner(4, 4));
  EXPECT_EQ(state.mean().head(4), x0.head(4));                            // agent 0 did not move
  EXPECT_EQ(state.Mean(kPos1), Eigen::VectorXd(Eigen::Vector2d(0, 4)));  // (2, 3) + 2 * (-1, 0.5)
}

TEST(ConstantVelocity, AllAgentsMoveOverTheSameDt) {
  // Per-agent calls would move only agent 0 (its call stamps the state with t_s, so agent 1 sees
  // dt = 0); the all-agents form moves both by the same dt, as F = blkdiag(F, F) (Kulmer Eq. 5).
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kPosition, 1);
  layout.Append(blocks::kVelocity, 1);
  const Eigen::MatrixXd P0 = RandomSpd(8, 5);
  Eigen::VectorXd x0(8);
  x0 << 1, 1, 9, 9, 2, 3, -1, 0.5;
  State state(layout, x0, P0, 1.0);
  const ConstantVelocity both(ConstantVelocityOptions{0.5}, 2, 2);
  Propagate(state, 3.0, {&both});
  Eigen::MatrixXd F_full = Eigen::MatrixXd::Identity(8, 8);
  F_full.topLeftCorner(4, 4) = ExpectedF(2.0);
  F_full.bottomRightCorner(4, 4) = ExpectedF(2.0);
  Eigen::MatrixXd Q_full = Eigen::MatrixXd::Zero(8, 8);
  Q_full.topLeftCorner(4, 4) = ExpectedQ(2.0, 0.5);
  Q_full.bottomRightCorner(4, 4) = ExpectedQ(2.0, 0.5);
  EXPECT_TRUE(state.covariance().isApprox(F_full * P0 * F_full.transpose() + Q_full, 1e-13));
  EXPECT_EQ(state.Mean(kPos0), Eigen::VectorXd(Eigen::Vector2d(19, 19)));
  EXPECT_EQ(state.Mean(kPos1), Eigen::VectorXd(Eigen::Vector2d(0, 4)));
  EXPECT_EQ(state.t_s(), 3.0);
}

TEST(ConstantVelocity, MovesAThreeDimensionalAgentOnEveryAxisWithThePerAxisQ) {
  // [pos3 | vel3]: p = (1, 2, 3), v = (0.5, -1, 0.25), dt = 0.4, sigma_a = 2; P = 0.
  StateLayout layout;
  layout.Append(blocks::kPosition3, 0);
  layout.Append(blocks::kVelocity3, 0);
  Eigen::VectorXd x0(6);
  x0 << 1, 2, 3, 0.5, -1, 0.25;
  State state(layout, x0, Eigen::MatrixXd::Zero(6, 6), 1.0);
  const ConstantVelocity model(ConstantVelocityOptions{2.0}, 3, 1);

  Propagate(state, 1.4, {&model});

  EXPECT_TRUE(state.Mean(BlockKey(blocks::kPosition3, 0)).isApprox(Eigen::Vector3d(1.2, 1.6, 3.1), 1e-14));
  const double q = 4.0, dt = 0.4;
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(state.covariance()(axis, axis), q * std::pow(dt, 4) / 4.0, 1e-15);
    EXPECT_NEAR(state.covariance()(axis, axis + 3), q * std::pow(dt, 3) / 2.0, 1e-15);
    EXPECT_NEAR(state.covariance()(axis + 3, axis + 3), q * dt * dt, 1e-15);
    EXPECT_EQ(state.covariance()(axis, (axis + 1) % 3), 0.0);  // axes stay independent
  }
  EXPECT_DOUBLE_EQ(state.t_s(), 1.4);
}

TEST(ConstantVelocityOptions, DefaultsAreValid) {
  EXPECT_TRUE(Validate(ConstantVelocityOptions{}).empty());
  EXPECT_TRUE(Validate(ConstantVelocityOptions{1e-3}).empty());
}

TEST(ConstantVelocityOptions, RejectsNonPositiveAndNonFiniteAccelerationSigma) {
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    const auto problems = Validate(ConstantVelocityOptions{bad});

    ASSERT_EQ(problems.size(), 1U) << bad;
    EXPECT_NE(problems[0].find("accel_sigma_mps2"), std::string::npos);
  }
}

TEST(ConstantVelocityOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(ConstantVelocityOptionsDescriptor(), {"accel_sigma_mps2"});
}

}  // namespace
}  // namespace mirage::estimation
