// SPDX-License-Identifier: MIT
#include "mirage/estimation/meas/toa.h"

namespace mirage::estimation {

std::optional<ToaPrediction> PredictToa(const Vec3& sender_m, const Vec3& receiver_m, double offset_m) {
  const Vec3 d = sender_m - receiver_m;
  const double range_m = d.norm();
  if (range_m < kMinToaRange_m) return std::nullopt;
  return ToaPrediction{range_m + offset_m, d / range_m, range_m};
}

}  // namespace mirage::estimation
