// SPDX-License-Identifier: MIT
// What one run of an experiment produced, for every method alike: per tracked agent the estimate,
// covariance, truth and error at every epoch, the simulated paths' truth, the map and floor-plan
// scores when the method estimates them, and the run's health.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/types.h"
#include "mirage/eval/rigid_alignment.h"
#include "mirage/methods/estimator.h"
#include "mirage/pipeline/los_labels.h"
#include "mirage/pipeline/map_evaluation.h"

namespace mirage::pipeline {

/// One agent's estimate at one epoch, compared with the truth where it is known.
struct TrackStep {
  double t_s = 0.0;
  std::optional<Vec3> truth_m;  ///< empty on recorded data without truth
  Vec3 estimate_m = Vec3::Zero();
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
  std::optional<double> error_m;  ///< |estimate - truth| (the plane's for planar methods)
  /// |z estimate - z truth| for a 3-D estimate (z with a non-zero variance); empty for planar ones.
  /// At an epoch without a fix the estimate is the last one, as for error_m.
  std::optional<double> height_error_m;
  std::optional<double> hdop;  ///< the method's DOPs of this epoch (methods::StepOutput)
  std::optional<double> vdop;
  std::optional<double> bound_m;  ///< the position error bound at this epoch (simulations only)
  /// Relative to the estimated floor plan (methods that estimate walls): the error after
  /// removing the translation that best explains the walls' estimated offsets.
  std::optional<double> relative_error_m;
  int associations = 0;  ///< measurements used at this epoch, all agents
  int expected = 0;      ///< measurements the model expected at this epoch, all agents
  bool relocalized = false;
  bool fixed = true;  ///< the method made an estimate at this epoch (methods::StepOutput::fixed)
  /// The epoch's LOS labels against the simulation's (the first agent's step only); empty when
  /// the method labels no stamps or the source has no labels.
  std::optional<LosLabelCount> los_labels;
};

/// One tracked agent over a run.
struct AgentTrack {
  std::string name;  ///< the trajectory's name
  std::vector<TrackStep> steps;
  bool diverged = false;  ///< eval::IsDiverged on its errors (false without truth)
  /// The rigid alignment applied to the estimates (Experiment::align_rigid), if any.
  std::optional<eval::RigidTransform> alignment;
};

/// Ground truth of one specular path at one epoch, with the estimator's SINR estimate of it.
struct PathRecord {
  int step = 0;              ///< epoch index in the run
  int anchor = 0;            ///< physical anchor index
  int va_id = 0;             ///< VA id in the simulated channel's VA set
  int order = 0;             ///< reflection order
  double delay_s = 0.0;      ///< true delay (s)
  Complex amplitude;         ///< true complex amplitude
  double true_sinr_db = 0.0;
  std::optional<double> estimated_sinr_db;
};

/// The estimated floor plan against the true one (methods that estimate walls, e.g. coop).
struct WallScore {
  /// Per epoch: the biased wall's offset error after removing the estimated translation (m).
  std::vector<double> biased_wall_error_m;
  /// RMS over the given walls of the final offset error, translation removed (m).
  double rms_error_m = 0.0;
};

/// How a run went, whether or not the truth is known: what an operator of a live system sees.
struct RunHealth {
  int steps = 0;
  int steps_without_association = 0;  ///< epochs whose update used no measurement
  int deferred_steps = 0;             ///< epochs whose measurements waited for a later update
  int lost_track_episodes = 0;        ///< restarts of a lost track
  int rejected_updates = 0;           ///< updates skipped (S not positive definite)
  int constrained_steps = 0;          ///< epochs whose estimate a constraint moved
  /// Largest position standard deviation of the run over the smallest after the first epoch
  /// (sqrt tr P): how far the uncertainty grew while coasting.
  double covariance_growth = 1.0;
  int steps_outside_plan = 0;   ///< epochs with an estimate outside the floor plan's walls
  int out_of_order_records = 0;  ///< records that arrived older than their epoch, dropped
  /// The estimator started (from the truth, a start point, or itself), and after how many
  /// epochs it started itself (those epochs have no estimate). A run that never started has no
  /// track: it counts as drifted and, with truth, as diverged.
  bool started = true;
  int epochs_before_start = 0;
  /// The track drifted away (outside the floor plan at the end, uncertainty above the divergence
  /// threshold, or more than half of the epochs without a measurement) or never started, and why.
  bool drifted = false;
  std::string drift_reason;
};

/// One run.
struct RunRecord {
  int variant = 0;  ///< index in the experiment's grid (0 without a grid)
  int group = 0;    ///< trajectory index (single-agent methods), 0 for a joint run
  int run = 0;
  Vec2 offset_m = Vec2::Zero();  ///< start offset on the run grid
  std::vector<AgentTrack> agents;
  std::vector<PathRecord> paths;  ///< every simulated specular path at every epoch (first run only)
  std::vector<methods::MapFeature> map;
  std::optional<MapScore> map_score;
  std::optional<WallScore> walls;
  RunHealth health;
  double simulate_s = 0.0;  ///< CPU time of the simulation (s)
  double estimate_s = 0.0;  ///< CPU time of the estimator (s)
  [[nodiscard]] bool diverged() const {
    for (const auto& a : agents) {
      if (a.diverged) return true;
    }
    return false;
  }
};

}  // namespace mirage::pipeline
