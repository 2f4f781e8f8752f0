// SPDX-License-Identifier: MIT
// Test fixture for the MINT tests: a 6 m x 6 m square room with two anchors, its VAs, and
// synthetic unlabeled range measurements generated from the VAs visible at the true position
// (clean ranges with seeded Gaussian noise and Rician amplitudes, optional uniform clutter), and
// an epoch with one range made an outlier (the gate tests).
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "mirage/core/records.h"
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
inline std::vector<core::RangeSet> MeasureRanges(const geometry::VirtualAnchorSet& vas,
                                                    const geometry::FloorPlan& plan, const Vec2& p_m,
                                                    const MeasurementModel& model, core::Rng& rng) {
  std::vector<core::RangeSet> out;
  for (int a = 0; a < vas.anchor_count(); ++a) {
    core::RangeSet anchor;
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

// An epoch with one range made an outlier: `with` has the range of anchor anchor_index nearest to
// path_m (within 5 cm of it) made offset_m longer, `without` leaves that range out.
struct OutlierEpoch {
  std::vector<core::RangeSet> with;
  std::vector<core::RangeSet> without;
};
inline OutlierEpoch WithOutlier(const std::vector<core::RangeSet>& ranges, int anchor_index, double path_m,
                                double offset_m) {
  OutlierEpoch out{ranges, ranges};
  for (std::size_t a = 0; a < ranges.size(); ++a) {
    if (ranges[a].anchor_index != anchor_index) continue;
    for (std::size_t j = 0; j < ranges[a].ranges.size(); ++j) {
      if (std::abs(ranges[a].ranges[j].range_m - path_m) > 0.05) continue;
      out.with[a].ranges[j].range_m = path_m + offset_m;
      out.without[a].ranges.erase(out.without[a].ranges.begin() + static_cast<std::ptrdiff_t>(j));
      return out;
    }
  }
  return out;
}

// The gate tests' walk: `tracker` (a MintTracker or SlamTracker on `vas` and `plan`) starts at
// (1.5, 2) and takes 20 steps of 5 cm east on 1 cm ranges; then `twin` becomes a copy of it, and
// at step 21, at (2.55, 2), `tracker` takes the epoch with the range of outlier_va made offset_m
// longer and `twin` the same epoch without that range. Returns their step results in that order.
template <class Tracker>
auto StepWithAndWithoutOutlier(Tracker& tracker, Tracker& twin, const geometry::VirtualAnchorSet& vas,
                               const geometry::FloorPlan& plan, int outlier_va, double offset_m) {
  const auto at = [](int k) { return Vec2(1.5 + 0.05 * k, 2.0); };
  tracker.Initialize(0.0, at(0));
  core::Rng rng(5, 0);
  for (int k = 1; k <= 20; ++k) tracker.Step(0.1 * k, MeasureRanges(vas, plan, at(k), {}, rng));
  const double path_m = (vas[outlier_va].position_m - at(21)).norm();
  const OutlierEpoch epoch =
      WithOutlier(MeasureRanges(vas, plan, at(21), {}, rng), vas[outlier_va].anchor_index, path_m, offset_m);
  twin = tracker;
  auto with = tracker.Step(2.1, epoch.with);
  return std::pair(with, twin.Step(2.1, epoch.without));
}

// Whether a step result (MintStepResult or SlamStepResult) lists an association to va_id.
template <class StepResult>
bool Associated(const StepResult& step, int va_id) {
  for (const auto& a : step.associations) {
    if (a.va_id == va_id) return true;
  }
  return false;
}

// A first-order VA of anchor anchor_index visible at p_m whose range there is at least min_gap_m
// from every other visible range of its anchor, so that only its own range competes for it; -1 if
// there is none.
inline int IsolatedReflection(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
                              int anchor_index, const Vec2& p_m, double min_gap_m) {
  const auto visible = geometry::VisibleVirtualAnchors(vas, anchor_index, plan, p_m, 1);
  for (const int id : visible) {
    if (vas[id].order != 1) continue;
    bool isolated = true;
    for (const int other : visible) {
      const double gap_m = (vas[id].position_m - p_m).norm() - (vas[other].position_m - p_m).norm();
      if (other != id && std::abs(gap_m) < min_gap_m) isolated = false;
    }
    if (isolated) return id;
  }
  return -1;
}

}  // namespace mirage::methods::mint::testing
