// SPDX-License-Identifier: MIT
#include "mirage/estimation/meas/image_path_range.h"

#include <cassert>

namespace mirage::estimation {

MeasurementRow ImagePathRangeRow(const geometry::ImagePath& path, const std::optional<Block>& tx_agent,
                                 const std::optional<Block>& rx_agent, std::span<const std::optional<Block>> wall_blocks,
                                 double variance_m2) {
  assert(wall_blocks.empty() || wall_blocks.size() == path.d_offset.size());
  MeasurementRow row;
  row.predicted = path.length_m;
  row.variance = variance_m2;
  const bool self = tx_agent && rx_agent && tx_agent->key == rx_agent->key;
  if (self) {
    // App. C: d length / d p = (I - Phi^T) u = d_rx + d_tx for an agent's own channel.
    const Vec2 d = path.d_rx + path.d_tx;
    row.Add(*rx_agent, Eigen::RowVector2d(d.transpose()));
  } else {
    if (tx_agent) row.Add(*tx_agent, Eigen::RowVector2d(path.d_tx.transpose()));
    if (rx_agent) row.Add(*rx_agent, Eigen::RowVector2d(path.d_rx.transpose()));
  }
  for (std::size_t i = 0; i < wall_blocks.size(); ++i) {
    if (wall_blocks[i]) row.Add(*wall_blocks[i], &path.d_offset[i]);
  }
  return row;
}

}  // namespace mirage::estimation
