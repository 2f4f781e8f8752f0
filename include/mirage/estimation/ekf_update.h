// SPDX-License-Identifier: MIT
// The one EKF measurement update (Lafer 2014 Eq. 3.20-3.24): the measurement models hand in
// linearised rows (measurement_row.h), the update stacks them into a sparse H, forms S and K,
// corrects the mean through each block's boxplus and the covariance in the Joseph or the
// standard form. It knows nothing about ranges or UWB. The weights hook is where robust
// M-estimators (iteratively reweighted least squares) plug in: a weight w_i divides row i's
// variance.
#pragma once

#include <span>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "mirage/estimation/measurement_row.h"
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

/// Options of one update.
struct UpdateOptions {
  CovarianceForm form = CovarianceForm::kJoseph;
  /// Robust weights w_i in (0, 1], one per row: row i enters with variance R_ii / w_i (the
  /// IRLS step of an M-estimator). Empty: every weight is 1.
  std::span<const double> weights;
};

/// Applies the rows' measurements, innovations nu_i = z_i - h_i(x^-) (one per row).
UpdateResult Update(State& state, std::span<const MeasurementRow> rows, std::span<const double> innovations,
                    const UpdateOptions& options = {});

/// The stacked H (rows x state.dimension(), row-major sparse) of the rows at `state`'s layout.
Eigen::SparseMatrix<double, Eigen::RowMajor> StackJacobian(const State& state, std::span<const MeasurementRow> rows);

/// The matrix form the rows are stacked into: z = h(x) + v, v ~ N(0, R), linearised as H, with
/// innovation nu = z - h(x^-). For callers that already hold H (the error bounds).
UpdateResult EkfUpdate(State& state, const Eigen::SparseMatrix<double, Eigen::RowMajor>& H,
                       const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R,
                       CovarianceForm form = CovarianceForm::kJoseph);
/// The same with a dense H (small states, tests).
UpdateResult EkfUpdate(State& state, const Eigen::MatrixXd& H, const Eigen::VectorXd& innovation,
                       const Eigen::MatrixXd& R, CovarianceForm form = CovarianceForm::kJoseph);

}  // namespace mirage::estimation
