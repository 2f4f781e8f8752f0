// SPDX-License-Identifier: MIT
#include "mirage/geometry/visibility.h"

#include <array>
#include <span>

#include "mirage/geometry/image_source.h"

namespace mirage::geometry {
namespace {

using Vertices = std::array<Vec2, kMaxImageOrder + 2>;

bool Trace(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan, const Vec2& agent_m, Vertices& vertices) {
  const auto chain = vas.ImageChainOf(va_id);
  return TraceImageChain(plan, vas[va_id].walls, chain, agent_m, std::span<Vec2>(vertices.data(), chain.size() + 1));
}

}  // namespace

std::optional<ReflectionPath> TraceVirtualAnchor(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan,
                                                 const Vec2& agent_m) {
  Vertices vertices;
  if (!Trace(vas, va_id, plan, agent_m, vertices)) return std::nullopt;
  ReflectionPath path;
  // The engine's back-trace order is already agent, w_k .. w_1, anchor.
  path.points_m.assign(vertices.begin(), vertices.begin() + vas[va_id].order + 2);
  path.length_m = (vas[va_id].position_m - agent_m).norm();
  return path;
}

std::optional<ReflectionPath3> TraceVirtualAnchor(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan,
                                                  const Vec3& agent_m) {
  const VirtualAnchor& va = vas[va_id];
  const auto chain = vas.ImageChainOf(va_id);
  std::array<Vec3, kMaxImageOrder + 1> images;
  for (std::size_t k = 0; k < chain.size(); ++k) images[k] = Vec3(chain[k].x(), chain[k].y(), va.height_m);
  std::array<Vec3, kMaxImageOrder + 2> vertices;
  if (!TraceImageChain(plan, va.walls, std::span<const Vec3>(images.data(), chain.size()), agent_m,
                       std::span<Vec3>(vertices.data(), chain.size() + 1))) {
    return std::nullopt;
  }
  ReflectionPath3 path;
  path.points_m.assign(vertices.begin(), vertices.begin() + static_cast<std::ptrdiff_t>(chain.size() + 1));
  path.length_m = (va.position3_m() - agent_m).norm();
  return path;
}

bool IsVisible(const VirtualAnchorSet& vas, int va_id, const FloorPlan& plan, const Vec2& agent_m) {
  Vertices vertices;
  return Trace(vas, va_id, plan, agent_m, vertices);
}

std::vector<int> VisibleVirtualAnchors(const VirtualAnchorSet& vas, int anchor_index, const FloorPlan& plan,
                                       const Vec2& agent_m, int max_order) {
  std::vector<int> visible;
  Vertices vertices;
  for (const int id : vas.ForAnchor(anchor_index)) {
    if (vas[id].order > max_order) break;  // an anchor's VAs are sorted by order
    if (Trace(vas, id, plan, agent_m, vertices)) visible.push_back(id);
  }
  return visible;
}

}  // namespace mirage::geometry
