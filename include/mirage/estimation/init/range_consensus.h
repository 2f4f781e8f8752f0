// SPDX-License-Identifier: MIT
// Consensus search for a point q seen in ranges from many agent positions, each with several
// unlabeled ranges (mirage; the VA discovery's sweep, docs/methods/slam.md "The sweep for far
// VAs"). Pairs of ranges from two positions far apart propose the two intersections of their
// circles; a point scores the positions with a range within a gate of |q - a| (a
// hypothesise-and-verify search in the manner of RANSAC, here exhaustive over the range pairs of
// three pairs of positions, so the result is deterministic); the best proposals are refined by a
// least-squares fit to their supporting ranges (LO-RANSAC). A weak, far reflection whose range
// changes by almost a step length per step and that is missed at some steps cannot be chained
// range by range among clutter, but its ranges still agree with one point over metres of walk.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// The ranges measured from one agent position, sorted ascending.
struct RangeScan {
  Vec2 position_m = Vec2::Zero();
  std::vector<double> ranges_m;
};

/// Options of the search.
struct RangeConsensusOptions {
  /// A range supports a point if within this distance of its predicted range (m). The defaults
  /// are the VA discovery's (which sets all of them from DiscoveryOptions).
  double gate_m = 0.04;
  /// Smallest number of supporting scans after the refinement (at most one range per scan
  /// counts); proposals need half of it (at least 3) to be refined.
  std::size_t min_support = 10;
  /// Proposals come from scan pairs at least this far apart (m); closer circles intersect at
  /// grazing angles and place the point metres off.
  double min_pair_distance_m = 0.5;
  /// Points within this distance of an excluded point are neither proposed nor returned (m);
  /// also the distance below which two proposals are the same point.
  double exclusion_radius_m = 0.2;
};

/// The best-supported point.
struct RangeConsensus {
  Vec2 position_m = Vec2::Zero();
  /// The mirror image of position_m about the line through the two proposing positions: the
  /// other point that explains the same ranges if the scans lie on that line (a straight walk).
  Vec2 mirror_m = Vec2::Zero();
  /// The supporting ranges: (scan index, index of the range in that scan), the nearest range of
  /// each supporting scan, scans in order.
  std::vector<std::pair<std::size_t, std::size_t>> support;
};

/// Searches the scans (in walking order; each scan's ranges sorted ascending) for a well-supported
/// point. Proposals come from the range pairs of the first and last scans and of the scans n/8
/// and n/4 in from either end; the three best with at least half of min_support (further apart
/// than exclusion_radius_m; ties keep the first) are refined by a least-squares fit to their
/// supporting ranges, re-scored, and refined again while the support grows (at most 3 rounds).
/// Returns the refined point with the most support that reaches min_support and is not within
/// exclusion_radius_m of an excluded point, or std::nullopt. Only these proposals are refined: a
/// point that no proposing pair of scans saw (both missed it) is not found.
std::optional<RangeConsensus> FindRangeConsensus(std::span<const RangeScan> scans, std::span<const Vec2> excluded_m,
                                                 const RangeConsensusOptions& options);

}  // namespace mirage::estimation
