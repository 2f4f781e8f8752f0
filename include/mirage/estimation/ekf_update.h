// SPDX-License-Identifier: MIT
// Generic EKF measurement update (Lafer 2014 Eq. 3.20-3.24, Joseph form for the covariance).
// It knows nothing about ranges or UWB: callers stack H, the innovation and R.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Why an update was not applied.
enum class UpdateRejection {
  kNone,                  ///< applied
  kNoMeasurements,        ///< empty H
  kNotPositiveDefinite,   ///< S = H P H^T + R could not be factorised
};

/// Outcome of one update.
struct UpdateResult {
  bool applied = false;
  /// Normalised innovation squared nu^T S^{-1} nu (chi^2 with `dof` degrees of freedom when the
  /// filter is consistent).
  double nis = 0.0;
  int dof = 0;
  UpdateRejection rejection = UpdateRejection::kNone;
};

/// How the covariance is updated.
enum class CovarianceForm {
  kJoseph,    ///< (I - K H) P (I - K H)^T + K R K^T: keeps P positive definite under rounding
  kStandard,  ///< P - K H P, symmetrised: half the cost; exact for the optimal gain
};

/// Applies z = h(x) + v, v ~ N(0, R), linearised as H, with innovation nu = z - h(x^-).
UpdateResult EkfUpdate(State& state, const Eigen::MatrixXd& H, const Eigen::VectorXd& innovation,
                       const Eigen::MatrixXd& R, CovarianceForm form = CovarianceForm::kJoseph);

/// The same with a sparse H (SLAM: a range row has 4 non-zeros among hundreds of columns), which
/// makes P H^T and H P H^T cost O(n m) and O(m^2) instead of O(n^2 m) and O(n m^2); the
/// covariance update (O(n^2 m)) is then the only term quadratic in the state size.
UpdateResult EkfUpdate(State& state, const Eigen::SparseMatrix<double, Eigen::RowMajor>& H,
                       const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R,
                       CovarianceForm form = CovarianceForm::kJoseph);

}  // namespace mirage::estimation
