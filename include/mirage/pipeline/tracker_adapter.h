// SPDX-License-Identifier: MIT
// One interface over the estimators, so that the drivers (simulated Monte-Carlo runs, recorded
// files) run MINT and SLAM alike: initialise, step with the ranges of all anchors, read the
// map at the end.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/measurements.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/pipeline/experiment_config.h"

namespace mirage::pipeline {

/// What one step of either tracker produced, as the drivers record it.
struct TrackerStep {
  Vec2 position_m = Vec2::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Zero();
  /// (known VA id, estimated SINR) of each association with an SINR estimate at this step;
  /// discovered VAs (SLAM) have ids >= methods::slam::kFirstDiscoveredVaId.
  std::vector<std::pair<int, double>> sinr_estimates;
  int associations = 0;
  bool relocalized = false;
  bool constrained = false;
  bool rejected_update = false;
  int discovered = 0;  ///< SLAM: VAs promoted into the state
};

/// The tracker of one run.
class TrackerAdapter {
 public:
  /// @param known_vas VAs generated from the known floor plan and anchors (up to the method's
  ///                  order), referenced, not copied.
  TrackerAdapter(const MintExperimentConfig& config, const geometry::VirtualAnchorSet& known_vas,
                 double range_sigma_at_unit_sinr_m);
  ~TrackerAdapter();
  TrackerAdapter(const TrackerAdapter&) = delete;
  TrackerAdapter& operator=(const TrackerAdapter&) = delete;

  void Initialize(double t_s, const Vec2& p0_m);
  TrackerStep Step(double t_s, std::span<const core::AnchorRanges> measurements);
  /// The SLAM map (empty for MINT).
  [[nodiscard]] std::vector<methods::slam::MapVa> Map() const;

 private:
  std::unique_ptr<methods::mint::MintTracker> mint_;
  std::unique_ptr<methods::slam::SlamTracker> slam_;
};

/// Highest VA order the method's tracker uses from the known floor plan.
int KnownVaOrder(const MintExperimentConfig& config);

}  // namespace mirage::pipeline
