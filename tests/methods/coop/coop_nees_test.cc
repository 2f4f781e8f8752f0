// SPDX-License-Identifier: MIT
// NEES consistency of the cooperative tracker (Kulmer et al. Algorithm 1, anchorless) on data
// drawn from its own model: each agent's prior N(start, sigma_agent^2 I) with a velocity drawn
// from N(0, velocity_sigma^2 I), its constant-velocity motion with sigma_a = v_max / (3 dt)
// (Sec. IV-B), each wall's true normal offset drawn from its prior N(0, sigma_seg^2), and Gaussian
// path lengths of the stated variance on every self and relative link. The NEES of the whole
// state (three agents' positions and velocities, four wall offsets: 16-D) averaged over steps and
// runs is then 16, within the chi-square interval of methods/own_model.h; a wrong H, R or Q moves
// it out.
#include <vector>

#include <gtest/gtest.h>

#include "methods/coop/path_signals.h"
#include "methods/own_model.h"

namespace mirage::methods::coop {
namespace {

using methods::testing::StateNees;
namespace blocks = estimation::blocks;

constexpr double kDtS = 1.0;
constexpr double kRangeSigmaM = 0.01;

// The filter's options and the truth's model: Kulmer's defaults (sigma_seg 3 mm, v_max 2.5 cm per
// 1 s step, d_c = c T_p, the 3-sigma innovation gate), a start velocity std of 1 cm/s, the range
// variance fixed at (1 cm)^2 instead of estimated from amplitudes, and the start known to 1 cm
// instead of 3 cm. Why: a self path moves by twice the agent's move towards its wall, so at 3 cm
// a start drawn 2-3 sigma off shifts the self ranges by 12-18 cm, and the cut-off assignment
// (Sec. III-B3) then pairs an expected path with its neighbour's range in about one run in 30
// (NEES 50-400 at the first step, one track lost for good): a test of the association, not of
// the filter's covariance.
CoopOptions ModelOptions() {
  CoopOptions options;
  options.agent_sigma_m = 0.01;
  options.velocity_sigma_mps = 0.01;
  options.variance.enabled = false;
  options.variance.default_sigma_m = kRangeSigmaM;
  return options;
}

// The provided plan with each wall moved along its normal by offsets_m.
geometry::FloorPlan Moved(const std::vector<double>& offsets_m) {
  std::vector<geometry::Wall> walls = testing::Room().walls();
  for (std::size_t s = 0; s < walls.size(); ++s) {
    const Vec2 shift_m = offsets_m[s] * geometry::WallNormal(walls[s]);
    walls[s].start_m += shift_m;
    walls[s].end_m += shift_m;
  }
  return geometry::FloorPlan(walls, {});
}

// The NEES over `runs` runs of `steps` steps of three agents, of the filter with options `filter`
// on data drawn from ModelOptions().
StateNees RunNees(const CoopOptions& filter, int runs, int steps) {
  const CoopOptions model = ModelOptions();
  const methods::testing::CvModel walker{model.agent_sigma_m, model.velocity_sigma_mps,
                                         CoopMotion(model, kDtS).accel_sigma_mps2, kDtS};
  const std::vector<Vec2> starts_m{Vec2(1.2, 1.5), Vec2(3.1, 3.2), Vec2(1.6, 5.4)};
  const auto inside = [](const Vec2& p) { return p.x() > 0.5 && p.x() < 3.9 && p.y() > 0.5 && p.y() < 6.5; };
  core::Rng rng(41);
  StateNees nees;
  for (int run = 0; run < runs; ++run) {
    std::vector<double> offsets_m;
    for (int s = 0; s < 4; ++s) offsets_m.push_back(model.wall_sigma_m * rng.Normal());
    const geometry::FloorPlan truth = Moved(offsets_m);
    std::vector<methods::testing::CvTrack> tracks;
    for (const Vec2& start_m : starts_m) tracks.push_back(methods::testing::DrawCvTrajectory(walker, start_m, steps, rng, inside));
    CoopTracker tracker(filter, testing::Room(), EnumerateLinks(3, false), AntennaLayout{}, std::nullopt,
                        testing::kPulse);
    tracker.Initialize(starts_m, 0.0);
    for (int n = 1; n <= steps; ++n) {
      const auto at = static_cast<std::size_t>(n);
      std::vector<Vec2> agents_m;
      for (const auto& track : tracks) agents_m.push_back(track.position_m[at]);
      testing::StepOnTruth(tracker, n * kDtS, truth, agents_m, kRangeSigmaM, 0, rng);
      // The truth in the state's layout (all Euclidean: mean and tangent coordinates coincide).
      const estimation::State& state = tracker.state();
      EXPECT_TRUE(state.layout().euclidean());
      Eigen::VectorXd truth_x(state.dimension());
      for (const estimation::Block& block : state.layout().blocks()) {
        const auto owner = static_cast<std::size_t>(block.key.id);
        if (block.key.type_id == blocks::kPosition.id) {
          truth_x.segment<2>(block.mean_offset) = tracks[owner].position_m[at];
        } else if (block.key.type_id == blocks::kVelocity.id) {
          truth_x.segment<2>(block.mean_offset) = tracks[owner].velocity_mps[at];
        } else if (block.key.type_id == blocks::kWallOffset.id) {
          truth_x(block.mean_offset) = offsets_m[owner];
        } else {
          ADD_FAILURE() << "a block the model has no truth for";
        }
      }
      nees.Add(state.mean() - truth_x, state.covariance());
    }
    nees.EndRun();
  }
  return nees;
}

TEST(CoopTracker, NeesIsConsistentOnDataOfItsOwnModel) {
  // 600 runs x 10 steps of the 16-D state (the steps of a run share their walls and start, so many
  // short runs beat few long ones): the interval is 1 -3.7 % / +3.8 %, the ratio 1.010 (0.991-1.027
  // over 40 other seeds). With R scaled by sqrt(2) or 0.7 in the filter the ratio is 0.84 or 1.27.
  const StateNees nees = RunNees(ModelOptions(), 600, 10);
  EXPECT_NEAR(nees.mean_dimension(), 16.0, 1e-12);
  EXPECT_TRUE(methods::testing::InChi2Interval99(nees, "coop"));
}

}  // namespace
}  // namespace mirage::methods::coop
