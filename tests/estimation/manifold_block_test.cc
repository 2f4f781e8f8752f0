// SPDX-License-Identifier: MIT
// The state's block types are open: a test-only orientation block (a unit quaternion, 4 mean
// values, 3 degrees of freedom) sits between Euclidean blocks, rows touch it through its 3-D
// tangent, and the one update path corrects it through its boxplus. Nothing in estimation/
// knows about orientations.
#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/estimation/covariance_ops.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/state.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

// q [+] delta = q * Exp(delta) (right perturbation), q stored as w, x, y, z.
Eigen::Quaterniond Exp(const Eigen::Vector3d& delta) {
  const double angle = delta.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * delta.x(), 0.5 * delta.y(), 0.5 * delta.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, delta / angle));
}

Eigen::Quaterniond Load(const double* q) { return Eigen::Quaterniond(q[0], q[1], q[2], q[3]); }

void Store(const Eigen::Quaterniond& q, double* out) {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

void QuaternionBoxPlus(const double* x, const double* delta, double* out) {
  Store((Load(x) * Exp(Eigen::Vector3d(delta[0], delta[1], delta[2]))).normalized(), out);
}

void QuaternionBoxMinus(const double* x, const double* y, double* out) {
  const Eigen::AngleAxisd d(Load(y).conjugate() * Load(x));
  Eigen::Vector3d v = d.angle() * d.axis();
  if (d.angle() > M_PI) v = (d.angle() - 2.0 * M_PI) * d.axis();
  for (int i = 0; i < 3; ++i) out[i] = v(i);
}

constexpr BlockType kOrientation{1000, "orientation_test", 4, 3, &QuaternionBoxPlus, &QuaternionBoxMinus};

// [position (2) | orientation (4 values, 3 dof) | wall offset (1)]: tangent 6, mean 7.
State MixedState(const Eigen::Quaterniond& q, double sigma_rad) {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(kOrientation, 0);
  layout.Append(blocks::kWallOffset, 3);
  Eigen::VectorXd mean(7);
  mean << 1.0, 2.0, q.w(), q.x(), q.y(), q.z(), 0.25;
  Eigen::VectorXd variance(6);
  variance << 0.01, 0.01, sigma_rad * sigma_rad, sigma_rad * sigma_rad, sigma_rad * sigma_rad, 0.04;
  return State(layout, mean, variance.asDiagonal(), 0.0);
}

Eigen::Quaterniond Orientation(const State& state) {
  return Load(state.mean().data() + state.layout().At(BlockKey(kOrientation, 0)).mean_offset);
}

// Row i of R(q) v: one component of a known body vector seen in the world frame (a toy
// measurement, e.g. a magnetometer's). dh/d delta = -e_i^T R(q) [v]x for q [+] delta.
MeasurementRow RotatedComponentRow(const State& state, const Eigen::Vector3d& v, int i, double variance) {
  const Eigen::Matrix3d R = Orientation(state).toRotationMatrix();
  Eigen::Matrix3d v_cross;
  v_cross << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  MeasurementRow row;
  row.predicted = (R * v)(i);
  row.variance = variance;
  const Eigen::RowVector3d J = -(R.row(i) * v_cross);
  row.Add(state.layout().At(BlockKey(kOrientation, 0)), J);
  return row;
}

TEST(ManifoldBlock, LayoutKeepsMeanAndTangentOffsetsApart) {
  const State state = MixedState(Eigen::Quaterniond::Identity(), 0.1);
  const Block orientation = state.layout().At(BlockKey(kOrientation, 0));
  const Block wall = state.layout().At(BlockKey(blocks::kWallOffset, 3));

  EXPECT_EQ(state.layout().dimension(), 6);
  EXPECT_EQ(state.layout().mean_dimension(), 7);
  EXPECT_FALSE(state.layout().euclidean());
  EXPECT_EQ(orientation.offset, 2);
  EXPECT_EQ(orientation.size, 3);
  EXPECT_EQ(orientation.mean_offset, 2);
  EXPECT_EQ(orientation.mean_size, 4);
  EXPECT_EQ(wall.offset, 5);       // covariance row
  EXPECT_EQ(wall.mean_offset, 6);  // mean value
  EXPECT_DOUBLE_EQ(state.Mean(BlockKey(blocks::kWallOffset, 3))(0), 0.25);
}

TEST(ManifoldBlock, CorrectAppliesBoxPlusToTheQuaternionAndAddsToEuclideanBlocks) {
  State state = MixedState(Eigen::Quaterniond::Identity(), 0.1);
  Eigen::VectorXd dx(6);
  dx << 0.5, -0.5, 0.0, 0.0, M_PI / 2.0, 0.1;

  CovarianceOps::Correct(state, dx);

  // A quarter turn about z; the position and the wall moved additively.
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(Orientation(state).angularDistance(expected), 0.0, 1e-12);
  EXPECT_NEAR(Orientation(state).norm(), 1.0, 1e-14);
  EXPECT_TRUE(state.Mean(BlockKey(blocks::kPosition, 0)).isApprox(Eigen::Vector2d(1.5, 1.5), 1e-15));
  EXPECT_NEAR(state.Mean(BlockKey(blocks::kWallOffset, 3))(0), 0.35, 1e-15);
}

TEST(ManifoldBlock, RowJacobianMatchesCentralDifferencesThroughBoxPlus) {
  core::Rng rng(11);
  const Eigen::Quaterniond q = Exp(testing::NormalVec3(rng));
  const State state = MixedState(q, 0.1);
  const Eigen::Vector3d v(0.3, -1.2, 0.7);
  for (int i = 0; i < 3; ++i) {
    const MeasurementRow row = RotatedComponentRow(state, v, i, 1.0);
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      Eigen::VectorXd dx = Eigen::VectorXd::Zero(6);
      dx(2 + k) = h;
      State plus = state, minus = state;
      CovarianceOps::Correct(plus, dx);
      CovarianceOps::Correct(minus, -dx);
      const double numeric = ((Orientation(plus).toRotationMatrix() * v)(i) - (Orientation(minus).toRotationMatrix() * v)(i)) / (2 * h);
      EXPECT_NEAR(row.jacobians[0](k), numeric, 1e-8) << "component " << i << " tangent " << k;
    }
  }
}

TEST(ManifoldBlock, RepeatedUpdatesThroughBoxPlusConvergeToTheTrueOrientation) {
  // Arrange: the estimate starts 0.3 rad off; two body vectors are seen with 0.01 noise.
  core::Rng rng(5);
  const Eigen::Quaterniond truth = Exp(Eigen::Vector3d(0.4, -0.2, 1.1));
  State state = MixedState(truth * Exp(Eigen::Vector3d(0.2, -0.15, 0.15)), 0.3);
  const std::vector<Eigen::Vector3d> body{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0.6, 0.8)};
  const double sigma = 0.01;

  // Act: 20 updates of 6 rows each.
  for (int n = 0; n < 20; ++n) {
    std::vector<MeasurementRow> rows;
    std::vector<double> innovations;
    for (const auto& v : body) {
      const Eigen::Vector3d z = truth.toRotationMatrix() * v;
      for (int i = 0; i < 3; ++i) {
        rows.push_back(RotatedComponentRow(state, v, i, sigma * sigma));
        innovations.push_back(z(i) + rng.Normal(0.0, sigma) - rows.back().predicted);
      }
    }
    ASSERT_TRUE(Update(state, rows, innovations).applied);
  }

  // Assert: within a few sigma of the truth, unit norm, and the position and wall untouched
  // (uncorrelated with the orientation).
  const double error_rad = Orientation(state).angularDistance(truth);
  const double sigma_rad = std::sqrt(state.Covariance(BlockKey(kOrientation, 0)).trace());
  EXPECT_LT(error_rad, 4.0 * sigma_rad) << "error " << error_rad << " rad, sigma " << sigma_rad;
  EXPECT_LT(error_rad, 0.01);
  EXPECT_NEAR(Orientation(state).norm(), 1.0, 1e-12);
  EXPECT_TRUE(state.Mean(BlockKey(blocks::kPosition, 0)).isApprox(Eigen::Vector2d(1.0, 2.0), 1e-15));
  EXPECT_DOUBLE_EQ(state.Mean(BlockKey(blocks::kWallOffset, 3))(0), 0.25);
}

TEST(ManifoldBlock, AugmentAndMarginalizeKeepTheLaterBlocksMeanValuesInPlace) {
  State state = MixedState(Eigen::Quaterniond::Identity(), 0.1);
  CovarianceOps::Augment(state, blocks::kVirtualAnchor, 9, Eigen::Vector2d(4.0, 5.0), Eigen::MatrixXd::Zero(2, 6),
                         Eigen::Matrix2d::Identity());
  EXPECT_EQ(state.layout().At(BlockKey(blocks::kVirtualAnchor, 9)).mean_offset, 7);

  CovarianceOps::Marginalize(state, BlockKey(kOrientation, 0));

  EXPECT_TRUE(state.layout().euclidean());
  EXPECT_EQ(state.layout().dimension(), 5);
  EXPECT_EQ(state.layout().mean_dimension(), 5);
  EXPECT_DOUBLE_EQ(state.Mean(BlockKey(blocks::kWallOffset, 3))(0), 0.25);
  EXPECT_TRUE(state.Mean(BlockKey(blocks::kVirtualAnchor, 9)).isApprox(Eigen::Vector2d(4.0, 5.0)));
}

}  // namespace
}  // namespace mirage::estimation
