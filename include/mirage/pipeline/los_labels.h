// SPDX-License-Identifier: MIT
// A method's line-of-sight labels of one epoch scored against the simulation's: the precision and
// recall of LOS identification (Bordoy 2020 Sec. 5.1) on simulated stamps, whose labels the
// simulator knows (channel/acoustic_stamps.h) and the estimator never sees.
#pragma once

#include <optional>
#include <vector>

#include "mirage/core/epoch.h"

namespace mirage::pipeline {

/// The labels of one epoch, or summed over many, counted per record (receiver).
struct LosLabelCount {
  int true_positives = 0;   ///< the labelled stamp is the direct path
  int false_positives = 0;  ///< the labelled stamp is not (an echo, a delayed direct path, noise)
  int false_negatives = 0;  ///< the record has a direct stamp and the labelled one is not it

  LosLabelCount& operator+=(const LosLabelCount& other) {
    true_positives += other.true_positives;
    false_positives += other.false_positives;
    false_negatives += other.false_negatives;
    return *this;
  }
  /// TP / (TP + FP); empty when nothing was labelled.
  [[nodiscard]] std::optional<double> Precision() const {
    const int labelled = true_positives + false_positives;
    return labelled > 0 ? std::optional<double>(static_cast<double>(true_positives) / labelled) : std::nullopt;
  }
  /// TP / (TP + FN): of the direct stamps, the share labelled; empty without direct stamps.
  [[nodiscard]] std::optional<double> Recall() const {
    const int direct = true_positives + false_negatives;
    return direct > 0 ? std::optional<double>(static_cast<double>(true_positives) / direct) : std::nullopt;
  }
};

/// The method's labels (methods::StepOutput::los_stamps: per record of epoch.toas, the labelled
/// stamp's index or -1) against the truth (SourceStep::direct_stamps: per record, per stamp,
/// whether it is the undelayed direct path). A record whose direct stamp is not labelled, also at
/// an emission without a fix, is a false negative. Empty when either side has no labels (also
/// an epoch without stamp records) or their shapes do not match the epoch's records.
std::optional<LosLabelCount> CountLosLabels(const core::Epoch& epoch, const std::vector<std::vector<bool>>& direct_stamps,
                                            const std::vector<int>& los_stamps);

}  // namespace mirage::pipeline
