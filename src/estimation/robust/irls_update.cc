// SPDX-License-Identifier: MIT
#include "mirage/estimation/robust/irls_update.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>
#include <span>
#include <utility>

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
               .doc = "Reweight from the unweighted fit and from the prediction (dx = 0) and keep the solution "
                      "that explains more whitened rows within 3 (the fit can absorb agreeing outliers, the "
                      "prediction can itself be off)."});
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

  Eigen::MatrixXd A(n, n);
  Eigen::LLT<Eigen::MatrixXd> llt_a(n);
  // Weighted least squares, Eq. (5.25): dx = (N^T W N)^-1 N^T W Y.
  const auto solve = [&](const Eigen::VectorXd& weights, Eigen::VectorXd& dx) {
    A.noalias() = N.transpose() * weights.asDiagonal() * N;
    llt_a.compute(A);
    if (llt_a.info() != Eigen::Success) return false;
    dx = llt_a.solve(N.transpose() * weights.asDiagonal() * Y);
    return true;
  };
  // The reweighting (5.30) from dx0 until the step is below the tolerance; the result's P is
  // (N^T W N)^-1 with the last weights.
  const auto reweight = [&](const Eigen::VectorXd& dx0) -> std::optional<IrlsResult> {
    IrlsResult result;
    result.weights = Eigen::VectorXd::Ones(n + m);
    result.dx = dx0;
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
      if (!solve(result.weights, next)) return std::nullopt;
      const Eigen::VectorXd step = next - result.dx;
      result.dx = next;
      result.iterations = k;
      if (std::sqrt(std::max(0.0, step.dot(A * step))) <= options.tolerance) {
        result.converged = true;
        break;
      }
    }
    result.P = llt_a.solve(Eigen::MatrixXd::Identity(n, n));
    result.P = 0.5 * (result.P + result.P.transpose()).eval();
    return result;
  };

  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n + m);
  Eigen::VectorXd fit(n);
  if (!solve(ones, fit)) return std::nullopt;
  if (!options.robust) {
    IrlsResult result;
    result.weights = ones;
    result.dx = fit;
    result.converged = true;
    result.P = llt_a.solve(Eigen::MatrixXd::Identity(n, n));
    result.P = 0.5 * (result.P + result.P.transpose()).eval();
    return result;
  }
  auto best = reweight(fit);
  if (!best || !options.start_at_prior) return best;
  // The redescending weights make the objective non-convex: the reweighting from the unweighted
  // fit (which absorbs outliers that agree with each other, e.g. late stamps pulling the emission
  // time and the position together) and from the prediction (dx = 0, wrong when the prediction is
  // itself the outlier) can settle in different minima. Both are run and the one that explains
  // more rows within 3 of the model's own unit scale (the same for both) is kept; ties go to the
  // smaller sum of squares of those rows, then to the fit. The second run is skipped when the
  // first explains every row.
  const auto consensus = [&](const Eigen::VectorXd& dx) {
    const Eigen::ArrayXd r = (Y - N * dx).array();
    const auto inlier = (r.abs() <= 3.0);
    return std::pair<Eigen::Index, double>(inlier.count(), inlier.select(r.square(), 0.0).sum());
  };
  const auto best_consensus = consensus(best->dx);
  if (best_consensus.first == n + m) return best;
  auto from_prior = reweight(Eigen::VectorXd::Zero(n));
  if (!from_prior) return best;
  const auto prior_consensus = consensus(from_prior->dx);
  if (prior_consensus.first > best_consensus.first ||
      (prior_consensus.first == best_consensus.first && prior_consensus.second < best_consensus.second)) {
    return from_prior;
  }
  return best;
}

}  // namespace mirage::estimation
