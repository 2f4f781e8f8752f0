// SPDX-License-Identifier: MIT
#include "mirage/estimation/ekf_update.h"

#include <cassert>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>

#include "mirage/estimation/covariance_ops.h"

namespace mirage::estimation {

namespace {

template <typename Jacobian>
UpdateResult Update(State& state, const Jacobian& H, const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R,
                    CovarianceForm form) {
  UpdateResult result;
  const auto m = H.rows();
  assert(H.cols() == state.dimension() && innovation.size() == m && R.rows() == m && R.cols() == m);
  if (m == 0) {
    result.rejection = UpdateRejection::kNoMeasurements;
    return result;
  }
  const Eigen::MatrixXd U = (H * state.covariance()).transpose();  // P H^T (P symmetric)
  const Eigen::MatrixXd S = H * U + R;                             // Eq. (3.21)
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) {
    result.rejection = UpdateRejection::kNotPositiveDefinite;
    return result;
  }
  const Eigen::MatrixXd K = llt.solve(U.transpose()).transpose();  // Eq. (3.23): P H^T S^{-1}
  result.nis = innovation.dot(llt.solve(innovation));
  result.dof = static_cast<int>(m);
  if (form == CovarianceForm::kJoseph) {
    CovarianceOps::JosephUpdate(state, K, U, S, innovation);  // Eq. (3.22), Joseph form of (3.24)
  } else {
    CovarianceOps::StandardUpdate(state, K, U, innovation);  // Eq. (3.22), (3.24)
  }
  result.applied = true;
  return result;
}

}  // namespace

UpdateResult EkfUpdate(State& state, const Eigen::MatrixXd& H, const Eigen::VectorXd& innovation,
                       const Eigen::MatrixXd& R, CovarianceForm form) {
  return Update(state, H, innovation, R, form);
}

UpdateResult EkfUpdate(State& state, const Eigen::SparseMatrix<double, Eigen::RowMajor>& H,
                       const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R, CovarianceForm form) {
  return Update(state, H, innovation, R, form);
}

}  // namespace mirage::estimation
