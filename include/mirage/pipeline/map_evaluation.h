// SPDX-License-Identifier: MIT
// Map error of a SLAM run: the estimated VAs against the true VAs of the simulated channel that
// were visible somewhere along the run, by the OSPA distance (Schuhmacher et al. 2008) with a
// cut-off, plus the counts a reader wants (discovered, true, matched, false) and how far the
// matched VAs are from their true positions.
#pragma once

#include <optional>
#include <set>
#include <span>
#include <vector>

#include "mirage/geometry/virtual_anchor.h"
#include "mirage/methods/estimator.h"

namespace mirage::pipeline {

/// Map error of one run.
struct MapScore {
  double ospa_m = 0.0;               ///< OSPA distance, order 1 (m)
  double ospa_localization_m = 0.0;  ///< its localisation part (m)
  double ospa_cardinality_m = 0.0;   ///< its cardinality part (m)
  int estimated = 0;    ///< map VAs scored: not filtered, associated at least once, anchors excluded
  int discovered = 0;   ///< VAs found by discovery (filtered ones included)
  int filtered = 0;     ///< map VAs not scored (excluded by the method's filter or never used)
  int true_vas = 0;     ///< true VAs (order >= 1) visible at some step of the run
  int matched = 0;      ///< scored VAs assigned to a true VA closer than the cut-off
  int false_vas = 0;    ///< scored VAs without such a match
  std::optional<double> matched_mean_error_m;  ///< mean distance of the matched pairs (m)
};

/// Scores a method's map features, the scored ones (MapFeature::scored), against the channel VAs
/// with ids in visible_channel_ids, per anchor (a VA of anchor 1 never matches a true VA of
/// anchor 2); cutoff_m is the OSPA cut-off c. `filtered` counts the features that are neither
/// scored nor physical anchors.
MapScore EvaluateMap(std::span<const methods::MapFeature> map, const geometry::VirtualAnchorSet& channel_vas,
                     const std::set<int>& visible_channel_ids, double cutoff_m);

}  // namespace mirage::pipeline
