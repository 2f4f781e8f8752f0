// SPDX-License-Identifier: MIT
#include "mirage/geometry/feasible_region.h"

#include <algorithm>

#include "mirage/geometry/segment.h"

namespace mirage::geometry {

Vec2 ConstrainMove(const FloorPlan& plan, const Vec2& from_m, const Vec2& to_m, double margin_m) {
  Vec2 result = to_m;
  const double length_m = (to_m - from_m).norm();
  if (length_m > 0.0) {
    double first_t = 2.0;
    for (const auto& wall : plan.walls()) {
      const auto crossing = CrossSegments(from_m, to_m, wall.start_m, wall.end_m);
      if (crossing && crossing->t < first_t) first_t = crossing->t;
    }
    if (first_t <= 1.0) result = from_m + std::max(0.0, first_t - margin_m / length_m) * (to_m - from_m);
  }
  for (const auto& obstacle : plan.obstacles()) {
    const Vec2 d = result - obstacle.center_m;
    const double distance_m = d.norm();
    if (distance_m >= obstacle.radius_m) continue;
    // Out through the side the move came from when the point sits on the centre.
    const Vec2 direction = distance_m > 1e-9 ? Vec2(d / distance_m) : Vec2((from_m - obstacle.center_m).normalized());
    result = obstacle.center_m + (obstacle.radius_m + margin_m) * direction;
  }
  return result;
}

}  // namespace mirage::geometry
