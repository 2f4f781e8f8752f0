// SPDX-License-Identifier: MIT
#include "mirage/geometry/feasible_region.h"

#include <algorithm>
#include <cmath>

#include "mirage/geometry/segment.h"

namespace mirage::geometry {
namespace {

// Parameter t in [0, 1] where the move from + t (to - from) first enters the disc, if it does.
std::optional<double> EntersCircle(const Vec2& from, const Vec2& to, const CircleObstacle& circle) {
  const Vec2 d = to - from;
  const Vec2 f = from - circle.center_m;
  const double a = d.squaredNorm();
  const double b = 2.0 * f.dot(d);
  const double c = f.squaredNorm() - circle.radius_m * circle.radius_m;
  if (c <= 0.0) return 0.0;  // starts inside or on the circle
  const double discriminant = b * b - 4.0 * a * c;
  if (a == 0.0 || discriminant <= 0.0) return std::nullopt;
  const double t = (-b - std::sqrt(discriminant)) / (2.0 * a);
  if (t < 0.0 || t > 1.0) return std::nullopt;
  return t;
}

}  // namespace

Vec2 ConstrainMove(const FloorPlan& plan, const Vec2& from_m, const Vec2& to_m, double margin_m) {
  const double length_m = (to_m - from_m).norm();
  if (length_m == 0.0) return to_m;
  // The first wall crossing or obstacle entry along the move; the move stops margin_m before it,
  // so the result always lies on the move and never beyond a wall.
  double first_t = 2.0;
  for (const auto& wall : plan.walls()) {
    const auto crossing = CrossSegments(from_m, to_m, wall.start_m, wall.end_m);
    if (crossing) first_t = std::min(first_t, crossing->t);
  }
  for (const auto& obstacle : plan.obstacles()) {
    const auto t = EntersCircle(from_m, to_m, obstacle);
    if (t) first_t = std::min(first_t, *t);
  }
  if (first_t > 1.0) return to_m;
  return from_m + std::max(0.0, first_t - margin_m / length_m) * (to_m - from_m);
}

}  // namespace mirage::geometry
