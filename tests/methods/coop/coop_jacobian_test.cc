// SPDX-License-Identifier: MIT
// The H that the cooperative tracker stacks for its update (Kulmer et al. Eq. 13, 14, 17: each
// path's length differentiated by the transmitting agent, the receiving agent and the normal
// offset of every wall on the path; App. C: an agent's own channel by both ends at once) against
// central differences of the path length written out as plain geometry: the transmit antenna
// mirrored at the walls (moved by their offsets in the state), then its distance to the receive
// antenna. Three agents, all three kinds of link (self, relative, from a fixed anchor), first- and
// second-order paths, a state after some steps (velocities, cross-covariances and wall offsets
// not zero) and random states near it.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "estimation/jacobian_check.h"
#include "methods/coop/path_signals.h"
#include "methods/plane_mirror.h"

namespace mirage::methods::coop {
namespace {

namespace blocks = estimation::blocks;

const Vec2 kAnchorAt(0.6, 6.4);
const Vec2 kTxOffset(0.025, 0.0);  // AntennaLayout{}: 5 cm apart along x, TX east of the agent
const Vec2 kRxOffset(-0.025, 0.0);

std::vector<Vec2> Agents(const estimation::State& s) {
  std::vector<Vec2> out;
  for (int m = 0; m < 3; ++m) out.push_back(s.Mean(estimation::BlockKey(blocks::kPosition, m)));
  return out;
}

// The length of `walls` on `link` at state s, from the definition of the image path.
double PathLength(const estimation::State& s, const Link& link, const geometry::WallSequence& walls) {
  const std::vector<Vec2> agents_m = Agents(s);
  const Vec2 tx_m =
      link.kind == LinkKind::kAnchor ? kAnchorAt : agents_m[static_cast<std::size_t>(link.tx_agent)] + kTxOffset;
  const Vec2 rx_m = agents_m[static_cast<std::size_t>(link.rx_agent)] + kRxOffset;
  const geometry::FloorPlan provided = testing::Room();
  std::vector<methods::testing::MirrorLine> lines;
  for (const int w : walls) {
    const geometry::Wall& wall = provided.walls()[static_cast<std::size_t>(w)];
    const double offset_m = s.mean()(s.layout().At(estimation::BlockKey(blocks::kWallOffset, w)).mean_offset);
    lines.push_back({wall.start_m, wall.end_m, offset_m});
  }
  return (rx_m - methods::testing::ImageOf(tx_m, lines)).norm();
}

// The provided plan with each wall moved along its normal by its offset in s (CurrentPlan at s).
geometry::FloorPlan PlanAt(const estimation::State& s) {
  std::vector<geometry::Wall> walls = testing::Room().walls();
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const double offset_m =
        s.mean()(s.layout().At(estimation::BlockKey(blocks::kWallOffset, static_cast<int>(w))).mean_offset);
    const Vec2 shift_m = offset_m * geometry::WallNormal(walls[w]);
    walls[w].start_m += shift_m;
    walls[w].end_m += shift_m;
  }
  return geometry::FloorPlan(walls, {});
}

TEST(CoopTracker, AssembledJacobianMatchesCentralDifferences) {
  // Three agents walking for 8 steps in a room whose west wall is 3 cm east of the provided one:
  // the filter moves the wall offsets off zero.
  CoopOptions options;
  options.anchor_links = true;
  options.wall_sigma_m = 0.01;
  CoopTracker tracker(options, testing::Room(), EnumerateLinks(3, true), AntennaLayout{}, kAnchorAt, testing::kPulse);
  std::vector<Vec2> agents_m{Vec2(1.0, 1.5), Vec2(3.2, 2.5), Vec2(2.0, 5.3)};
  tracker.Initialize(agents_m, 0.0);
  core::Rng rng(21);
  for (int n = 1; n <= 8; ++n) {
    agents_m = {Vec2(1.0 + 0.02 * n, 1.5 + 0.01 * n), Vec2(3.2 - 0.01 * n, 2.5 + 0.02 * n), Vec2(2.0, 5.3 - 0.02 * n)};
    testing::StepOnTruth(tracker, n, testing::Room(0.03), agents_m, 0.005, 0, rng, kAnchorAt);
  }
  ASSERT_GT(std::abs(tracker.WallOffset(3)), 1e-3);

  const estimation::State& state = tracker.state();
  std::vector<estimation::MeasurementRow> rows;
  std::vector<std::pair<Link, geometry::WallSequence>> paths;
  // The rows of every link's expected paths, as Step builds them, at the tracker's state and at
  // three random states within ~10 cm (cm/s) of it: the paths that exist there on the walls moved
  // by the state's offsets. The tolerance is relative to the largest entry: direction cosines for
  // the agents (|.| <= 1) and 2 cos(angle of incidence) for a wall's offset (Eq. 17: |.| <= 2). With
  // h = 1e-6 the central difference's truncation error is h^2/6 |d^3 r/dx^3| <= h^2 / d^2 (1e-12
  // at d = 1 m; the antennas of a self link are 5 cm apart but its paths are >= 1 m long) and its
  // rounding error eps d / h (4e-9 at d = 20 m): 1e-7 x 2 leaves a margin of 50, while a wrong
  // sign, a wall column missing or a factor 2 lost is off by orders of magnitude more.
  constexpr double kStep = 1e-6;
  constexpr double kRelativeTolerance = 1e-7;
  constexpr double kLargestEntry = 2.0;
  const auto predict = [&](const estimation::State& s, std::size_t i) {
    return PathLength(s, paths[i].first, paths[i].second);
  };
  core::Rng perturb(5, 0);
  for (int trial = 0; trial < 4; ++trial) {
    const estimation::State s = trial == 0 ? state : estimation::testing::RandomNearby(state, 0.1, perturb);
    rows.clear();
    paths.clear();
    int second_order = 0;
    for (std::size_t l = 0; l < tracker.links().size(); ++l) {
      const Link& link = tracker.links()[l];
      for (const ExpectedPath& path : tracker.ExpectedPaths(static_cast<int>(l), Agents(s), PlanAt(s))) {
        rows.push_back(tracker.JacobianRow(link, path, 1e-4));
        paths.emplace_back(link, path.walls);
        if (path.walls.size() == 2) ++second_order;
      }
    }
    ASSERT_GE(rows.size(), 40u) << "state " << trial;
    ASSERT_GE(second_order, 10) << "state " << trial;
    estimation::testing::ExpectRowsMatchCentralDifferences(s, rows, predict, kStep, kRelativeTolerance * kLargestEntry,
                                                           "state " + std::to_string(trial));
  }
}

}  // namespace
}  // namespace mirage::methods::coop
