// SPDX-License-Identifier: MIT
#include "mirage/geometry/virtual_anchor.h"

#include <cassert>

namespace mirage::geometry {

VirtualAnchorSet VirtualAnchorSet::Generate(std::span<const Vec3> anchors_m, const FloorPlan& plan, int max_order) {
  assert(max_order >= 0 && max_order <= kMaxVirtualAnchorOrder);
  VirtualAnchorSet set;
  set.max_order_ = max_order;
  const auto& walls = plan.walls();
  for (int a = 0; a < static_cast<int>(anchors_m.size()); ++a) {
    std::vector<int> ids;
    VirtualAnchor root;
    root.id = static_cast<int>(set.vas_.size());
    root.anchor_index = a;
    root.position_m = anchors_m[static_cast<std::size_t>(a)].head<2>();
    root.height_m = anchors_m[static_cast<std::size_t>(a)].z();
    ids.push_back(root.id);
    set.vas_.push_back(root);

    std::size_t level_begin = ids.size() - 1;
    for (int order = 1; order <= max_order; ++order) {
      const std::size_t level_end = ids.size();
      for (std::size_t i = level_begin; i < level_end; ++i) {
        // Copy: push_back below may reallocate vas_.
        const VirtualAnchor parent = set.vas_[static_cast<std::size_t>(ids[i])];
        for (int w = 0; w < static_cast<int>(walls.size()); ++w) {
          if (!CanMirror(plan, parent.walls.empty() ? -1 : parent.walls.back(), w, parent.position_m)) continue;
          const Wall& wall = walls[static_cast<std::size_t>(w)];
          VirtualAnchor va;
          va.id = static_cast<int>(set.vas_.size());
          va.anchor_index = a;
          va.order = order;
          va.walls = parent.walls;
          va.walls.push_back(w);
          va.parent = parent.id;
          // One mirror per generation: the position is the engine's image chain of the anchor.
          va.position_m = MirrorAtWall(wall, parent.position_m);
          va.height_m = parent.height_m;
          va.reflection_gain = parent.reflection_gain * wall.reflection_coeff;
          ids.push_back(va.id);
          set.vas_.push_back(std::move(va));
        }
      }
      level_begin = level_end;
    }
    set.by_anchor_.push_back(std::move(ids));
  }
  set.chain_offset_.reserve(set.vas_.size());
  for (const auto& va : set.vas_) {
    set.chain_offset_.push_back(set.chains_.size());
    set.chains_.resize(set.chains_.size() + static_cast<std::size_t>(va.order) + 1);
    // Walk up the parents, filling the chain from its end.
    const VirtualAnchor* ancestor = &va;
    for (std::size_t k = set.chains_.size(); k-- > set.chain_offset_.back();) {
      set.chains_[k] = ancestor->position_m;
      if (ancestor->parent >= 0) ancestor = &set.vas_[static_cast<std::size_t>(ancestor->parent)];
    }
  }
  return set;
}

VirtualAnchorSet VirtualAnchorSet::Generate(std::span<const Vec2> anchors_m, const FloorPlan& plan, int max_order) {
  std::vector<Vec3> anchors3;
  anchors3.reserve(anchors_m.size());
  for (const Vec2& a : anchors_m) anchors3.emplace_back(a.x(), a.y(), 0.0);
  return Generate(std::span<const Vec3>(anchors3), plan, max_order);
}

std::span<const int> VirtualAnchorSet::ForAnchor(int anchor_index) const {
  return by_anchor_[static_cast<std::size_t>(anchor_index)];
}

}  // namespace mirage::geometry
