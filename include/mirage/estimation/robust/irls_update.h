// SPDX-License-Identifier: MIT
// The robust EKF (REKF) measurement update as iteratively reweighted least squares (Bordoy 2020
// PhD thesis, Univ. Freiburg, Sec. 5.2, Eq. 5.25-5.30, after El-Hawary & Jing 1995): the prior and
// the measurements are stacked into one whitened regression, N = V^-1 [I; H] (5.26), V V^T =
// blkdiag(P_hat, R) (5.29), and solved with Hampel weights (hampel.h) on every row, prior rows
// included, so a wrong prediction is down-weighted as well as a wrong measurement.
// Choices where the thesis is silent (digest Sec. 2.7 [GAP]/[SUG]):
//  - Innovation form: the unknown is dx = x - x_hat and the rows are -L_P^-1 dx (prior, target 0)
//    and L_R^-1 (y - H dx) with y = z - h(x_hat). This is (5.27)-(5.28) with x_hat subtracted
//    (z_tilde - H x = y - H dx), and avoids differencing the large numbers x_hat and H x_hat.
//  - V is blkdiag(L_P, L_R), the Cholesky factors of P_hat and R, each factored once per update.
//  - Iteration 0 is the plain least-squares solution (all weights 1, i.e. the EKF), and, with
//    start_at_prior, also the prior (dx = 0); the converged solution with the larger consensus is
//    kept (see IrlsOptions::start_at_prior).
//  - The scale a = 1.4826 MAD / theta is re-estimated at every iteration from all n + m whitened
//    residuals and floored at HampelOptions::min_a.
//  - Prior-row weights are floored at prior_weight_floor > 0, so N^T W N stays positive definite
//    even when no measurement informs a state whose prior row was rejected: that state's variance
//    is then inflated by at most 1 / floor instead of becoming infinite.
//  - Posterior covariance P = (N^T W N)^-1 with the last weights (digest [SUG]); with all weights 1
//    it equals the EKF's (I - K H) P_hat.
//  - Convergence: the last step's length in the posterior metric, sqrt(dx_step^T N^T W N dx_step)
//    (standard deviations of the estimate), below `tolerance`; at most max_iterations reweightings.
//  - Whitened rows are combinations: L_P^-1 is lower triangular, so prior row j mixes states 0..j
//    (one state per row when P_hat is diagonal), and likewise for measurement rows under a full R.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/options_descriptor.h"
#include "mirage/estimation/robust/hampel.h"

namespace mirage::estimation {

/// Options of the REKF update.
struct IrlsOptions {
  /// The Hampel weight of every whitened row, Eq. (5.24) and (5.30).
  HampelOptions hampel = {};
  /// Reweighting iterations after the least-squares start, in [1, 1000]. 10: the thesis gives no
  /// count; a redescending weight settles in a few iterations when the start is near the inliers.
  int max_iterations = 10;
  /// Stop when the last step is shorter than this many posterior standard deviations, > 0. 1e-6:
  /// far below the estimate's uncertainty.
  double tolerance = 1e-6;
  /// Smallest weight of a prior row, in (0, 1]. 1e-3 inflates a rejected prior direction's standard
  /// deviation by at most ~32 and keeps N^T W N invertible when no measurement informs it.
  double prior_weight_floor = 1e-3;
  /// Reweight from two starts, the unweighted least-squares fit and the prediction (dx = 0), and
  /// keep the solution that explains more whitened rows within 3 (ties: the smaller sum of their
  /// squares): outliers that agree with each other (late stamps pulling the emission time and the
  /// position together) hide in small residuals of the fit, while a prediction that is itself off
  /// (an unknown velocity after one step) loses to the fit. Eq. 5.30 evaluates w at x^{k-1} and
  /// leaves x^0 open. The second start is skipped when the first solution explains every row.
  bool start_at_prior = true;
  /// false: all weights stay 1 and the result is the plain EKF update (for comparison).
  bool robust = true;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<IrlsOptions>& IrlsOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const IrlsOptions& options);

/// The REKF update's result.
struct IrlsResult {
  /// The correction of the state, x = x_hat + dx (state units).
  Eigen::VectorXd dx;
  /// The posterior covariance (N^T W N)^-1 (n x n, state units squared).
  Eigen::MatrixXd P;
  /// The weights of the last solve: the n whitened prior rows first, then the m measurement rows.
  Eigen::VectorXd weights;
  /// The Hampel parameters of the last reweighting (whitened units; defaults when not robust).
  HampelParameters hampel;
  /// Reweighting iterations done (0 when not robust).
  int iterations = 0;
  /// The last step was below the tolerance (always true when not robust).
  bool converged = false;
};

/// The REKF measurement update, Eq. (5.25)-(5.30), in innovation form around the prior mean.
/// std::nullopt when P_hat or R is not positive definite (or the weighted normal matrix is not,
/// which the prior-weight floor prevents in exact arithmetic).
/// @param P_hat      prior covariance (n x n, state units squared), positive definite.
/// @param H          measurement Jacobian at x_hat (m x n, measurement unit per state unit).
/// @param innovation y = z - h(x_hat) (m, measurement units).
/// @param R          measurement noise covariance (m x m, measurement units squared), positive
///                   definite; full allowed (the weights then apply to whitened combinations).
std::optional<IrlsResult> IrlsUpdate(const Eigen::MatrixXd& P_hat, const Eigen::MatrixXd& H,
                                     const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R,
                                     const IrlsOptions& options = {});

}  // namespace mirage::estimation
