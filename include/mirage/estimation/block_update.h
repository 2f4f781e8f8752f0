// SPDX-License-Identifier: MIT
// An EKF update whose rows touch only one 2-D block b of the state (the agent position, for
// ranges to anchors that are not in the state), kept in a form from which any block's posterior
// can be read off without updating, or copying, the whole state.
//
// With H = [0 .. H_b .. 0], S = H_b P_bb H_b^T + R, and the standard form of the update
// (Lafer 2014 Eq. 3.22-3.24: P' = P - P H^T S^-1 H P, x' = x + P H^T S^-1 nu), every block v, w
// of the state gets
//   x_v'  = x_v + P_vb u,          u = H_b^T S^-1 nu   (2-vector, 1/m for range rows)
//   P_vw' = P_vw - P_vb W P_bw,    W = H_b^T S^-1 H_b  (2x2, 1/m^2 for range rows)
// so a posterior block costs O(1) instead of the O(n^2) of a full update.
#pragma once

#include <optional>

#include <Eigen/Core>

#include "mirage/estimation/state.h"

namespace mirage::estimation {

class BlockUpdate {
 public:
  /// The update of `state` with rows H_b (m x 2, on the 2-D block at `block_offset`), innovation
  /// nu (m) and R (m x m). Nothing when m = 0 or S is not positive definite (as EkfUpdate's
  /// rejections).
  static std::optional<BlockUpdate> Make(const State& state, int block_offset, const Eigen::MatrixXd& H_b,
                                         const Eigen::VectorXd& innovation, const Eigen::MatrixXd& R);

  /// The posterior mean of the 2-D block at `offset`.
  [[nodiscard]] Eigen::Vector2d Mean(const State& state, int offset) const;
  /// The posterior covariance between the 2-D blocks at `row_offset` and `col_offset`
  /// (symmetrised when they are the same block).
  [[nodiscard]] Eigen::Matrix2d Covariance(const State& state, int row_offset, int col_offset) const;

 private:
  BlockUpdate(int block_offset, const Eigen::Matrix2d& W, const Eigen::Vector2d& u)
      : block_offset_(block_offset), W_(W), u_(u) {}

  int block_offset_;
  Eigen::Matrix2d W_;
  Eigen::Vector2d u_;
};

}  // namespace mirage::estimation
