// SPDX-License-Identifier: MIT
#include "mirage/pipeline/uwb_tdoa_source.h"

#include <chrono>

#include "mirage/channel/uwb_tdoa_simulator.h"
#include "mirage/pipeline/anchor_channel_source.h"

namespace mirage::pipeline {

UwbTdoaSource::UwbTdoaSource(const Experiment& e, int trajectory, int run)
    : experiment_(e),
      trajectory_(e.trajectories[static_cast<std::size_t>(trajectory)]),
      rng_(RunRng(e.seed, trajectory, run).Substream("uwb tdoa")) {
  samples_ = geometry::SampleTrajectory(trajectory_.waypoints_m, trajectory_.speed_mps, trajectory_.dt_s,
                                        RunOffset(e.run_grid, run), trajectory_.turn_radius_m, trajectory_.stops);
  for (const auto& a : e.anchors) {
    anchors_m_.push_back(a.position_m);
    anchor_ids_.push_back(a.id);
  }
}

std::optional<SourceStep> UwbTdoaSource::Next() {
  if (next_ >= samples_.size()) return std::nullopt;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t k = next_++;
  SourceStep step;
  step.epoch.t_s = samples_[k].t_s;
  step.truth_m = {TruthAt(k)};
  for (auto& sample : channel::SimulateUwbTdoaStep(experiment_.uwb_tdoa, anchors_m_, anchor_ids_, experiment_.reflectors,
                                                   samples_[k].t_s, trajectory_.dt_s, TruthAt(k), rng_)) {
    step.epoch.tdoas.push_back(std::move(sample.measurement));
  }
  // The epoch is the receiver's: it starts with its first packet's time (the slot grid's k /
  // rate_hz, which may differ from the trajectory's k dt_s in the last bits), as the replay of
  // tdoa.csv sees it.
  if (!step.epoch.tdoas.empty()) step.epoch.t_s = step.epoch.tdoas.front().t_s;
  step.simulate_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return step;
}

}  // namespace mirage::pipeline
