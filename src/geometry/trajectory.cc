// SPDX-License-Identifier: MIT
#include "mirage/geometry/trajectory.h"

#include <cassert>
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace mirage::geometry {

double PolylineLength(std::span<const Vec2> waypoints_m) {
  double length_m = 0.0;
  for (std::size_t i = 1; i < waypoints_m.size(); ++i) length_m += (waypoints_m[i] - waypoints_m[i - 1]).norm();
  return length_m;
}

namespace {

// One piece of a path with rounded corners: a straight leg, or an arc about `center`.
struct Piece {
  bool arc = false;
  Vec2 start = Vec2::Zero();  // straight: start point; arc: start point on the circle
  Vec2 direction = Vec2::Zero();  // straight: unit direction
  Vec2 center = Vec2::Zero();
  double radius_m = 0.0;
  double turn = 0.0;  // arc: +1 turning left, -1 right
  double length_m = 0.0;
};

double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The fraction of the walking speed at t_s: 0 inside a stop, ramping linearly over kStopRamp_s
// before it (down) and after it (up).
double SpeedFactor(double t_s, std::span<const Stop> stops) {
  for (const auto& s : stops) {
    if (t_s < s.at_s - kStopRamp_s) break;
    if (t_s < s.at_s) return (s.at_s - t_s) / kStopRamp_s;
    if (t_s < s.at_s + s.duration_s) return 0.0;
    if (t_s < s.at_s + s.duration_s + kStopRamp_s) return (t_s - s.at_s - s.duration_s) / kStopRamp_s;
  }
  return 1.0;
}

// The path length walked at sample n: n steps without stops (exactly as before stops existed),
// else the speed times the time walked.
double WalkedLength(std::size_t n, double step_m, double speed_mps, double dt_s, std::span<const Stop> stops) {
  if (stops.empty()) return static_cast<double>(n) * step_m;
  return speed_mps * WalkedTime(static_cast<double>(n) * dt_s, stops);
}

// Samples up to the end of the path: the walk's time plus the stops that begin before it ends.
// Small slack so that a trajectory whose length is a multiple of the step keeps its end point.
std::size_t SampleCount(double total_m, double speed_mps, double dt_s, std::span<const Stop> stops) {
  const double step_m = speed_mps * dt_s;
  if (stops.empty()) return static_cast<std::size_t>(std::floor(total_m / step_m + 1e-9)) + 1;
  double end_s = total_m / speed_mps;
  for (const auto& s : stops) {
    if (s.at_s < end_s) end_s += s.duration_s + kStopRamp_s;  // the ramps lose half of it each
  }
  return static_cast<std::size_t>(std::floor(end_s / dt_s + 1e-9)) + 1;
}

// The polyline with each corner replaced by an arc of radius r tangent to both legs; an arc's
// tangent length r tan(theta / 2) is limited to half of the shorter adjoining leg.
std::vector<Piece> RoundCorners(std::span<const Vec2> points, double r) {
  std::vector<Vec2> p;
  for (const Vec2& q : points) {
    if (p.empty() || (q - p.back()).norm() > 0.0) p.push_back(q);
  }
  std::vector<Piece> pieces;
  Vec2 from = p.front();
  for (std::size_t i = 1; i < p.size(); ++i) {
    const Vec2 in = (p[i] - p[i - 1]).normalized();
    Piece line;
    line.start = from;
    line.direction = in;
    if (i + 1 == p.size()) {
      line.length_m = (p[i] - from).norm();
      pieces.push_back(line);
      break;
    }
    const Vec2 out = (p[i + 1] - p[i]).normalized();
    const double theta = std::acos(std::clamp(in.dot(out), -1.0, 1.0));  // turning angle
    const double room_m = 0.5 * std::min((p[i] - p[i - 1]).norm(), (p[i + 1] - p[i]).norm());
    // A straight continuation needs no arc; a reversal (theta = pi) cannot hold one: turn in place.
    const bool arc_fits = theta > 1e-9 && theta < std::acos(-1.0) - 1e-6;
    double tangent_m = arc_fits ? r * std::tan(0.5 * theta) : 0.0;
    const double radius_m = tangent_m > room_m ? room_m / std::tan(0.5 * theta) : r;
    tangent_m = std::min(tangent_m, room_m);
    line.length_m = std::max((p[i] - from).norm() - tangent_m, 0.0);
    pieces.push_back(line);
    if (tangent_m > 0.0) {
      Piece arc;
      arc.arc = true;
      arc.start = p[i] - tangent_m * in;
      arc.turn = Cross(in, out) > 0.0 ? 1.0 : -1.0;
      arc.center = arc.start + arc.turn * radius_m * Vec2(-in.y(), in.x());
      arc.radius_m = radius_m;
      arc.length_m = radius_m * theta;
      arc.direction = in;
      pieces.push_back(arc);
    }
    from = p[i] + tangent_m * out;
  }
  return pieces;
}

std::vector<TrajectorySample> SampleRounded(std::span<const Vec2> waypoints_m, double speed_mps, double dt_s,
                                            const Vec2& offset_m, double turn_radius_m, std::span<const Stop> stops) {
  const std::vector<Piece> pieces = RoundCorners(waypoints_m, turn_radius_m);
  double total_m = 0.0;
  for (const auto& piece : pieces) total_m += piece.length_m;
  const double step_m = speed_mps * dt_s;
  const auto steps = SampleCount(total_m, speed_mps, dt_s, stops);
  std::vector<TrajectorySample> samples;
  std::size_t k = 0;
  double piece_start_m = 0.0;
  for (std::size_t n = 0; n < steps; ++n) {
    const double s_m = std::min(WalkedLength(n, step_m, speed_mps, dt_s, stops), total_m);
    while (k + 1 < pieces.size() && s_m > piece_start_m + pieces[k].length_m) piece_start_m += pieces[k++].length_m;
    const Piece& piece = pieces[k];
    const double along_m = s_m - piece_start_m;
    TrajectorySample sample;
    sample.t_s = static_cast<double>(n) * dt_s;
    if (!piece.arc) {
      sample.position_m = piece.start + along_m * piece.direction + offset_m;
      sample.velocity_mps = speed_mps * piece.direction;
    } else {
      // Rotate the start point about the centre by the angle walked.
      const double angle = piece.turn * along_m / piece.radius_m;
      const Eigen::Rotation2Dd rotation(angle);
      const Vec2 radial = rotation * (piece.start - piece.center);
      const Vec2 tangent = rotation * piece.direction;
      sample.position_m = piece.center + radial + offset_m;
      sample.velocity_mps = speed_mps * tangent;
    }
    sample.velocity_mps *= SpeedFactor(sample.t_s, stops);
    samples.push_back(sample);
  }
  return samples;
}

}  // namespace

double WalkedTime(double t_s, std::span<const Stop> stops) {
  // Time lost to each stop by t_s: the integral of (1 - the speed factor).
  const double r = kStopRamp_s;
  double lost_s = 0.0;
  for (const auto& s : stops) {
    const double x = t_s - (s.at_s - r);  // time since the slowing down began
    if (x <= 0.0) break;
    if (x <= r) {
      lost_s += 0.5 * x * x / r;
    } else if (x <= r + s.duration_s) {
      lost_s += 0.5 * r + (x - r);
    } else if (x <= 2.0 * r + s.duration_s) {
      const double y = x - r - s.duration_s;  // time since the walk resumed
      lost_s += 0.5 * r + s.duration_s + y - 0.5 * y * y / r;
    } else {
      lost_s += s.duration_s + r;
    }
  }
  return t_s - lost_s;
}

double PathLength(std::span<const Vec2> waypoints_m, double turn_radius_m) {
  if (!(turn_radius_m > 0.0) || waypoints_m.size() < 2) return PolylineLength(waypoints_m);
  double length_m = 0.0;
  for (const auto& piece : RoundCorners(waypoints_m, turn_radius_m)) length_m += piece.length_m;
  return length_m;
}

std::vector<TrajectorySample> SampleTrajectory(std::span<const Vec2> waypoints_m, double speed_mps, double dt_s,
                                               const Vec2& offset_m, double turn_radius_m, std::span<const Stop> stops) {
  assert(waypoints_m.size() >= 2 && speed_mps > 0.0 && dt_s > 0.0 && turn_radius_m >= 0.0);
  if (turn_radius_m > 0.0) return SampleRounded(waypoints_m, speed_mps, dt_s, offset_m, turn_radius_m, stops);
  const double total_m = PolylineLength(waypoints_m);
  const double step_m = speed_mps * dt_s;
  const auto steps = SampleCount(total_m, speed_mps, dt_s, stops);
  std::vector<TrajectorySample> samples;
  samples.reserve(steps);
  std::size_t segment = 0;
  double segment_start_m = 0.0;  // arc length at the start of the current segment
  for (std::size_t n = 0; n < steps; ++n) {
    const double s_m = std::min(WalkedLength(n, step_m, speed_mps, dt_s, stops), total_m);
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
    sample.velocity_mps = SpeedFactor(sample.t_s, stops) * speed_mps * dir;
    samples.push_back(sample);
  }
  return samples;
}

}  // namespace mirage::geometry
