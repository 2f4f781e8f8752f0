// SPDX-License-Identifier: MIT
// Cooperative scenario files (YAML, `method: coop`) -> the configuration of a cooperative
// multi-agent tracking experiment (pipeline/coop_experiment.h). Every key is documented with its
// unit and default in docs/scenario.md, section "Cooperative scenarios"; the sections the file
// shares with the MINT scenario (materials, floor_plan, channel, mpc) are read by the same code
// (scenario_sections.h). Unknown keys, missing required keys, out-of-range values and
// inconsistent variant grids are errors whose message names the file, line and key path.
#pragma once

#include <string>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/coop_experiment.h"

namespace mirage::io {

/// A parsed cooperative scenario.
struct CoopScenario {
  std::string file;                      ///< path it was read from
  pipeline::CoopExperimentConfig config;  ///< the experiment, with its variant grid expanded
};

/// Reads and validates a cooperative scenario, then applies the command-line overrides (runs,
/// seed, threads) with the same ranges as the file's values; throws InputError.
CoopScenario LoadCoopScenario(const std::string& path, const ScenarioOverrides& overrides = {});

/// True when the document (after `extends:`) has the top-level `method: coop`. Files that cannot
/// be read or parsed give false, so that the normal loader (LoadScenario) reports them.
bool IsCoopScenario(const std::string& path);

}  // namespace mirage::io
