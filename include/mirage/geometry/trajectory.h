// SPDX-License-Identifier: MIT
// Ground-truth agent trajectories: a polyline of waypoints walked at constant speed and sampled
// at a fixed time step (Lafer 2014 Sec. 3.7: 5 cm steps at 0.1 s), its corners turned instantly or
// along arcs.
#pragma once

#include <span>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::geometry {

/// One sampled point of a trajectory.
struct TrajectorySample {
  double t_s = 0.0;                  ///< time since the start (s)
  Vec2 position_m = Vec2::Zero();    ///< position (m)
  Vec2 velocity_mps = Vec2::Zero();  ///< velocity of the segment being walked (m/s)
};

/// Samples the polyline through waypoints_m (at least 2 distinct points), walked at speed_mps
/// (> 0) and sampled every dt_s (> 0), shifted by offset_m. The first sample is the first
/// waypoint; the last is the last sample that does not pass the final waypoint.
/// turn_radius_m = 0 turns instantly at each waypoint, as along the thesis's measured grid points;
/// > 0 rounds each corner into a circular arc of that radius tangent to both legs (a walker turns
/// with a lateral acceleration of speed^2 / radius), shrunk where a leg is too short to hold it.
std::vector<TrajectorySample> SampleTrajectory(std::span<const Vec2> waypoints_m, double speed_mps, double dt_s,
                                               const Vec2& offset_m = Vec2::Zero(), double turn_radius_m = 0.0);

/// Length of the polyline (m).
double PolylineLength(std::span<const Vec2> waypoints_m);

}  // namespace mirage::geometry
