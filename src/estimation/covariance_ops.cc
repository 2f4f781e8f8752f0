// SPDX-License-Identifier: MIT
#include "mirage/estimation/covariance_ops.h"

#include <cassert>

namespace mirage::estimation {

void CovarianceOps::PropagateBlock(State& state, BlockKey first, const Eigen::MatrixXd& F, const Eigen::MatrixXd& Q) {
  const Block block = state.layout_.At(first);
  const int offset = block.offset;
  const int k = static_cast<int>(F.rows());
  assert(F.cols() == k && Q.rows() == k && Q.cols() == k && offset + k <= state.dimension());
  // The rows must be Euclidean blocks: then their mean values sit at the same relative places.
  assert(block.type->euclidean());
  auto& P = state.covariance_;
  state.mean_.segment(block.mean_offset, k) = F * state.mean_.segment(block.mean_offset, k);
  // Rows then columns: P[b, :] = F P[b, :]; P[:, b] = P[:, b] F^T.
  const Eigen::MatrixXd rows = F * P.middleRows(offset, k);
  P.middleRows(offset, k) = rows;
  const Eigen::MatrixXd cols = P.middleCols(offset, k) * F.transpose();
  P.middleCols(offset, k) = cols;
  P.block(offset, offset, k, k) += Q;
}

void CovarianceOps::Stamp(State& state, double t_s) { state.t_s_ = t_s; }

void CovarianceOps::Correct(State& state, const Eigen::VectorXd& dx) {
  assert(dx.size() == state.dimension());
  if (state.layout_.euclidean()) {
    state.mean_ += dx;
    return;
  }
  for (const Block& b : state.layout_.blocks()) {
    double* x = state.mean_.data() + b.mean_offset;
    if (b.type->euclidean()) {
      state.mean_.segment(b.mean_offset, b.mean_size) += dx.segment(b.offset, b.size);
    } else {
      b.type->boxplus(x, dx.data() + b.offset, x);
    }
  }
}

void CovarianceOps::JosephUpdate(State& state, const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                                 const Eigen::MatrixXd& S, const Eigen::VectorXd& innovation) {
  auto& P = state.covariance_;
  // Euclidean states keep the single expression (and its rounding) of the additive update.
  if (state.layout_.euclidean()) {
    state.mean_ += K * innovation;
  } else {
    Correct(state, K * innovation);
  }
  const Eigen::MatrixXd KUt = K * U.transpose();
  P -= KUt + KUt.transpose();
  P.noalias() += K * S * K.transpose();
  Symmetrize(state);
}

void CovarianceOps::StandardUpdate(State& state, const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                                   const Eigen::VectorXd& innovation) {
  if (state.layout_.euclidean()) {
    state.mean_ += K * innovation;
  } else {
    Correct(state, K * innovation);
  }
  state.covariance_.noalias() -= K * U.transpose();
  Symmetrize(state);
}

void CovarianceOps::Symmetrize(State& state) {
  auto& P = state.covariance_;
  P = 0.5 * (P + P.transpose()).eval();
}

void CovarianceOps::Augment(State& state, const BlockType& type, int id, const Eigen::VectorXd& x_new,
                            const Eigen::MatrixXd& P_new_x, const Eigen::MatrixXd& P_new) {
  const int n = state.dimension();
  const int n_mean = state.layout_.mean_dimension();
  const int k = type.tangent_dim;
  assert(x_new.size() == type.dim && P_new_x.rows() == k && P_new_x.cols() == n && P_new.rows() == k &&
         P_new.cols() == k);
  state.layout_.Append(type, id);
  Eigen::VectorXd mean(n_mean + type.dim);
  mean << state.mean_, x_new;
  Eigen::MatrixXd P(n + k, n + k);
  P.topLeftCorner(n, n) = state.covariance_;
  P.bottomLeftCorner(k, n) = P_new_x;
  P.topRightCorner(n, k) = P_new_x.transpose();
  P.bottomRightCorner(k, k) = P_new;
  state.mean_ = std::move(mean);
  state.covariance_ = std::move(P);
}

void CovarianceOps::Marginalize(State& state, BlockKey key) {
  const Block b = state.layout_.At(key);
  const int n = state.dimension();
  const int tail = n - b.offset - b.size;
  const int mean_tail = state.layout_.mean_dimension() - b.mean_offset - b.mean_size;
  Eigen::VectorXd mean(state.layout_.mean_dimension() - b.mean_size);
  mean << state.mean_.head(b.mean_offset), state.mean_.tail(mean_tail);
  Eigen::MatrixXd P(n - b.size, n - b.size);
  P.topLeftCorner(b.offset, b.offset) = state.covariance_.topLeftCorner(b.offset, b.offset);
  P.topRightCorner(b.offset, tail) = state.covariance_.topRightCorner(b.offset, tail);
  P.bottomLeftCorner(tail, b.offset) = state.covariance_.bottomLeftCorner(tail, b.offset);
  P.bottomRightCorner(tail, tail) = state.covariance_.bottomRightCorner(tail, tail);
  state.layout_.Remove(key);
  state.mean_ = std::move(mean);
  state.covariance_ = std::move(P);
}

void CovarianceOps::Reinitialize(State& state, BlockKey key, const Eigen::VectorXd& x_new, const Eigen::MatrixXd& P_new) {
  const Block b = state.layout_.At(key);
  assert(x_new.size() == b.mean_size && P_new.rows() == b.size && P_new.cols() == b.size);
  state.mean_.segment(b.mean_offset, b.mean_size) = x_new;
  state.covariance_.middleRows(b.offset, b.size).setZero();
  state.covariance_.middleCols(b.offset, b.size).setZero();
  state.covariance_.block(b.offset, b.offset, b.size, b.size) = P_new;
}

}  // namespace mirage::estimation
