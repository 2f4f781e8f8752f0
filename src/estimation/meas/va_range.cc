// SPDX-License-Identifier: MIT
#include "mirage/estimation/meas/va_range.h"

namespace mirage::estimation {

std::optional<VaRangePrediction> PredictVaRange(const Vec2& p_agent_m, const Vec2& p_va_m) {
  const Vec2 d = p_agent_m - p_va_m;
  const double range_m = d.norm();
  if (range_m < kMinVaRange_m) return std::nullopt;
  VaRangePrediction out;
  out.range_m = range_m;
  out.J_range_p = (d / range_m).transpose();
  out.J_range_va = -out.J_range_p;
  return out;
}

std::optional<MeasurementRow> VaRangeRow(const State& state, const Block& agent_position, const Vec2& va_m,
                                         const std::optional<Block>& va_block, double variance_m2) {
  const Vec2 p_m = state.mean().segment<2>(agent_position.mean_offset);
  const auto prediction = PredictVaRange(p_m, va_m);
  if (!prediction) return std::nullopt;
  MeasurementRow row;
  row.predicted = prediction->range_m;
  row.variance = variance_m2;
  row.Add(agent_position, prediction->J_range_p);
  if (va_block) row.Add(*va_block, prediction->J_range_va);
  return row;
}

}  // namespace mirage::estimation
