// SPDX-License-Identifier: MIT
// Plain measurement records shared by the simulator, the file readers and the estimators, so
// that every estimator runs unchanged on simulated, recorded and live data (ROADMAP.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::core {

/// A sampled complex-baseband channel impulse response.
struct Cir {
  /// Delay of samples[0] relative to the transmit time (s).
  double start_s = 0.0;
  /// Sample period T_s (s).
  double sample_period_s = 0.0;
  /// Complex baseband samples; sample n is at delay start_s + n * sample_period_s.
  std::vector<Complex> samples;
};

/// One unlabeled range measurement, e.g. one extracted multipath component.
struct RangeMeasurement {
  /// Range, i.e. propagation delay times c (m).
  double range_m = 0.0;
  /// Magnitude of the estimated complex amplitude |alpha| (linear, the CIR's unit), if known.
  std::optional<double> amplitude;
};

/// All unlabeled ranges measured to one physical anchor at one time step.
struct AnchorRanges {
  /// Index of the physical anchor in the scenario's anchor list.
  int anchor_index = 0;
  /// Ranges in any order; clutter and missing detections are possible.
  std::vector<RangeMeasurement> ranges;
};

/// True if one of `ranges` lies within tolerance_m (exclusive) of expected_m: the match test of
/// the relocalization scores (MINT's grid search, SLAM's track-loss recovery).
inline bool HasRangeNear(std::span<const RangeMeasurement> ranges, double expected_m, double tolerance_m) {
  return std::any_of(ranges.begin(), ranges.end(),
                     [&](const RangeMeasurement& r) { return std::abs(r.range_m - expected_m) < tolerance_m; });
}

}  // namespace mirage::core
