// SPDX-License-Identifier: MIT
// Virtual anchors (VAs): mirror images of the physical anchors at the walls, up to a maximum
// reflection order. A reflected path has the length of the straight line from the agent to the
// VA (Lafer 2014 Sec. 3.1, 3.2; image-source method). A VirtualAnchorSet is a cache of the
// image-source engine (image_source.h) for fixed anchors: its positions are the engine's image
// chains, generated under the engine's rules, and its visibility (visibility.h) is the engine's
// trace over the cached chain.
#pragma once

#include <span>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/image_source.h"

namespace mirage::geometry {

/// Highest reflection order supported: the engine's (orders above 3 are rarely above the noise
/// indoors).
inline constexpr int kMaxVirtualAnchorOrder = kMaxImageOrder;

/// One virtual anchor; order 0 is the physical anchor itself.
struct VirtualAnchor {
  int id = 0;            ///< index in its VirtualAnchorSet
  int anchor_index = 0;  ///< physical anchor it derives from
  int order = 0;         ///< number of reflections
  /// Walls of the path, w_1..w_k: w_1 is the bounce next to the physical anchor, w_k the bounce
  /// next to the agent (the wall this VA was mirrored at last).
  std::vector<int> walls;
  int parent = -1;                   ///< id of the order-(k-1) VA it was mirrored from, -1 for order 0
  Vec2 position_m = Vec2::Zero();    ///< VA position in the plane (m)
  /// Height z of the VA (m): its physical anchor's, since vertical walls keep z.
  double height_m = 0.0;
  double reflection_gain = 1.0;      ///< product of the walls' reflection coefficients

  /// The VA in 3-D: (position_m, height_m) (m).
  [[nodiscard]] Vec3 position3_m() const { return Vec3(position_m.x(), position_m.y(), height_m); }
};

/// All VAs of a set of anchors, ordered by anchor, then by order.
class VirtualAnchorSet {
 public:
  VirtualAnchorSet() = default;

  /// Mirrors every anchor (m) up to max_order (>= 0). Order-k VAs come from mirroring each
  /// order-(k-1) VA at every wall the engine's generation rules allow (CanMirror): not the one
  /// that generated it, not a wall collinear with it (the image would return to the grandparent)
  /// and not a wall on whose line the VA lies, because no physical path realises them.
  /// max_order must be in [0, kMaxVirtualAnchorOrder]. Each VA keeps its anchor's height.
  static VirtualAnchorSet Generate(std::span<const Vec3> anchors_m, const FloorPlan& plan, int max_order);
  /// The same for planar anchors (m), all at height 0.
  static VirtualAnchorSet Generate(std::span<const Vec2> anchors_m, const FloorPlan& plan, int max_order);

  [[nodiscard]] const std::vector<VirtualAnchor>& all() const { return vas_; }
  [[nodiscard]] const VirtualAnchor& operator[](int id) const { return vas_[static_cast<std::size_t>(id)]; }
  [[nodiscard]] int size() const { return static_cast<int>(vas_.size()); }
  /// Ids of the VAs of one anchor (a contiguous range, physical anchor first).
  [[nodiscard]] std::span<const int> ForAnchor(int anchor_index) const;
  /// The cached image chain of a VA in the plane: its physical anchor first, then its ancestors
  /// by order, the VA itself last (order + 1 points, m); ImageChain of the anchor and the VA's
  /// walls, bit for bit.
  [[nodiscard]] std::span<const Vec2> ImageChainOf(int id) const {
    const auto& va = vas_[static_cast<std::size_t>(id)];
    return {chains_.data() + chain_offset_[static_cast<std::size_t>(id)], static_cast<std::size_t>(va.order) + 1};
  }
  [[nodiscard]] int anchor_count() const { return static_cast<int>(by_anchor_.size()); }
  [[nodiscard]] int max_order() const { return max_order_; }

 private:
  std::vector<VirtualAnchor> vas_;
  std::vector<std::vector<int>> by_anchor_;
  // The image chains of all VAs back to back (VA id's chain starts at chain_offset_[id]), so
  // that a visibility test reads its images from one place instead of chasing parents.
  std::vector<Vec2> chains_;
  std::vector<std::size_t> chain_offset_;
  int max_order_ = 0;
};

}  // namespace mirage::geometry
