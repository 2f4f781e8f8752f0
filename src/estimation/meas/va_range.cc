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

}  // namespace mirage::estimation
