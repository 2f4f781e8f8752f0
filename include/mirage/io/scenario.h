// SPDX-License-Identifier: MIT
// Scenario files (YAML) -> experiments, in the one schema every method shares
// (docs/scenario.md): common sections (name, seed, medium, floor plan, anchors, trajectories,
// channel, measurements, evaluation), then `method: {name: ..., <its options>}`, read through
// the method's options descriptor, and optionally `grid:`, a list of variants over any key
// path. Unknown keys, missing required keys, out-of-range values, NaNs, zero-length walls,
// anchors outside the floor plan and trajectories through walls are errors whose message names
// the file, line and key; a file in the layout before this schema gets a message that says how
// to write it now.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mirage/io/recorded_data.h"
#include "mirage/methods/registry.h"
#include "mirage/pipeline/runner.h"

namespace mirage::io {

/// A parsed scenario.
struct Scenario {
  std::string file;  ///< path it was read from
  const methods::MethodInfo* method = nullptr;
  /// The experiment of every grid variant (one without a grid), in grid order.
  std::vector<pipeline::Variant> variants;
  /// The files of `measurements: {model: recorded}` (resolved paths); the data are in the
  /// experiments' recording.
  std::optional<RecordingFiles> recording_files;
  /// The document with `extends:` resolved (what `mirage simulate` derives its recorded
  /// scenario from).
  YAML::Node document;
  [[nodiscard]] bool has_grid() const { return variants.size() > 1 || !variants.front().overrides.empty(); }
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
