// SPDX-License-Identifier: MIT
// Time of arrival with an unknown emission time, in metres (Bordoy 2020 Eq. 3.37, 5.1): a stamp
// T_i of receiver M_i, multiplied by the signal speed c and taken relative to a reference time
// t_ref, is z_i = c (T_i - t_ref) = |S - M_i| + b with b = c (t_s - t_ref) the sender's emission
// time as a distance. Row of the Jacobian: d z / d S = u_i^T = (S - M_i)^T / |S - M_i|,
// d z / d b = 1. The same model serves the pseudo-ranges of Sec. 8.3 (Eq. 8.59).
#pragma once

#include <optional>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// Sender-receiver distances below this are degenerate: the direction is undefined (m).
inline constexpr double kMinToaRange_m = 1e-6;

/// The predicted stamp of one receiver and its derivatives.
struct ToaPrediction {
  double predicted_m = 0.0;       ///< |S - M| + b (m)
  Vec3 d_sender = Vec3::Zero();   ///< d z / d S = (S - M) / |S - M| (unitless)
  double range_m = 0.0;           ///< |S - M| (m)
};

/// The predicted stamp of the receiver at receiver_m for a sender at sender_m emitting at the
/// offset offset_m (b); std::nullopt when they are within kMinToaRange_m.
std::optional<ToaPrediction> PredictToa(const Vec3& sender_m, const Vec3& receiver_m, double offset_m);

}  // namespace mirage::estimation
