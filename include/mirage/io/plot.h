// SPDX-License-Identifier: MIT
// `--plot FILE`: the picture of a run, drawn from the same results as the report by
// tools/plot_run.py (Debian's python3-matplotlib): floor plan, anchors, the simulated channel's
// VAs and the method's map, true and estimated tracks with error ellipses, the error CDFs, and
// for a grid the mean error per epoch of every variant.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::io {

/// The data the plot script draws.
nlohmann::json PlotData(const Scenario& scenario, const pipeline::ExperimentResult& result,
                        const std::vector<pipeline::VariantSummary>& summaries, const std::string& table);

/// Writes `data` next to png_path (png_path + ".json") and runs the script on it
/// (`python3 SCRIPT DATA.json OUT.png`, OUT rendered under a temporary name and renamed);
/// InputError when the script is missing or fails. The interpreter is $MIRAGE_PYTHON, else
/// /usr/bin/python3 (where Debian installs matplotlib), else python3 on the PATH.
void RenderPlot(const std::string& png_path, const std::string& script_path, const nlohmann::json& data);

}  // namespace mirage::io
