// SPDX-License-Identifier: MIT
// The outputs of `mirage run`, one schema for every method (ROADMAP.md "Interfaces"): the result
// table on the console, the JSON report (the top-level keys every method has, `groups` per
// trajectory, `variants` per grid point, `health`, and the method's block), and the CSV files
// (tracks.csv and runs.csv for every method; paths.csv, map.csv, variants.csv and
// error_by_step.csv when there is something to put in them).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::io {

/// The JSON report.
nlohmann::json MakeJsonReport(const Scenario& scenario, const pipeline::ExperimentResult& result,
                              const std::vector<pipeline::VariantSummary>& summaries);

/// The result table printed by `mirage run`, with a warning line for each run that drifted away.
std::string FormatResultTable(const Scenario& scenario, const pipeline::ExperimentResult& result,
                              const std::vector<pipeline::VariantSummary>& summaries);

/// Writes json to path (pretty-printed); throws InputError when the file cannot be written.
void WriteJson(const std::string& path, const nlohmann::json& json);

/// Writes the CSV files into dir (created if needed); returns the paths written.
std::vector<std::string> WriteCsv(const std::string& dir, const Scenario& scenario, const pipeline::ExperimentResult& result,
                                  const std::vector<pipeline::VariantSummary>& summaries);

}  // namespace mirage::io
