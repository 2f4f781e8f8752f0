// SPDX-License-Identifier: MIT
// Simulated epochs of a UWB tag moving along a trajectory among TDOA anchors (the scenario's
// anchors) with box obstacles (channel/uwb_tdoa_simulator.h): one epoch per trajectory sample,
// carrying the pairwise differences of the slots in [t_k, t_k + dt_s), all for the tag at sample
// k; the epoch's time is its first row's (an epoch without rows keeps the sample's). With
// dt_s = 1 / rate_hz every epoch holds one slot, as a replay of the written tdoa.csv sees them
// (pipeline/recorded_source.h makes one epoch per time stamp).
#pragma once

#include <optional>
#include <vector>

#include "mirage/core/rng.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/epoch_source.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::pipeline {

/// The epochs of one run of a UWB TDOA scenario.
class UwbTdoaSource final : public EpochSource {
 public:
  UwbTdoaSource(const Experiment& experiment, int trajectory, int run);

  std::optional<SourceStep> Next() override;
  [[nodiscard]] std::optional<std::vector<Vec3>> TrueStart() const override { return std::vector<Vec3>{TruthAt(0)}; }
  [[nodiscard]] double start_s() const override { return samples_.front().t_s; }

  /// The tag's true position at trajectory sample k (height motion included).
  [[nodiscard]] Vec3 TruthAt(std::size_t k) const { return TrajectoryPositionAt(trajectory_, samples_[k]); }
  /// The trajectory's samples (one per epoch).
  [[nodiscard]] const std::vector<geometry::TrajectorySample>& samples() const { return samples_; }

 private:
  const Experiment& experiment_;
  const TrajectorySpec& trajectory_;
  std::vector<geometry::TrajectorySample> samples_;
  std::vector<Vec3> anchors_m_;
  std::vector<std::string> anchor_ids_;
  core::Rng rng_;
  std::size_t next_ = 0;
};

}  // namespace mirage::pipeline
