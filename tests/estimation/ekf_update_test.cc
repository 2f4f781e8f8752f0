// SPDX-License-Identifier: MIT
#include "mirage/estimation/ekf_update.h"

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

constexpr BlockKey kPos0(blocks::kPosition, 0);
constexpr BlockKey kWall0(blocks::kWallOffset, 0);

State ScalarState(double mean, double variance) {
  StateLayout layout;
  layout.Append(blocks::kWallOffset, 0);
  return State(layout, Eigen::VectorXd::Constant(1, mean), Eigen::MatrixXd::Constant(1, 1, variance), 0.0);
}

State PositionState(const Eigen::Vector2d& mean, const Eigen::Matrix2d& P) {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  return State(layout, mean, P, 0.0);
}

Eigen::MatrixXd Scalar(double v) { return Eigen::MatrixXd::Constant(1, 1, v); }

// ---------------------------------------------------------------------------------------------
// Closed-form cases
// ---------------------------------------------------------------------------------------------

TEST(EkfUpdate, MatchesTheScalarKalmanUpdate) {
  // x = 1, P = 4, z = 3 (innovation 2), H = 1, R = 1:
  // S = 4 + 1 = 5, K = 4 / 5 = 0.8, x+ = 1 + 0.8 * 2 = 2.6, P+ = (1 - 0.8) * 4 = 0.8,
  // NIS = 2^2 / 5 = 0.8.
  State state = ScalarState(1.0, 4.0);

  const UpdateResult result = EkfUpdate(state, Scalar(1.0), Eigen::VectorXd::Constant(1, 2.0), Scalar(1.0));

  ASSERT_TRUE(result.applied);
  EXPECT_EQ(result.rejection, UpdateRejection::kNone);
  EXPECT_EQ(result.dof, 1);
  EXPECT_NEAR(result.nis, 0.8, 1e-14);
  EXPECT_NEAR(state.mean()(0), 2.6, 1e-14);
  EXPECT_NEAR(state.covariance()(0, 0), 0.8, 1e-14);
}

TEST(EkfUpdate, ScalesTheGainByTheMeasurementCoefficient) {
  // z = 2 x + v: x = 0, P = 1, H = 2, R = 4, innovation 3:
  // S = 2*1*2 + 4 = 8, K = 1*2/8 = 0.25, x+ = 0.75, P+ = (1 - 0.25*2) * 1 = 0.5, NIS = 9/8.
  State state = ScalarState(0.0, 1.0);

  const UpdateResult result = EkfUpdate(state, Scalar(2.0), Eigen::VectorXd::Constant(1, 3.0), Scalar(4.0));

  ASSERT_TRUE(result.applied);
  EXPECT_NEAR(result.nis, 9.0 / 8.0, 1e-14);
  EXPECT_NEAR(state.mean()(0), 0.75, 1e-14);
  EXPECT_NEAR(state.covariance()(0, 0), 0.5, 1e-14);
}

TEST(EkfUpdate, CorrectsAnUnobservedCoordinateThroughTheCrossCovariance) {
  // P = [[2, 1], [1, 3]], H = [1, 0], R = 1, innovation 1.5:
  // S = 2 + 1 = 3, K = P H^T / S = [2/3, 1/3], x+ = [1, 0.5] (from 0),
  // P+ = P - K S K^T = [[2 - 4/3, 1 - 2/3], [1 - 2/3, 3 - 1/3]] = [[2/3, 1/3], [1/3, 8/3]],
  // NIS = 1.5^2 / 3 = 0.75.
  Eigen::Matrix2d P;
  P << 2, 1, 1, 3;
  State state = PositionState(Eigen::Vector2d::Zero(), P);
  Eigen::MatrixXd H(1, 2);
  H << 1, 0;

  const UpdateResult result = EkfUpdate(state, H, Eigen::VectorXd::Constant(1, 1.5), Scalar(1.0));

  ASSERT_TRUE(result.applied);
  EXPECT_NEAR(result.nis, 0.75, 1e-14);
  EXPECT_NEAR(state.mean()(0), 1.0, 1e-14);
  EXPECT_NEAR(state.mean()(1), 0.5, 1e-14);
  EXPECT_NEAR(state.covariance()(0, 0), 2.0 / 3.0, 1e-14);
  EXPECT_NEAR(state.covariance()(0, 1), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(state.covariance()(1, 0), 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(state.covariance()(1, 1), 8.0 / 3.0, 1e-14);
}

TEST(EkfUpdate, ReportsTheNisOfAStackedMeasurement) {
  // P = I, H = I, R = diag(1, 3) -> S = diag(2, 4); innovation [2, -2]:
  // NIS = 4/2 + 4/4 = 3 with 2 degrees of freedom.
  State state = PositionState(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity());
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::MatrixXd R = Eigen::Vector2d(1.0, 3.0).asDiagonal();

  const UpdateResult result = EkfUpdate(state, H, Eigen::Vector2d(2.0, -2.0), R);

  ASSERT_TRUE(result.applied);
  EXPECT_EQ(result.dof, 2);
  EXPECT_NEAR(result.nis, 3.0, 1e-14);
  // K = diag(1/2, 1/4): x+ = [1, -0.5], P+ = diag(1/2, 3/4).
  EXPECT_NEAR(state.mean()(0), 1.0, 1e-14);
  EXPECT_NEAR(state.mean()(1), -0.5, 1e-14);
  EXPECT_NEAR(state.covariance()(0, 0), 0.5, 1e-14);
  EXPECT_NEAR(state.covariance()(1, 1), 0.75, 1e-14);
  EXPECT_NEAR(state.covariance()(0, 1), 0.0, 1e-14);
}

TEST(EkfUpdate, StackedAndSequentialIndependentMeasurementsGiveTheSamePosteriorAndTotalNis) {
  // For a linear model with independent noise the joint likelihood factorises, so both the
  // posterior and the summed NIS (nu^T S^-1 nu = sum of the sequential quadratic forms) agree.
  Eigen::Matrix2d P;
  P << 0.5, 0.1, 0.1, 0.3;
  const Eigen::Vector2d x0(2.0, 1.0);
  Eigen::MatrixXd H(3, 2);
  H << 0.8, 0.6, -1.0, 0.0, 0.0, 1.0;
  const Eigen::Vector3d z(2.3, -1.9, 1.2);
  const Eigen::Vector3d sigma2(0.01, 0.04, 0.02);
  State stacked = PositionState(x0, P);
  State sequential = PositionState(x0, P);

  const UpdateResult joint =
      EkfUpdate(stacked, H, z - H * x0, Eigen::MatrixXd(sigma2.asDiagonal()));
  double nis_sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::MatrixXd Hi = H.row(i);
    const Eigen::VectorXd nu = Eigen::VectorXd::Constant(1, z(i)) - Hi * sequential.mean();
    nis_sum += EkfUpdate(sequential, Hi, nu, Scalar(sigma2(i))).nis;
  }

  EXPECT_EQ(joint.dof, 3);
  EXPECT_NEAR(joint.nis, nis_sum, 1e-10);
  EXPECT_TRUE(stacked.mean().isApprox(sequential.mean(), 1e-12));
  EXPECT_TRUE(stacked.covariance().isApprox(sequential.covariance(), 1e-10));
}

// ---------------------------------------------------------------------------------------------
// Rejections
// ---------------------------------------------------------------------------------------------

TEST(EkfUpdate, RejectsAnEmptyMeasurementAndLeavesTheStateAlone) {
  State state = PositionState(Eigen::Vector2d(1, 2), Eigen::Matrix2d::Identity());
  const State before = state;

  const UpdateResult result = EkfUpdate(state, Eigen::MatrixXd(0, 2), Eigen::VectorXd(0), Eigen::MatrixXd(0, 0));

  EXPECT_FALSE(result.applied);
  EXPECT_EQ(result.rejection, UpdateRejection::kNoMeasurements);
  EXPECT_EQ(result.dof, 0);
  EXPECT_EQ(state.mean(), before.mean());
  EXPECT_EQ(state.covariance(), before.covariance());
}

TEST(EkfUpdate, RejectsANegativeInnovationCovarianceAndLeavesTheStateAlone) {
  // P = 1, R = -2 -> S = -1 < 0.
  State state = ScalarState(1.0, 1.0);

  const UpdateResult result = EkfUpdate(state, Scalar(1.0), Eigen::VectorXd::Constant(1, 0.5), Scalar(-2.0));

  EXPECT_FALSE(result.applied);
  EXPECT_EQ(result.rejection, UpdateRejection::kNotPositiveDefinite);
  EXPECT_DOUBLE_EQ(state.mean()(0), 1.0);
  EXPECT_DOUBLE_EQ(state.covariance()(0, 0), 1.0);
}

TEST(EkfUpdate, RejectsAnIndefiniteInnovationCovariance) {
  // P = I, H = I, R = diag(1, -3) -> S = diag(2, -2): one negative eigenvalue.
  State state = PositionState(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity());
  const Eigen::MatrixXd R = Eigen::Vector2d(1.0, -3.0).asDiagonal();

  const UpdateResult result = EkfUpdate(state, Eigen::MatrixXd::Identity(2, 2), Eigen::Vector2d(1, 1), R);

  EXPECT_FALSE(result.applied);
  EXPECT_EQ(result.rejection, UpdateRejection::kNotPositiveDefinite);
  EXPECT_EQ(state.mean(), Eigen::VectorXd(Eigen::Vector2d::Zero()));
}

TEST(EkfUpdate, RejectsASingularInnovationCovariance) {
  // H = 0 and R = 0 -> S = 0, which has no Cholesky factor.
  State state = PositionState(Eigen::Vector2d::Zero(), Eigen::Matrix2d::Identity());

  const UpdateResult result =
      EkfUpdate(state, Eigen::MatrixXd::Zero(1, 2), Eigen::VectorXd::Constant(1, 1.0), Scalar(0.0));

  EXPECT_FALSE(result.applied);
  EXPECT_EQ(result.rejection, UpdateRejection::kNotPositiveDefinite);
}

// ---------------------------------------------------------------------------------------------
// Monte-Carlo consistency
// ---------------------------------------------------------------------------------------------

// Quantile of chi^2 with k degrees of freedom by the Wilson-Hilferty approximation
// chi^2_k(q) ~ k (1 - 2/(9k) + z_q sqrt(2/(9k)))^3, accurate to well under 0.1 % for k >= 1000.
double ChiSquareQuantile(double k, double z) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

struct ConsistencyResult {
  double mean_nees = 0.0;  // average over trials of e^T P^-1 e (2 dof each)
  double mean_nis = 0.0;   // average over all scalar updates (1 dof each)
  int updates = 0;
};

// Linear-Gaussian 2-D position: truth x ~ N(m0, P0); three range-like linear measurements
// z_i = u_i^T x + v_i, v_i ~ N(0, sigma^2), where u_i is the unit vector from anchor i to the prior
// mean (the linearised range direction), applied one at a time. The filter believes the noise
// standard deviation is filter_sigma.
ConsistencyResult RunConsistencyTrials(int trials, double true_sigma, double filter_sigma) {
  const Eigen::Vector2d m0(2.5, 2.0);
  Eigen::Matrix2d P0;
  P0 << 0.25, 0.05, 0.05, 0.16;
  const Eigen::Matrix2d L = P0.llt().matrixL();
  const std::vector<Eigen::Vector2d> anchors{{0.0, 0.0}, {6.0, 0.0}, {0.0, 5.0}};
  core::Rng rng(2014);
  ConsistencyResult out;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Vector2d truth = m0 + L * testing::NormalVec2(rng);
    State state = PositionState(m0, P0);
    for (const auto& anchor : anchors) {
      const Eigen::RowVector2d u = (m0 - anchor).normalized().transpose();
      const double z = u * truth + rng.Normal(0.0, true_sigma);
      const Eigen::VectorXd nu = Eigen::VectorXd::Constant(1, z - u * state.mean().head<2>());
      const UpdateResult r = EkfUpdate(state, Eigen::MatrixXd(u), nu, Scalar(filter_sigma * filter_sigma));
      EXPECT_TRUE(r.applied);
      out.mean_nis += r.nis;
      ++out.updates;
    }
    const Eigen::Vector2d e = truth - state.mean().head<2>();
    out.mean_nees += e.dot(state.covariance().ldlt().solve(e));
  }
  out.mean_nees /= trials;
  out.mean_nis /= out.updates;
  return out;
}

TEST(EkfUpdateConsistency, AverageNeesAndNisOfALinearGaussianFilterLieInsideChiSquareBounds) {
  // With N trials, N * mean NEES ~ chi^2(2N) and M * mean NIS ~ chi^2(M) for M = 3N scalar updates
  // (Bar-Shalom, Li & Kirubarajan 2001, Sec. 5.4): the trials are independent, and so are the
  // sequential innovations of a consistent linear filter. Two-sided 99 % acceptance region, z = 2.5758:
  // for N = 1000, mean NEES in [1.841, 2.167]; mean NIS (M = 3000) in [0.935, 1.068].
  const int trials = 1000;
  const double z99 = 2.5758;
  const double nees_lo = ChiSquareQuantile(2.0 * trials, -z99) / trials;
  const double nees_hi = ChiSquareQuantile(2.0 * trials, z99) / trials;
  const double nis_lo = ChiSquareQuantile(3.0 * trials, -z99) / (3.0 * trials);
  const double nis_hi = ChiSquareQuantile(3.0 * trials, z99) / (3.0 * trials);
  ASSERT_NEAR(nees_lo, 1.841, 0.002);
  ASSERT_NEAR(nees_hi, 2.167, 0.002);

  const ConsistencyResult r = RunConsistencyTrials(trials, 0.1, 0.1);

  EXPECT_EQ(r.updates, 3 * trials);
  EXPECT_GT(r.mean_nees, nees_lo);
  EXPECT_LT(r.mean_nees, nees_hi);
  EXPECT_GT(r.mean_nis, nis_lo);
  EXPECT_LT(r.mean_nis, nis_hi);
}

TEST(EkfUpdateConsistency, TheNeesBoundFlagsAFilterThatUnderstatesItsNoise) {
  // The same trials with the filter assuming half the true noise sigma: the posterior covariance
  // is roughly 4x too small, so the average NEES must leave the 99 % region from above.
  // The NIS leaves its region too, by less (about 2 instead of 1): the first update's S is
  // dominated by the correct prior, only the later ones by the understated R.
  const int trials = 1000;
  const double nees_hi = ChiSquareQuantile(2.0 * trials, 2.5758) / trials;
  const double nis_hi = ChiSquareQuantile(3.0 * trials, 2.5758) / (3.0 * trials);

  const ConsistencyResult r = RunConsistencyTrials(trials, 0.1, 0.05);

  EXPECT_GT(r.mean_nees, 2.0 * nees_hi);  // about 8 = 4 x 2
  EXPECT_GT(r.mean_nis, nis_hi);
}

// ---------------------------------------------------------------------------------------------
// Sparse Jacobian and standard covariance form (the SLAM tracker's fast path)
// ---------------------------------------------------------------------------------------------

TEST(EkfUpdate, SparseJacobianAndStandardFormAgreeWithDenseJoseph) {
  // A 12-dimensional state with a random SPD covariance and 5 rows of 4 non-zeros each, as a
  // range row to a VA has (agent position and VA position columns).
  core::Rng rng(3, 0);
  const int n = 12;
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = rng.Normal(0.0, 1.0);
  }
  const Eigen::MatrixXd P = A * A.transpose() + Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x(i) = rng.Normal(0.0, 1.0);
  StateLayout layout;
  for (int b = 0; b < n / 2; ++b) layout.Append(blocks::kVirtualAnchor, b);
  const State prior(layout, x, P, 0.0);

  const int m = 5;
  Eigen::MatrixXd H_dense = Eigen::MatrixXd::Zero(m, n);
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < m; ++r) {
    for (const int c : {0, 1, 2 + 2 * r, 3 + 2 * r}) {
      const double v = rng.Normal(0.0, 1.0);
      H_dense(r, c) = v;
      entries.emplace_back(r, c, v);
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> H_sparse(m, n);
  H_sparse.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd nu(m);
  for (int r = 0; r < m; ++r) nu(r) = rng.Normal(0.0, 1.0);
  const Eigen::MatrixXd R = 0.3 * Eigen::MatrixXd::Identity(m, m);

  State dense_joseph = prior, sparse_joseph = prior, sparse_standard = prior;
  const auto a = EkfUpdate(dense_joseph, H_dense, nu, R);
  const auto b = EkfUpdate(sparse_joseph, H_sparse, nu, R);
  const auto c = EkfUpdate(sparse_standard, H_sparse, nu, R, CovarianceForm::kStandard);
  ASSERT_TRUE(a.applied && b.applied && c.applied);
  EXPECT_NEAR(a.nis, b.nis, 1e-10);
  EXPECT_LT((dense_joseph.mean() - sparse_joseph.mean()).norm(), 1e-10);
  EXPECT_LT((dense_joseph.covariance() - sparse_joseph.covariance()).norm(), 1e-10);
  EXPECT_LT((dense_joseph.mean() - sparse_standard.mean()).norm(), 1e-10);
  EXPECT_LT((dense_joseph.covariance() - sparse_standard.covariance()).norm(), 1e-9);
  EXPECT_EQ(sparse_standard.covariance(), sparse_standard.covariance().transpose());
}


// ---------------------------------------------------------------------------------------------
// The row-based update path
// ---------------------------------------------------------------------------------------------

// Two rows on [position | wall]: x-range and a row touching both blocks.
std::vector<MeasurementRow> TwoRows(const State& state) {
  const Block position = state.layout().At(kPos0);
  const Block wall = state.layout().At(kWall0);
  MeasurementRow a;
  a.predicted = 1.0;
  a.variance = 0.04;
  a.Add(position, Eigen::RowVector2d(1.0, 0.0));
  MeasurementRow b;
  b.predicted = 2.0;
  b.variance = 0.09;
  b.Add(position, Eigen::RowVector2d(0.6, 0.8));
  b.Add(wall, Eigen::Matrix<double, 1, 1>(-2.0));
  return {a, b};
}

State PositionAndWall() {
  StateLayout layout;
  layout.Append(blocks::kPosition, 0);
  layout.Append(blocks::kWallOffset, 0);
  Eigen::Matrix3d P;
  P << 0.5, 0.1, 0.05, 0.1, 0.4, -0.02, 0.05, -0.02, 0.01;
  return State(layout, Eigen::Vector3d(1.0, 2.0, 0.1), P, 0.0);
}

TEST(Update, RowsGiveTheSamePosteriorAsTheirStackedMatrixForm) {
  State by_rows = PositionAndWall();
  State by_matrix = by_rows;
  const auto rows = TwoRows(by_rows);
  const std::vector<double> nu{0.3, -0.2};
  Eigen::MatrixXd H(2, 3);
  H << 1.0, 0.0, 0.0, 0.6, 0.8, -2.0;

  const auto a = Update(by_rows, rows, nu);
  const auto b = EkfUpdate(by_matrix, H, Eigen::Vector2d(0.3, -0.2), Eigen::Vector2d(0.04, 0.09).asDiagonal().toDenseMatrix());

  ASSERT_TRUE(a.applied && b.applied);
  EXPECT_NEAR(a.nis, b.nis, 1e-12);
  EXPECT_TRUE(by_rows.mean().isApprox(by_matrix.mean(), 1e-12));
  EXPECT_TRUE(by_rows.covariance().isApprox(by_matrix.covariance(), 1e-12));
}

TEST(Update, AWeightDividesTheRowsVarianceAsTheRobustHookPromises) {
  // A weight of 0.25 on row 1 is the same update as row 1 with four times its variance.
  State weighted = PositionAndWall();
  State inflated = weighted;
  auto rows = TwoRows(weighted);
  const std::vector<double> nu{0.3, -0.2};
  const std::vector<double> weights{1.0, 0.25};
  UpdateOptions options;
  options.weights = weights;

  Update(weighted, rows, nu, options);
  rows[1].variance *= 4.0;
  Update(inflated, rows, nu);

  EXPECT_TRUE(weighted.mean().isApprox(inflated.mean(), 1e-14));
  EXPECT_TRUE(weighted.covariance().isApprox(inflated.covariance(), 1e-14));
  // ... and not the unweighted update.
  State plain = PositionAndWall();
  Update(plain, TwoRows(plain), nu);
  EXPECT_FALSE(plain.mean().isApprox(weighted.mean(), 1e-6));
}

TEST(InnovationVariance, EqualsHPHtPlusR) {
  const State state = PositionAndWall();
  const auto rows = TwoRows(state);
  const Eigen::MatrixXd H = Eigen::MatrixXd(StackJacobian(state, rows));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Eigen::RowVectorXd h = H.row(static_cast<Eigen::Index>(i));
    EXPECT_NEAR(InnovationVariance(state, rows[i]), (h * state.covariance() * h.transpose())(0, 0) + rows[i].variance, 1e-15);
  }
}

TEST(MeasurementRow, ABlockAddedTwiceSumsIntoOneEntry) {
  // A path that meets the same wall twice has two derivatives for its offset; they add.
  const State state = PositionAndWall();
  MeasurementRow row;
  row.Add(state.layout().At(kWall0), Eigen::Matrix<double, 1, 1>(0.5));
  row.Add(state.layout().At(kWall0), Eigen::Matrix<double, 1, 1>(-2.0));
  EXPECT_EQ(row.block_count, 1);
  EXPECT_DOUBLE_EQ(row.jacobians[0](0), -1.5);
}

}  // namespace
}  // namespace mirage::estimation
