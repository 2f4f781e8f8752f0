// SPDX-License-Identifier: MIT
#include "mirage/estimation/block_update.h"

#include <cassert>

#include <Eigen/Cholesky>

namespace mirage::estimation {

std::optional<BlockUpdate> BlockUpdate::Make(const State& state, int block_offset, const Eigen::MatrixXd& H_b,
                                             const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R) {
  const auto m = H_b.rows();
  assert(H_b.cols() == 2 && innovation.size() == m && R.rows() == m && R.cols() == m);
  if (m == 0) return std::nullopt;
  const Eigen::Matrix2d P_bb = state.covariance().block<2, 2>(block_offset, block_offset);
  const Eigen::MatrixXd S = H_b * P_bb * H_b.transpose() + R;  // Eq. (3.21) with H's one block
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix2d W = H_b.transpose() * llt.solve(H_b);
  const Eigen::Vector2d u = H_b.transpose() * llt.solve(innovation);
  return BlockUpdate(block_offset, W, u);
}

Eigen::Vector2d BlockUpdate::Mean(const State& state, int offset) const {
  const Eigen::Matrix2d P_vb = state.covariance().block<2, 2>(offset, block_offset_);
  return state.mean().segment<2>(offset) + P_vb * u_;
}

Eigen::Matrix2d BlockUpdate::Covariance(const State& state, int row_offset, int col_offset) const {
  const Eigen::MatrixXd& P = state.covariance();
  Eigen::Matrix2d out = P.block<2, 2>(row_offset, col_offset) -
                        P.block<2, 2>(row_offset, block_offset_) * W_ * P.block<2, 2>(block_offset_, col_offset);
  if (row_offset == col_offset) out = (0.5 * (out + out.transpose())).eval();
  return out;
}

}  // namespace mirage::estimation
