// SPDX-License-Identifier: MIT
// Position error bound (PEB) from the specular paths' SINRs: the equivalent Fisher information
// of the position is J = sum_k 8 pi^2 beta^2 SINR_k / c^2 u_k u_k^T, with u_k the unit vector from
// the VA to the agent (Lafer 2014 Eq. 3.28 per range, summed over independent ranges), and
// PEB = sqrt(trace(J^{-1})).
#pragma once

#include <optional>
#include <span>

#include "mirage/core/types.h"

namespace mirage::eval {

/// One range's contribution: the VA's position and its SINR.
struct RangeInformation {
  Vec2 va_m = Vec2::Zero();  ///< VA position (m)
  double sinr = 0.0;         ///< SINR (linear)
};

/// PEB (m) at agent_m, or std::nullopt if the information is singular (fewer than two
/// independent directions).
/// @param range_sigma_at_unit_sinr_m c / (sqrt(8) pi beta) (m).
std::optional<double> PositionErrorBound(const Vec2& agent_m, std::span<const RangeInformation> ranges,
                                         double range_sigma_at_unit_sinr_m);

}  // namespace mirage::eval
