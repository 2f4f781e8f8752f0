// SPDX-License-Identifier: MIT
#include "mirage/estimation/ekf_update.h"

#include <cassert>

#include <Eigen/Cholesky>

#include "mirage/estimation/covariance_ops.h"

namespace mirage::estimation {

UpdateResult EkfUpdate(State& state, const Eigen::MatrixXd& H, const Eigen::VectorXd& innovation,
                       const Eigen::MatrixXd& R) {
  UpdateResult result;
  const auto m = H.rows();
  assert(H.cols() == state.dimension() && innovation.size() == m && R.rows() == m && R.cols() == m);
  if (m == 0) {
    result.rejection = UpdateRejection::kNoMeasurements;
    return result;
  }
  const Eigen::MatrixXd U = state.covariance() * H.transpose();  // P H^T
  const Eigen::MatrixXd S = H * U + R;                           // Eq. (3.21)
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) {
    result.rejection = UpdateRejection::kNotPositiveDefinite;
    return result;
  }
  const Eigen::MatrixXd K = llt.solve(U.transpose()).transpose();  // Eq. (3.23): P H^T S^{-1}
  result.nis = innovation.dot(llt.solve(innovation));
  result.dof = static_cast<int>(m);
  CovarianceOps::JosephUpdate(state, K, U, S, innovation);  // Eq. (3.22), Joseph form of (3.24)
  result.applied = true;
  return result;
}

}  // namespace mirage::estimation
