// SPDX-License-Identifier: MIT
// NEES consistency of SLAM with the floor plan's VAs known (the known-VA baseline: the VAs in the
// state with their prior covariance, Leitinger Eq. 14, 16; Lafer Eq. 4.1-4.5) on data drawn from
// the filter's own model: the agent's prior and constant-velocity motion (Leitinger Eq. 13), each
// VA's true position drawn from its prior N(VA of the plan, prior_va_sigma^2 I), and Gaussian
// ranges of the stated variance to the anchors and the VAs visible at the truth, each detected
// with probability 1/2 (independent misses leave the model intact and give the motion model a
// say). The NEES of the whole state (the agent's position and velocity and every VA in the state)
// averaged over steps and runs is then its dimension, within the chi-square interval of
// methods/own_model.h; a wrong H, R or Q moves it out.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "methods/mint/square_room.h"
#include "methods/own_model.h"
#include "mirage/geometry/visibility.h"
#include "mirage/methods/slam/slam_tracker.h"
#include "rng_vectors.h"

namespace mirage::methods::slam {
namespace {

using methods::testing::CvModel;
using methods::testing::StateNees;
namespace blocks = estimation::blocks;

// The truth: a walker around (2.2, 2.2) at 1 m/s^2 (a person's typical acceleration), 0.1 s
// steps, 2 cm ranges, VAs known to 3 cm.
constexpr CvModel kWalker{0.03, 0.1, 1.0, 0.1};
constexpr double kRangeSigmaM = 0.02;
constexpr double kVaSigmaM = 0.03;
constexpr double kDetectionProbability = 0.5;

// The filter's model: the options a scenario with known first-order VAs would give, with the
// mirage additions that are not part of the model switched off (the variance estimation and the
// innovation scaling replace R, the recovery restarts, discovery adds VAs; without amplitudes the
// amplitude gates and the LOS re-acquisition have nothing to test).
SlamOptions ModelOptions() {
  SlamOptions options;
  options.prior_max_order = 1;
  options.prior_va_sigma_m = kVaSigmaM;
  options.discovery.enabled = false;
  options.variance.enabled = false;
  options.range_sigma_m = kRangeSigmaM;
  options.nis_window_updates = 0;
  options.recovery.enabled = false;
  options.initial_position_sigma_m = kWalker.position_sigma_m;
  options.initial_velocity_sigma_mps = kWalker.velocity_sigma_mps;
  options.motion.accel_sigma_mps2 = kWalker.accel_sigma_mps2;
  return options;
}

// The NEES of `runs` runs of `steps` steps of the filter with options `filter` on data drawn from
// the model above.
StateNees RunNees(const SlamOptions& filter, int runs, int steps) {
  const auto plan = mint::testing::EmptySquareRoom();
  const auto vas = mint::testing::SquareRoomVas(plan, 1);
  // Both anchors' LOS ranges agree with a position and its mirror at the line through the anchors
  // (x + y = 6): the walker keeps 0.5 m from it, and 0.5 m from the walls.
  const Vec2 start_m(2.2, 2.2);
  const auto inside = [](const Vec2& p) { return p.x() > 0.5 && p.y() > 0.5 && p.x() + p.y() < 5.3; };
  core::Rng rng(31, 0);
  StateNees nees;
  for (int run = 0; run < runs; ++run) {
    std::vector<Vec2> va_m;  // the truth: each VA drawn from its prior, the anchors exact
    for (const auto& va : vas.all()) {
      const double sigma_m = va.order == 0 ? 0.0 : kVaSigmaM;
      va_m.push_back(va.position_m + Vec2(sigma_m * mirage::testing::NormalVec2(rng)));
    }
    const auto truth = methods::testing::DrawCvTrajectory(kWalker, start_m, steps, rng, inside);
    SlamTracker tracker(filter, vas, plan, 0.01);
    tracker.Initialize(0.0, start_m);
    for (int k = 1; k <= steps; ++k) {
      const Vec2& p_m = truth.position_m[static_cast<std::size_t>(k)];
      std::vector<core::RangeSet> ranges;
      for (int a = 0; a < vas.anchor_count(); ++a) {
        core::RangeSet anchor;
        anchor.anchor_index = a;
        for (const int id : geometry::VisibleVirtualAnchors(vas, a, plan, p_m, 1)) {
          const double range_m = (va_m[static_cast<std::size_t>(id)] - p_m).norm() + kRangeSigmaM * rng.Normal();
          if (rng.Uniform() < kDetectionProbability) anchor.ranges.push_back({range_m, std::nullopt});
        }
        ranges.push_back(std::move(anchor));
      }
      tracker.Step(k * kWalker.dt_s, ranges);
      // The truth in the state's layout: the agent's position and velocity, each VA's drawn
      // position (all Euclidean: mean and tangent coordinates coincide).
      const estimation::State& state = tracker.state();
      EXPECT_TRUE(state.layout().euclidean());
      Eigen::VectorXd truth_x(state.dimension());
      for (const estimation::Block& block : state.layout().blocks()) {
        Vec2 truth_block = Vec2::Zero();
        if (block.key.type_id == blocks::kPosition.id) {
          truth_block = p_m;
        } else if (block.key.type_id == blocks::kVelocity.id) {
          truth_block = truth.velocity_mps[static_cast<std::size_t>(k)];
        } else if (block.key.type_id == blocks::kVirtualAnchor.id) {
          truth_block = va_m[static_cast<std::size_t>(block.key.id)];
        } else {
          ADD_FAILURE() << "a block the model has no truth for";
        }
        truth_x.segment<2>(block.mean_offset) = truth_block;
      }
      nees.Add(state.mean() - truth_x, state.covariance());
    }
    nees.EndRun();
  }
  return nees;
}

TEST(SlamTracker, KnownVaNeesIsConsistentOnDataOfItsOwnModel) {
  // 1000 runs of 20 steps, the state 4-D at the start and 20-D once each of the 8 first-order VAs
  // has had a range (19.2-D on average): the interval is 1 -2.6 % / +2.7 %, the ratio 1.008
  // (0.992-1.022 over 40 other seeds). With R scaled by sqrt(2) or 0.7 in the filter the ratio is
  // 0.88 or 1.21.
  EXPECT_TRUE(methods::testing::InChi2Interval99(RunNees(ModelOptions(), 1000, 20), "SLAM, known VAs"));
}

}  // namespace
}  // namespace mirage::methods::slam
