// SPDX-License-Identifier: MIT
// Outputs of `mirage run`: the result table, the JSON report (keys of ROADMAP.md plus the
// sinr_db block), and the CSV files (tracks, runs, virtual anchors).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/mint_experiment.h"
#include "mirage/pipeline/mint_summary.h"

namespace mirage::io {

/// The JSON report.
nlohmann::json MakeJsonReport(const Scenario& scenario, const pipeline::MintExperimentResult& result,
                              const pipeline::MintSummary& summary);

/// The result table printed by `mirage run`.
std::string FormatResultTable(const Scenario& scenario, const pipeline::MintSummary& summary);

/// Writes json to path (pretty-printed); throws InputError when the file cannot be written.
void WriteJson(const std::string& path, const nlohmann::json& json);

/// Writes tracks.csv, runs.csv, paths.csv (ground truth per specular path, first run of each
/// trajectory) and virtual_anchors.csv (the tracker's VAs) into dir (created if needed); returns
/// the paths written.
std::vector<std::string> WriteCsv(const std::string& dir, const Scenario& scenario, const pipeline::MintExperimentResult& result);

}  // namespace mirage::io
