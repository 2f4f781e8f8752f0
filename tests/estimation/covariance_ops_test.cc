// SPDX-License-Identifier: MIT
#include "mirage/estimation/covariance_ops.h"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"

namespace mirage::estimation {
namespace {

constexpr BlockKey kPos0(blocks::kPosition, 0);
constexpr BlockKey kVel0(blocks::kVelocity, 0);
constexpr BlockKey kVa3(blocks::kVirtualAnchor, 3);
constexpr BlockKey kWall1(blocks::kWallOffset, 1);
constexpr BlockKey kVa5(blocks::kVirtualAnchor, 5);

constexpr double kTol = 1e-12;

Eigen::MatrixXd RandomMatrix(int rows, int cols, core::Rng& rng) {
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) m(i, j) = rng.Uniform(-1.0, 1.0);
  }
  return m;
}

// A A^T + 0.5 I: symmetric positive definite with generic (non-zero) cross terms.
Eigen::MatrixXd RandomSpd(int n, core::Rng& rng) {
  const Eigen::MatrixXd a = RandomMatrix(n, n, rng);
  return a * a.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
}

// [pos0 (2) | vel0 (2) | va3 (2) | wall1 (1)], n = 7, random mean and SPD covariance at t = 1 s.
State RandomState(std::uint64_t seed) {
  core::Rng rng(seed);
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kVelocity, 0);
  layout.Append(blocks::kVirtualAnchor, 3);
  layout.Append(blocks::kWallOffset, 1);
  const Eigen::MatrixXd P = RandomSpd(7, rng);  // drawn first: see tests/rng_vectors.h
  return State(layout, RandomMatrix(7, 1, rng), P, 1.0);
}

// Identity of size n with F placed at [offset, offset + k).
Eigen::MatrixXd EmbedF(int n, int offset, const Eigen::MatrixXd& F) {
  Eigen::MatrixXd full = Eigen::MatrixXd::Identity(n, n);
  full.block(offset, offset, F.rows(), F.cols()) = F;
  return full;
}

Eigen::MatrixXd EmbedQ(int n, int offset, const Eigen::MatrixXd& Q) {
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(n, n);
  full.block(offset, offset, Q.rows(), Q.cols()) = Q;
  return full;
}

// ---------------------------------------------------------------------------------------------
// PropagateBlock
// ---------------------------------------------------------------------------------------------

TEST(CovarianceOpsPropagateBlock, MatchesTheDenseProductIncludingCrossCovariancesOfLaterBlocks) {
  // The agent block [pos0, vel0] (offset 0, size 4) with constant-velocity F (dt = 0.3); va3 and
  // wall1 follow it and their cross-covariances with the agent must become F P_agent,other.
  State state = RandomState(1);
  const Eigen::MatrixXd P0 = state.covariance();
  const Eigen::VectorXd x0 = state.mean();
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(4, 4);
  F(0, 2) = F(1, 3) = 0.3;
  core::Rng rng(2);
  const Eigen::MatrixXd Q = RandomSpd(4, rng);

  CovarianceOps::PropagateBlock(state, kPos0, F, Q);

  const Eigen::MatrixXd F_full = EmbedF(7, 0, F);
  const Eigen::MatrixXd expected_P = F_full * P0 * F_full.transpose() + EmbedQ(7, 0, Q);
  EXPECT_TRUE(state.covariance().isApprox(expected_P, kTol)) << state.covariance() << "\n\n" << expected_P;
  EXPECT_TRUE(state.mean().isApprox(F_full * x0, kTol));
  // The blocks after the agent: cross terms changed, their own covariance did not.
  EXPECT_FALSE(state.covariance().block(0, 4, 4, 3).isApprox(P0.block(0, 4, 4, 3), 1e-6));
  EXPECT_EQ(state.covariance().bottomRightCorner(3, 3), P0.bottomRightCorner(3, 3));
}

TEST(CovarianceOpsPropagateBlock, MatchesTheDenseProductForABlockInTheMiddle) {
  // A generic (non-symmetric) 2x2 F on va3 (offset 4) between vel0 and wall1.
  State state = RandomState(3);
  const Eigen::MatrixXd P0 = state.covariance();
  const Eigen::VectorXd x0 = state.mean();
  Eigen::Matrix2d F;
  F << 0.9, -0.4, 0.2, 1.1;
  Eigen::Matrix2d Q;
  Q << 0.3, 0.1, 0.1, 0.2;

  CovarianceOps::PropagateBlock(state, kVa3, F, Q);

  const Eigen::MatrixXd F_full = EmbedF(7, 4, F);
  EXPECT_TRUE(state.covariance().isApprox(F_full * P0 * F_full.transpose() + EmbedQ(7, 4, Q), kTol));
  EXPECT_TRUE(state.mean().isApprox(F_full * x0, kTol));
  EXPECT_EQ(state.covariance().topLeftCorner(4, 4), P0.topLeftCorner(4, 4));
}

TEST(CovarianceOpsPropagateBlock, WithIdentityAndZeroNoiseChangesNothingAndStampSetsOnlyTheTime) {
  State state = RandomState(4);
  const State before = state;

  CovarianceOps::PropagateBlock(state, kVel0, Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Zero(3, 3));
  CovarianceOps::Stamp(state, 5.0);

  EXPECT_EQ(state.covariance(), before.covariance());
  EXPECT_EQ(state.mean(), before.mean());
  EXPECT_DOUBLE_EQ(state.t_s(), 5.0);
}

// ---------------------------------------------------------------------------------------------
// JosephUpdate
// ---------------------------------------------------------------------------------------------

struct UpdateProblem {
  State state;
  Eigen::MatrixXd H, R, U, S;
  Eigen::VectorXd innovation;
};

// Two measurements of the 7-dim random state with a dense H and a correlated R.
UpdateProblem RandomUpdateProblem(std::uint64_t seed) {
  core::Rng rng(seed);
  UpdateProblem p;
  p.state = RandomState(seed + 100);
  p.H = RandomMatrix(2, 7, rng);
  p.R = RandomSpd(2, rng);
  p.innovation = Eigen::VectorXd(RandomMatrix(2, 1, rng));
  p.U = p.state.covariance() * p.H.transpose();
  p.S = p.H * p.U + p.R;
  return p;
}

TEST(CovarianceOpsJosephUpdate, EqualsTheTextbookJosephFormForAnArbitraryGain) {
  UpdateProblem p = RandomUpdateProblem(10);
  core::Rng rng(11);
  const Eigen::MatrixXd K = RandomMatrix(7, 2, rng);  // not the Kalman gain
  const Eigen::MatrixXd P0 = p.state.covariance();
  const Eigen::VectorXd x0 = p.state.mean();

  CovarianceOps::JosephUpdate(p.state, K, p.U, p.S, p.innovation);

  const Eigen::MatrixXd I_KH = Eigen::MatrixXd::Identity(7, 7) - K * p.H;
  const Eigen::MatrixXd expected = I_KH * P0 * I_KH.transpose() + K * p.R * K.transpose();
  EXPECT_TRUE(p.state.covariance().isApprox(expected, kTol)) << p.state.covariance() << "\n\n" << expected;
  EXPECT_TRUE(p.state.mean().isApprox(x0 + K * p.innovation, kTol));
  // An arbitrary gain must not collapse to the short form (I - K H) P.
  EXPECT_FALSE(p.state.covariance().isApprox(I_KH * P0, 1e-3));
}

TEST(CovarianceOpsJosephUpdate, EqualsTheShortFormForTheOptimalGain) {
  UpdateProblem p = RandomUpdateProblem(20);
  const Eigen::MatrixXd P0 = p.state.covariance();
  const Eigen::MatrixXd K = p.U * p.S.inverse();  // P H^T S^-1

  CovarianceOps::JosephUpdate(p.state, K, p.U, p.S, p.innovation);

  const Eigen::MatrixXd I_KH = Eigen::MatrixXd::Identity(7, 7) - K * p.H;
  EXPECT_TRUE(p.state.covariance().isApprox(I_KH * P0, 1e-10));
  EXPECT_TRUE(p.state.covariance().isApprox(P0 - K * p.S * K.transpose(), 1e-10));
  EXPECT_EQ(p.state.covariance(), Eigen::MatrixXd(p.state.covariance().transpose()));  // exactly symmetric
}

TEST(CovarianceOpsJosephUpdate, KeepsTheCovariancePositiveDefinite) {
  UpdateProblem p = RandomUpdateProblem(30);
  const Eigen::MatrixXd K = p.U * p.S.inverse();
  const double trace_before = p.state.covariance().trace();

  CovarianceOps::JosephUpdate(p.state, K, p.U, p.S, p.innovation);

  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(p.state.covariance());
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  // With the optimal gain P+ = P - K S K^T, so the trace drops by trace(K S K^T) > 0.
  EXPECT_NEAR(p.state.covariance().trace(), trace_before - (K * p.S * K.transpose()).trace(), 1e-10);
  EXPECT_LT(p.state.covariance().trace(), trace_before);
}

// ---------------------------------------------------------------------------------------------
// Symmetrize
// ---------------------------------------------------------------------------------------------

TEST(CovarianceOpsSymmetrize, AveragesTheMatrixWithItsTranspose) {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  Eigen::Matrix2d P;
  P << 1, 2, 4, 3;
  State state(layout, Eigen::Vector2d(0, 0), P, 0.0);

  CovarianceOps::Symmetrize(state);

  Eigen::Matrix2d expected;
  expected << 1, 3, 3, 3;  // off-diagonal (2 + 4) / 2
  EXPECT_EQ(state.covariance(), Eigen::MatrixXd(expected));
}

// ---------------------------------------------------------------------------------------------
// Augment / Marginalize
// ---------------------------------------------------------------------------------------------

TEST(CovarianceOpsAugment, AppendsTheBlockWithItsCrossCovariance) {
  State state = RandomState(40);
  const State before = state;
  core::Rng rng(41);
  const Eigen::Vector2d x_new(3.5, -1.0);
  const Eigen::MatrixXd P_new_x = RandomMatrix(2, 7, rng);
  Eigen::Matrix2d P_new;
  P_new << 4.0, 0.5, 0.5, 3.0;

  CovarianceOps::Augment(state, blocks::kVirtualAnchor, 5, x_new, P_new_x, P_new);

  ASSERT_EQ(state.dimension(), 9);
  EXPECT_EQ(state.layout().At(kVa5).offset, 7);
  EXPECT_EQ(state.mean().head(7), before.mean());
  EXPECT_EQ(state.Mean(kVa5), Eigen::VectorXd(x_new));
  EXPECT_EQ(state.covariance().topLeftCorner(7, 7), before.covariance());
  EXPECT_EQ(state.covariance().block(7, 0, 2, 7), P_new_x);
  EXPECT_EQ(state.covariance().block(0, 7, 7, 2), P_new_x.transpose());
  EXPECT_EQ(state.Covariance(kVa5), Eigen::MatrixXd(P_new));
  EXPECT_DOUBLE_EQ(state.t_s(), before.t_s());
}

TEST(CovarianceOpsMarginalize, UndoesAugment) {
  State state = RandomState(50);
  const State before = state;
  core::Rng rng(51);

  const Eigen::MatrixXd R = RandomSpd(2, rng);  // drawn first: see tests/rng_vectors.h
  CovarianceOps::Augment(state, blocks::kVirtualAnchor, 5, Eigen::Vector2d(1, 2), RandomMatrix(2, 7, rng), R);
  CovarianceOps::Marginalize(state, kVa5);

  EXPECT_EQ(state.dimension(), 7);
  EXPECT_FALSE(state.layout().Find(kVa5).has_value());
  EXPECT_EQ(state.mean(), before.mean());
  EXPECT_EQ(state.covariance(), before.covariance());
}

TEST(CovarianceOpsMarginalize, DropsTheRowsAndColumnsOfAMiddleBlock) {
  // Removing vel0 (rows/cols 2-3) keeps indices {0, 1, 4, 5, 6}.
  State state = RandomState(60);
  const State before = state;
  const int keep[] = {0, 1, 4, 5, 6};

  CovarianceOps::Marginalize(state, kVel0);

  ASSERT_EQ(state.dimension(), 5);
  for (int i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(state.mean()(i), before.mean()(keep[i]));
    for (int j = 0; j < 5; ++j) EXPECT_DOUBLE_EQ(state.covariance()(i, j), before.covariance()(keep[i], keep[j]));
  }
  EXPECT_EQ(state.layout().At(kVa3).offset, 2);
  EXPECT_EQ(state.layout().At(kWall1).offset, 4);
  EXPECT_EQ(state.Covariance(kVa3), before.Covariance(kVa3));
}

TEST(CovarianceOpsMarginalize, DropsTheFirstAndTheLastBlock) {
  State first = RandomState(70);
  State last = first;
  const State before = first;

  CovarianceOps::Marginalize(first, kPos0);
  CovarianceOps::Marginalize(last, kWall1);

  EXPECT_EQ(first.covariance(), before.covariance().bottomRightCorner(5, 5));
  EXPECT_EQ(first.mean(), before.mean().tail(5));
  EXPECT_EQ(first.layout().At(kVel0).offset, 0);
  EXPECT_EQ(last.covariance(), before.covariance().topLeftCorner(6, 6));
  EXPECT_EQ(last.mean(), before.mean().head(6));
}

// ---------------------------------------------------------------------------------------------
// Reinitialize
// ---------------------------------------------------------------------------------------------

TEST(CovarianceOpsReinitialize, SetsTheBlockAndDecorrelatesItKeepingTheRest) {
  State s = RandomState(41);
  const Eigen::MatrixXd before = s.covariance();
  const Eigen::VectorXd mean_before = s.mean();
  const Eigen::Vector2d x_new(3.0, -4.0);
  const Eigen::Matrix2d P_new = Eigen::Vector2d(0.01, 0.02).asDiagonal();
  CovarianceOps::Reinitialize(s, kVel0, x_new, P_new);
  const int v = s.layout().At(kVel0).offset;
  EXPECT_TRUE(s.Mean(kVel0).isApprox(x_new));
  EXPECT_TRUE(s.covariance().block(v, v, 2, 2).isApprox(P_new));
  for (int i = 0; i < s.dimension(); ++i) {
    const bool in_block = i == v || i == v + 1;
    for (int j = 0; j < s.dimension(); ++j) {
      const bool other_in_block = j == v || j == v + 1;
      if (in_block != other_in_block) {
        EXPECT_EQ(s.covariance()(i, j), 0.0) << i << "," << j;  // no correlation left
      } else if (!in_block) {
        EXPECT_EQ(s.covariance()(i, j), before(i, j)) << i << "," << j;  // the rest's marginal kept
      }
    }
    if (!in_block) {
      EXPECT_EQ(s.mean()(i), mean_before(i));
    }
  }
  // Still a valid covariance.
  Eigen::LLT<Eigen::MatrixXd> llt(s.covariance());
  EXPECT_EQ(llt.info(), Eigen::Success);
}

}  // namespace
}  // namespace mirage::estimation
