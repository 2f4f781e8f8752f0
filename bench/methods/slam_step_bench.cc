// SPDX-License-Identifier: MIT
// One multipath-SLAM step (prediction, two-stage association, EKF update, discovery) with at
// least 40 VAs in the EKF state (the target is at least 5,000 such steps per second on one
// core). The state size, not the signal chain, drives the cost (the joint covariance is dense),
// so the tracker is fed exact ranges of the visible VAs (no CIRs, no MPC extraction) in an
// 8 m x 6 m empty room with 3 anchors, and first warmed up until the lazily added prior VAs fill
// the state. 3 anchors x 16 prior VAs up to order 2 give 40-42 VAs in the state along the loop
// (4 anchors would give 56, and the dense covariance update grows roughly with the cube).
// Two variants of the covariance update: the standard form (the tracker's default) and the
// Joseph form (joseph:1).
#include <cstddef>
#include <vector>

#include <benchmark/benchmark.h>

#include "mirage/core/records.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/geometry/visibility.h"
#include "mirage/methods/slam/slam_tracker.h"

namespace mirage::bench {
namespace {

constexpr int kMaxOrder = 2;         // prior VAs and measured paths up to 2nd order
constexpr int kMinStateVas = 40;     // what the benchmark is about
constexpr int kMaxWarmupLaps = 5;    // give up (and report an error) after this many laps
// c / (sqrt(8) pi beta) of a ~500 MHz pulse; only scales the variance estimator's SINR.
constexpr double kRangeSigmaAtUnitSinrM = 0.0316;

// An 8 m x 6 m room, walls counter-clockwise from (0, 0). Anchors off-symmetric, so that no two
// VAs of different walls coincide by symmetry.
struct Room {
  geometry::FloorPlan plan;
  geometry::VirtualAnchorSet vas;
  std::vector<geometry::TrajectorySample> lap;          // one closed lap, last sample != first
  std::vector<std::vector<core::RangeSet>> ranges;  // [lap step][anchor], precomputed
  double dt_s = 0.0;
};

const Room& EmptyRoom() {
  static const Room room = [] {
    Room r;
    r.plan = geometry::FloorPlan({{Vec2(0, 0), Vec2(8, 0), 0.6, "south"},
                                  {Vec2(8, 0), Vec2(8, 6), 0.6, "east"},
                                  {Vec2(8, 6), Vec2(0, 6), 0.6, "north"},
                                  {Vec2(0, 6), Vec2(0, 0), 0.6, "west"}},
                                 {});
    const std::vector<Vec2> anchors_m{Vec2(0.8, 1.2), Vec2(7.1, 0.9), Vec2(6.6, 5.3)};
    r.vas = geometry::VirtualAnchorSet::Generate(anchors_m, r.plan, kMaxOrder);
    // A closed rectangular loop at least 1.5 m from the walls (12 m, 240 steps of 5 cm at 10 Hz): the
    // tracker walks it again and again, so it always stays inside the room.
    const std::vector<Vec2> loop_m{Vec2(2.0, 1.5), Vec2(6.0, 1.5), Vec2(6.0, 4.5), Vec2(2.0, 4.5), Vec2(2.0, 1.5)};
    r.lap = geometry::SampleTrajectory(loop_m, 0.5, 0.1);
    // The end point (if sampled) is the start of the next lap.
    if ((r.lap.back().position_m - r.lap.front().position_m).norm() < 1e-9) r.lap.pop_back();
    r.dt_s = r.lap[1].t_s - r.lap[0].t_s;
    // Exact ranges of every VA visible at the true position, amplitude gain / distance: clean
    // data, so the cost measured is the filter's and not that of clutter handling.
    for (const auto& s : r.lap) {
      std::vector<core::RangeSet> all(static_cast<std::size_t>(r.vas.anchor_count()));
      for (int a = 0; a < r.vas.anchor_count(); ++a) {
        auto& anchor = all[static_cast<std::size_t>(a)];
        anchor.anchor_index = a;
        for (const int id : geometry::VisibleVirtualAnchors(r.vas, a, r.plan, s.position_m, kMaxOrder)) {
          const double range_m = (r.vas[id].position_m - s.position_m).norm();
          anchor.ranges.push_back({range_m, r.vas[id].reflection_gain / range_m});
        }
      }
      r.ranges.push_back(std::move(all));
    }
    return r;
  }();
  return room;
}

void BM_SlamStep40Vas(benchmark::State& state) {
  const Room& room = EmptyRoom();
  methods::slam::SlamOptions options;  // defaults, with the floor plan's VAs known up to order 2
  options.prior_max_order = kMaxOrder;
  options.joseph_update = state.range(0) != 0;  // the default standard form, or the Joseph form
  methods::slam::SlamTracker tracker(options, room.vas, room.plan, kRangeSigmaAtUnitSinrM);
  const std::size_t lap_steps = room.lap.size();
  double t_s = room.lap.front().t_s;
  tracker.Initialize(t_s, room.lap.front().position_m);

  // Warm-up (not timed): walk until the prior VAs that were associated fill the state. The VAs
  // visible from the start enter at the first step; the rest (2nd order round the corners) only
  // when the loop reaches their visibility regions (40 after ~150 steps here, 42 later).
  std::size_t k = 0;
  int vas_in_state = 0;
  while (vas_in_state < kMinStateVas && k < kMaxWarmupLaps * lap_steps) {
    ++k;
    t_s += room.dt_s;
    vas_in_state = tracker.Step(t_s, room.ranges[k % lap_steps]).state_vas;
  }
  if (vas_in_state < kMinStateVas) {
    state.SkipWithError("fewer than 40 VAs in the SLAM state after the warm-up");
    return;
  }

  // Timed: one iteration = one Step() with the ranges of all anchors, further along the loop.
  // The state keeps evolving (VAs seen again are updated, new ones may still enter).
  for (auto _ : state) {
    ++k;
    t_s += room.dt_s;
    auto result = tracker.Step(t_s, room.ranges[k % lap_steps]);
    vas_in_state = result.state_vas;
    benchmark::DoNotOptimize(result);
  }
  state.counters["vas_in_state"] = vas_in_state;
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SlamStep40Vas)->ArgName("joseph")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mirage::bench
