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

/// A walker slows to a stop, and back to the walking speed, within one step: the speed ramps
/// linearly over this time (s) before and after a stop (a deceleration of speed / 0.5 s, 2-3 m/s^2
/// at 1-1.5 m/s, where an instant stop would be an unphysical jump of the velocity).
inline constexpr double kStopRamp_s = 0.5;

/// A pause of the walk: from at_s (time since the start, s) the walker stands for duration_s (s),
/// slowing down over the kStopRamp_s before at_s and speeding up over the kStopRamp_s after.
struct Stop {
  double at_s = 0.0;
  double duration_s = 0.0;
};

/// Samples the polyline through waypoints_m (at least 2 distinct points), walked at speed_mps
/// (> 0) and sampled every dt_s (> 0), shifted by offset_m. The first sample is the first
/// waypoint; the last is the last sample that does not pass the final waypoint.
/// turn_radius_m = 0 turns instantly at each waypoint, as along the thesis's measured grid points;
/// > 0 rounds each corner into a circular arc of that radius tangent to both legs (a walker turns
/// with a lateral acceleration of speed^2 / radius), shrunk where a leg is too short to hold it.
/// stops (sorted by at_s, at_s >= kStopRamp_s, each beginning 2 kStopRamp_s or more after the
/// previous one ends, durations > 0): the walker slows down, stands still (velocity zero) and walks
/// on from where it stopped (Bordoy 2020 Sec. 6.2: walking trajectories with stops).
std::vector<TrajectorySample> SampleTrajectory(std::span<const Vec2> waypoints_m, double speed_mps, double dt_s,
                                               const Vec2& offset_m = Vec2::Zero(), double turn_radius_m = 0.0,
                                               std::span<const Stop> stops = {});

/// The time walked at full speed (s) by time t_s (s) since the start: t_s less the time the stops
/// (with their ramps) cost before it; the path length walked is the speed times it.
double WalkedTime(double t_s, std::span<const Stop> stops);

/// Length of the polyline (m).
double PolylineLength(std::span<const Vec2> waypoints_m);

/// Length of the path SampleTrajectory walks (m): the polyline with its corners rounded to
/// turn_radius_m (the polyline's length for 0).
double PathLength(std::span<const Vec2> waypoints_m, double turn_radius_m);

}  // namespace mirage::geometry
