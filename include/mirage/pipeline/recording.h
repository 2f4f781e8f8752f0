// SPDX-License-Identifier: MIT
// Recorded range-level data, as read from (or written to) anchors.csv, ranges.csv and truth.csv
// (ROADMAP.md "Recorded data", docs/recorded_data.md): the anchors, the unlabeled ranges of every
// anchor at every time step, and optionally the true positions.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mirage/core/records.h"
#include "mirage/core/types.h"

namespace mirage::pipeline {

/// The ranges of all anchors at one time.
struct RecordedStep {
  double t_s = 0.0;
  /// One entry per anchor, in anchor order (anchor_index == position); an anchor without rows at
  /// this time has no ranges (missed detections, or no reply).
  std::vector<core::RangeSet> anchors;
};

/// A true position at one time.
struct TruthSample {
  double t_s = 0.0;
  Vec3 position_m = Vec3::Zero();  ///< z is 0 when truth.csv has no z_m column
};

/// One recorded run.
struct Recording {
  std::vector<std::string> anchor_ids;
  std::vector<Vec3> anchors_m;    ///< z is 0 when anchors.csv has no z_m column
  bool anchors_have_z = false;    ///< anchors.csv has a z_m column
  std::vector<RecordedStep> steps;  ///< strictly increasing t_s
  std::vector<TruthSample> truth;   ///< strictly increasing t_s; empty when there is no truth file
  bool truth_has_z = false;         ///< truth.csv has a z_m column

  [[nodiscard]] bool has_truth() const { return !truth.empty(); }
  /// The true position at t_s, linearly interpolated between truth samples; empty outside the
  /// truth's time span (or without truth).
  [[nodiscard]] std::optional<Vec3> TruthAt(double t_s) const;
};

}  // namespace mirage::pipeline
