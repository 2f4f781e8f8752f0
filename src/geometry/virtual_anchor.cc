// SPDX-License-Identifier: MIT
#include "mirage/geometry/virtual_anchor.h"

#include <cassert>
#include <cmath>

#include "mirage/geometry/segment.h"

namespace mirage::geometry {
namespace {

bool Collinear(const Wall& a, const Wall& b) {
  constexpr double kTolerance_m = 1e-9;
  return std::abs(SignedDistanceToLine(b.start_m, a.start_m, a.end_m)) < kTolerance_m &&
         std::abs(SignedDistanceToLine(b.end_m, a.start_m, a.end_m)) < kTolerance_m;
}

}  // namespace

VirtualAnchorSet VirtualAnchorSet::Generate(std::span<const Vec2> anchors_m, const FloorPlan& plan, int max_order) {
  assert(max_order >= 0 && max_order <= kMaxVirtualAnchorOrder);
  VirtualAnchorSet set;
  set.max_order_ = max_order;
  const auto& walls = plan.walls();
  for (int a = 0; a < static_cast<int>(anchors_m.size()); ++a) {
    std::vector<int> ids;
    VirtualAnchor root;
    root.id = static_cast<int>(set.vas_.size());
    root.anchor_index = a;
    root.position_m = anchors_m[static_cast<std::size_t>(a)];
    ids.push_back(root.id);
    set.vas_.push_back(root);

    std::size_t level_begin = ids.size() - 1;
    for (int order = 1; order <= max_order; ++order) {
      const std::size_t level_end = ids.size();
      for (std::size_t i = level_begin; i < level_end; ++i) {
        // Copy: push_back below may reallocate vas_.
        const VirtualAnchor parent = set.vas_[static_cast<std::size_t>(ids[i])];
        for (int w = 0; w < static_cast<int>(walls.size()); ++w) {
          const Wall& wall = walls[static_cast<std::size_t>(w)];
          if (!parent.walls.empty()) {
            const Wall& last = walls[static_cast<std::size_t>(parent.walls.back())];
            if (w == parent.walls.back() || Collinear(wall, last)) continue;
          }
          if (std::abs(SignedDistanceToLine(parent.position_m, wall.start_m, wall.end_m)) < 1e-9) continue;
          VirtualAnchor va;
          va.id = static_cast<int>(set.vas_.size());
          va.anchor_index = a;
          va.order = order;
          va.walls = parent.walls;
          va.walls.push_back(w);
          va.parent = parent.id;
          va.position_m = MirrorPoint(parent.position_m, wall.start_m, wall.end_m);
          va.reflection_gain = parent.reflection_gain * wall.reflection_coeff;
          ids.push_back(va.id);
          set.vas_.push_back(std::move(va));
        }
      }
      level_begin = level_end;
    }
    set.by_anchor_.push_back(std::move(ids));
  }
  return set;
}

std::span<const int> VirtualAnchorSet::ForAnchor(int anchor_index) const {
  return by_anchor_[static_cast<std::size_t>(anchor_index)];
}

}  // namespace mirage::geometry
