// SPDX-License-Identifier: MIT
// Time difference of arrival in metres (Bordoy 2020 Eq. 3.36; the UWB TDOA convention of
// tdoa.csv): d_ij = |S - M_j| - |S - M_i|, the stamp of receiver j minus that of receiver i,
// times c. Row of the Jacobian: d d_ij / d S = u_j^T - u_i^T with u = (S - M) / |S - M|. The
// emission time cancels; the price is that receiver i's noise enters every difference taken
// against it (R_TD = D R D^T, Eq. 8.54-8.55).
#pragma once

#include <optional>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// The predicted difference and its derivative.
struct TdoaPrediction {
  double predicted_m = 0.0;      ///< |S - M_j| - |S - M_i| (m)
  Vec3 d_sender = Vec3::Zero();  ///< u_j - u_i (unitless)
};

/// The predicted difference of receivers i (receiver_i_m) and j (receiver_j_m) for a sender at
/// sender_m; std::nullopt when the sender is within kMinToaRange_m (toa.h) of either.
std::optional<TdoaPrediction> PredictTdoa(const Vec3& sender_m, const Vec3& receiver_i_m, const Vec3& receiver_j_m);

}  // namespace mirage::estimation
