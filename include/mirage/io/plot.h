// SPDX-License-Identifier: MIT
// `--plot FILE`: writes the data of the run to FILE.json and renders FILE with matplotlib
// (tools/plot_run.py, Debian's python3-matplotlib): floor plan, anchors, VAs, true and estimated
// trajectories with error ellipses, and the error CDFs.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/mint_experiment.h"
#include "mirage/pipeline/mint_summary.h"

namespace mirage::io {

/// Writes png_path.json and renders png_path (any extension matplotlib knows: .png, .pdf,
/// .svg). script_path is tools/plot_run.py; the interpreter is $MIRAGE_PYTHON, else
/// /usr/bin/python3 (where Debian installs matplotlib), else python3 on the PATH.
/// Throws InputError when the file cannot be written or the renderer fails.
/// Writes `data` next to png_path (png_path + ".json") and runs the Python script on it:
/// `python3 SCRIPT DATA.json OUT.png`; InputError when the script is missing or fails.
void RenderPlot(const std::string& png_path, const std::string& script_path, const nlohmann::json& data);

void WritePlot(const std::string& png_path, const std::string& script_path, const Scenario& scenario,
               const pipeline::MintExperimentResult& result, const pipeline::MintSummary& summary);

}  // namespace mirage::io
