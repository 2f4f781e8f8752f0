// SPDX-License-Identifier: MIT
// Monte-Carlo driver of the MINT pipeline on simulated UWB signals:
// trajectory -> visible VAs -> CIR per anchor -> MPC extraction -> MINT tracker -> errors, PEB.
// Runs are independent and spread over threads; run i of trajectory t draws all its randomness
// from Rng(seed, stream(t, i)) sub-streams, so results do not depend on the thread count.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/types.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/pipeline/experiment_config.h"
#include "mirage/pipeline/map_evaluation.h"

namespace mirage::pipeline {

/// One estimate compared with the truth at one step.
struct StepRecord {
  double t_s = 0.0;
  std::optional<Vec2> truth_m;  ///< empty on recorded data without truth
  Vec2 estimate_m = Vec2::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
  std::optional<double> error_m;  ///< |estimate - truth|, empty without truth
  std::optional<double> peb_m;  ///< position error bound at the true position (simulations only)
  int associations = 0;         ///< associated ranges, all anchors
  bool relocalized = false;     ///< the tracker declared the track lost and restarted
};

/// Ground truth of one specular path at one step, with the tracker's SINR estimate for it.
struct PathRecord {
  int step = 0;                   ///< step index in the run
  int anchor = 0;                 ///< physical anchor index
  int va_id = 0;                  ///< VA id in the simulated channel's VA set
  int order = 0;                  ///< reflection order of the VA
  double delay_s = 0.0;           ///< true delay (s)
  Complex amplitude;              ///< true complex amplitude
  double true_sinr_db = 0.0;      ///< simulator truth, Eq. (3.25)
  std::optional<double> estimated_sinr_db;  ///< the tracker's online estimate at this step, if any
};

/// The position errors of the steps that have one (none on recorded data without truth).
std::vector<double> StepErrors(const std::vector<StepRecord>& steps);

/// One Monte-Carlo run (or the one run over recorded data).
struct RunRecord {
  int trajectory = 0;
  int run = 0;
  Vec2 offset_m = Vec2::Zero();
  std::vector<StepRecord> steps;
  std::vector<PathRecord> paths;  ///< every visible path at every step
  bool diverged = false;
  int relocalizations = 0;       ///< steps at which the tracker declared the track lost and restarted
  int constrained_steps = 0;     ///< steps whose estimate the in-room constraint moved
  int rejected_updates = 0;      ///< updates skipped because S was not positive definite
  std::vector<methods::slam::MapVa> map;  ///< SLAM: the map at the end of the run
  std::optional<MapScore> map_score;      ///< SLAM: its error against the visible true VAs
  double simulate_s = 0.0;       ///< time spent simulating CIRs (s)
  double estimate_s = 0.0;       ///< time spent in MPC extraction and tracking (s)
};

/// All runs of an experiment.
struct MintExperimentResult {
  /// Whether the runs have a true trajectory (always for simulations; recorded data with truth.csv).
  bool has_truth = true;
  /// False for a run over recorded data (no path truth, no PEB).
  bool simulated = true;
  std::vector<RunRecord> runs;  ///< ordered by trajectory, then run
  geometry::VirtualAnchorSet known_vas;    ///< VAs the tracker used
  geometry::VirtualAnchorSet channel_vas;  ///< VAs of the simulated channel (PathRecord::va_id)
  double wall_s = 0.0;
};

/// Called after each finished run with (finished, total); may be called from worker threads.
using ProgressCallback = std::function<void(int, int)>;

/// Runs the experiment: the Monte-Carlo runs of a simulation, or the one run over recorded data
/// (config.recording). Rethrows the first exception of a worker (e.g. std::bad_alloc).
MintExperimentResult RunMintExperiment(const MintExperimentConfig& config, const ProgressCallback& progress = {});

}  // namespace mirage::pipeline
