// SPDX-License-Identifier: MIT
#include "mirage/geometry/trajectory.h"

#include <cassert>
#include <cmath>

namespace mirage::geometry {

double PolylineLength(std::span<const Vec2> waypoints_m) {
  double length_m = 0.0;
  for (std::size_t i = 1; i < waypoints_m.size(); ++i) length_m += (waypoints_m[i] - waypoints_m[i - 1]).norm();
  return length_m;
}

std::vector<TrajectorySample> SampleTrajectory(std::span<const Vec2> waypoints_m, double speed_mps, double dt_s,
                                               const Vec2& offset_m) {
  assert(waypoints_m.size() >= 2 && speed_mps > 0.0 && dt_s > 0.0);
  const double total_m = PolylineLength(waypoints_m);
  const double step_m = speed_mps * dt_s;
  // Small slack so that a trajectory whose length is a multiple of the step keeps its end point.
  const auto steps = static_cast<std::size_t>(std::floor(total_m / step_m + 1e-9)) + 1;
  std::vector<TrajectorySample> samples;
  samples.reserve(steps);
  std::size_t segment = 0;
  double segment_start_m = 0.0;  // arc length at the start of the current segment
  for (std::size_t n = 0; n < steps; ++n) {
    const double s_m = std::min(static_cast<double>(n) * step_m, total_m);
    // Advance to the segment that contains s_m (skipping zero-length segments).
    while (segment + 2 < waypoints_m.size() &&
           s_m > segment_start_m + (waypoints_m[segment + 1] - waypoints_m[segment]).norm()) {
      segment_start_m += (waypoints_m[segment + 1] - waypoints_m[segment]).norm();
      ++segment;
    }
    const Vec2 a = waypoints_m[segment];
    const Vec2 b = waypoints_m[segment + 1];
    const double len_m = (b - a).norm();
    const Vec2 dir = len_m > 0.0 ? Vec2((b - a) / len_m) : Vec2(Vec2::Zero());
    TrajectorySample sample;
    sample.t_s = static_cast<double>(n) * dt_s;
    sample.position_m = a + (s_m - segment_start_m) * dir + offset_m;
    sample.velocity_mps = speed_mps * dir;
    samples.push_back(sample);
  }
  return samples;
}

}  // namespace mirage::geometry
