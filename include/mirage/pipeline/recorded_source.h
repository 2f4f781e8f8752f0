// SPDX-License-Identifier: MIT
// Epochs read from a recording (docs/recorded_data.md): the range sets of each time (anchors.csv,
// ranges.csv), grouped by the epoch rule (the experiment's epoch window), or one epoch per
// emission with one ToaStamps record per microphone (mics.csv, toa.csv; the window does not
// apply), or one epoch per time stamp with its pairwise TDOAs (anchors.csv, tdoa.csv; the window
// does not apply), with the truth interpolated at each epoch when the recording has it
// (truth.csv).
#pragma once

#include <optional>
#include <vector>

#include "mirage/pipeline/epoch_source.h"
#include "mirage/pipeline/recording.h"

namespace mirage::pipeline {

class RecordedSource final : public EpochSource {
 public:
  /// @param epoch_window_s the epoch rule's window (s), >= 0 (0: rows with one time stamp);
  ///        unused for a recording of stamps or of TDOAs.
  RecordedSource(const Recording& recording, double epoch_window_s);

  std::optional<SourceStep> Next() override;
  /// The truth at the first epoch, when the recording has truth there.
  [[nodiscard]] std::optional<std::vector<Vec3>> TrueStart() const override;
  [[nodiscard]] double start_s() const override;
  [[nodiscard]] int out_of_order() const override { return out_of_order_; }

 private:
  const Recording& recording_;
  std::vector<core::Epoch> epochs_;
  int out_of_order_ = 0;
  std::size_t next_ = 0;
};

}  // namespace mirage::pipeline
