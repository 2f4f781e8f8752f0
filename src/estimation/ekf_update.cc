// SPDX-License-Identifier: MIT
#include "mirage/estimation/ekf_update.h"

#include <cassert>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>

#include "mirage/estimation/covariance_ops.h"

namespace mirage::estimation {
namespace {

template <typename Jacobian>
UpdateResult UpdateWith(State& state, const Jacobian& H, const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R,
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

Eigen::SparseMatrix<double, Eigen::RowMajor> StackJacobian(const State& state, std::span<const MeasurementRow> rows) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(rows.size() * 4);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const MeasurementRow& row = rows[r];
    for (int b = 0; b < row.block_count; ++b) {
      const auto ib = static_cast<std::size_t>(b);
      assert(state.layout().At(row.keys[ib]).offset == row.offsets[ib]);  // built on this layout
      for (int c = 0; c < row.sizes[ib]; ++c) {
        entries.emplace_back(static_cast<int>(r), row.offsets[ib] + c, row.jacobians[ib](c));
      }
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> H(static_cast<Eigen::Index>(rows.size()), state.dimension());
  H.setFromTriplets(entries.begin(), entries.end());
  return H;
}

UpdateResult Update(State& state, std::span<const MeasurementRow> rows, std::span<const double> innovations,
                    const UpdateOptions& options) {
  assert(innovations.size() == rows.size());
  assert(options.weights.empty() || options.weights.size() == rows.size());
  const auto m = static_cast<Eigen::Index>(rows.size());
  Eigen::VectorXd nu(m);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto k = static_cast<std::size_t>(i);
    nu(i) = innovations[k];
    R(i, i) = options.weights.empty() ? rows[k].variance : rows[k].variance / options.weights[k];
  }
  return UpdateWith(state, StackJacobian(state, rows), nu, R, options.form);
}

UpdateResult EkfUpdate(State& state, const Eigen::SparseMatrix<double, Eigen::RowMajor>& H,
                       const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R, CovarianceForm form) {
  return UpdateWith(state, H, innovation, R, form);
}

UpdateResult EkfUpdate(State& state, const Eigen::MatrixXd& H, const Eigen::VectorXd& innovation,
                       const Eigen::MatrixXd& R, CovarianceForm form) {
  return UpdateWith(state, H, innovation, R, form);
}

}  // namespace mirage::estimation
