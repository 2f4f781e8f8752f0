// SPDX-License-Identifier: MIT
#include "mirage/pipeline/simulated_recording.h"

#include <algorithm>

#include "mirage/pipeline/acoustic_source.h"
#include "mirage/pipeline/anchor_channel_source.h"

namespace mirage::pipeline {
namespace {

Recording SimulateStamps(const Experiment& experiment, int trajectory, int run) {
  AcousticSource source(experiment, trajectory, run);
  Recording recording;
  recording.toa_stamps = true;
  for (const auto& a : experiment.anchors) {
    recording.anchor_ids.push_back(a.id);
    recording.anchors_m.push_back(a.position_m);
  }
  recording.anchors_have_z = true;
  recording.truth_has_z = true;
  while (auto step = source.Next()) {
    const double t_s = step->epoch.t_s;
    // The truth on the receivers' time axis (the epoch's time), so that the replay finds each
    // emission's true position at its step. An emission nobody heard has its nominal time, which
    // could precede the previous emission's earliest stamp in a very large hall: then it has no
    // truth row (it has no stamps either).
    if (recording.truth.empty() || t_s > recording.truth.back().t_s) {
      recording.truth.push_back({t_s, *step->truth_m.front()});
    }
    const auto& toas = step->epoch.toas;
    if (std::any_of(toas.begin(), toas.end(), [](const auto& r) { return !r.toa_s.empty(); })) {
      recording.steps.push_back({t_s, {}, toas, {}});
    }
  }
  return recording;
}

}  // namespace

Recording SimulateRecording(const Experiment& experiment, int trajectory, int run) {
  if (experiment.measurement_model == MeasurementModel::kAcoustic) return SimulateStamps(experiment, trajectory, run);
  const AnchorChannelContext context(experiment);
  AnchorChannelSource source(context, trajectory, run);
  Recording recording;
  for (const auto& a : experiment.anchors) {
    recording.anchor_ids.push_back(a.id);
    recording.anchors_m.push_back(a.position_m);
    recording.anchors_have_z = recording.anchors_have_z || a.position_m.z() != 0.0;
  }
  const double height_m = experiment.trajectories[static_cast<std::size_t>(trajectory)].height_m;
  recording.truth_has_z = recording.anchors_have_z || height_m != 0.0;
  while (auto step = source.Next()) {
    recording.truth.push_back({step->epoch.t_s, *step->truth_m.front()});
    const auto& sets = step->epoch.range_sets;
    if (std::any_of(sets.begin(), sets.end(), [](const auto& s) { return !s.ranges.empty(); })) {
      recording.steps.push_back({step->epoch.t_s, sets, {}, {}});
    }
  }
  return recording;
}

}  // namespace mirage::pipeline
