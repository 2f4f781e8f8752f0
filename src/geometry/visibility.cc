// SPDX-License-Identifier: MIT
#include "mirage/geometry/visibility.h"

#include <array>
#include <cassert>

#include "mirage/geometry/segment.h"

namespace mirage::geometry {
namespace {

// Traces the path; when points is non-null, records the agent, the reflection points and the
// anchor. All wall crossings are tested before any obstruction test because the crossing tests
// are cheap and reject most VAs.
bool Trace(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan, const Vec2& agent_m,
           std::vector<Vec2>* points) {
  const auto& walls = plan.walls();
  const VirtualAnchor& target = vas[va_id];
  const int order = target.order;
  assert(order <= kMaxVirtualAnchorOrder);
  // legs[i] starts at leg_start[i]; leg 0 starts at the agent, leg `order` ends at the anchor.
  std::array<Vec2, kMaxVirtualAnchorOrder + 2> vertex;
  std::array<int, kMaxVirtualAnchorOrder + 2> vertex_wall;
  vertex[0] = agent_m;
  vertex_wall[0] = -1;
  const VirtualAnchor* va = &target;
  for (int i = 1; i <= order; ++i) {
    const int w = va->walls.back();
    const Wall& wall = walls[static_cast<std::size_t>(w)];
    const Vec2& from = vertex[static_cast<std::size_t>(i - 1)];
    const auto crossing = CrossSegments(from, va->position_m, wall.start_m, wall.end_m);
    if (!crossing || crossing->t <= 1e-12) return false;
    vertex[static_cast<std::size_t>(i)] = from + crossing->t * (va->position_m - from);
    vertex_wall[static_cast<std::size_t>(i)] = w;
    va = &vas[va->parent];
  }
  vertex[static_cast<std::size_t>(order + 1)] = va->position_m;
  vertex_wall[static_cast<std::size_t>(order + 1)] = -1;
  for (int i = 0; i <= order; ++i) {
    const auto a = static_cast<std::size_t>(i);
    if (!plan.IsLegClear(vertex[a], vertex[a + 1], vertex_wall[a], vertex_wall[a + 1])) return false;
  }
  if (points != nullptr) points->assign(vertex.begin(), vertex.begin() + order + 2);
  return true;
}

}  // namespace

std::optional<ReflectionPath> TraceVirtualAnchor(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan,
                                                 const Vec2& agent_m) {
  ReflectionPath path;
  if (!Trace(vas, va_id, plan, agent_m, &path.points_m)) return std::nullopt;
  path.length_m = (vas[va_id].position_m - agent_m).norm();
  return path;
}

bool IsVisible(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan, const Vec2& agent_m) {
  return Trace(vas, va_id, plan, agent_m, nullptr);
}

std::vector<int> VisibleVirtualAnchors(const VirtualAnchorSet& vas, int anchor_index, const FloorPlan& plan,
                                       const Vec2& agent_m, int max_order) {
  std::vector<int> visible;
  for (const int id : vas.ForAnchor(anchor_index)) {
    if (vas[id].order > max_order) break;  // an anchor's VAs are sorted by order
    if (Trace(vas, id, plan, agent_m, nullptr)) visible.push_back(id);
  }
  return visible;
}

}  // namespace mirage::geometry
