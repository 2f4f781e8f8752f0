// SPDX-License-Identifier: MIT
#include "mirage/estimation/meas/tdoa.h"

#include "mirage/estimation/meas/toa.h"

namespace mirage::estimation {

std::optional<TdoaPrediction> PredictTdoa(const Vec3& sender_m, const Vec3& receiver_i_m, const Vec3& receiver_j_m) {
  const auto i = PredictToa(sender_m, receiver_i_m, 0.0);
  const auto j = PredictToa(sender_m, receiver_j_m, 0.0);
  if (!i || !j) return std::nullopt;
  return TdoaPrediction{j->range_m - i->range_m, j->d_sender - i->d_sender};
}

}  // namespace mirage::estimation
