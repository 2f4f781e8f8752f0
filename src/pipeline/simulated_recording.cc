// SPDX-License-Identifier: MIT
#include "mirage/pipeline/simulated_recording.h"

#include <algorithm>

#include "mirage/pipeline/anchor_channel_source.h"

namespace mirage::pipeline {

Recording SimulateRecording(const Experiment& experiment, int trajectory, int run) {
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
      recording.steps.push_back({step->epoch.t_s, sets});
    }
  }
  return recording;
}

}  // namespace mirage::pipeline
