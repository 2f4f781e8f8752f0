// SPDX-License-Identifier: MIT
// Output of a cooperative grid (mirage run on a `method: coop` scenario): the console table, the
// JSON report (one entry per variant plus the timing block), the CSV tables and the plot data.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mirage/pipeline/coop_experiment.h"
#include "mirage/pipeline/coop_summary.h"

namespace mirage::io {

/// One line per variant: errors (cm), diverged runs, the bound, wall errors.
std::string FormatCoopTable(const pipeline::CoopExperimentConfig& config,
                            const std::vector<pipeline::CoopVariantSummary>& summary);

/// The JSON report: scenario, seed, runs, steps, one object per variant, timing.
nlohmann::json MakeCoopJson(const std::string& scenario_file, const pipeline::CoopExperimentConfig& config,
                            const pipeline::CoopExperimentResult& result,
                            const std::vector<pipeline::CoopVariantSummary>& summary);

/// variants.csv (the summary table), error_by_step.csv (mean error and bound per variant and
/// step), and tracks.csv and runs.csv (per variant, agent, run and step, in the columns of the
/// MINT report with a leading variant index) in dir (created); returns the paths written.
std::vector<std::string> WriteCoopCsv(const std::string& dir, const pipeline::CoopExperimentConfig& config,
                                      const pipeline::CoopExperimentResult& result,
                                      const std::vector<pipeline::CoopVariantSummary>& summary);

/// Data for tools/plot_coop.py: the room, true and estimated tracks of the first run of the
/// first variant, and the error per variant.
nlohmann::json CoopPlotData(const pipeline::CoopExperimentConfig& config, const pipeline::CoopExperimentResult& result,
                            const std::vector<pipeline::CoopVariantSummary>& summary);

}  // namespace mirage::io
