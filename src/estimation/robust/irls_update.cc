// SPDX-License-Identifier: MIT
#include "mirage/estimation/robust/irls_update.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <span>

#include <Eigen/Cholesky>

namespace mirage::estimation {

const core::OptionsDescriptor<IrlsOptions>& IrlsOptionsDescriptor() {
  using core::ValueRange;
  using O = IrlsOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("estimation::IrlsOptions");
    d.Section(&O::hampel,
              {.key = "hampel", .doc = "Hampel tanh weight of every whitened row (Bordoy Eq. 5.24, 5.30)."},
              HampelOptionsDescriptor());
    d.Integer(&O::max_iterations, {.key = "max_iterations",
                                   .range = ValueRange::Closed(1.0, 1000.0),
                                   .doc = "Reweighting iterations after the least-squares start. 10 (not in the "
                                          "thesis)."});
    d.Number(&O::tolerance, {.key = "tolerance",
                             .range = ValueRange::Positive(),
                             .doc = "Stop when the last step is shorter than this many posterior standard "
                                    "deviations. 1e-6."});
    d.Number(&O::prior_weight_floor, {.key = "prior_weight_floor",
                                      .range = ValueRange::LeftOpen(0.0, 1.0),
                                      .doc = "Smallest weight of a prior row; keeps the posterior covariance finite "
                                             "when no measurement informs a rejected prior direction. 1e-3."});
    d.Boolean(&O::start_at_prior,
              {.key = "start_at_prior",
               .doc = "Start the reweighting at the prediction (dx = 0) when that gives the rows more total "
                      "Hampel weight than the unweighted fit, which can absorb agreeing outliers."});
    d.Boolean(&O::robust, {.key = "robust",
                           .doc = "false: all weights 1, the plain EKF update (for comparison)."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const IrlsOptions& options) { return IrlsOptionsDescriptor().Validate(options); }

std::optional<IrlsResult> IrlsUpdate(const Eigen::MatrixXd& P_hat, const Eigen::MatrixXd& H,
                                     const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R,
                                     const IrlsOptions& options) {
  const Eigen::Index n = P_hat.rows();
  const Eigen::Index m = H.rows();
  assert(P_hat.cols() == n && H.cols() == n && innovation.size() == m && R.rows() == m && R.cols() == m);

  // V = blkdiag(L_P, L_R), Eq. (5.29): the two factors, each computed once.
  const Eigen::LLT<Eigen::MatrixXd> llt_p(P_hat);
  if (llt_p.info() != Eigen::Success) return std::nullopt;
  const Eigen::LLT<Eigen::MatrixXd> llt_r(R);
  if (m > 0 && llt_r.info() != Eigen::Success) return std::nullopt;

  // N = V^-1 [I; H] (5.26) and Y = V^-1 [0; y] (5.27)-(5.28) in innovation form.
  Eigen::MatrixXd N(n + m, n);
  Eigen::VectorXd Y = Eigen::VectorXd::Zero(n + m);
  N.topRows(n) = llt_p.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
  if (m > 0) {
    N.bottomRows(m) = llt_r.matrixL().solve(H);
    Y.tail(m) = llt_r.matrixL().solve(innovation);
  }

  IrlsResult result;
  result.weights = Eigen::VectorXd::Ones(n + m);
  Eigen::MatrixXd A(n, n);
  Eigen::LLT<Eigen::MatrixXd> llt_a(n);
  // Weighted least squares, Eq. (5.25): dx = (N^T W N)^-1 N^T W Y.
  const auto solve = [&](Eigen::VectorXd& dx) {
    A.noalias() = N.transpose() * result.weights.asDiagonal() * N;
    llt_a.compute(A);
    if (llt_a.info() != Eigen::Success) return false;
    dx = llt_a.solve(N.transpose() * result.weights.asDiagonal() * Y);
    return true;
  };

  if (!solve(result.dx)) return std::nullopt;
  if (options.robust && options.start_at_prior) {
    // Two starts: the unweighted fit, and the prediction (dx = 0). The fit absorbs outliers that
    // agree with each other into the emission time, the prediction fails when it is itself the
    // outlier. Start where more whitened rows are consistent (|r| <= 3, the model's own unit
    // scale, the same for both starts); ties keep the fit.
    const auto consistent_rows = [&](const Eigen::VectorXd& dx) { return ((Y - N * dx).array().abs() <= 3.0).count(); };
    const Eigen::VectorXd at_prior = Eigen::VectorXd::Zero(n);
    if (consistent_rows(at_prior) > consistent_rows(result.dx)) result.dx = at_prior;
  }
  result.converged = true;
  if (options.robust) {
    result.converged = false;
    Eigen::VectorXd residual(n + m);
    Eigen::VectorXd next(n);
    for (int k = 1; k <= options.max_iterations; ++k) {
      // Eq. (5.30): every whitened residual against the previous estimate.
      residual.noalias() = Y - N * result.dx;
      result.hampel = HampelFromResiduals(std::span<const double>(residual.data(), static_cast<std::size_t>(n + m)),
                                          options.hampel);
      for (Eigen::Index j = 0; j < n + m; ++j) result.weights(j) = HampelWeight(residual(j), result.hampel);
      for (Eigen::Index j = 0; j < n; ++j) {
        result.weights(j) = std::max(result.weights(j), options.prior_weight_floor);
      }
      if (!solve(next)) return std::nullopt;
      const Eigen::VectorXd step = next - result.dx;
      result.dx = next;
      result.iterations = k;
      if (std::sqrt(std::max(0.0, step.dot(A * step))) <= options.tolerance) {
        result.converged = true;
        break;
      }
    }
  }
  result.P = llt_a.solve(Eigen::MatrixXd::Identity(n, n));
  result.P = 0.5 * (result.P + result.P.transpose()).eval();
  return result;
}

}  // namespace mirage::estimation
