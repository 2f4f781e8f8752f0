// SPDX-License-Identifier: MIT
// Statistics of a cooperative Monte-Carlo grid, one row per variant: position errors pooled over
// steps 1..N, agents and runs (per agent, not the paper's sum over agents, digest Sec. 2.12
// item 9), the floor-plan-relative error (Sec. IV-E), the error at the last step, diverged runs,
// the posterior position error bound, and the biased wall's and all walls' final offset errors.
#pragma once

#include <string>
#include <vector>

#include "mirage/pipeline/coop_experiment.h"

namespace mirage::pipeline {

/// One variant's statistics.
struct CoopVariantSummary {
  CoopVariant variant;
  std::string name;
  int runs = 0;
  double error_p50_m = 0.0;
  double error_p90_m = 0.0;
  double error_rmse_m = 0.0;
  double relative_p90_m = 0.0;      ///< floor-plan-relative error, p90
  double final_mean_m = 0.0;        ///< error at the last step, mean over agents and runs
  double final_p90_m = 0.0;
  int diverged = 0;                 ///< runs with an agent more than 0.5 m off at the end
  double peb_rms_m = 0.0;           ///< RMS of the bound over steps 1..N and agents
  double rmse_over_peb = 0.0;       ///< error_rmse_m / peb_rms_m
  /// Non-diverged runs only: RMSE over PEB, the filter's efficiency where it tracks.
  double tracked_rmse_over_peb = 0.0;
  bool has_bias = false;
  double bias_final_mean_abs_m = 0.0;  ///< |biased wall offset error| at the last step, mean over runs
  double bias_final_p90_abs_m = 0.0;
  double wall_rms_mean_m = 0.0;     ///< final RMS wall offset error, mean over runs
  double associated_per_step = 0.0; ///< associated ranges per step (all links)
  double expected_per_step = 0.0;   ///< expected paths per step after pruning (all links)
  /// Mean error over agents and runs per step (m), and the bound per step (RMS over agents).
  std::vector<double> error_by_step_m;
  std::vector<double> peb_by_step_m;
};

/// Summaries of all variants, in grid order.
std::vector<CoopVariantSummary> SummarizeCoop(const CoopExperimentResult& result);

}  // namespace mirage::pipeline
