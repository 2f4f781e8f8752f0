// SPDX-License-Identifier: MIT
// Track-loss recovery for SLAM (a mirage addition; the thesis names re-localization as open
// work, Lafer 2014 Sec. 6.1, and the paper's filter cannot recover from a lost track).
//
// Why SLAM needs its own: MINT's search (methods/mint/relocalization) scores positions by the
// VAs the known floor plan makes visible there; SLAM has no floor plan, only the anchors and the
// VAs it has found. With two anchors a position is fixed by their LOS ranges up to a mirror
// image across the line through them; in the seminar room a track that is pulled off in an
// obstacle's shadow either runs away or settles on that mirror image, where both LOS ranges fit
// and only the reflections disagree. The recovery therefore
//   1. takes the candidate positions where two anchors' LOS circles intersect, trying each
//      anchor's first few measured ranges as its LOS (the LOS is the earliest path when it is
//      there at all);
//   2. counts, at each candidate and at the current estimate, the map points (the anchors and
//      the VAs in the state) that have a measured range within a tolerance of their expected
//      range, each map point at most once. Discovered VAs have no visibility region, so the
//      counts of two positions are compared, never a fraction;
//   3. restarts the agent at a candidate that beats the estimate by a margin at several
//      consecutive steps, the candidates of those steps following one another as a walker
//      could.
// With a known floor plan (the known-VA baseline) the tracker supplies the score instead: every
// VA of the floor plan, the anchors' LOS included, counts at its known position and only where
// ray tracing makes it visible, as in MINT's search.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"

namespace mirage::methods::slam {

/// Parameters of the track-loss recovery.
struct TrackRecoveryOptions {
  /// Detect a lost track and restart it.
  bool enabled = true;
  /// A map point matches when a measured range lies within this distance of its expected range
  /// (m), > 0. 5 cm: about 2 sigma of a first-order reflection's range at 5 dB SINR, as in MINT.
  /// Derived: 2 range sigmas.
  double match_tolerance_m = 0.05;
  /// Two LOS circles that miss each other by less than this still give a candidate, the point
  /// between them (m), > 0: range noise and a few centimetres of detection bias can separate
  /// circles that should touch. 5 cm. Derived: 2 sigma of the gap, a sum of two range errors,
  /// 2 sqrt(2) range sigmas.
  double circle_slack_m = 0.05;
  /// Measured ranges of each anchor, earliest first, tried as its LOS, >= 1. 3: the LOS is the
  /// first range unless a clutter or noise peak came before it.
  int los_candidates = 3;
  /// Matched map points by which a candidate must beat the estimate, >= 1. 2: one chance match
  /// among ~15 clutter ranges per anchor and step is common, two at the same position are not.
  int min_margin = 2;
  /// Used instead of min_margin when the map is a known floor plan's VAs (the tracker's
  /// prior_visibility with prior_max_order > 0 and walls), which score only where ray tracing
  /// makes them visible, >= 1. About 35 VAs are visible per anchor there, so the estimate and a
  /// candidate each collect a few chance matches among ~15 ranges per anchor and step. Seminar
  /// room, seeds 1-9, 450 known-VA runs: with 4 only the two lost runs (seeds 5 and 9) restart;
  /// with 2 good tracks restart too (8 times on seeds 4 and 7; one left with 0.42 m rmse).
  int min_margin_floor_plan = 4;
  /// With the floor plan's VAs, the search runs only within this time after a step at which an
  /// anchor's LOS found no range (at stage 1, or in the joint association without the tracker's
  /// reassociate), and while a pending candidate's chain continues (s), >= 0 (0: the miss step
  /// only). Ray tracing every candidate costs about 110 us per step, and both lost known-VA
  /// tracks began with a LOS lost at a corner. 1 s (10 steps of 0.1 s): both restart, no good track
  /// restarts (seeds 1-9); searching at every step after the first miss restarts one good track
  /// more (seed 5, harmlessly). Derived: the time to walk 0.5 m, past the corner.
  double floor_plan_watch_s = 1.0;
  /// Consecutive steps at which a candidate must win before the restart, >= 1.
  int lost_steps = 3;
  /// The winning candidates of consecutive steps must lie within this distance of one another
  /// (m), > 0: a walker's step (0.05 m at 0.5 m/s and 10 Hz) plus the candidates' scatter. 0.3 m.
  /// Derived: one step of motion plus the 0.25 m of scatter.
  double follow_gate_m = 0.3;
  /// Candidates farther than this from the estimate are not considered (m), > 0. 3 m: a track
  /// that settled on the mirror image of the two-anchor geometry is twice its distance from the
  /// anchors' line away (about 1 m in the seminar room); far candidates are chance
  /// intersections of reflections and clutter (on range-level input with clutter before the LOS
  /// one 6 m away won at 3 steps and restarted good tracks in 18 of 25 runs).
  double max_jump_m = 3.0;
  /// A chain whose winning candidates move faster than this from its first step to its last (m/s),
  /// > 0, is not a walker but chance intersections: no restart. 1.5 m/s, a brisk walk (the
  /// scenarios walk at 0.5). Seminar room, seed 18, trajectory 2, run 9, step 85: a chain 3 m off
  /// at 2.2 m/s (within follow_gate_m at every step) restarted a track that was 3 cm off; the
  /// track then followed clutter at that speed, 40 m off by the end, and max_jump_m kept every
  /// later candidate out. The restarts of good chains (seeds 1-27 anchors only, 1-15 known VAs)
  /// moved at 0.42-0.99 m/s. With lost_steps 1 there is no chain, and no limit. Not derived from
  /// the walker's speed: the chain's speed from its first step to its last includes the
  /// candidates' scatter over those few steps, which at a slow walk is far above the walk itself.
  double max_speed_mps = 1.5;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<TrackRecoveryOptions>& TrackRecoveryOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const TrackRecoveryOptions& options);

/// A point of the map as the recovery sees it: whose ranges it explains and where it is.
struct MapPoint {
  int anchor_index = 0;
  Vec2 position_m = Vec2::Zero();
};

/// Map points with a measured range of their anchor within tolerance_m of the expected range.
int CountMatches(const Vec2& p_m, std::span<const MapPoint> map, std::span<const core::RangeSet> measurements,
                 double tolerance_m);

/// Intersections of the LOS circles of every pair of anchors, each anchor's first
/// `los_candidates` ranges tried as its LOS radius. Circles that miss each other by less than
/// slack_m (noise; TrackRecoveryOptions::circle_slack_m) give the point between them.
std::vector<Vec2> LosCandidates(std::span<const MapPoint> anchors, std::span<const core::RangeSet> measurements,
                                int los_candidates, double slack_m = TrackRecoveryOptions{}.circle_slack_m);

/// Where to restart a lost track.
struct Restart {
  Vec2 position_m = Vec2::Zero();
  /// The winning candidates' mean velocity over the steps that triggered the restart, zero
  /// when one step triggers it.
  Vec2 velocity_mps = Vec2::Zero();
};

/// The recovery's state across steps. Not thread-safe; one per tracker.
class TrackRecovery {
 public:
  explicit TrackRecovery(const TrackRecoveryOptions& options) : options_(options) {}

  /// Forgets the pending candidate.
  void Reset();
  /// A candidate has won at the last step and waits for more.
  [[nodiscard]] bool pending() const { return pending_steps_ > 0; }

  /// Checks the estimate after the step at t_s; returns where to restart when the track is
  /// lost. `anchors` are the physical anchors (the LOS centres); score_at(p) is the number of
  /// map points whose expected range a measured range matches at p (CountMatches over the map,
  /// plus the floor plan's VAs counted only where visible, as the tracker scores).
  std::optional<Restart> Check(double t_s, const Vec2& estimate_m, std::span<const MapPoint> anchors,
                               const std::function<int(const Vec2&)>& score_at,
                               std::span<const core::RangeSet> measurements);

 private:
  TrackRecoveryOptions options_;
  int pending_steps_ = 0;
  Vec2 pending_m_ = Vec2::Zero();        // the last winning candidate
  Vec2 first_pending_m_ = Vec2::Zero();  // the first winning candidate of the run
  double first_pending_t_s_ = 0.0;
};

}  // namespace mirage::methods::slam
