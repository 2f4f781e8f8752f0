// SPDX-License-Identifier: MIT
// Summary of a MINT experiment: error statistics overall and per trajectory, divergence, PEB,
// SINR statistics (true and estimated) and timing; what the report prints and writes.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mirage/eval/error_stats.h"
#include "mirage/pipeline/mint_experiment.h"

namespace mirage::pipeline {

/// Distribution of a set of SINR values (dB).
struct SinrStats {
  std::size_t count = 0;
  double mean_db = 0.0;
  double p10_db = 0.0;
  double p50_db = 0.0;
  double p90_db = 0.0;
};

/// Map error of a group of SLAM runs: means over the runs of the per-run MapScore.
struct MapSummary {
  double ospa_mean_m = 0.0;
  double ospa_p50_m = 0.0;
  double discovered_mean = 0.0;
  double estimated_mean = 0.0;
  double true_mean = 0.0;
  double matched_mean = 0.0;
  double false_mean = 0.0;
  double filtered_mean = 0.0;
  /// Mean distance of matched VAs to their true positions, over all matched pairs of all runs.
  std::optional<double> matched_error_mean_m;
};

/// Statistics of a group of runs.
struct GroupSummary {
  std::string name;
  int runs = 0;
  int steps = 0;
  /// False on recorded data without truth: then error and diverged_runs mean nothing.
  bool has_truth = true;
  eval::ErrorStats error;
  int diverged_runs = 0;
  std::optional<double> peb_mean_m;  ///< empty when no step had a finite PEB
  std::optional<double> peb_p50_m;
  std::optional<double> peb_rms_m;   ///< sqrt(mean PEB^2): the like-for-like companion of the RMSE
  int relocalizations = 0;           ///< summed over the runs
  int constrained_steps = 0;
  int rejected_updates = 0;
  int peb_singular_steps = 0;        ///< steps without two independent directions
  std::optional<MapSummary> map;     ///< SLAM runs only
};

/// The whole summary.
struct MintSummary {
  GroupSummary overall;
  std::vector<GroupSummary> trajectories;
  /// Keyed by "los", "order1", "order2", ...
  std::map<std::string, SinrStats> true_sinr;
  std::map<std::string, SinrStats> estimated_sinr;
  /// Estimated minus true SINR (dB), for VAs associated with an estimate at a step.
  std::map<std::string, SinrStats> sinr_estimate_error;
  double wall_s = 0.0;
  double simulate_s = 0.0;  ///< summed over runs (CPU time of the simulator)
  double estimate_s = 0.0;  ///< summed over runs (CPU time of extraction + tracking)
};

/// Name of an order group: "los" for 0, "orderK" otherwise.
std::string OrderName(int order);

/// Computes the summary.
MintSummary Summarize(const MintExperimentConfig& config, const MintExperimentResult& result);

}  // namespace mirage::pipeline
