// SPDX-License-Identifier: MIT
// Multipath SLAM behind the Estimator interface: the anchors (and, with
// SlamOptions::prior_max_order > 0, the given floor plan's VAs) start the map, the tracker runs on
// the epochs' range sets, and its map is reported as map features.
#pragma once

#include "mirage/geometry/virtual_anchor.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/mint/relocalization.h"
#include "mirage/methods/slam/slam_tracker.h"
#include "mirage/methods/world.h"

namespace mirage::methods::slam {

class SlamEstimator final : public Estimator {
 public:
  SlamEstimator(const SlamOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  /// Starts without a start point: from a least-squares fix of the earliest range of each
  /// anchor when at least 3 anchors answered and the fix's residuals are consistent (RMS at most
  /// 3 range sigma), else, with a floor plan, at the unique position whose visible LOS and
  /// first-order VAs of the plan best explain the ranges (MINT's SearchFloorPlan, confirmed by
  /// the next epoch's); false (try
  /// the next epoch) otherwise. Two anchors without a plan cannot tell the two crossings of their
  /// range circles apart, and such a run never starts.
  bool InitializeFromEpoch(const core::Epoch& epoch) override;
  StepOutput Process(const core::Epoch& epoch) override;
  /// The map: anchors (not scored), prior and discovered VAs (scored when not filtered and
  /// associated at least once), with map.csv's attributes.
  [[nodiscard]] std::vector<MapFeature> Map() const override;

 private:
  World world_;
  double range_sigma_m_;
  mint::RelocalizationOptions search_;
  mint::ConfirmedStart start_;
  geometry::VirtualAnchorSet search_vas_;  // the plan's first-order VAs, for the start search
  geometry::VirtualAnchorSet known_vas_;
  SlamTracker tracker_;  // refers to known_vas_ and world_.floor_plan: declared after them
};

}  // namespace mirage::methods::slam
