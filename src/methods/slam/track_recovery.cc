// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/track_recovery.h"

#include <algorithm>
#include <cmath>

#include "mirage/core/derived_defaults.h"
#include "mirage/geometry/segment.h"

namespace mirage::methods::slam {

const core::OptionsDescriptor<TrackRecoveryOptions>& TrackRecoveryOptionsDescriptor() {
  using core::ValueRange;
  using O = TrackRecoveryOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("methods::slam::TrackRecoveryOptions");
    d.Boolean(&O::enabled, {.key = "enabled", .doc = "Detect a lost track and restart it (mirage)."});
    d.Number(&O::match_tolerance_m,
             {.key = "match_tolerance_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "A map point matches when a measured range lies within this distance of its expected range. 5 "
                     "cm: about 2 sigma of a first-order reflection's range at 5 dB SINR, as in MINT. Derived: 2 "
                     "range sigmas.",
              .derived = core::RangeSigmas(2.0)});
    d.Number(&O::circle_slack_m,
             {.key = "circle_slack_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Two LOS circles that miss each other by less than this still give a candidate, the point between "
                     "them: range noise and detection bias can separate circles that should touch. 5 cm. Derived: 2 "
                     "sigma of the gap, which is a sum of two range errors.",
              .derived = core::DerivedDefault{
                  .formula = "2 * sqrt(2) * range_sigma_m",
                  .needs = {core::PhysicalKey::kRangeSigma},
                  .compute = [](const core::PhysicalKeys& k) { return 2.0 * std::sqrt(2.0) * *k.range_sigma_m; }}});
    d.Integer(&O::los_candidates,
              {.key = "los_candidates",
               .range = ValueRange::Closed(1.0, 100.0),
               .doc = "Measured ranges of each anchor, earliest first, tried as its LOS. 3: the LOS is the first range "
                      "unless a clutter or noise peak came before it."});
    d.Integer(&O::min_margin,
              {.key = "min_margin",
               .range = ValueRange::Closed(1.0, 1000.0),
               .doc = "Matched map points by which a candidate must beat the estimate. 2: one chance match among ~15 "
                      "clutter ranges per anchor and step is common, two at the same position are not."});
    d.Integer(&O::min_margin_floor_plan,
              {.key = "min_margin_floor_plan",
               .range = ValueRange::Closed(1.0, 1000.0),
               .doc = "Replaces min_margin when the map is a known floor plan's VAs, which score only where visible "
                      "(about 35 per anchor: more chance matches). 4: only the two lost runs restart (seminar room, "
                      "seeds 1-9); with 2 good tracks restart too."});
    d.Number(&O::floor_plan_watch_s,
             {.key = "floor_plan_watch_s",
              .unit = "s",
              .range = ValueRange::NonNegative(),
              .doc = "With the floor plan's VAs the search (ray tracing every candidate, about 110 us a step) runs "
                     "only this long after an anchor's LOS found no range, and while a pending chain continues (0: "
                     "the miss step only). 1 s (10 steps of 0.1 s): both lost known-VA tracks restart, no good one "
                     "does (seeds 1-9). Derived: the time to walk 0.5 m; the lost tracks began with a LOS lost at a "
                     "corner, and what is visible changes with the distance walked past it.",
              .derived = core::WalkingTime(0.5)});
    d.Retired("floor_plan_watch_steps", "floor_plan_watch_s", "seconds, not steps: the old value times dt_s (10 steps of 0.1 s = 1 s), or leave it out for the default derived from speed_mps");
    d.Integer(&O::lost_steps, {.key = "lost_steps",
                               .unit = "steps",
                               .range = ValueRange::Closed(1.0, 1e6),
                               .doc = "Consecutive steps at which a candidate must win before the restart. 3."});
    d.Number(&O::follow_gate_m,
             {.key = "follow_gate_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "The winning candidates of consecutive steps must lie within this distance of one another: a "
                     "walker's step (0.05 m at 0.5 m/s and 10 Hz) plus the candidates' scatter. 0.3 m. Derived: one "
                     "step of motion plus the 0.25 m of scatter.",
              .derived = core::StepLengthPlus(0.25)});
    d.Number(&O::max_jump_m,
             {.key = "max_jump_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Candidates farther than this from the estimate are not considered. 3 m: a track on the mirror "
                     "image of the two-anchor geometry is about 1 m off in the seminar room; farther candidates are "
                     "chance intersections of reflections and clutter."});
    d.Number(&O::max_speed_mps,
             {.key = "max_speed_mps",
              .unit = "m/s",
              .range = ValueRange::Positive(),
              .doc = "A chain of winning candidates moving faster than this from its first step to its last is chance "
                     "intersections, not a walker: no restart. 1.5 m/s, a brisk walk; good restarts moved at "
                     "0.42-0.99 m/s (seminar room). Not derived from the walker's speed: the chain's speed includes "
                     "the candidates' scatter over its few steps, far above a slow walk."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const TrackRecoveryOptions& options) {
  return TrackRecoveryOptionsDescriptor().Validate(options);
}

int CountMatches(const Vec2& p_m, std::span<const MapPoint> map, std::span<const core::RangeSet> measurements,
                 double tolerance_m) {
  int matched = 0;
  for (const MapPoint& point : map) {
    const double expected_m = (point.position_m - p_m).norm();
    for (const auto& anchor : measurements) {
      if (anchor.anchor_index != point.anchor_index) continue;
      if (core::HasRangeNear(anchor.ranges, expected_m, tolerance_m)) {
        ++matched;
        break;
      }
    }
  }
  return matched;
}

namespace {

// The `count` earliest ranges of an anchor: the LOS is the first path when it is there. (The
// strongest ranges as well were tried: on the seminar-room signals the extra candidates won by
// chance often enough to restart good tracks, trajectory 2 p90 5.1 -> 6.1 cm and 0 -> 2-3
// diverged runs on seeds 2 and 3.)
std::vector<double> LosRanges(std::span<const core::RangeSet> measurements, int anchor_index, int count) {
  std::vector<double> out;
  for (const auto& anchor : measurements) {
    if (anchor.anchor_index != anchor_index) continue;
    for (const auto& r : anchor.ranges) out.push_back(r.range_m);
  }
  std::sort(out.begin(), out.end());
  if (out.size() > static_cast<std::size_t>(count)) out.resize(static_cast<std::size_t>(count));
  return out;
}

// Intersections of the circles (c1, r1) and (c2, r2); circles that miss by up to slack_m give the
// point on the centre line between them.
void LooseCircleIntersections(const Vec2& c1, double r1, const Vec2& c2, double r2, double slack_m,
                              std::vector<Vec2>& out) {
  const Vec2 d = c2 - c1;
  const double l = d.norm();
  if (l < 1e-9) return;
  const Vec2 u = d / l;
  if (r1 + r2 < l) {
    if (l - (r1 + r2) < slack_m) out.push_back(c1 + u * (r1 + 0.5 * (l - r1 - r2)));
    return;
  }
  if (std::abs(r1 - r2) > l) {
    const double gap = std::abs(r1 - r2) - l;
    if (gap >= slack_m) return;
    // One circle inside the other, nearly touching: the touching point on the line.
    const double s = r1 > r2 ? r1 - 0.5 * gap : -(r1 - 0.5 * gap);
    out.push_back(c1 + u * s);
    return;
  }
  const auto points = geometry::IntersectCircles(c1, r1, c2, r2);
  if (!points) return;
  out.push_back((*points)[0]);
  if ((*points)[1] != (*points)[0]) out.push_back((*points)[1]);  // touching circles: one point
}

}  // namespace

std::vector<Vec2> LosCandidates(std::span<const MapPoint> anchors, std::span<const core::RangeSet> measurements,
                                int los_candidates, double slack_m) {
  std::vector<std::vector<double>> radii_m;
  for (const MapPoint& anchor : anchors) radii_m.push_back(LosRanges(measurements, anchor.anchor_index, los_candidates));
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    for (std::size_t j = i + 1; j < anchors.size(); ++j) {
      for (const double a : radii_m[i]) {
        for (const double b : radii_m[j]) {
          LooseCircleIntersections(anchors[i].position_m, a, anchors[j].position_m, b, slack_m, out);
        }
      }
    }
  }
  return out;
}

void TrackRecovery::Reset() { pending_steps_ = 0; }

std::optional<Restart> TrackRecovery::Check(double t_s, const Vec2& estimate_m, std::span<const MapPoint> anchors,
                                            const std::function<int(const Vec2&)>& score_at,
                                            std::span<const core::RangeSet> measurements) {
  if (!options_.enabled) return std::nullopt;
  const int estimate_score = score_at(estimate_m);
  const int needed = estimate_score + options_.min_margin;
  // Two bests: over all candidates (a new chain starts there), and among the continuations of
  // the pending chain (within follow_gate_m of its last point). With ~15 clutter ranges per
  // anchor a chance intersection often scores as well as the true position at one step, but it
  // does not recur next to itself at the following steps; the true position does.
  int best_score = -1;
  Vec2 best_m = Vec2::Zero();
  int follow_score = -1;
  Vec2 follow_m = Vec2::Zero();
  for (const Vec2& c : LosCandidates(anchors, measurements, options_.los_candidates, options_.circle_slack_m)) {
    if ((c - estimate_m).norm() > options_.max_jump_m) continue;
    const int score = score_at(c);
    if (score > best_score || (score == best_score && (c - estimate_m).norm() < (best_m - estimate_m).norm())) {
      best_score = score;
      best_m = c;
    }
    if (pending_steps_ > 0 && (c - pending_m_).norm() < options_.follow_gate_m &&
        (score > follow_score || (score == follow_score && (c - pending_m_).norm() < (follow_m - pending_m_).norm()))) {
      follow_score = score;
      follow_m = c;
    }
  }
  if (pending_steps_ > 0 && follow_score >= needed) {
    ++pending_steps_;
    pending_m_ = follow_m;
  } else if (best_score >= needed) {
    pending_steps_ = 1;
    pending_m_ = best_m;
    first_pending_m_ = best_m;
    first_pending_t_s_ = t_s;
  } else {
    pending_steps_ = 0;
    return std::nullopt;
  }
  if (pending_steps_ < options_.lost_steps) return std::nullopt;
  Restart restart;
  restart.position_m = pending_m_;
  const double span_s = t_s - first_pending_t_s_;
  if (span_s > 0.0) restart.velocity_mps = (pending_m_ - first_pending_m_) / span_s;
  pending_steps_ = 0;
  if (restart.velocity_mps.norm() > options_.max_speed_mps) return std::nullopt;  // no walker
  return restart;
}

}  // namespace mirage::methods::slam
