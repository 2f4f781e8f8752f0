// SPDX-License-Identifier: MIT
// Range from an agent to a fixed point (an anchor that is not in the state): h = |p - a|, with
// J_range_p = (p - a)^T / h. In 3-D the agent's position block is blocks::kPosition3; in the
// plane (blocks::kPosition) the agent's height is known, so h = sqrt(|p_xy - a_xy|^2 + dz^2)
// with dz = agent height - point height, and only x, y enter the Jacobian (a tag worn at a fixed
// height, anchors on the ceiling).
#pragma once

#include <optional>

#include "mirage/core/types.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Agent-point distances below this are degenerate: the direction (and the Jacobian) is undefined.
inline constexpr double kMinPointRange_m = 1e-3;

/// The linearised row of a range from the agent's position block to point_m at `state`.
/// @param agent_height_m the agent's known height (m), used when the block is 2-D.
/// @param variance_m2    the range variance R (m^2).
/// std::nullopt when the agent is within kMinPointRange_m of the point.
std::optional<MeasurementRow> RangeToPointRow(const State& state, const Block& agent_position, const Vec3& point_m,
                                              double agent_height_m, double variance_m2);

}  // namespace mirage::estimation
