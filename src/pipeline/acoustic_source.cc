// SPDX-License-Identifier: MIT
#include "mirage/pipeline/acoustic_source.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>

#include "mirage/channel/acoustic_stamps.h"
#include "mirage/pipeline/anchor_channel_source.h"

namespace mirage::pipeline {

AcousticSource::AcousticSource(const Experiment& e, int trajectory, int run)
    : experiment_(e),
      trajectory_(e.trajectories[static_cast<std::size_t>(trajectory)]),
      stamps_rng_(RunRng(e.seed, trajectory, run).Substream("acoustic")),
      imu_rng_(RunRng(e.seed, trajectory, run).Substream("imu")) {
  const Vec2 offset_m = RunOffset(e.run_grid, run);
  samples_ = geometry::SampleTrajectory(trajectory_.waypoints_m, trajectory_.speed_mps, trajectory_.dt_s, offset_m,
                                        trajectory_.turn_radius_m, trajectory_.stops);
  for (const auto& a : e.anchors) mics_m_.push_back(a.position_m);
  core::Rng offset = RunRng(e.seed, trajectory, run).Substream("emission offset");
  first_emission_s_ = offset.Uniform(0.0, trajectory_.dt_s);
}

// The whole run's IMU samples, made at the first epoch: a source built only for its truth (the
// runner's bound job) never pays for them.
void AcousticSource::SimulateImuOnce() {
  const Experiment& e = experiment_;
  if (imu_done_ || e.inertial != InertialModel::kImu) return;
  imu_done_ = true;
  std::vector<double> t_s;
  std::vector<Vec3> positions_m;
  for (std::size_t k = 0; k < samples_.size(); ++k) {
    t_s.push_back(samples_[k].t_s);
    positions_m.push_back(TruthAt(k));
  }
  imu_ = channel::SimulateImu(e.imu, t_s, positions_m, imu_rng_);
  for (auto& s : imu_) s.sensor_id = "imu";
}

Vec3 AcousticSource::TruthAt(std::size_t k) const { return TrajectoryPositionAt(trajectory_, samples_[k]); }

std::optional<std::vector<Vec3>> AcousticSource::TrueStart() const { return std::vector<Vec3>{TruthAt(0)}; }

std::optional<SourceStep> AcousticSource::Next() {
  if (next_ >= samples_.size()) return std::nullopt;
  const auto start = std::chrono::steady_clock::now();
  SimulateImuOnce();
  const std::size_t k = next_++;
  const Experiment& e = experiment_;
  // The walking direction: towards the next sample (the last keeps the previous one's); a walker
  // who stands (a stop) still faces the way they walked.
  Vec2 heading = Vec2::Zero();
  for (std::size_t a = std::min(k + 1, samples_.size() - 1); a > 0; --a) {
    const Vec2 d = samples_[a].position_m - samples_[a - 1].position_m;
    if (d.norm() > 0.0) {
      heading = d.normalized();
      break;
    }
  }
  // Emission k leaves at the sender clock's k-th tick, which runs clock_drift_ppm fast.
  const double t_emit_s = first_emission_s_ + (samples_[k].t_s - samples_.front().t_s) * (1.0 + 1e-6 * e.acoustic.clock_drift_ppm);
  const channel::AcousticEmission emission =
      channel::SimulateEmission(e.acoustic, e.reflectors, mics_m_, TruthAt(k), heading, t_emit_s, stamps_rng_);

  SourceStep step;
  double earliest_s = std::numeric_limits<double>::infinity();
  for (const auto& stamps : emission.stamps) {
    for (const auto& s : stamps) earliest_s = std::min(earliest_s, s.toa_s);
  }
  step.epoch.t_s = std::isfinite(earliest_s) ? earliest_s : t_emit_s;
  step.truth_m = {TruthAt(k)};
  for (std::size_t m = 0; m < mics_m_.size(); ++m) {
    core::ToaStamps record;
    record.t_s = step.epoch.t_s;
    record.receiver_id = e.anchors[m].id;
    record.receiver_index = static_cast<int>(m);
    std::vector<bool> direct;
    for (const auto& s : emission.stamps[m]) {
      record.toa_s.push_back(s.toa_s);
      direct.push_back(s.label == channel::StampLabel::kDirect);
    }
    step.direct_stamps.push_back(std::move(direct));
    if (e.acoustic.emission_time_known) record.emission_s = t_emit_s;
    step.epoch.toas.push_back(std::move(record));
  }
  // The inertial input since the previous emission (on the trajectory's time axis).
  if (e.inertial == InertialModel::kImu) {
    while (next_imu_ < imu_.size() && imu_[next_imu_].t_s <= samples_[k].t_s) step.epoch.imus.push_back(imu_[next_imu_++]);
  } else if (e.inertial == InertialModel::kConstantHeadingError && k > 0) {
    const auto increment = estimation::ConstantHeadingErrorIncrement(e.heading_error, TruthAt(k - 1).head<2>(), TruthAt(k).head<2>(),
                                                                     samples_[k - 1].t_s, samples_[k].t_s);
    core::PositionIncrement record;
    record.t_s = samples_[k].t_s;
    record.sensor_id = "pdr";
    record.t_from_s = samples_[k - 1].t_s;
    record.delta_m = increment.delta_m;
    record.covariance_m2 = increment.covariance_m2;
    step.epoch.increments.push_back(record);
  }
  step.simulate_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return step;
}

}  // namespace mirage::pipeline
