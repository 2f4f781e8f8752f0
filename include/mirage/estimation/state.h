// SPDX-License-Identifier: MIT
// Filter state: mean, covariance and a named block layout (STYLE.md Sec. 3). Blocks are addressed
// by key, e.g. {kPosition, agent 0} or {kVirtualAnchor, va id}, never by raw offsets; adding or
// removing a block goes through covariance_ops, the only code that writes the covariance.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

namespace mirage::estimation {

/// What a state block holds.
enum class BlockKind {
  kPosition,       ///< agent position [x, y] (m)
  kVelocity,       ///< agent velocity [vx, vy] (m/s)
  kVirtualAnchor,  ///< VA position [x, y] (m)
  kWallOffset,     ///< offset of a wall along its normal (m)
};

/// Key of one block: its kind and the id of its owner (agent index, VA id, wall index).
struct BlockKey {
  BlockKind kind = BlockKind::kPosition;
  int id = 0;
  friend bool operator==(const BlockKey&, const BlockKey&) = default;
};

/// Location of one block in the state vector.
struct Block {
  BlockKey key;
  int offset = 0;
  int size = 0;
};

/// Ordered list of blocks.
class StateLayout {
 public:
  /// Appends a block at the end; the key must be new.
  int Append(BlockKey key, int size);
  /// Removes a block and shifts the ones after it.
  void Remove(BlockKey key);
  [[nodiscard]] std::optional<Block> Find(BlockKey key) const;
  /// The block with this key; it must exist.
  [[nodiscard]] Block At(BlockKey key) const;
  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] const std::vector<Block>& blocks() const { return blocks_; }

 private:
  std::vector<Block> blocks_;
  int dimension_ = 0;
};

class CovarianceOps;

/// Mean, covariance and layout of a Gaussian filter state at time t_s.
class State {
 public:
  State() = default;
  State(StateLayout layout, Eigen::VectorXd mean, Eigen::MatrixXd covariance, double t_s);

  [[nodiscard]] const StateLayout& layout() const { return layout_; }
  [[nodiscard]] const Eigen::VectorXd& mean() const { return mean_; }
  [[nodiscard]] const Eigen::MatrixXd& covariance() const { return covariance_; }
  [[nodiscard]] int dimension() const { return layout_.dimension(); }
  [[nodiscard]] double t_s() const { return t_s_; }

  /// Mean of one block.
  [[nodiscard]] Eigen::VectorXd Mean(BlockKey key) const;
  /// Covariance of one block.
  [[nodiscard]] Eigen::MatrixXd Covariance(BlockKey key) const;
  /// Sets the mean of one block (e.g. velocity clipping); the covariance is unchanged.
  void SetMean(BlockKey key, const Eigen::VectorXd& value);

 private:
  friend class CovarianceOps;
  StateLayout layout_;
  Eigen::VectorXd mean_;
  Eigen::MatrixXd covariance_;
  double t_s_ = 0.0;
};

}  // namespace mirage::estimation
