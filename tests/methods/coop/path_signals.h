// SPDX-License-Identifier: MIT
// Test fixture for the cooperative tracker's tests: the 4.4 m x 7 m room of Kulmer's examples and
// link signals that give the true path lengths of a link (plus seeded noise and clutter) instead of
// a CIR, so the tests isolate the filter from the channel simulator and the MPC extractor.
#pragma once

#include <memory>
#include <vector>

#include "mirage/core/rng.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/image_source.h"
#include "mirage/methods/coop/coop_tracker.h"

namespace mirage::methods::coop::testing {

/// 4.4 m x 7 m, walls counter-clockwise from (0, 0): 0 south, 1 east, 2 north, 3 west; the west
/// wall moved east by west_offset_m.
inline geometry::FloorPlan Room(double west_offset_m = 0.0) {
  using geometry::Wall;
  return geometry::FloorPlan({Wall{Vec2(0, 0), Vec2(4.4, 0), 0.5, "south"}, Wall{Vec2(4.4, 0), Vec2(4.4, 7), 0.5, "east"},
                              Wall{Vec2(4.4, 7), Vec2(0, 7), 0.5, "north"},
                              Wall{Vec2(west_offset_m, 7), Vec2(west_offset_m, 0), 0.5, "west"}},
                             {});
}

/// T_p = 0.5 ns (d_c = c T_p = 15 cm) and a CRLB scale of 6.3 cm.
inline constexpr PulseFacts kPulse{0.5e-9, 0.063, core::Medium{}};

/// The lengths of every path of a link that exists on `truth` (order <= 2, the line of sight of a
/// self link, i.e. the antenna coupling, included), each plus N(0, sigma_m^2), then `clutter`
/// ranges uniform in [0.5, 15) m; Ranges(count) gives the first `count` of them.
class ExactSignal final : public LinkSignal {
 public:
  ExactSignal(const geometry::FloorPlan& truth, const Link& link, const std::vector<Vec2>& agents,
              const AntennaLayout& antennas, double sigma_m, int clutter, core::Rng& rng,
              const Vec2& anchor_m = Vec2::Zero()) {
    const LinkEnds ends = AntennaPositions(link, agents, anchor_m, antennas);
    for (const auto& walls : geometry::VisibleImagePaths(truth, ends.tx_m, ends.rx_m, 2)) {
      ranges_.push_back(geometry::ComputeImagePath(truth, walls, ends.tx_m, ends.rx_m).length_m + rng.Normal(0.0, sigma_m));
    }
    for (int i = 0; i < clutter; ++i) ranges_.push_back(rng.Uniform(0.5, 15.0));
  }
  [[nodiscard]] std::vector<double> Ranges(int count) const override {
    std::vector<double> out = ranges_;
    if (static_cast<int>(out.size()) > count) out.resize(static_cast<std::size_t>(count));
    return out;
  }
  [[nodiscard]] double AmplitudeAt(double /*range_m*/) const override { return 1.0; }

 private:
  std::vector<double> ranges_;
};

/// One step of the tracker at t_s on exact signals of every link from the agents at agents_m on
/// the `truth` plan (the default antenna layout).
inline CoopStepInfo StepOnTruth(CoopTracker& tracker, double t_s, const geometry::FloorPlan& truth,
                                const std::vector<Vec2>& agents_m, double sigma_m, int clutter, core::Rng& rng,
                                const Vec2& anchor_m = Vec2::Zero()) {
  std::vector<std::unique_ptr<ExactSignal>> signals;
  std::vector<const LinkSignal*> pointers;
  for (const auto& link : tracker.links()) {
    signals.push_back(
        std::make_unique<ExactSignal>(truth, link, agents_m, AntennaLayout{}, sigma_m, clutter, rng, anchor_m));
    pointers.push_back(signals.back().get());
  }
  return tracker.Step(t_s, pointers);
}

}  // namespace mirage::methods::coop::testing
