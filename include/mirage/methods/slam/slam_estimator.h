// SPDX-License-Identifier: MIT
// Multipath SLAM behind the Estimator interface: the anchors (and, with
// SlamOptions::prior_max_order > 0, the given floor plan's VAs) start the map, the tracker runs on
// the epochs' range sets, and its map is reported as map features.
#pragma once

#include "mirage/geometry/virtual_anchor.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/slam/slam_tracker.h"
#include "mirage/methods/world.h"

namespace mirage::methods::slam {

class SlamEstimator final : public Estimator {
 public:
  SlamEstimator(const SlamOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  StepOutput Process(const core::Epoch& epoch) override;
  /// The map: anchors (not scored), prior and discovered VAs (scored when not filtered and
  /// associated at least once), with map.csv's attributes.
  [[nodiscard]] std::vector<MapFeature> Map() const override;

 private:
  World world_;
  geometry::VirtualAnchorSet known_vas_;
  SlamTracker tracker_;  // refers to known_vas_ and world_.floor_plan: declared after them
};

}  // namespace mirage::methods::slam
