// SPDX-License-Identifier: MIT
// Test fixture for the MINT tests: a 6 m x 6 m square room with two anchors, its VAs, and
// synthetic unlabeled range measurements generated from the VAs visible at the true position
// (clean ranges with seeded Gaussian noise and Rician amplitudes, optional uniform clutter).
#pragma once

#include <cmath>
#include <vector>

#include "mirage/core/measurements.h"
#include "mirage/core/rng.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/geometry/visibility.h"

namespace mirage::methods::mint::testing {

// Walls counter-clockwise from (0, 0): 0 south y = 0, 1 east x = 6, 2 north y = 6, 3 west x = 0.
inline std::vector<geometry::Wall> SquareWalls() {
  return {{Vec2(0, 0), Vec2(6, 0), 0.6, "south"},
          {Vec2(6, 0), Vec2(6, 6), 0.6, "east"},
          {Vec2(6, 6), Vec2(0, 6), 0.6, "north"},
          {Vec2(0, 6), Vec2(0, 0), 0.6, "west"}};
}

inline geometry::FloorPlan EmptySquareRoom() { return geometry::FloorPlan(SquareWalls(), {}); }

// The square room with a pillar of radius 0.3 m at (2.5, 3.0): it blocks some paths.
inline geometry::FloorPlan SquareRoomWithPillar() {
  return geometry::FloorPlan(SquareWalls(), {{Vec2(2.5, 3.0), 0.3, "pillar"}});
}

inline std::vector<Vec2> TwoAnchors() { return {Vec2(1.0, 5.0), Vec2(5.0, 1.0)}; }

inline geometry::VirtualAnchorSet SquareRoomVas(const geometry::FloorPlan& plan, int max_order) {
  const std::vector<Vec2> anchors = TwoAnchors();
  return geometry::VirtualAnchorSet::Generate(anchors, plan, max_order);
}

// How the measurements are made.
struct MeasurementModel {
  double range_sigma_m = 0.01;  // Gaussian range noise (m)
  double k_factor = 10.0;       // Rician K of the amplitudes (10 dB)
  int max_order = 1;            // highest VA order that produces a range
  bool only_visible = true;     // false: every VA up to max_order produces a range (ghosts too)
  int clutter_per_anchor = 0;   // extra ranges uniform in [0, clutter_max_range_m)
  double clutter_max_range_m = 10.0;
};

// Ranges to both anchors at the true position p_m; the range to VA k is |p - VA_k| + noise and
// its amplitude gain_k / d_k * |sqrt(K) + CN(0, 1)|.
inline std::vector<core::AnchorRanges> MeasureRanges(const geometry::VirtualAnchorSet& vas,
                                                    const geometry::FloorPlan& plan, const Vec2& p_m,
                                                    const MeasurementModel& model, core::Rng& rng) {
  std::vector<core::AnchorRanges> out;
  for (int a = 0; a < vas.anchor_count(); ++a) {
    core::AnchorRanges anchor;
    anchor.anchor_index = a;
    std::vector<int> ids;
    if (model.only_visible) {
      ids = geometry::VisibleVirtualAnchors(vas, a, plan, p_m, model.max_order);
    } else {
      for (const int id : vas.ForAnchor(a)) {
        if (vas[id].order <= model.max_order) ids.push_back(id);
      }
    }
    for (const int id : ids) {
      const double d_m = (vas[id].position_m - p_m).norm();
      const double fading = std::abs(Complex(std::sqrt(model.k_factor), 0.0) + rng.ComplexNormal(1.0));
      anchor.ranges.push_back({d_m + rng.Normal(0.0, model.range_sigma_m), vas[id].reflection_gain / d_m * fading});
    }
    for (int c = 0; c < model.clutter_per_anchor; ++c) {
      anchor.ranges.push_back({rng.Uniform(0.0, model.clutter_max_range_m), 0.05 * rng.Uniform()});
    }
    out.push_back(std::move(anchor));
  }
  return out;
}

}  // namespace mirage::methods::mint::testing
