// SPDX-License-Identifier: MIT
// One scalar measurement linearised at a state, as every measurement model hands it to the one
// update path (ekf_update.h): the prediction h(x), the Jacobian dh/dx by block (tangent
// coordinates, only the blocks the measurement touches) and the noise variance. Fixed capacity,
// so building a row allocates nothing (a step builds hundreds of them).
#pragma once

#include <array>
#include <cassert>

#include <Eigen/Core>

#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// A linearised scalar measurement z = h(x) + v, v ~ N(0, variance).
struct MeasurementRow {
  /// Most blocks one row touches: a coop path touches two agents and up to three walls.
  static constexpr int kMaxBlocks = 6;
  /// Largest tangent dimension of a block a row may touch.
  static constexpr int kMaxBlockDim = 3;
  using BlockJacobian = Eigen::Matrix<double, 1, kMaxBlockDim>;

  double predicted = 0.0;  ///< h(x), in the measurement's unit
  double variance = 0.0;   ///< noise variance R (unit^2), > 0
  int block_count = 0;
  std::array<BlockKey, kMaxBlocks> keys{};
  std::array<int, kMaxBlocks> offsets{};  ///< tangent offsets in the layout the row was built on
  std::array<int, kMaxBlocks> sizes{};
  std::array<BlockJacobian, kMaxBlocks> jacobians{};

  /// Adds dh/d(block) (block.size entries, its tangent dimension), in the order given (the
  /// order of the columns' contributions to sums). A block added again sums into its entry (a
  /// wall met twice on one path). The row is valid for states with the layout `block` is from.
  void Add(const Block& block, const double* J) {
    assert(block.size > 0 && block.size <= kMaxBlockDim);
    for (int b = 0; b < block_count; ++b) {
      if (keys[static_cast<std::size_t>(b)] == block.key) {
        for (int c = 0; c < block.size; ++c) jacobians[static_cast<std::size_t>(b)](c) += J[c];
        return;
      }
    }
    assert(block_count < kMaxBlocks);
    const auto b = static_cast<std::size_t>(block_count++);
    keys[b] = block.key;
    offsets[b] = block.offset;
    sizes[b] = block.size;
    jacobians[b].setZero();
    for (int c = 0; c < block.size; ++c) jacobians[b](c) = J[c];
  }
  template <int N>
  void Add(const Block& block, const Eigen::Matrix<double, 1, N>& J) {
    assert(block.size == N);
    Add(block, J.data());
  }
};

/// h P h^T + R of one row at `state`: the innovation variance a chi-square gate compares the
/// squared innovation with. Entries are summed in the row's block and column order.
double InnovationVariance(const State& state, const MeasurementRow& row);

}  // namespace mirage::estimation
