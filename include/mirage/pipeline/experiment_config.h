// SPDX-License-Identifier: MIT
// Everything one simulated experiment needs: room, anchors, trajectories, Monte-Carlo runs,
// channel, front-end and method options. Filled by io/ from a scenario file; no YAML here.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/range_level_simulator.h"
#include "mirage/core/types.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/eval/error_stats.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/methods/mint/mint_tracker.h"
#include "mirage/methods/slam/slam_tracker.h"
#include "mirage/pipeline/recording.h"

namespace mirage::pipeline {

/// A trajectory: waypoints walked at constant speed, sampled every dt_s.
struct TrajectorySpec {
  std::string name;               ///< label for reports
  std::vector<Vec2> waypoints_m;  ///< at least two points (m)
  double speed_mps = 0.5;         ///< walking speed (m/s), > 0; 5 cm per 0.1 s step (Sec. 3.7)
  double dt_s = 0.1;              ///< time step (s), > 0 (Tab. 3.1)
};

/// Start offsets of the Monte-Carlo runs: run i is shifted by grid point i mod (nx * ny), the
/// grid centred on the trajectory (Lafer 2014 Sec. 3.7: 5 x 5 points, 1 cm apart).
struct RunGrid {
  int nx = 5;               ///< points along x, >= 1
  int ny = 5;               ///< points along y, >= 1
  double spacing_m = 0.01;  ///< grid spacing (m), >= 0
};

/// Offset (m) of run `run` on the grid.
Vec2 RunOffset(const RunGrid& grid, int run);

/// The estimator a run uses.
enum class Method {
  kMint,  ///< MINT with a known floor plan (Lafer 2014 ch. 3)
  kSlam,  ///< multipath SLAM (Leitinger et al.; Lafer 2014 ch. 4)
};

/// What the simulator produces for the estimator.
enum class MeasurementModel {
  kCir,         ///< sampled CIRs with diffuse multipath, then MPC extraction (the full path)
  kRangeLevel,  ///< ranges drawn directly: CRLB noise, missed detections, Poisson clutter
  kRecorded,    ///< no simulation: the ranges of a recording (anchors.csv, ranges.csv, truth.csv)
};

/// A complete simulated experiment (MINT or SLAM).
struct MintExperimentConfig {
  std::string name;                 ///< scenario name
  std::uint64_t seed = 1;           ///< master seed; run i of trajectory t uses Rng(seed, stream(t, i))
  int runs = 25;                    ///< runs per trajectory, >= 1
  RunGrid run_grid;                 ///< start offsets of the runs
  geometry::FloorPlan plan;         ///< the room the signals are simulated in
  geometry::FloorPlan known_plan;   ///< the floor plan the tracker knows (usually the same)
  std::vector<std::string> anchor_ids;
  std::vector<Vec2> anchors_m;      ///< true anchor positions (m)
  std::vector<Vec2> known_anchors_m;  ///< anchor positions the tracker knows (m)
  std::vector<TrajectorySpec> trajectories;
  channel::ChannelOptions channel;
  int channel_max_order = 2;        ///< highest reflection order simulated, in [0, 6]
  dsp::MpcExtractorOptions mpc;
  Method method = Method::kMint;
  methods::mint::MintOptions mint;
  methods::slam::SlamOptions slam;
  MeasurementModel measurement_model = MeasurementModel::kCir;
  channel::RangeLevelOptions range_level;  ///< used with MeasurementModel::kRangeLevel
  /// With MeasurementModel::kRecorded: the data (anchors_m and anchor_ids are the recording's;
  /// trajectories holds one entry naming it; runs is 1).
  std::shared_ptr<const Recording> recording;
  /// Where the tracker starts on recorded data (m); empty: the truth at the first step.
  std::optional<Vec2> start_m;
  /// OSPA cut-off of the map error (m), > 0: 0.5 m (issue 4).
  double map_cutoff_m = 0.5;
  eval::DivergenceRule divergence;
  /// Start the tracker at a draw from N(true start, sigma_i^2 I) instead of at the true start.
  /// The thesis starts at the known start point with variance sigma_i^2 (Tab. 3.1; digest [GAP]).
  bool perturb_initial_position = false;
  int threads = 0;                  ///< worker threads; 0 = all cores. Results do not depend on it.
};

}  // namespace mirage::pipeline
