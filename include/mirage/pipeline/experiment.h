// SPDX-License-Identifier: MIT
// Everything one experiment needs, for every method: the true world it is simulated in (floor
// plan, anchors, trajectories, channel) or the recording it reads, what the estimator is told
// (the plan it is given, with its errors), the method with its options, the Monte-Carlo runs and
// the evaluation rule. Filled by io/ from a scenario file (docs/scenario.md); no YAML here.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mirage/channel/acoustic_stamps.h"
#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/imu_simulator.h"
#include "mirage/channel/link.h"
#include "mirage/channel/range_level_simulator.h"
#include "mirage/channel/ranging_simulator.h"
#include "mirage/channel/uwb_tdoa_simulator.h"
#include "mirage/core/medium.h"
#include "mirage/core/physical_keys.h"
#include "mirage/core/types.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/estimation/imu/pdr.h"
#include "mirage/eval/error_stats.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/reflector_3d.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/registry.h"
#include "mirage/methods/world.h"
#include "mirage/pipeline/recording.h"

namespace mirage::pipeline {

/// A trajectory: waypoints walked at constant speed at a fixed height, sampled every dt_s.
struct TrajectorySpec {
  std::string name;               ///< label for reports; unique within a scenario
  std::vector<Vec2> waypoints_m;  ///< at least two points (m)
  double speed_mps = 0.5;         ///< walking speed (m/s), > 0; 5 cm per 0.1 s step (Lafer Sec. 3.7)
  double dt_s = 0.1;              ///< time step (s), > 0 (Lafer Tab. 3.1)
  double height_m = 0.0;          ///< the agent's height z (m)
  /// Corners turned along arcs of this radius (m), >= 0; 0 turns instantly at the waypoints.
  double turn_radius_m = 0.0;
  /// Height motion (acoustic and UWB TDOA scenarios: a phone in the hand, a flying tag): the height swings as height_m + amplitude sin(2 pi t /
  /// period) (Bordoy 2020 Sec. 8.5: the phone moved up and down while walking). Amplitude (m),
  /// >= 0; period (s), > 0.
  double height_amplitude_m = 0.0;
  double height_period_s = 4.0;
  /// Pauses of the walk (sorted, not overlapping): the agent stands still during each (Bordoy 2020
  /// Sec. 6.2: walking trajectories with stops); the hand motion goes on.
  std::vector<geometry::Stop> stops;
};

/// The agent's 3-D position at a sample of its trajectory: the sample's x, y at the trajectory's
/// height, with the hand motion's swing (TrajectorySpec::height_amplitude_m).
Vec3 TrajectoryPositionAt(const TrajectorySpec& trajectory, const geometry::TrajectorySample& sample);

/// Start offsets of the Monte-Carlo runs: run i is shifted by grid point i mod (nx * ny), the
/// grid centred on the trajectory (Lafer 2014 Sec. 3.7: 5 x 5 points, 1 cm apart).
struct RunGrid {
  int nx = 5;               ///< points along x, >= 1
  int ny = 5;               ///< points along y, >= 1
  double spacing_m = 0.01;  ///< grid spacing (m), >= 0
};

/// Offset (m) of run `run` on the grid.
Vec2 RunOffset(const RunGrid& grid, int run);

/// A physical anchor.
struct AnchorSpec {
  std::string id;
  Vec3 position_m = Vec3::Zero();
};

/// What the simulator produces (or that the data are recorded).
enum class MeasurementModel {
  kCir,         ///< sampled CIRs with diffuse multipath; range sets by MPC extraction
  kRangeLevel,  ///< ranges drawn at each path's CRLB: missed detections, Poisson clutter
  kRanging,     ///< one range per anchor at a fixed noise (a ranging system), 3-D
  kAcoustic,    ///< arrival-time stamps per microphone and emission of a sound sender (Bordoy 2020), 3-D
  kUwbTdoa,     ///< pairwise UWB TDOA rows of a tag among anchors (channel/uwb_tdoa_simulator.h), 3-D
  kRecorded,    ///< no simulation: the ranges of a recording (anchors.csv, ranges.csv, truth.csv)
};

/// The inertial input an acoustic simulation adds to its epochs.
enum class InertialModel {
  kNone,
  kImu,                   ///< raw smartphone IMU samples (channel/imu_simulator.h) at its rate
  kConstantHeadingError,  ///< the thesis's synthetic IMU (Bordoy 2020 Sec. 5.3): the true
                          ///< displacement per emission rotated by a constant angle
};

/// The errors of the floor plan the estimator is given (Kulmer et al. Sec. IV-C2, IV-E). Walls of
/// the true plan with in_plan false are missing from it altogether.
struct PlanError {
  /// Each given wall is shifted by a draw from U(-r/2, r/2) per coordinate, r this (m), >= 0;
  /// a new draw per run.
  double wall_shift_m = 0.0;
  /// A wall moved along its normal by bias_m (index into the true plan's walls, -1 for none).
  int biased_wall = -1;
  double bias_m = 0.0;
};

/// A method bound to its options: what the runner needs to make its estimators.
struct MethodSpec {
  std::string name;
  methods::MethodInput input = methods::MethodInput::kRangeSets;
  /// One estimator tracks all walking agents at once (cooperative tracking); otherwise each
  /// trajectory is run on its own.
  bool joint = false;
  /// A new estimator for one run.
  std::function<std::unique_ptr<methods::Estimator>(const methods::World&)> create;
  /// The links a kLinkCirs method measures.
  std::function<std::vector<channel::LinkSpec>(const methods::World&)> links;
  /// The standard deviation of the start position the method assumes (m): a perturbed start
  /// (Experiment::perturb_initial_position) is drawn with it.
  double start_sigma_m = 0.1;
  /// The method's options object (the struct its descriptor describes), for callers that know
  /// the method (benchmarks, tests).
  std::shared_ptr<const void> options;
  /// The method's effective options, as the report records them (set by io).
  std::string options_json;
};

/// One experiment: a scenario (or one variant of its grid).
struct Experiment {
  std::string name;
  std::uint64_t seed = 1;  ///< run i of trajectory group g uses Rng(seed, g * 1000003 + i)
  int runs = 25;           ///< runs per trajectory (per grid variant for a joint method), >= 1
  int threads = 0;         ///< worker threads, 0 = all cores; results do not depend on it
  RunGrid run_grid;
  core::Medium medium = core::Medium::Radio();

  // The true world.
  geometry::FloorPlan plan;            ///< as it reflects; may be empty
  std::vector<bool> in_plan;           ///< per wall: whether the estimator's plan has it
  std::vector<AnchorSpec> anchors;
  std::vector<TrajectorySpec> trajectories;
  /// Joint methods: the first `agents` trajectories walk together (0 = all), for `steps` steps
  /// (0 = until the longest has ended; an agent at its end stays there).
  int agents = 0;
  int steps = 0;

  // The measurements.
  MeasurementModel measurement_model = MeasurementModel::kCir;
  channel::ChannelOptions channel;
  int channel_max_order = 2;           ///< highest reflection order simulated
  /// Energy of an agent's own transmit-receive antenna coupling relative to a free-space path of
  /// the antenna spacing (dB), for links with both ends on one agent.
  double self_coupling_db = -20.0;
  dsp::MpcExtractorOptions mpc;
  channel::RangeLevelOptions range_level;
  channel::RangingOptions ranging;
  channel::AcousticStampOptions acoustic;
  channel::UwbTdoaOptions uwb_tdoa;
  InertialModel inertial = InertialModel::kNone;  ///< kAcoustic
  channel::ImuOptions imu;                        ///< InertialModel::kImu
  estimation::ConstantHeadingErrorOptions heading_error;  ///< InertialModel::kConstantHeadingError
  /// kAcoustic: the hall's reflecting surfaces (the floor plan's walls, floor and ceiling, then
  /// the partitions and tables), in the order stamps' labels index them. kUwbTdoa: the obstacles
  /// (the faces of its boxes) whose crossing biases a leg.
  std::vector<geometry::Reflector3> reflectors;
  std::shared_ptr<const Recording> recording;  ///< kRecorded
  double epoch_window_s = 0.0;                  ///< recorded data: the epoch rule's window
  /// Recorded data: the range noise and walking speed the recording's owner states (the
  /// physical facts a file cannot show), if given.
  std::optional<double> recorded_range_sigma_m;
  std::optional<double> recorded_speed_mps;
  /// Recorded data: the step time (a sender's emission interval) the owner states, if given; else
  /// the median time between steps.
  std::optional<double> recorded_dt_s;
  /// Recorded stamps: the detection probability and the false alarms per microphone and emission
  /// the owner states, if given.
  std::optional<double> recorded_detection_probability;
  std::optional<double> recorded_clutter_rate;
  /// Recorded stamps: the sender's known height (m), World::agent_height_m of the planar methods.
  std::optional<double> recorded_height_m;

  // What the estimator is told.
  PlanError plan_error;
  /// Where the estimator starts on recorded data without truth (m); empty: the truth at the first
  /// epoch, or, without truth, self-initialisation from the first epochs.
  std::optional<Vec3> start_m;
  /// Start at a draw from N(true start, sigma^2 I), sigma the method's MethodSpec::start_sigma_m
  /// (the thesis starts at the true start with that variance, Tab. 3.1), not at the true start.
  bool perturb_initial_position = false;
  /// The estimator starts itself from the first epochs (Estimator::InitializeFromEpoch) even
  /// when the truth or a start point is known: measures self-initialisation with error figures.
  bool self_start = false;

  MethodSpec method;

  // Evaluation.
  eval::DivergenceRule divergence;
  double map_cutoff_m = 0.5;  ///< OSPA cut-off of the map error (m)
  /// Recorded data with truth in another frame (a motion-capture system): each run's estimates are
  /// rigidly aligned to its truth before the errors (eval/rigid_alignment.h, Bordoy 2020 Eq.
  /// 3.49-3.52). Only for recordings with truth.
  bool align_rigid = false;
};

/// The method of `info` bound to its options (an object of the struct info.descriptor describes,
/// shared by every estimator made from it); options_json is left to the caller.
MethodSpec BindMethod(const methods::MethodInfo& info, std::shared_ptr<const void> options);

/// Problems with the experiment beyond what the parser checks, empty if valid.
std::vector<std::string> Validate(const Experiment& experiment);

/// The scenario's physical facts, as far as it states them: the range noise of a ranging model
/// or a recording's stated one, detection probability and clutter rate of the range models, the
/// trajectories' common step time and the largest walking speed (or a recording's stated keys,
/// its step time by default the median interval between its steps). The defaults that depend on
/// noise or motion are derived from these (core/options_descriptor.h).
core::PhysicalKeys PhysicalKeysOf(const Experiment& experiment);

}  // namespace mirage::pipeline
