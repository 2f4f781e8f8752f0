// SPDX-License-Identifier: MIT
// Floor plan (2.5-D): wall segments with a reflection coefficient and circular obstacles
// (pillars) in the plane, between a floor and a ceiling height. Walls and obstacles are vertical
// and span the floor to the ceiling, so a 2-D method sees the plan unchanged. Walls reflect and
// block; obstacles only block (they are too small and curved to produce a usable specular
// reflection, Lafer 2014 Sec. 3.7).
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::geometry {

/// A wall segment.
struct Wall {
  Vec2 start_m = Vec2::Zero();  ///< first end point (m)
  Vec2 end_m = Vec2::Zero();    ///< second end point (m)
  /// Amplitude reflection coefficient |Gamma| of the surface, in (0, 1].
  double reflection_coeff = 0.5;
  /// Free-form label (material or wall name), for reports and plots.
  std::string label;
};

/// A circular obstacle that blocks every path crossing it.
struct CircleObstacle {
  Vec2 center_m = Vec2::Zero();  ///< centre (m)
  double radius_m = 0.0;         ///< radius (m), > 0
  std::string label;             ///< free-form label
};

/// Ceiling height of a plan without a ceiling (m): walls of unbounded height.
inline constexpr double kNoCeiling_m = std::numeric_limits<double>::infinity();

/// Walls and obstacles of one room (or building floor), between floor and ceiling.
class FloorPlan {
 public:
  FloorPlan() = default;
  /// @param floor_z_m   height of the floor (m), finite. 0: heights are measured from the floor.
  /// @param ceiling_z_m height of the ceiling (m), above the floor. kNoCeiling_m (the default)
  ///                    keeps a plan without heights working in 3-D: nothing is too high.
  FloorPlan(std::vector<Wall> walls, std::vector<CircleObstacle> obstacles, double floor_z_m = 0.0,
            double ceiling_z_m = kNoCeiling_m);

  [[nodiscard]] const std::vector<Wall>& walls() const { return walls_; }
  [[nodiscard]] const std::vector<CircleObstacle>& obstacles() const { return obstacles_; }
  /// Height of the floor (m).
  [[nodiscard]] double floor_z_m() const { return floor_z_m_; }
  /// Height of the ceiling (m), kNoCeiling_m if there is none.
  [[nodiscard]] double ceiling_z_m() const { return ceiling_z_m_; }

  /// True if the straight leg a->b crosses no wall and no obstacle. Walls skip_wall_a and
  /// skip_wall_b (indices, -1 for none) are ignored: they are the walls the leg starts or ends
  /// on at a reflection point. Touching a wall within 1 nm of either end of the leg does not
  /// count, so that legs starting at a reflection point next to a corner are not blocked by the
  /// neighbouring wall.
  [[nodiscard]] bool IsLegClear(const Vec2& a, const Vec2& b, int skip_wall_a = -1, int skip_wall_b = -1) const;

  /// True if rays from p in 32 directions all hit a wall, i.e. p lies inside the walls.
  [[nodiscard]] bool Encloses(const Vec2& p) const;

  /// True if p lies inside (or on) an obstacle.
  [[nodiscard]] bool InsideObstacle(const Vec2& p) const;

  /// Axis-aligned bounding box of all walls: {min corner, max corner} (m).
  [[nodiscard]] std::pair<Vec2, Vec2> Bounds() const;

 private:
  std::vector<Wall> walls_;
  std::vector<CircleObstacle> obstacles_;
  double floor_z_m_ = 0.0;
  double ceiling_z_m_ = kNoCeiling_m;
};

}  // namespace mirage::geometry
