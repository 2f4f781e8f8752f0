// SPDX-License-Identifier: MIT
// Keeping a position estimate where an agent can be: inside the walls and outside obstacles.
// This generalises the "in-room check" of Lafer 2014 Sec. 4.4.3 as the digest suggests (a
// segment-crossing test between consecutive estimates), which also catches the jump through a
// wall and back that the thesis's point-in-room test missed.
#pragma once

#include <optional>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::geometry {

/// The point on the move from_m -> to_m that keeps the agent feasible: to_m itself when the move
/// crosses no wall and enters no obstacle; otherwise the move is stopped margin_m (m) before the
/// first wall crossing or obstacle entry. from_m is assumed feasible.
Vec2 ConstrainMove(const FloorPlan& plan, const Vec2& from_m, const Vec2& to_m, double margin_m = 0.01);

}  // namespace mirage::geometry
