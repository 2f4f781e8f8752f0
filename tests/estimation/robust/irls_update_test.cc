// SPDX-License-Identifier: MIT
// The REKF update as IRLS (Bordoy Eq. 5.25-5.30): with all weights 1 it is the Kalman update; a
// gross outlier row is rejected while the EKF is pulled away; a wrong prior is down-weighted in
// favour of consistent measurements; the posterior stays finite; and it is fast enough for a
// 12-row, 7-state update.
#include "mirage/estimation/robust/irls_update.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "rng_vectors.h"

namespace mirage::estimation {
namespace {

// State: position (3, m), velocity (3, m/s), clock offset (1, m). Rows are linearised ranges to
// anchors in random directions plus the offset: [u^T, 0 0 0, 1].
constexpr int kN = 7;

Eigen::MatrixXd RangeRows(int m, core::Rng& rng) {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, kN);
  for (int i = 0; i < m; ++i) {
    const Vec3 u = testing::NormalVec3(rng).normalized();
    H.block<1, 3>(i, 0) = u.transpose();
    H(i, 6) = 1.0;
  }
  return H;
}

Eigen::MatrixXd RandomSpd(int n, core::Rng& rng) {
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) A(i, j) = rng.Normal();
  }
  return A * A.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
}

Eigen::VectorXd NormalVector(int n, double sigma, core::Rng& rng) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = rng.Normal(0.0, sigma);
  return v;
}

template <typename M>
Eigen::MatrixXd WithoutRow(const M& A, int row) {
  Eigen::MatrixXd out(A.rows() - 1, A.cols());
  out << A.topRows(row), A.bottomRows(A.rows() - row - 1);
  return out;
}

// The textbook Kalman update's correction K y and covariance (I - K H) P.
struct Kalman {
  Eigen::VectorXd dx;
  Eigen::MatrixXd P;
};
Kalman KalmanUpdate(const Eigen::MatrixXd& P, const Eigen::MatrixXd& H, const Eigen::VectorXd& y,
                    const Eigen::MatrixXd& R) {
  const Eigen::MatrixXd S = H * P * H.transpose() + R;
  const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
  return {K * y, (Eigen::MatrixXd::Identity(P.rows(), P.rows()) - K * H) * P};
}

// The largest Mahalanobis-per-axis error: max_i |e_i| / sqrt(P_ii).
double WorstAxisSigmas(const Eigen::VectorXd& error, const Eigen::MatrixXd& P) {
  return (error.array().abs() / P.diagonal().array().sqrt()).maxCoeff();
}

TEST(IrlsUpdate, EqualsTheKalmanUpdateWithAllWeightsOne) {
  core::Rng rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::MatrixXd P = RandomSpd(kN, rng);
    Eigen::MatrixXd H(12, kN);
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < kN; ++j) H(i, j) = rng.Normal();
    }
    // Diagonal R in even trials, full R in odd ones.
    const Eigen::VectorXd variances = NormalVector(12, 1.0, rng).array().square() + 0.1;
    const Eigen::MatrixXd R = trial % 2 == 0 ? Eigen::MatrixXd(variances.asDiagonal()) : RandomSpd(12, rng);
    const Eigen::VectorXd y = NormalVector(12, 3.0, rng);

    const auto result = IrlsUpdate(P, H, y, R, IrlsOptions{.robust = false});
    const Kalman expected = KalmanUpdate(P, H, y, R);

    ASSERT_TRUE(result.has_value());
    EXPECT_LT((result->dx - expected.dx).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((result->P - expected.P).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_TRUE((result->weights.array() == 1.0).all());
    EXPECT_EQ(result->iterations, 0);
    EXPECT_TRUE(result->converged);
  }
}

TEST(IrlsUpdate, KeepsTheKalmanUpdateWhenEveryResidualIsSmall) {
  // Innovations consistent to a tenth of a sigma: every whitened residual stays below min_a = 1,
  // so every weight is 1 and the robust update is the Kalman update.
  core::Rng rng(4);
  const Eigen::MatrixXd P = 0.04 * Eigen::MatrixXd::Identity(kN, kN);
  const Eigen::MatrixXd H = RangeRows(10, rng);
  const Eigen::MatrixXd R = 0.01 * Eigen::MatrixXd::Identity(10, 10);
  const Eigen::VectorXd y = NormalVector(10, 0.01, rng);

  const auto result = IrlsUpdate(P, H, y, R);
  const Kalman expected = KalmanUpdate(P, H, y, R);

  ASSERT_TRUE(result.has_value());
  EXPECT_TRUE((result->weights.array() == 1.0).all());
  EXPECT_TRUE(result->converged);
  EXPECT_LT((result->dx - expected.dx).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((result->P - expected.P).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(IrlsUpdate, RejectsAFiftySigmaOutlierThatPullsTheEkfAway) {
  // Prior: 0.5 m / 0.5 m/s / 0.5 m standard deviations; 10 range rows with 0.1 m noise, one of
  // them 5 m (50 sigma) long as an NLOS path would be.
  core::Rng rng(21);
  const double sigma_r = 0.1;
  const Eigen::MatrixXd P = 0.25 * Eigen::MatrixXd::Identity(kN, kN);
  const Eigen::MatrixXd H = RangeRows(10, rng);
  const Eigen::MatrixXd R = sigma_r * sigma_r * Eigen::MatrixXd::Identity(10, 10);
  const Eigen::VectorXd truth_dx = NormalVector(kN, 0.5, rng);  // x_true - x_hat, drawn from the prior
  Eigen::VectorXd y = H * truth_dx + NormalVector(10, sigma_r, rng);
  constexpr int kOutlier = 6;
  y(kOutlier) += 50.0 * sigma_r;

  const auto robust = IrlsUpdate(P, H, y, R);
  const auto ekf = IrlsUpdate(P, H, y, R, IrlsOptions{.robust = false});

  ASSERT_TRUE(robust.has_value() && ekf.has_value());
  EXPECT_TRUE(robust->converged);
  EXPECT_EQ(robust->weights(kN + kOutlier), 0.0);
  for (int i = 0; i < 10; ++i) {
    if (i != kOutlier) {
      EXPECT_GT(robust->weights(kN + i), 0.2) << "row " << i;
    }
  }
  // The oracle: the EKF without the outlier row.
  const auto oracle = IrlsUpdate(P, WithoutRow(H, kOutlier), WithoutRow(y, kOutlier),
                                 sigma_r * sigma_r * Eigen::MatrixXd::Identity(9, 9), IrlsOptions{.robust = false});
  ASSERT_TRUE(oracle.has_value());
  EXPECT_LT(WorstAxisSigmas(robust->dx - oracle->dx, robust->P), 0.5);
  // 2.1 sigma for the oracle on its worst of 7 axes with this seed's noise.
  EXPECT_LT(WorstAxisSigmas(robust->dx - truth_dx, robust->P), 2.5);
  EXPECT_GT(WorstAxisSigmas(ekf->dx - truth_dx, ekf->P), 4.0);
}

TEST(IrlsUpdate, DownWeightsAPriorThirtySigmaOff) {
  // The prediction is 30 sigma (9 m) off in position; 8 consistent range rows of 0.1 m.
  core::Rng rng(8);
  const double sigma_p = 0.3;
  const double sigma_r = 0.1;
  const Eigen::MatrixXd P = sigma_p * sigma_p * Eigen::MatrixXd::Identity(kN, kN);
  const Eigen::MatrixXd H = RangeRows(8, rng);
  const Eigen::MatrixXd R = sigma_r * sigma_r * Eigen::MatrixXd::Identity(8, 8);
  Eigen::VectorXd truth_dx = NormalVector(kN, sigma_p, rng);
  truth_dx.head<3>() += 30.0 * sigma_p * Vec3(1.0, -2.0, 0.5).normalized();
  const Eigen::VectorXd y = H * truth_dx + NormalVector(8, sigma_r, rng);

  const auto robust = IrlsUpdate(P, H, y, R);
  const auto ekf = IrlsUpdate(P, H, y, R, IrlsOptions{.robust = false});

  ASSERT_TRUE(robust.has_value() && ekf.has_value());
  EXPECT_TRUE(robust->converged);
  // The position prior rows are rejected (down to the floor); velocity's rows, which no
  // measurement informs, keep weight 1.
  for (int i = 0; i < 3; ++i) EXPECT_LT(robust->weights(i), 0.05) << "prior row " << i;
  for (int i = 3; i < 6; ++i) EXPECT_EQ(robust->weights(i), 1.0) << "prior row " << i;
  for (int i = 0; i < 3; ++i) EXPECT_GE(robust->weights(i), IrlsOptions{}.prior_weight_floor);
  for (int i = 0; i < 8; ++i) EXPECT_GT(robust->weights(kN + i), 0.2) << "row " << i;
  const Eigen::Vector3d robust_error = (robust->dx - truth_dx).head<3>();
  const Eigen::Vector3d ekf_error = (ekf->dx - truth_dx).head<3>();
  EXPECT_LT(WorstAxisSigmas(robust_error, robust->P.topLeftCorner<3, 3>()), 3.0);
  EXPECT_GT(WorstAxisSigmas(ekf_error, ekf->P.topLeftCorner<3, 3>()), 5.0);
  // The posterior is finite and positive definite; the unobserved velocity keeps its prior.
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(robust->P).info(), Eigen::Success);
  EXPECT_LT((robust->P.block<3, 3>(3, 3) - P.block<3, 3>(3, 3)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(IrlsUpdate, KeepsTheCovarianceFiniteWhenEveryPriorRowOfAnUnobservedStateIsRejected) {
  // Two states with a correlated prior (rho = 0.9); the measurements see state 1 only, 20 prior
  // sigma away. Both whitened prior rows involve the unobserved state 0 (L_P^-1 is lower
  // triangular), and both are 8-18 whitened units off at the EKF solution, far beyond b = 4
  // (the measurement rows fit exactly, so a is at its floor): both are rejected. Without the
  // floor N^T W N would be singular; with it, state 0 keeps its conditional prior variance
  // (1 - rho^2) inflated by 1 / floor.
  const Eigen::Matrix2d P{{1.0, 0.9}, {0.9, 1.0}};
  Eigen::MatrixXd H(3, 2);
  H << 0.0, 1.0, 0.0, 1.0, 0.0, 1.0;
  const Eigen::MatrixXd R = 1e-6 * Eigen::MatrixXd::Identity(3, 3);
  const Eigen::Vector3d y(20.0, 20.0, 20.0);
  const IrlsOptions options;

  const auto result = IrlsUpdate(P, H, y, R, options);

  ASSERT_TRUE(result.has_value());
  EXPECT_TRUE(result->converged);
  EXPECT_EQ(result->weights(0), options.prior_weight_floor);
  EXPECT_EQ(result->weights(1), options.prior_weight_floor);
  EXPECT_TRUE((result->weights.tail(3).array() == 1.0).all());
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(result->P).info(), Eigen::Success);
  EXPECT_NEAR(result->P(0, 0), (1.0 - 0.81) / options.prior_weight_floor, 1e-3);
  EXPECT_NEAR(result->dx(1), 20.0, 1e-3);
  EXPECT_NEAR(result->dx(0), 18.0, 1e-3);  // the prior's regression of state 0 on state 1
}

TEST(IrlsUpdate, KeepsTheSolutionThatExplainsMoreRows) {
  // One state: the prediction 0 (sigma 0.3, a step of unknown velocity), four rows at 0.3 and two
  // at 0 (sigma 0.03). At the prediction the prior row and the two agree (3 rows within 3); at the
  // unweighted fit (~0.2) only the prior row does, so a start chosen before reweighting takes the
  // prediction and rejects the four. Reweighted from the fit the solution settles at 0.3, where 5
  // rows are within 3: that one is kept.
  const Eigen::MatrixXd P = Eigen::MatrixXd::Constant(1, 1, 0.09);
  const Eigen::MatrixXd H = Eigen::MatrixXd::Ones(6, 1);
  Eigen::VectorXd y(6);
  y << 0.3, 0.3, 0.3, 0.3, 0.0, 0.0;
  const Eigen::MatrixXd R = 0.03 * 0.03 * Eigen::MatrixXd::Identity(6, 6);
  const auto robust = IrlsUpdate(P, H, y, R, IrlsOptions{});
  ASSERT_TRUE(robust.has_value());
  EXPECT_NEAR(robust->dx(0), 0.3, 0.01);
  EXPECT_LT(robust->weights(5), 0.01);  // the two rows at 0 are the outliers
  // The mirror case: two rows at 0.3 and four at 0 settle at the prediction.
  y << 0.3, 0.3, 0.0, 0.0, 0.0, 0.0;
  const auto prior = IrlsUpdate(P, H, y, R, IrlsOptions{});
  ASSERT_TRUE(prior.has_value());
  EXPECT_NEAR(prior->dx(0), 0.0, 0.01);
}

TEST(IrlsUpdate, RefusesACovarianceThatIsNotPositiveDefinite) {
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd y = Eigen::VectorXd::Ones(2);
  const Eigen::Matrix2d bad{{1.0, 2.0}, {2.0, 1.0}};
  EXPECT_FALSE(IrlsUpdate(bad, H, y, Eigen::MatrixXd::Identity(2, 2)).has_value());
  EXPECT_FALSE(IrlsUpdate(Eigen::MatrixXd::Identity(2, 2), H, y, bad).has_value());
}

TEST(IrlsOptions, DefaultsAreValidAndBadValuesAreReported) {
  EXPECT_TRUE(Validate(IrlsOptions{}).empty());
  EXPECT_FALSE(Validate(IrlsOptions{.max_iterations = 0}).empty());
  EXPECT_FALSE(Validate(IrlsOptions{.prior_weight_floor = 0.0}).empty());
  EXPECT_FALSE(Validate(IrlsOptions{.hampel = {.theta = -1.0}}).empty());
}


}  // namespace
}  // namespace mirage::estimation
