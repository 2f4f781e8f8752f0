// SPDX-License-Identifier: MIT
// Visibility of a virtual anchor from an agent position by back-tracing the reflected path
// (Lafer 2014 Sec. 4.3.2, Fig. 4.17): the ray from the agent towards the VA must hit the VA's last
// wall segment, from there the ray towards the parent VA must hit the previous wall, and so on
// down to the physical anchor; no leg may be blocked by another wall or an obstacle. This is the
// image-source engine's trace (image_source.h, TraceImageChain) over the VA set's cached image
// chain, with the engine's tolerances.
#pragma once

#include <optional>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/virtual_anchor.h"

namespace mirage::geometry {

/// The traced path of a visible VA.
struct ReflectionPath {
  /// Agent position, reflection points (at w_k, ..., w_1), physical anchor position (m).
  std::vector<Vec2> points_m;
  /// Path length, equal to |agent - VA| (m).
  double length_m = 0.0;
};

/// The traced path of a visible VA in 3-D.
struct ReflectionPath3 {
  /// Agent position, reflection points (at w_k, ..., w_1) with their interpolated heights,
  /// physical anchor position (m).
  std::vector<Vec3> points_m;
  /// Path length, equal to |agent - VA| in 3-D (m).
  double length_m = 0.0;
};

/// The path from the agent (m) to the VA's physical anchor over the VA's walls, if it exists and
/// is unobstructed; std::nullopt if the VA is not visible from agent_m.
std::optional<ReflectionPath> TraceVirtualAnchor(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan,
                                                 const Vec2& agent_m);
/// The same in 3-D: the VA stands at its anchor's height; a path whose reflection point lies
/// below the plan's floor or above its ceiling is not visible.
std::optional<ReflectionPath3> TraceVirtualAnchor(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan,
                                                  const Vec3& agent_m);

/// True if the VA is visible from agent_m (m) (same test as TraceVirtualAnchor, without the points).
bool IsVisible(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan, const Vec2& agent_m);

/// Ids of the VAs of one anchor up to max_order visible from agent_m (m), in increasing id order.
std::vector<int> VisibleVirtualAnchors(const VirtualAnchorSet& vas, int anchor_index, const FloorPlan& plan,
                                       const Vec2& agent_m, int max_order = kMaxVirtualAnchorOrder);

}  // namespace mirage::geometry
