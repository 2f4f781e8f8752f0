// SPDX-License-Identifier: MIT
// The runner on a joint method (cooperative tracking) on simulated link CIRs: results do not
// depend on the number of threads; the filter tracks on the simulated channel and its posterior
// bound lies below its error; the anchor's links lower the bound; a biased wall keeps its full
// error without the wall update and is corrected with it.
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "mirage/methods/coop/coop_tracker.h"
#include "mirage/methods/registry.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

Variant Coop(const std::string& name, methods::coop::CoopOptions options, double bias_m = 0.0) {
  using geometry::Wall;
  Experiment e;
  e.name = "small";
  e.runs = 3;
  e.steps = 60;
  e.plan = geometry::FloorPlan({Wall{Vec2(0, 0), Vec2(1.5, 0), 0.5, "south_a"}, Wall{Vec2(1.5, 0), Vec2(4.4, 0), 0.5, "south_b"},
                                Wall{Vec2(4.4, 0), Vec2(4.4, 7), 0.5, "east"}, Wall{Vec2(4.4, 7), Vec2(0, 7), 0.5, "north"},
                                Wall{Vec2(0, 7), Vec2(0, 0), 0.5, "west"}, Wall{Vec2(0.02, 3.0), Vec2(0.02, 4.0), 0.6, "pinboard"}},
                               {});
  e.in_plan = {true, true, true, true, true, false};
  e.plan_error.wall_shift_m = 0.001;
  e.plan_error.biased_wall = 1;
  e.plan_error.bias_m = bias_m;
  e.trajectories = {{"a", {Vec2(1.0, 1.0), Vec2(1.0, 3.0)}, 0.025, 1.0, 0.0, 0.0, 0.0, 4.0, {}}, {"b", {Vec2(3.4, 1.2), Vec2(3.4, 3.2)}, 0.02, 1.0, 0.0, 0.0, 0.0, 4.0, {}}};
  e.anchors = {{"A", Vec3(0.5, 6.0, 0.0)}};
  e.channel.window_length_s = 80e-9;
  e.channel.diffuse.power_ratio_db = -10.0;
  e.mpc.relative_threshold_db = -60.0;
  e.method = BindMethod(*methods::FindMethod("coop"), std::make_shared<methods::coop::CoopOptions>(options));
  return {name, {}, e};
}

TEST(RunExperimentJoint, ResultsDoNotDependOnTheNumberOfThreads) {
  std::vector<Variant> variants{Coop("plain", {})};
  variants[0].experiment.threads = 1;
  const auto one = RunExperiment(variants);
  variants[0].experiment.threads = 2;
  const auto two = RunExperiment(variants);
  ASSERT_EQ(one.runs.size(), two.runs.size());
  for (std::size_t r = 0; r < one.runs.size(); ++r) {
    for (std::size_t a = 0; a < one.runs[r].agents.size(); ++a) {
      const auto& sa = one.runs[r].agents[a].steps;
      const auto& sb = two.runs[r].agents[a].steps;
      ASSERT_EQ(sa.size(), sb.size());
      for (std::size_t k = 0; k < sa.size(); ++k) {
        EXPECT_EQ(sa[k].estimate_m, sb[k].estimate_m);
        EXPECT_EQ(sa[k].bound_m, sb[k].bound_m);
      }
    }
  }
}

TEST(RunExperimentJoint, TracksTwoAgentsOnSimulatedChannelsAndTheBoundLiesBelowTheError) {
  methods::coop::CoopOptions with_anchor;
  with_anchor.anchor_links = true;
  const std::vector<Variant> variants{Coop("plain", {}), Coop("anchor", with_anchor)};
  const auto result = RunExperiment(variants);
  const auto summary = Summarize(variants, result);
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_EQ(result.variants[0].bound, "posterior");
  for (const auto& s : summary) {
    const auto& g = s.overall;
    EXPECT_EQ(g.steps, 3 * 2 * 60) << s.name;  // runs x agents x epochs (the start is no epoch)
    EXPECT_EQ(g.diverged_runs, 0) << s.name;
    EXPECT_LT(g.error.p90, 0.05) << s.name;
    ASSERT_TRUE(g.bound_rms_m.has_value()) << s.name;
    EXPECT_GT(*g.bound_rms_m, 0.0) << s.name;
    EXPECT_LT(*g.bound_rms_m, g.error.rmse) << s.name << ": the filter beat its own bound";
    EXPECT_GT(g.associations_per_step, 3.0) << s.name;
    EXPECT_GE(g.expected_per_step, g.associations_per_step) << s.name;
    ASSERT_TRUE(g.walls.has_value()) << s.name;
  }
  // The anchor adds information: a lower bound.
  EXPECT_LT(*summary[1].overall.bound_rms_m, *summary[0].overall.bound_rms_m);
}

TEST(RunExperimentJoint, ABiasedWallKeepsItsErrorWithoutTheWallUpdateAndLosesItWithIt) {
  methods::coop::CoopOptions fixed, learning;
  fixed.wall_update = false;
  learning.wall_sigma_m = 0.01;
  std::vector<Variant> variants{Coop("fixed", fixed, 0.06), Coop("learning", learning, 0.06)};
  for (auto& v : variants) v.experiment.runs = 2;
  const auto result = RunExperiment(variants);
  for (const auto& run : result.runs) {
    ASSERT_TRUE(run.walls.has_value());
    ASSERT_FALSE(run.walls->biased_wall_error_m.empty());
    const double final_m = std::abs(run.walls->biased_wall_error_m.back());
    if (run.variant == 0) {
      EXPECT_NEAR(final_m, 0.06, 0.002);  // plus the 1 mm perturbation
    } else {
      EXPECT_LT(final_m, 0.06);
    }
  }
}

TEST(RunExperimentJoint, RejectsAnInconsistentExperiment) {
  std::vector<Variant> variants{Coop("x", {})};
  variants[0].experiment.agents = 3;  // two trajectories
  EXPECT_FALSE(Validate(variants[0].experiment).empty());
  EXPECT_THROW(RunExperiment(variants), std::invalid_argument);
  variants = {Coop("x", {})};
  variants[0].experiment.plan_error.biased_wall = 5;  // the pin board is not in the plan
  EXPECT_FALSE(Validate(variants[0].experiment).empty());
}

}  // namespace
}  // namespace mirage::pipeline
