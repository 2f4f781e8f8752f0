// SPDX-License-Identifier: MIT
// Recorded data, as read from (or written to) CSV files (ROADMAP.md "Recorded data",
// docs/recorded_data.md): the anchors and the unlabeled ranges of every anchor at every time step
// (anchors.csv, ranges.csv), or the microphones and the arrival-time stamps of every microphone
// for every emission of a sound sender (mics.csv, toa.csv); optionally the true positions
// (truth.csv).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mirage/core/records.h"
#include "mirage/core/types.h"

namespace mirage::pipeline {

/// The ranges of all anchors at one time, or the stamps of all microphones of one emission.
struct RecordedStep {
  double t_s = 0.0;
  /// Range recordings: one entry per anchor, in anchor order (anchor_index == position); an
  /// anchor without rows at this time has no ranges (missed detections, or no reply).
  std::vector<core::RangeSet> anchors;
  /// Stamp recordings: one entry per microphone, in microphone order (receiver_index ==
  /// position), t_s and receiver_id set as the estimator sees them; a microphone without rows
  /// for this emission has no stamps.
  std::vector<core::ToaStamps> toas;
  /// Pairwise TDOA recordings (tdoa.csv): the rows of this time, in file order.
  std::vector<core::TdoaMeasurement> tdoas;
};

/// A true position at one time.
struct TruthSample {
  double t_s = 0.0;
  Vec3 position_m = Vec3::Zero();  ///< z is 0 when truth.csv has no z_m column
};

/// One recorded run.
struct Recording {
  /// The steps carry arrival-time stamps (mics.csv, toa.csv), not range sets; the anchors are
  /// then the microphones.
  bool toa_stamps = false;
  /// The steps carry pairwise time differences (tdoa.csv), not range sets or stamps; the anchors
  /// (anchors.csv with a z_m column) are the TDOA receivers.
  bool tdoa = false;
  std::vector<std::string> anchor_ids;
  std::vector<Vec3> anchors_m;    ///< z is 0 when anchors.csv has no z_m column
  bool anchors_have_z = false;    ///< anchors.csv has a z_m column (always for mics.csv)
  std::vector<RecordedStep> steps;  ///< strictly increasing t_s
  std::vector<TruthSample> truth;   ///< strictly increasing t_s; empty when there is no truth file
  bool truth_has_z = false;         ///< truth.csv has a z_m column

  [[nodiscard]] bool has_truth() const { return !truth.empty(); }
  /// The true position at t_s, linearly interpolated between truth samples; empty outside the
  /// truth's time span (or without truth).
  [[nodiscard]] std::optional<Vec3> TruthAt(double t_s) const;
};

}  // namespace mirage::pipeline
