// SPDX-License-Identifier: MIT
// The scenario that runs a recording written by `mirage simulate`: the simulated scenario's room,
// channel, front-end and method sections, with `measurements: {model: recorded, ...}` naming the
// files, and without the keys recorded data replace (anchors, trajectories, run grid, runs).
#pragma once

#include <string>

namespace mirage::io {

/// Writes `dir/scenario.yaml` for the recording in `dir` (anchors.csv, ranges.csv, truth.csv),
/// derived from the scenario at `scenario_path` (its `extends:` chain resolved).
/// @param name the new scenario's name
void WriteRecordedScenario(const std::string& scenario_path, const std::string& dir, const std::string& name);

}  // namespace mirage::io
