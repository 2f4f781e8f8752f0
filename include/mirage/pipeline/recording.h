// SPDX-License-Identifier: MIT
// Recorded range-level data, as read from (or written to) anchors.csv, ranges.csv and truth.csv
// (ROADMAP.md "Recorded data", docs/recorded_data.md): the anchors, the unlabeled ranges of every
// anchor at every time step, and optionally the true positions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mirage/core/measurements.h"
#include "mirage/core/types.h"

namespace mirage::pipeline {

/// The ranges of all anchors at one time.
struct RecordedStep {
  double t_s = 0.0;
  /// One entry per anchor, in anchor order (anchor_index == position); an anchor without rows at
  /// this time has no ranges (missed detections, or no reply).
  std::vector<core::AnchorRanges> anchors;
};

/// A true position at one time.
struct TruthSample {
  double t_s = 0.0;
  Vec2 position_m = Vec2::Zero();
};

/// One recorded run.
struct Recording {
  std::vector<std::string> anchor_ids;
  std::vector<Vec2> anchors_m;
  /// Heights (m) when anchors.csv has z_m; the 2-D methods do not use them.
  std::vector<std::optional<double>> anchor_heights_m;
  std::vector<RecordedStep> steps;  ///< strictly increasing t_s
  std::vector<TruthSample> truth;   ///< strictly increasing t_s; empty when there is no truth file

  [[nodiscard]] bool has_truth() const { return !truth.empty(); }
  /// The true position at t_s, linearly interpolated between truth samples; empty outside the
  /// truth's time span (or without truth).
  [[nodiscard]] std::optional<Vec2> TruthAt(double t_s) const;
};

}  // namespace mirage::pipeline
