// SPDX-License-Identifier: MIT
// The VA discovery's sweep (stage D', mirage; docs/methods/slam.md "The sweep for far VAs"): a
// consensus search over the last steps' ranges that no candidate took, for VAs whose ranges the
// step-to-step groups of stage D cannot chain. A far, weak VA changes its range by up to a step
// length per step and is extracted at 3-4 steps in 5, so its groups break at the 7 cm gate, and a
// wider gate chains clutter in (seminar room: A2's bottom-wall VA entered the map in 3 of 25 runs
// of trajectory 2, in 22 with the sweep). Per anchor, the ranges are buffered with the agent
// positions; every few steps, estimation/init/range_consensus looks for a point most of the
// buffered steps agree on. Its ranges leave the buffer and start a candidate pair (the point
// and its mirror image) in VaDiscovery, which still needs the batch check to be promoted.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/estimation/init/range_consensus.h"
#include "mirage/methods/slam/discovery_sample.h"

namespace mirage::methods::slam {

/// Parameters of the sweep (scenario keys slam.discovery.sweep.*).
struct SweepOptions {
  /// Run the sweep at all.
  bool enabled = true;
  /// How far back ranges are searched (s), > 0: 6 s, 60 steps of 0.1 s. Derived: the time to walk
  /// 3 m (the far VA must be seen from a baseline of min_baseline_m within it; the steps of that
  /// walk, however many, are buffered).
  double window_s = 6.0;
  /// The sweep runs for an anchor every this many steps (>= 1), the anchors on different steps.
  /// A search costs about 130 us at 15 unexplained ranges per step (BM_RangeConsensus); 10
  /// halves the sweep's cost for p90 0-0.3 cm worse in the seminar room.
  int every_steps = 5;
  /// The buffered agent positions must span at least this distance (m), > 0: the intersection
  /// of two circles is well conditioned only over a long baseline; proposing pairs of steps must
  /// be half of it apart.
  double min_baseline_m = 1.0;
  /// A range supports a point if within this distance of its predicted range (m), > 0: range
  /// noise (1-2 cm) plus the agent's error (about 2-3 cm). Derived: 2 range sigmas (95 % of the
  /// VA's ranges support it).
  double gate_m = 0.04;
  /// Smallest fraction of the buffered steps that must support a point, in (0, 1]. Diffuse
  /// multipath and clutter put about one range per metre of range window: a wrong point collects
  /// about 10 % of the steps within a 4 cm gate, a VA extracted at 80 % of the steps 80 %. Gates
  /// of 3 and 5 cm, fractions of 0.5 and 0.7 and windows of 40 and 80 steps gave p90 within
  /// 0.5 cm of these defaults (seminar room, seeds 1 and 3).
  double min_support_fraction = 0.6;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<SweepOptions>& SweepOptionsDescriptor();

/// Problems with the options ("key: message"; DiscoveryOptions' Validate() prefixes "sweep."),
/// empty if valid; see the descriptor.
std::vector<std::string> Validate(const SweepOptions& options);

/// What a search found: the supporting ranges and the two starting points of a candidate pair
/// (the point and its mirror image about the proposing steps, each fitted to the ranges).
struct SweepFind {
  std::vector<DiscoverySample> samples;
  std::array<Vec2, 2> starts = {Vec2::Zero(), Vec2::Zero()};
};

/// The buffers and searches of all anchors. Not thread-safe.
class VaSweep {
 public:
  /// min_measurements: a point needs at least this many supporting steps whatever the fraction
  /// (the candidates' N_rls); exclusion_radius_m: a point this close to an excluded one is no
  /// new VA (the discovery's duplicate radius).
  VaSweep(const SweepOptions& options, int min_measurements, double exclusion_radius_m);

  /// Keeps the ranges of anchor_index at time t_s (s) that no candidate took (used[j] false) with
  /// the agent position; steps window_s or more before t_s leave the buffer. Non-finite ranges
  /// are dropped.
  void Buffer(double t_s, int anchor_index, const Vec2& agent_m, std::span<const core::RangeMeasurement> ranges,
              const std::vector<bool>& used);

  /// True at the steps the sweep runs for this anchor ((step + anchor_index) % every_steps == 0;
  /// the anchors on different steps spread the cost).
  [[nodiscard]] bool Due(int step, int anchor_index) const;

  /// At the steps the sweep runs for this anchor (Due), searches its buffer for a point not
  /// within the exclusion radius of excluded_m (the anchor's active VAs and live candidate
  /// hypotheses). The supporting ranges of a find leave the buffer
  /// whether or not the caller makes a candidate of them, so that the same point cannot win every
  /// search and hide the next one.
  std::optional<SweepFind> Search(int step, int anchor_index, std::span<const Vec2> excluded_m);

  /// Steps buffered for an anchor, and the ranges in them.
  [[nodiscard]] std::size_t buffered_steps(int anchor_index) const;
  [[nodiscard]] std::size_t buffered_ranges(int anchor_index) const;

  /// Forgets all buffers.
  void Reset();

 private:
  // One anchor's buffered steps, oldest first, in parallel vectors (the scans are handed to the
  // consensus search as they are).
  struct AnchorBuffer {
    std::vector<double> times_s;
    std::vector<estimation::RangeScan> scans;                    // agent position, ranges sorted
    std::vector<std::vector<std::optional<double>>> amplitudes;  // of scans[k].ranges_m, same order
  };
  SweepOptions options_;
  int min_measurements_ = 1;
  double exclusion_radius_m_ = 0.0;
  std::vector<AnchorBuffer> buffers_;  // per anchor index
};

}  // namespace mirage::methods::slam
