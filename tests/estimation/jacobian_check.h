// SPDX-License-Identifier: MIT
// Test helper: checks linearised rows against central differences of the prediction over EVERY
// tangent coordinate of the state (perturbed through CovarianceOps::Correct, i.e. each block's
// boxplus), so that a wrong entry, a missing block and a spurious one all fail. Used by the
// measurement-model tests and by the methods' tests of their assembled H.
#pragma once

#include <cmath>
#include <functional>
#include <span>
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/estimation/covariance_ops.h"
#include "mirage/estimation/ekf_update.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/state.h"

namespace mirage::estimation::testing {

/// The prediction of row i at a (perturbed) state.
using Prediction = std::function<double(const State& state, std::size_t row)>;

/// The stacked H of `rows` equals the central differences of `predict` at `state` within `tol`,
/// column by column, with step `step` in each tangent coordinate; the rows' predicted values
/// equal predict(state). Returns the largest absolute difference.
inline double ExpectRowsMatchCentralDifferences(const State& state, std::span<const MeasurementRow> rows,
                                                const Prediction& predict, double step, double tol,
                                                const std::string& what = "") {
  const Eigen::MatrixXd H = Eigen::MatrixXd(StackJacobian(state, rows));
  double worst = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_NEAR(rows[i].predicted, predict(state, i), 1e-9) << what << " row " << i << ": prediction";
  }
  for (int j = 0; j < state.dimension(); ++j) {
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(state.dimension());
    dx(j) = step;
    State plus = state;
    State minus = state;
    CovarianceOps::Correct(plus, dx);
    CovarianceOps::Correct(minus, -dx);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double numeric = (predict(plus, i) - predict(minus, i)) / (2.0 * step);
      const double difference = std::abs(H(static_cast<Eigen::Index>(i), j) - numeric);
      worst = std::max(worst, difference);
      EXPECT_LE(difference, tol) << what << " row " << i << " column " << j << ": analytic "
                                 << H(static_cast<Eigen::Index>(i), j) << ", central difference " << numeric;
    }
  }
  return worst;
}

/// `state` moved by an independent N(0, sigma^2) step in every tangent coordinate (through its
/// boxplus, CovarianceOps::Correct): a random state near a realistic one, at which the methods'
/// Jacobian tests check their rows again.
inline State RandomNearby(const State& state, double sigma, core::Rng& rng) {
  Eigen::VectorXd dx(state.dimension());
  for (int j = 0; j < state.dimension(); ++j) dx(j) = sigma * rng.Normal();
  State out = state;
  CovarianceOps::Correct(out, dx);
  return out;
}

}  // namespace mirage::estimation::testing
