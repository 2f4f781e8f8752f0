// SPDX-License-Identifier: MIT
// The one runner (ROADMAP.md "Architecture"): for every variant of a scenario's grid, every
// trajectory (or the group of agents of a joint method) and every Monte-Carlo run, a source
// (simulation or recording) feeds an estimator of the scenario's method epoch by epoch, and each
// estimate is compared with the truth the source knows. Runs are spread over threads; every run
// draws from its own seeded streams, so results do not depend on the thread count. The runner
// knows no method: it talks to every one through methods::Estimator.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mirage/geometry/virtual_anchor.h"
#include "mirage/pipeline/experiment.h"
#include "mirage/pipeline/run_record.h"

namespace mirage::pipeline {

/// One point of a scenario's grid (a scenario without a grid is one variant).
struct Variant {
  std::string name;  ///< "key=value, key=value" of the overrides; the scenario's name without a grid
  std::vector<std::pair<std::string, std::string>> overrides;  ///< key path -> value, as written
  Experiment experiment;
};

/// What a variant's runs share in the results.
struct VariantResult {
  std::vector<std::string> groups;  ///< trajectory names (one "joint" group for a joint method)
  /// The kind of position bound the runs carry: "posterior" (the method's own recursion on the
  /// truth), "snapshot" (the channel's per-epoch PEB), or "" (none: recorded data).
  std::string bound;
  geometry::VirtualAnchorSet channel_vas;  ///< the simulated channel's VAs (anchor channels)
};

/// Everything the runs produced.
struct ExperimentResult {
  std::vector<VariantResult> variants;
  std::vector<RunRecord> runs;  ///< ordered by variant, then group, then run
  double wall_s = 0.0;          ///< wall-clock time of everything (s)
};

/// Called after each finished job with (done, total); may be called from worker threads.
using Progress = std::function<void(int, int)>;

/// Runs every variant. Rethrows the first exception of a worker.
ExperimentResult RunExperiment(std::span<const Variant> variants, const Progress& progress = {});

}  // namespace mirage::pipeline
