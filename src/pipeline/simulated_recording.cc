// SPDX-License-Identifier: MIT
#include "mirage/pipeline/simulated_recording.h"

#include <algorithm>

#include "mirage/pipeline/acoustic_source.h"
#include "mirage/pipeline/anchor_channel_source.h"
#include "mirage/pipeline/uwb_tdoa_source.h"

namespace mirage::pipeline {
namespace {

// A recording of the experiment's receivers in 3-D (anchors.csv or mics.csv with z_m) and a 3-D
// truth.
Recording Recording3d(const Experiment& experiment) {
  Recording recording;
  for (const auto& a : experiment.anchors) {
    recording.anchor_ids.push_back(a.id);
    recording.anchors_m.push_back(a.position_m);
  }
  recording.anchors_have_z = true;
  recording.truth_has_z = true;
  return recording;
}

Recording SimulateStamps(const Experiment& experiment, int trajectory, int run) {
  AcousticSource source(experiment, trajectory, run);
  Recording recording = Recording3d(experiment);
  recording.toa_stamps = true;
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

// One step per time stamp of a difference (as tdoa.csv lists them); the truth at every epoch.
Recording SimulateTdoa(const Experiment& experiment, int trajectory, int run) {
  UwbTdoaSource source(experiment, trajectory, run);
  Recording recording = Recording3d(experiment);
  recording.tdoa = true;
  while (auto step = source.Next()) {
    recording.truth.push_back({step->epoch.t_s, *step->truth_m.front()});
    for (const auto& m : step->epoch.tdoas) {
      if (recording.steps.empty() || recording.steps.back().t_s != m.t_s) recording.steps.push_back({m.t_s, {}, {}, {}});
      recording.steps.back().tdoas.push_back(m);
    }
  }
  // The last epoch's slots after its start were made for the tag at its position: the truth
  // stays there, so that every row lies inside the truth's span.
  if (!recording.steps.empty() && !recording.truth.empty() && recording.steps.back().t_s > recording.truth.back().t_s) {
    recording.truth.push_back({recording.steps.back().t_s, recording.truth.back().position_m});
  }
  return recording;
}

}  // namespace

Recording SimulateRecording(const Experiment& experiment, int trajectory, int run) {
  if (experiment.measurement_model == MeasurementModel::kAcoustic) return SimulateStamps(experiment, trajectory, run);
  if (experiment.measurement_model == MeasurementModel::kUwbTdoa) return SimulateTdoa(experiment, trajectory, run);
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
