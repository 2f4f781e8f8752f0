// SPDX-License-Identifier: MIT
#include "mirage/pipeline/recorded_source.h"

#include "mirage/core/epoch_assembler.h"

namespace mirage::pipeline {

RecordedSource::RecordedSource(const Recording& recording, double epoch_window_s) : recording_(recording) {
  if (recording.toa_stamps) {
    // One epoch per emission, as the acoustic simulator makes them: the step's time, one
    // record per microphone (the rows already say which stamps belong to one emission).
    for (const auto& step : recording.steps) {
      core::Epoch epoch;
      epoch.t_s = step.t_s;
      epoch.toas = step.toas;
      epochs_.push_back(std::move(epoch));
    }
    return;
  }
  if (recording.tdoa) {
    // One epoch per time stamp, the differences in file order: a UWB TDOA system reports one
    // pair per packet at up to a few hundred Hz, and the filter updates with each as it comes
    // (crazyflie's kalman_core), so the window does not merge them. The time and ids are set
    // from the step and the indices, as for range sets.
    for (const auto& step : recording.steps) {
      core::Epoch epoch;
      epoch.t_s = step.t_s;
      epoch.tdoas = step.tdoas;
      for (auto& m : epoch.tdoas) {
        m.t_s = step.t_s;
        m.id_i = recording.anchor_ids[static_cast<std::size_t>(m.index_i)];
        m.id_j = recording.anchor_ids[static_cast<std::size_t>(m.index_j)];
      }
      epochs_.push_back(std::move(epoch));
    }
    return;
  }
  core::EpochAssembler assembler(epoch_window_s);
  for (const auto& step : recording.steps) {
    for (const auto& anchor : step.anchors) {
      core::RangeSet set = anchor;
      set.t_s = step.t_s;
      set.anchor_id = recording.anchor_ids[static_cast<std::size_t>(anchor.anchor_index)];
      if (auto closed = assembler.Add(std::move(set))) epochs_.push_back(std::move(*closed));
    }
  }
  if (auto last = assembler.Flush()) epochs_.push_back(std::move(*last));
  out_of_order_ = assembler.out_of_order();
}

std::optional<SourceStep> RecordedSource::Next() {
  if (next_ >= epochs_.size()) return std::nullopt;
  SourceStep step;
  step.epoch = epochs_[next_++];
  step.truth_m = {recording_.TruthAt(step.epoch.t_s)};
  return step;
}

std::optional<std::vector<Vec3>> RecordedSource::TrueStart() const {
  if (epochs_.empty()) return std::nullopt;
  const auto truth = recording_.TruthAt(epochs_.front().t_s);
  if (!truth) return std::nullopt;
  return std::vector<Vec3>{*truth};
}

double RecordedSource::start_s() const { return epochs_.empty() ? 0.0 : epochs_.front().t_s; }

}  // namespace mirage::pipeline
