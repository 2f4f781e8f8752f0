// SPDX-License-Identifier: MIT
// Statistics of the runs, the same for every method: per variant of the grid, per trajectory
// group and over all of them, the position errors (pooled over epochs, agents and runs), the
// diverged runs by the one divergence rule, the position bound, the runs' health, and the map,
// floor-plan and SINR statistics when the method provides what they need.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mirage/eval/error_stats.h"
#include "mirage/pipeline/runner.h"

namespace mirage::pipeline {

/// Distribution of a set of SINR values (dB).
struct SinrStats {
  std::size_t count = 0;
  double mean_db = 0.0;
  double p10_db = 0.0;
  double p50_db = 0.0;
  double p90_db = 0.0;
};

/// Map error of a group of runs: means over the runs of the per-run MapScore.
struct MapSummary {
  double ospa_mean_m = 0.0;
  double ospa_p50_m = 0.0;
  double discovered_mean = 0.0;
  double estimated_mean = 0.0;
  double true_mean = 0.0;
  double matched_mean = 0.0;
  double false_mean = 0.0;
  double unscored_mean = 0.0;
  /// Mean distance of matched VAs to their true positions, over all matched pairs of all runs.
  std::optional<double> matched_error_mean_m;
};

/// The estimated floor plan of a group of runs (methods that estimate walls).
struct WallSummary {
  double relative_error_p90_m = 0.0;  ///< position error in the plan's frame, p90 (m)
  std::optional<double> biased_wall_final_mean_abs_m;  ///< |biased wall's error| at the end, mean over runs
  std::optional<double> biased_wall_final_p90_abs_m;
  double rms_error_mean_m = 0.0;  ///< final RMS wall offset error, mean over runs
};

/// The health of a group of runs, summed (largest for the growth).
struct HealthSummary {
  int drifted_runs = 0;
  int steps_without_association = 0;
  int lost_track_episodes = 0;
  int rejected_updates = 0;
  int constrained_steps = 0;
  int steps_outside_plan = 0;
  int out_of_order_records = 0;
  double largest_covariance_growth = 1.0;
};

/// Distribution of a dilution of precision over the epochs that have one.
struct DopStats {
  std::size_t count = 0;
  double p50 = 0.0;
  double max = 0.0;  ///< may be +infinity (an unidentifiable coordinate)
  double rms = 0.0;  ///< sqrt(mean DOP^2): sigma times it is the RMS of the per-epoch CRLBs
};

/// Statistics of a group of runs.
struct GroupSummary {
  std::string name;
  int runs = 0;
  int steps = 0;           ///< epochs, summed over runs and agents
  bool has_truth = true;   ///< false on recorded data without truth: no error statistics
  eval::ErrorStats error;
  /// |z error| of the epochs with a 3-D estimate and truth; empty when there is none.
  std::optional<eval::ErrorStats> height_error;
  std::optional<DopStats> hdop;  ///< empty when no epoch has one
  std::optional<DopStats> vdop;
  /// Methods that label stamps as line of sight, on simulations: the labels' counts over the
  /// group's epochs (their Precision() and Recall()).
  std::optional<LosLabelCount> los_labels;
  int diverged_runs = 0;   ///< runs with an agent diverged
  /// Fractions of the epochs with truth whose error exceeds 1 m and 2 m, an epoch without a fix
  /// counted as a failure (Bordoy 2020 Sec. 5.3: the failure rate of Fig. 5.5).
  double failure_rate_1m = 0.0;
  double failure_rate_2m = 0.0;
  int no_fix_steps = 0;  ///< epochs at which the method made no estimate
  double final_error_mean_m = 0.0;  ///< error at the last epoch, mean over agents and runs
  double final_error_p90_m = 0.0;
  std::optional<double> bound_mean_m;  ///< empty when no epoch had a finite bound
  std::optional<double> bound_p50_m;
  std::optional<double> bound_rms_m;   ///< sqrt(mean bound^2): the like-for-like companion of the RMSE
  /// RMSE over the bound's RMS of the runs that did not diverge: the estimator's efficiency where
  /// it tracks.
  std::optional<double> tracked_rmse_over_bound;
  int bound_missing_steps = 0;  ///< simulated epochs without a bound (fewer than two directions)
  double associations_per_step = 0.0;
  double expected_per_step = 0.0;
  HealthSummary health;
  std::optional<MapSummary> map;
  std::optional<WallSummary> walls;
  /// Mean error over agents and runs per epoch (m), and the bound per epoch (m).
  std::vector<double> error_by_step_m;
  std::vector<double> bound_by_step_m;
};

/// The statistics of one variant.
struct VariantSummary {
  std::string name;
  GroupSummary overall;
  std::vector<GroupSummary> groups;  ///< per trajectory (one group for a joint method)
  /// Keyed by "los", "order1", "order2", ...: the simulated paths' true SINR, the estimator's
  /// estimates of them and the estimate's error.
  std::map<std::string, SinrStats> true_sinr;
  std::map<std::string, SinrStats> estimated_sinr;
  std::map<std::string, SinrStats> sinr_estimate_error;
  double simulate_s = 0.0;  ///< summed over runs (CPU time)
  double estimate_s = 0.0;
};

/// Name of an order group: "los" for 0, "orderK" otherwise.
std::string OrderName(int order);

/// The statistics of every variant of `result`.
std::vector<VariantSummary> Summarize(std::span<const Variant> variants, const ExperimentResult& result);

/// The statistics of a set of runs (all of them: the top level of a report over a grid).
GroupSummary SummarizeRuns(const std::string& name, std::span<const RunRecord* const> runs);

}  // namespace mirage::pipeline
