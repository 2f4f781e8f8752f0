// SPDX-License-Identifier: MIT
// Filter state: mean, covariance and a named block layout (STYLE.md Sec. 3). Blocks are addressed
// by key (their type and the id of their owner), e.g. {blocks::kPosition, agent 0} or
// {blocks::kVirtualAnchor, va id}, never by raw offsets; adding or removing a block goes
// through covariance_ops, the only code that writes the covariance. A block's mean has
// type.dim values and its covariance type.tangent_dim rows (block_type.h), so a manifold block
// (an orientation) sits beside Euclidean ones; corrections are applied with its boxplus.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mirage/estimation/block_type.h"
#include "mirage/estimation/block_types.h"

namespace mirage::estimation {

/// Key of one block: its type and the id of its owner (agent index, VA id, wall index).
struct BlockKey {
  int type_id = 0;  ///< BlockType::id
  int id = 0;       ///< owner id
  constexpr BlockKey() = default;
  constexpr BlockKey(const BlockType& type, int owner) : type_id(type.id), id(owner) {}
  friend bool operator==(const BlockKey&, const BlockKey&) = default;
};

/// Location of one block in the state: its tangent rows (offset, size: the covariance and every
/// Jacobian column) and its mean values (mean_offset, mean_size; equal to the tangent ones while
/// every block before it is Euclidean).
struct Block {
  BlockKey key;
  const BlockType* type = nullptr;
  int offset = 0;       ///< first tangent row / covariance row
  int size = 0;         ///< tangent dimension
  int mean_offset = 0;  ///< first mean value
  int mean_size = 0;    ///< mean dimension
};

/// Ordered list of blocks.
class StateLayout {
 public:
  /// Appends a block of `type` owned by `id` at the end; the key must be new, and the type's id
  /// must not name a different type elsewhere in the layout. Returns its tangent offset.
  int Append(const BlockType& type, int id);
  /// Removes a block and shifts the ones after it.
  void Remove(BlockKey key);
  [[nodiscard]] std::optional<Block> Find(BlockKey key) const;
  /// The block with this key; it must exist.
  [[nodiscard]] Block At(BlockKey key) const;
  /// Tangent dimension: the size of the covariance.
  [[nodiscard]] int dimension() const { return dimension_; }
  /// Number of mean values.
  [[nodiscard]] int mean_dimension() const { return mean_dimension_; }
  /// True when every block is Euclidean (mean and tangent coordinates coincide).
  [[nodiscard]] bool euclidean() const { return manifold_blocks_ == 0; }
  [[nodiscard]] const std::vector<Block>& blocks() const { return blocks_; }

 private:
  std::vector<Block> blocks_;
  int dimension_ = 0;
  int mean_dimension_ = 0;
  int manifold_blocks_ = 0;
};

class CovarianceOps;

/// Mean, covariance and layout of a Gaussian filter state at time t_s.
class State {
 public:
  State() = default;
  /// mean has layout.mean_dimension() values, covariance layout.dimension() rows and columns.
  State(StateLayout layout, Eigen::VectorXd mean, Eigen::MatrixXd covariance, double t_s);

  [[nodiscard]] const StateLayout& layout() const { return layout_; }
  [[nodiscard]] const Eigen::VectorXd& mean() const { return mean_; }
  [[nodiscard]] const Eigen::MatrixXd& covariance() const { return covariance_; }
  /// Tangent dimension (rows of the covariance).
  [[nodiscard]] int dimension() const { return layout_.dimension(); }
  [[nodiscard]] double t_s() const { return t_s_; }

  /// Mean of one block (type.dim values).
  [[nodiscard]] Eigen::VectorXd Mean(BlockKey key) const;
  /// Covariance of one block (tangent_dim x tangent_dim).
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
