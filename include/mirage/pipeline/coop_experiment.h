// SPDX-License-Identifier: MIT
// Monte-Carlo driver of anchorless cooperative tracking (Kulmer et al. Sec. IV-D, IV-E; issue 5):
// a grid of variants (number of agents, fixed anchor, pulse duration, floor-plan error, a biased
// wall, wall update on or off, sigma_seg), each run `runs` times on simulated CIRs of the self,
// relative and anchor links, on both cores, with a progress callback.
//
// Truth and plan. The scenario's floor plan is the building as it reflects (the truth). The
// filter gets the provided plan: the walls marked in_plan, each moved by a draw from
// U(-r/2, r/2) per coordinate (Sec. IV-E), and the scenario's biased wall moved by its bias
// along its normal (Sec. IV-C2). Walls with in_plan: false (pin boards, cabinets) reflect in the
// simulation but are unknown to the filter.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/core/types.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/methods/coop/coop_link.h"
#include "mirage/methods/coop/coop_tracker.h"

namespace mirage::pipeline {

/// One agent: a polyline walked at constant speed, one step per second.
struct CoopAgent {
  std::string name;
  std::vector<Vec2> waypoints_m;   ///< at least 2 distinct points, inside the plan
  double speed_m_per_step = 0.025; ///< (0, 0.1] m per step (the paper: 0.01 - 0.025)
};

/// The fixed anchor (not in the state) used by variants with anchor = true.
struct CoopAnchor {
  std::string id = "anchor";
  Vec2 position_m = Vec2::Zero();
};

/// A wall of the provided plan moved along its normal by offset_m (Sec. IV-C2: 0.1 m).
struct WallBias {
  int wall = -1;           ///< index into the true plan's walls (must be in_plan), -1 for none
  double offset_m = 0.1;   ///< signed, along the wall's normal U e_s (m)
};

/// One point of the variant grid.
struct CoopVariant {
  int agents = 2;                   ///< the first `agents` agents of the scenario, >= 2
  bool anchor = false;              ///< with the fixed anchor (needs CoopExperimentConfig::anchor)
  double pulse_duration_s = 0.5e-9; ///< T_p (s); d_c = c T_p unless coop.cutoff_m is set
  double wall_error_m = 0.001;      ///< r: each provided wall point moved by U(-r/2, r/2) per coordinate
  bool biased_wall = false;         ///< apply the scenario's wall_bias
  bool wall_update = true;          ///< walls in the state ("w su") or fixed ("w/o su")
  double wall_sigma_m = 0.003;      ///< sigma_seg (m)
  /// "M2 anchor Tp0.5ns r1mm su sseg3mm" (and "bias" when biased), unique within a grid.
  [[nodiscard]] std::string Name() const;
  friend bool operator==(const CoopVariant&, const CoopVariant&) = default;
};

/// Configuration of a cooperative experiment.
struct CoopExperimentConfig {
  std::string name;
  std::uint64_t seed = 1;  ///< run r of variant v uses the stream (r) of this seed: the same
                           ///< plan perturbation, noise and DM in every variant (common random numbers)
  int runs = 100;
  int threads = 0;         ///< 0 = all cores
  int steps = 200;         ///< steps per run (one per second)
  geometry::FloorPlan true_plan;
  std::vector<bool> in_plan;  ///< per true wall: whether the provided plan has it
  std::vector<CoopAgent> agents;
  std::optional<CoopAnchor> anchor;
  WallBias wall_bias;
  methods::coop::AntennaLayout antennas;
  /// Channel of every link; the pulse duration is replaced by each variant's.
  channel::ChannelOptions channel;
  /// Highest reflection order simulated (1..3); the DM stands for everything higher.
  int simulated_max_order = 2;
  /// Energy of the TX-RX antenna coupling on a self link relative to a free-space path of the
  /// antenna spacing (dB).
  double self_coupling_db = -20.0;
  /// MPC extraction; max_components is unused (the filter asks for round(1.5 |K|)).
  dsp::MpcExtractorOptions mpc;
  /// Filter options; wall_update and wall_sigma_m are replaced by each variant's.
  methods::coop::CoopOptions coop;
  /// The grid; at least one variant, no duplicates.
  std::vector<CoopVariant> variants;
};

/// Problems with the configuration (beyond what the parser checks), empty if valid.
std::vector<std::string> Validate(const CoopExperimentConfig& config);

/// One run of one variant.
struct CoopRun {
  /// Per step and agent: |p_hat - p| (m), absolute frame.
  std::vector<std::vector<double>> error_m;
  /// Per step and agent: the error relative to the floor plan (m): p_hat - p minus the
  /// translation that best explains the estimated wall offsets (the analogue of Sec. IV-E's
  /// centre of gravity for normal offsets); equal to error_m without wall update.
  std::vector<std::vector<double>> relative_error_m;
  /// Per step: the biased wall's estimated offset minus its true offset (m), after removing the
  /// estimated translation; empty without a biased wall.
  std::vector<double> bias_wall_error_m;
  /// RMS over the provided walls of the final wall offset error (estimated minus true position
  /// along the normal, after removing the estimated translation) (m).
  double wall_rms_error_m = 0.0;
  /// Per step: associated ranges over all links.
  std::vector<int> associated;
  /// Per step: expected paths over all links.
  std::vector<int> expected;
  /// Estimated positions per step and agent (m).
  std::vector<std::vector<Vec2>> estimate_m;
  /// Their covariances per step and agent (m^2).
  std::vector<std::vector<Eigen::Matrix2d>> covariance_m2;
  bool diverged = false;  ///< some agent ended more than 0.5 m off
};

/// The runs of one variant.
struct CoopVariantResult {
  CoopVariant variant;
  std::vector<CoopRun> runs;
  /// Per step and agent: the posterior position error bound sqrt(tr P_pos) (m): the filter's
  /// own linearised model run on the true trajectory and the true walls, with every visible,
  /// unambiguous path of its model measured at the CRLB variance of its true SINR (no misses, no
  /// wrong associations). The same for every run.
  std::vector<std::vector<double>> peb_m;
};

/// Everything an experiment produced.
struct CoopExperimentResult {
  std::vector<CoopVariantResult> variants;
  /// True agent positions per agent and step (the same in every run and variant).
  std::vector<std::vector<Vec2>> truth_m;
  double wall_s = 0.0;  ///< wall-clock time of the whole grid (s)
};

/// Progress: jobs done and total (one job = one run of one variant).
using CoopProgress = std::function<void(int done, int total)>;

/// Runs the grid; results do not depend on the number of threads.
CoopExperimentResult RunCoopExperiment(const CoopExperimentConfig& config, const CoopProgress& progress = {});

}  // namespace mirage::pipeline
