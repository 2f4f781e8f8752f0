// SPDX-License-Identifier: MIT
#include "mirage/estimation/state.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace mirage::estimation {

int StateLayout::Append(const BlockType& type, int id) {
  const BlockKey key(type, id);
  assert(!Find(key).has_value() && type.dim > 0 && type.tangent_dim > 0);
  assert(type.euclidean() ? type.dim == type.tangent_dim : type.boxminus != nullptr);
  assert(std::all_of(blocks_.begin(), blocks_.end(),
                     [&](const Block& b) { return b.key.type_id != type.id || b.type == &type; }));
  Block block;
  block.key = key;
  block.type = &type;
  block.offset = dimension_;
  block.size = type.tangent_dim;
  block.mean_offset = mean_dimension_;
  block.mean_size = type.dim;
  blocks_.push_back(block);
  dimension_ += type.tangent_dim;
  mean_dimension_ += type.dim;
  if (!type.euclidean()) ++manifold_blocks_;
  return block.offset;
}

void StateLayout::Remove(BlockKey key) {
  const auto it = std::find_if(blocks_.begin(), blocks_.end(), [&](const Block& b) { return b.key == key; });
  assert(it != blocks_.end());
  const int size = it->size;
  const int mean_size = it->mean_size;
  if (!it->type->euclidean()) --manifold_blocks_;
  for (auto later = it + 1; later != blocks_.end(); ++later) {
    later->offset -= size;
    later->mean_offset -= mean_size;
  }
  blocks_.erase(it);
  dimension_ -= size;
  mean_dimension_ -= mean_size;
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
  assert(mean_.size() == layout_.mean_dimension());
  assert(covariance_.rows() == layout_.dimension() && covariance_.cols() == layout_.dimension());
}

Eigen::VectorXd State::Mean(BlockKey key) const {
  const Block b = layout_.At(key);
  return mean_.segment(b.mean_offset, b.mean_size);
}

Eigen::MatrixXd State::Covariance(BlockKey key) const {
  const Block b = layout_.At(key);
  return covariance_.block(b.offset, b.offset, b.size, b.size);
}

void State::SetMean(BlockKey key, const Eigen::VectorXd& value) {
  const Block b = layout_.At(key);
  assert(value.size() == b.mean_size);
  mean_.segment(b.mean_offset, b.mean_size) = value;
}

}  // namespace mirage::estimation
