// SPDX-License-Identifier: MIT
// Test helper of the end-to-end tests: an example run with an overlay, a scenario file of this
// process's own that `extends:` the example (maps merge, lists replace), removed however the test
// ends.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline::testing {

/// The summaries of examples/<example> extended by `overlay` (YAML text), `runs` runs on all cores.
inline std::vector<VariantSummary> RunExtendedExample(const std::string& example, const std::string& overlay,
                                                      int runs) {
  namespace fs = std::filesystem;
  struct TempDir {
    fs::path path = fs::temp_directory_path() / ("mirage_e2e_overlay_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } dir;
  const fs::path file = dir.path / "overlay.yaml";
  std::ofstream(file) << "extends: " << MIRAGE_SOURCE_DIR << "/examples/" << example << "\n" << overlay;
  io::ScenarioOverrides overrides;
  overrides.runs = runs;
  overrides.threads = 0;
  const io::Scenario scenario = io::LoadScenario(file.string(), overrides);
  return Summarize(scenario.variants, RunExperiment(scenario.variants));
}

}  // namespace mirage::pipeline::testing
