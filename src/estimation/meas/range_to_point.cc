// SPDX-License-Identifier: MIT
#include "mirage/estimation/meas/range_to_point.h"

#include <cassert>

namespace mirage::estimation {

std::optional<MeasurementRow> RangeToPointRow(const State& state, const Block& agent_position, const Vec3& point_m,
                                              double agent_height_m, double variance_m2) {
  MeasurementRow row;
  row.variance = variance_m2;
  if (agent_position.size == 3) {
    const Vec3 d = state.mean().segment<3>(agent_position.mean_offset) - point_m;
    const double range_m = d.norm();
    if (range_m < kMinPointRange_m) return std::nullopt;
    row.predicted = range_m;
    row.Add(agent_position, Eigen::RowVector3d(d.transpose() / range_m));
    return row;
  }
  assert(agent_position.size == 2);
  const Vec2 d_xy = state.mean().segment<2>(agent_position.mean_offset) - point_m.head<2>();
  const double dz_m = agent_height_m - point_m.z();
  const double range_m = std::sqrt(d_xy.squaredNorm() + dz_m * dz_m);
  if (range_m < kMinPointRange_m) return std::nullopt;
  row.predicted = range_m;
  row.Add(agent_position, Eigen::RowVector2d(d_xy.transpose() / range_m));
  return row;
}

}  // namespace mirage::estimation
