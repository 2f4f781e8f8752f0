// SPDX-License-Identifier: MIT
// The scenario that runs a recording written by `mirage simulate`: the simulated scenario's
// room, channel, front-end, evaluation and method sections, with `measurements: {model:
// recorded, ...}` naming the files and stating the physical facts a file cannot show (the range
// noise of a ranging model, the walker's speed), and without the keys recorded data replace
// (anchors, trajectories, run grid, runs, grid).
#pragma once

#include <string>

#include "mirage/io/scenario.h"

namespace mirage::io {

/// Writes `dir/scenario.yaml` for the recording in `dir` (anchors.csv, ranges.csv, truth.csv) of
/// trajectory `trajectory` of `scenario`.
/// @param name the new scenario's name
void WriteRecordedScenario(const Scenario& scenario, int trajectory, const std::string& dir, const std::string& name);

}  // namespace mirage::io
