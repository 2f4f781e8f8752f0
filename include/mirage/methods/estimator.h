// SPDX-License-Identifier: MIT
// The one interface every method family implements (ROADMAP.md "Architecture"): initialise from
// a prior or from the first epochs, process an epoch, return the estimate with its covariance and
// diagnostics, plus an optional map. The runner (pipeline/) drives every method through it on
// simulated, recorded and live epochs alike, and never needs to know which method it runs.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/epoch.h"
#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::methods {

/// Where the estimator starts: the agents' positions at t_s (at rest), one per tracked agent.
struct Prior {
  double t_s = 0.0;
  std::vector<Vec3> positions_m;
};

/// The estimate of one agent. Planar methods report z as the agent's known height (or 0) with
/// zero variance.
struct AgentEstimate {
  Vec3 position_m = Vec3::Zero();
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
};

/// An online SINR estimate of one specular path, identified by its anchor and wall sequence (so
/// that the runner can compare it with the simulated truth of the same path).
struct PathSinr {
  int anchor_index = 0;
  std::vector<int> walls;  ///< empty: the line of sight
  double sinr = 0.0;       ///< linear
};

/// What one epoch did.
struct StepOutput {
  std::vector<AgentEstimate> agents;  ///< one per tracked agent, in World::agents order
  int associations = 0;               ///< measurements that entered the update
  int expected = 0;                   ///< measurements the model expected (visible paths, links' paths)
  bool relocalized = false;           ///< the track was declared lost and restarted
  bool constrained = false;           ///< a constraint (the floor plan, a speed limit) moved the estimate
  bool rejected_update = false;       ///< the update was skipped (S not positive definite)
  /// The method kept this epoch's measurements for a later update over a window (a batch): no
  /// update was due, so an epoch without associations is no sign of a lost track.
  bool deferred = false;
  /// False when the method made no estimate at this epoch (a snapshot solver without a fix): the
  /// agents' estimates repeat the last ones, and the evaluation counts the epoch as a failure.
  bool fixed = true;
  /// The horizontal and vertical dilution of precision of this epoch's fix (sqrt of the CRLB's
  /// horizontal / vertical variance over the noise sigma, eval/dop.h), for methods that compute it.
  std::optional<double> hdop;
  std::optional<double> vdop;
  std::vector<PathSinr> sinr_estimates;
  /// Methods that label arrival stamps as line of sight (LOS identification): per record of the
  /// epoch's toas, the index of its stamp labelled LOS, or -1 (none, or no fix). Empty when the
  /// method labels no stamps. The runner scores it against the simulation's labels.
  std::vector<int> los_stamps;
};

/// One feature of an estimated map (a virtual anchor of SLAM), in the plane.
struct MapFeature {
  int id = 0;
  int anchor_index = 0;  ///< the physical anchor it is an image of
  std::string origin;    ///< where it came from: "anchor", "prior" (a given floor plan), "discovered"
  Vec2 position_m = Vec2::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
  /// Counted in the map score: a feature of the map proper (not a physical anchor, not excluded).
  bool scored = true;
  /// Further columns for map.csv, name -> formatted value (the same names for every feature).
  std::vector<std::pair<std::string, std::string>> attributes;
};

/// The estimated offset of one wall of the given floor plan along its normal.
struct WallEstimate {
  double offset_m = 0.0;
  double sigma_m = 0.0;
};

/// The truth a posterior bound is computed on (simulations only). Entry 0 is the start (the
/// prior's time and the true start positions), entries 1.. are the epochs.
struct BoundInput {
  std::vector<double> t_s;                     ///< times (s)
  std::vector<std::vector<Vec3>> positions_m;  ///< per time, per tracked agent, the true position
  /// The walls as they are: every wall of the simulated building.
  const geometry::FloorPlan* true_plan = nullptr;
  /// The given floor plan's walls at their true places (without the walls the plan lacks).
  const geometry::FloorPlan* true_known_plan = nullptr;
};

/// A method's estimator for one run. Not thread-safe; one instance per run.
class Estimator {
 public:
  virtual ~Estimator() = default;

  /// Starts at the prior.
  virtual void Initialize(const Prior& prior) = 0;
  /// Self-initialisation: offered the first epochs one by one until it returns true; the epoch
  /// that initialises is not processed again. The default cannot initialise itself.
  virtual bool InitializeFromEpoch(const core::Epoch& epoch);
  /// Propagates to the epoch's records and updates with them.
  virtual StepOutput Process(const core::Epoch& epoch) = 0;
  /// The estimated map, if the method builds one.
  [[nodiscard]] virtual std::vector<MapFeature> Map() const { return {}; }
  /// The estimated offsets of the given floor plan's walls, if the method estimates them (one
  /// per wall of World::floor_plan), else empty.
  [[nodiscard]] virtual std::vector<WallEstimate> Walls() const { return {}; }
  /// The posterior bound of the method's own model on the truth (its covariance recursion along
  /// the true trajectory with every modelled measurement at its true noise, no misses and no
  /// wrong associations): per entry of `truth` (the start first), per agent, sqrt(tr P_position)
  /// (m). Empty if the method
  /// has none; the runner then reports the simulated channel's snapshot bound, if any.
  [[nodiscard]] virtual std::vector<std::vector<double>> PosteriorBound(const BoundInput& truth) const;
};

}  // namespace mirage::methods
