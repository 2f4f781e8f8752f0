// SPDX-License-Identifier: MIT
#include "mirage/estimation/state.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace mirage::estimation {

int StateLayout::Append(BlockKey key, int size) {
  assert(!Find(key).has_value() && size > 0);
  blocks_.push_back({key, dimension_, size});
  dimension_ += size;
  return blocks_.back().offset;
}

void StateLayout::Remove(BlockKey key) {
  const auto it = std::find_if(blocks_.begin(), blocks_.end(), [&](const Block& b) { return b.key == key; });
  assert(it != blocks_.end());
  const int size = it->size;
  for (auto later = it + 1; later != blocks_.end(); ++later) later->offset -= size;
  blocks_.erase(it);
  dimension_ -= size;
}

std::optional<Block> StateLayout::Find(BlockKey key) const {
  for (const auto& b : blocks_) {
    if (b.key == key) return b;
  }
  return std::nullopt;
}

Block StateLayout::At(BlockKey key) const {
  const auto block = Find(key);
  assert(block.has_value());
  return *block;
}

State::State(StateLayout layout, Eigen::VectorXd mean, Eigen::MatrixXd covariance, double t_s)
    : layout_(std::move(layout)), mean_(std::move(mean)), covariance_(std::move(covariance)), t_s_(t_s) {
  assert(mean_.size() == layout_.dimension());
  assert(covariance_.rows() == layout_.dimension() && covariance_.cols() == layout_.dimension());
}

Eigen::VectorXd State::Mean(BlockKey key) const {
  const Block b = layout_.At(key);
  return mean_.segment(b.offset, b.size);
}

Eigen::MatrixXd State::Covariance(BlockKey key) const {
  const Block b = layout_.At(key);
  return covariance_.block(b.offset, b.offset, b.size, b.size);
}

void State::SetMean(BlockKey key, const Eigen::VectorXd& value) {
  const Block b = layout_.At(key);
  assert(value.size() == b.size);
  mean_.segment(b.offset, b.size) = value;
}

}  // namespace mirage::estimation
