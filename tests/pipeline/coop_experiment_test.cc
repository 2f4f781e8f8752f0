// SPDX-License-Identifier: MIT
// The cooperative Monte-Carlo driver on simulated CIRs: results do not depend on the number of
// threads; the filter tracks on the simulated channel; a biased wall without the wall update
// keeps its full error and is corrected with it; the bound is finite and below the error.
#include "mirage/pipeline/coop_experiment.h"

#include <cmath>

#include <gtest/gtest.h>

#include "mirage/pipeline/coop_summary.h"

namespace mirage::pipeline {
namespace {

CoopExperimentConfig SmallConfig() {
  CoopExperimentConfig c;
  c.name = "small";
  c.runs = 3;
  c.steps = 60;
  using geometry::Wall;
  c.true_plan = geometry::FloorPlan({Wall{Vec2(0, 0), Vec2(1.5, 0), 0.5, "south_a"}, Wall{Vec2(1.5, 0), Vec2(4.4, 0), 0.5, "south_b"},
                                     Wall{Vec2(4.4, 0), Vec2(4.4, 7), 0.5, "east"}, Wall{Vec2(4.4, 7), Vec2(0, 7), 0.5, "north"},
                                     Wall{Vec2(0, 7), Vec2(0, 0), 0.5, "west"},
                                     Wall{Vec2(0.02, 3.0), Vec2(0.02, 4.0), 0.6, "pinboard"}},
                                    {});
  c.in_plan = {true, true, true, true, true, false};
  c.agents = {{"a", {Vec2(1.0, 1.0), Vec2(1.0, 3.0)}, 0.025}, {"b", {Vec2(3.4, 1.2), Vec2(3.4, 3.2)}, 0.02}};
  c.anchor = CoopAnchor{"A", Vec2(0.5, 6.0)};
  c.wall_bias = {1, 0.06};
  c.channel.window_length_s = 80e-9;
  c.channel.diffuse.power_ratio_db = -10.0;
  c.mpc.relative_threshold_db = -60.0;
  CoopVariant v;
  c.variants.push_back(v);
  v.anchor = true;
  c.variants.push_back(v);
  return c;
}

TEST(CoopExperiment, ResultsDoNotDependOnTheNumberOfThreads) {
  auto config = SmallConfig();
  config.threads = 1;
  const auto one = RunCoopExperiment(config);
  config.threads = 2;
  const auto two = RunCoopExperiment(config);
  ASSERT_EQ(one.variants.size(), two.variants.size());
  for (std::size_t v = 0; v < one.variants.size(); ++v) {
    for (std::size_t r = 0; r < one.variants[v].runs.size(); ++r) {
      EXPECT_EQ(one.variants[v].runs[r].error_m, two.variants[v].runs[r].error_m);
    }
    EXPECT_EQ(one.variants[v].peb_m, two.variants[v].peb_m);
  }
}

TEST(CoopExperiment, TracksTwoAgentsOnSimulatedChannelsAndBoundsTheError) {
  const auto result = RunCoopExperiment(SmallConfig());
  const auto summary = SummarizeCoop(result);
  ASSERT_EQ(summary.size(), 2u);
  for (const auto& s : summary) {
    EXPECT_EQ(s.diverged, 0) << s.name;
    EXPECT_LT(s.error_p90_m, 0.05) << s.name;
    EXPECT_GT(s.peb_rms_m, 0.0) << s.name;
    EXPECT_LT(s.peb_rms_m, s.error_rmse_m) << s.name << ": the filter beat its own bound";
    EXPECT_GT(s.associated_per_step, 3.0) << s.name;
  }
  // The anchor adds information: a lower bound.
  EXPECT_LT(summary[1].peb_rms_m, summary[0].peb_rms_m);
}

TEST(CoopExperiment, ABiasedWallKeepsItsErrorWithoutTheWallUpdate) {
  auto config = SmallConfig();
  config.runs = 2;
  CoopVariant v;
  v.biased_wall = true;
  v.wall_update = false;
  config.variants = {v};
  v.wall_update = true;
  v.wall_sigma_m = 0.01;
  config.variants.push_back(v);
  const auto result = RunCoopExperiment(config);
  for (const auto& run : result.variants[0].runs) {
    ASSERT_FALSE(run.bias_wall_error_m.empty());
    EXPECT_NEAR(std::abs(run.bias_wall_error_m.back()), 0.06, 0.002);  // plus the 1 mm perturbation
  }
  for (const auto& run : result.variants[1].runs) {
    EXPECT_LT(std::abs(run.bias_wall_error_m.back()), 0.06);
  }
}

TEST(CoopExperiment, RejectsAnInconsistentConfiguration) {
  auto config = SmallConfig();
  config.variants.front().agents = 3;
  EXPECT_FALSE(Validate(config).empty());
  EXPECT_THROW(RunCoopExperiment(config), std::invalid_argument);
  config = SmallConfig();
  config.wall_bias.wall = 5;  // the pin board is not in the plan
  EXPECT_FALSE(Validate(config).empty());
}

}  // namespace
}  // namespace mirage::pipeline
