// SPDX-License-Identifier: MIT
// MINT behind the Estimator interface: the known floor plan and anchors give the virtual
// anchors up to MintOptions::max_order (Lafer 2014 Sec. 3.1), the tracker runs on the epochs'
// range sets. The method is planar, as in the thesis: anchors and agent share one plane.
#pragma once

#include <memory>

#include "mirage/geometry/virtual_anchor.h"
#include "mirage/methods/estimator.h"
#include "mirage/methods/mint/mint_tracker.h"
#include "mirage/methods/world.h"

namespace mirage::methods::mint {

/// The range-variance scale c / (sqrt(8) pi beta) of the world's pulse (m), Eq. (3.28).
double RangeSigmaAtUnitSinr(const World& world);

class MintEstimator final : public Estimator {
 public:
  MintEstimator(const MintOptions& options, const World& world);

  void Initialize(const Prior& prior) override;
  /// Starts without a start point: the position in the floor plan whose visible LOS and
  /// first-order VAs best explain the epoch's ranges, if it is unique (SearchFloorPlan with the
  /// relocalization's score) and the next epoch's search confirms it (ConfirmedStart); false
  /// (try the next epoch) otherwise.
  bool InitializeFromEpoch(const core::Epoch& epoch) override;
  StepOutput Process(const core::Epoch& epoch) override;

  /// The virtual anchors the tracker uses (for reports and plots).
  [[nodiscard]] const geometry::VirtualAnchorSet& virtual_anchors() const { return vas_; }

 private:
  World world_;
  RelocalizationOptions search_;
  ConfirmedStart start_;
  geometry::VirtualAnchorSet vas_;
  MintTracker tracker_;  // refers to vas_ and world_.floor_plan: declared after them
};

}  // namespace mirage::methods::mint
