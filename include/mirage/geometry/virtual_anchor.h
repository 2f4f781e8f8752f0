// SPDX-License-Identifier: MIT
// Virtual anchors (VAs): mirror images of the physical anchors at the walls, up to a maximum
// reflection order. A reflected path has the length of the straight line from the agent to the
// VA (Lafer 2014 Sec. 3.1, 3.2; image-source method).
#pragma once

#include <span>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::geometry {

/// Highest reflection order supported (orders above 3 are rarely above the noise indoors).
inline constexpr int kMaxVirtualAnchorOrder = 6;

/// One virtual anchor; order 0 is the physical anchor itself.
struct VirtualAnchor {
  int id = 0;            ///< index in its VirtualAnchorSet
  int anchor_index = 0;  ///< physical anchor it derives from
  int order = 0;         ///< number of reflections
  /// Walls of the path, w_1..w_k: w_1 is the bounce next to the physical anchor, w_k the bounce
  /// next to the agent (the wall this VA was mirrored at last).
  std::vector<int> walls;
  int parent = -1;                   ///< id of the order-(k-1) VA it was mirrored from, -1 for order 0
  Vec2 position_m = Vec2::Zero();    ///< VA position (m)
  double reflection_gain = 1.0;      ///< product of the walls' reflection coefficients
};

/// All VAs of a set of anchors, ordered by anchor, then by order.
class VirtualAnchorSet {
 public:
  VirtualAnchorSet() = default;

  /// Mirrors every anchor up to max_order (>= 0). Order-k VAs come from mirroring each
  /// order-(k-1) VA at every wall except the one that generated it; mirrors at a wall collinear
  /// with the generating wall (the image would return to the grandparent) and mirrors of a point
  /// lying on the wall line are skipped because no physical path realises them.
  /// max_order must be in [0, kMaxVirtualAnchorOrder].
  static VirtualAnchorSet Generate(std::span<const Vec2> anchors_m, const FloorPlan& plan, int max_order);

  [[nodiscard]] const std::vector<VirtualAnchor>& all() const { return vas_; }
  [[nodiscard]] const VirtualAnchor& operator[](int id) const { return vas_[static_cast<std::size_t>(id)]; }
  [[nodiscard]] int size() const { return static_cast<int>(vas_.size()); }
  /// Ids of the VAs of one anchor (a contiguous range, physical anchor first).
  [[nodiscard]] std::span<const int> ForAnchor(int anchor_index) const;
  [[nodiscard]] int anchor_count() const { return static_cast<int>(by_anchor_.size()); }
  [[nodiscard]] int max_order() const { return max_order_; }

 private:
  std::vector<VirtualAnchor> vas_;
  std::vector<std::vector<int>> by_anchor_;
  int max_order_ = 0;
};

}  // namespace mirage::geometry
