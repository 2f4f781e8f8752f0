// SPDX-License-Identifier: MIT
// Simulated epochs of an acoustic sender walking a trajectory among microphones (the scenario's
// anchors) in a hall of 3-D reflectors (Bordoy 2020; channel/acoustic_stamps.h): one epoch per
// emission, with one ToaStamps record per microphone holding every stamp it detected (direct
// path, echoes, false alarms; unlabeled, as a detector reports them). The sender emits every
// dt_s of its own clock, which runs clock_drift_ppm fast, from an unknown start: run i draws the
// first emission's offset uniformly within one interval, so the emission times are unknown to
// the estimator. The epoch's time is the emission's earliest stamp (the receivers' time base
// knows nothing earlier); an emission nobody heard gives an empty epoch at its nominal time.
// With an inertial model, each epoch also carries the phone's IMU samples since the previous
// emission, or the thesis's synthetic position increment (the true displacement rotated by a
// constant heading error).
#pragma once

#include <optional>
#include <vector>

#include "mirage/core/rng.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/pipeline/epoch_source.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::pipeline {

/// The epochs of one run of an acoustic scenario.
class AcousticSource final : public EpochSource {
 public:
  AcousticSource(const Experiment& experiment, int trajectory, int run);

  std::optional<SourceStep> Next() override;
  [[nodiscard]] std::optional<std::vector<Vec3>> TrueStart() const override;
  [[nodiscard]] double start_s() const override { return samples_.front().t_s; }

  /// The sender's true position at trajectory sample k (hand motion included).
  [[nodiscard]] Vec3 TruthAt(std::size_t k) const;
  /// The trajectory's samples (one per emission).
  [[nodiscard]] const std::vector<geometry::TrajectorySample>& samples() const { return samples_; }

 private:
  const Experiment& experiment_;
  const TrajectorySpec& trajectory_;
  std::vector<geometry::TrajectorySample> samples_;
  std::vector<Vec3> mics_m_;
  core::Rng stamps_rng_;
  void SimulateImuOnce();

  core::Rng imu_rng_;
  bool imu_done_ = false;
  std::vector<core::ImuSample> imu_;  // InertialModel::kImu: the whole run's samples
  std::size_t next_imu_ = 0;
  double first_emission_s_ = 0.0;  // the sender clock's offset against the receivers' time base
  std::size_t next_ = 0;
};

}  // namespace mirage::pipeline
