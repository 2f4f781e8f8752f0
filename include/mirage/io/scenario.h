// SPDX-License-Identifier: MIT
// Scenario files (YAML) -> experiment configurations. Every key is documented with its unit and
// default in docs/scenario.md; unknown keys, missing required keys, out-of-range values, NaNs,
// zero-length walls, anchors outside the floor plan and trajectories through walls are errors
// whose message names the file, line and key.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mirage/io/recorded_data.h"
#include "mirage/pipeline/experiment_config.h"

namespace mirage::io {

/// A parsed scenario.
struct Scenario {
  std::string file;    ///< path it was read from
  std::string method;  ///< method name ("mint")
  pipeline::MintExperimentConfig mint;  ///< configuration of the experiment (MINT or SLAM)
  /// The files of `measurements: {model: recorded}` (resolved paths); the data are in mint.recording.
  std::optional<RecordingFiles> recording_files;
};

/// Command-line overrides applied after parsing (and validated like the file's values).
struct ScenarioOverrides {
  std::optional<int> runs;
  std::optional<std::uint64_t> seed;
  std::optional<int> threads;
};

/// Reads and validates a scenario; throws InputError.
Scenario LoadScenario(const std::string& path, const ScenarioOverrides& overrides = {});

}  // namespace mirage::io
