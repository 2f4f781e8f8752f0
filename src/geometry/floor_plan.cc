// SPDX-License-Identifier: MIT
#include "mirage/geometry/floor_plan.h"

#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "mirage/core/constants.h"
#include "mirage/geometry/segment.h"

namespace mirage::geometry {

FloorPlan::FloorPlan(std::vector<Wall> walls, std::vector<CircleObstacle> obstacles, double floor_z_m,
                     double ceiling_z_m)
    : walls_(std::move(walls)), obstacles_(std::move(obstacles)), floor_z_m_(floor_z_m), ceiling_z_m_(ceiling_z_m) {
  assert(std::isfinite(floor_z_m) && ceiling_z_m > floor_z_m);
}

bool FloorPlan::IsLegClear(const Vec2& a, const Vec2& b, int skip_wall_a, int skip_wall_b) const {
  const double length_m = (b - a).norm();
  if (length_m == 0.0) return true;
  const double end_tolerance = 1e-9 / length_m;  // 1 nm, as a fraction of the leg
  for (int i = 0; i < static_cast<int>(walls_.size()); ++i) {
    if (i == skip_wall_a || i == skip_wall_b) continue;
    const auto crossing = CrossSegments(a, b, walls_[i].start_m, walls_[i].end_m);
    if (crossing && crossing->t > end_tolerance && crossing->t < 1.0 - end_tolerance) return false;
  }
  for (const auto& obstacle : obstacles_) {
    if (SegmentHitsCircle(a, b, obstacle.center_m, obstacle.radius_m)) return false;
  }
  return true;
}

bool FloorPlan::Encloses(const Vec2& p) const {
  if (walls_.empty()) return false;
  const auto [lo, hi] = Bounds();
  const double reach_m = 2.0 * (hi - lo).norm() + (p - lo).norm() + 1.0;
  constexpr int kRays = 32;
  for (int k = 0; k < kRays; ++k) {
    // Offset angle so that rays do not run along axis-aligned walls.
    const double angle = 2.0 * core::kPi * (k + 0.2371) / kRays;
    const Vec2 far = p + reach_m * Vec2(std::cos(angle), std::sin(angle));
    bool hit = false;
    for (const auto& wall : walls_) {
      if (CrossSegments(p, far, wall.start_m, wall.end_m)) {
        hit = true;
        break;
      }
    }
    if (!hit) return false;
  }
  return true;
}

bool FloorPlan::InsideObstacle(const Vec2& p) const {
  for (const auto& obstacle : obstacles_) {
    if ((p - obstacle.center_m).norm() <= obstacle.radius_m) return true;
  }
  return false;
}

std::pair<Vec2, Vec2> FloorPlan::Bounds() const {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  Vec2 hi = -lo;
  for (const auto& wall : walls_) {
    lo = lo.cwiseMin(wall.start_m).cwiseMin(wall.end_m);
    hi = hi.cwiseMax(wall.start_m).cwiseMax(wall.end_m);
  }
  return {lo, hi};
}

}  // namespace mirage::geometry
