// SPDX-License-Identifier: MIT
// End-to-end regression of examples/acoustic_holdout.yaml with its default method (the REKF with
// echoes to order 2) started without the truth: by itself from the first emissions
// (`self_start`), and from a start drawn with the method's 0.5 m sigma
// (`perturb_initial_position`). Both start from the fixes over all stamps of two emissions that
// follow each other (multipath_fix.h, the estimator's StartFromStamps); a
// filter that paired the dense echoes at a start 0.5 m off lost 6 of 20 runs here. 10 runs each
// with the file's seed.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "e2e/extended_example.h"

#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

TEST(AcousticHoldout, StartsItselfAndFromAWidePriorWithoutLosingARun) {
  io::ScenarioOverrides overrides;
  overrides.runs = 10;
  overrides.threads = 0;
  const io::Scenario scenario =
      io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/acoustic_holdout.yaml", overrides);
  ASSERT_FALSE(scenario.variants.empty());
  std::vector<Variant> variants(2, scenario.variants.front());  // the file's method: the default REKF
  variants[0].name = "self start";
  variants[0].experiment.self_start = true;
  variants[1].name = "perturbed start";
  variants[1].experiment.perturb_initial_position = true;
  const auto summaries = Summarize(variants, RunExperiment(variants));
  ASSERT_EQ(summaries.size(), 2u);
  for (const auto& v : summaries) {
    SCOPED_TRACE(v.name);
    EXPECT_EQ(v.overall.diverged_runs, 0);
    EXPECT_LT(v.overall.error.p50, 0.03);  // measured 0.014 m over 20 runs
    EXPECT_LT(v.overall.error.p90, 0.05);  // 0.028-0.030 m
  }
  // The self-started runs begin within the first emissions (71 per run; the start needs two
  // whose fixes follow each other) and no run strays on the way. (The perturbed runs report their
  // start, up to 1.5 m off, until the second emission confirms the first fix.)
  EXPECT_GE(summaries[0].overall.steps, 10 * 65);
  EXPECT_LT(summaries[0].overall.error.max, 0.5);
}

// The room returns echoes of every order; the filter predicts them to order 2. With the room
// simulated to order 3 (about 60 paths per microphone instead of 25) single-emission fixes are
// often wrong and the start waits for one that the next emission confirms, while the walker walks
// on at 1.5 m/s; and a started track can pair the unmodelled echoes and run away with them. Two
// safeguards, each measured with the other's effect visible:
//  - the search around the waiting prior widens with the velocity prior over the time waited (the
//    motion model, AcousticEstimator::SearchRegion): without the track-loss restart, 5 of 20 runs
//    lost with it, 12 of 20 without (the prior's box frozen at the first emission);
//  - a track that leaves the room starts again from the stamps over the whole plan
//    (`restart_lost_track`): 2 of 20 lost with it, 5 without.
// Not solved: see docs/results/acoustic.md, "Echoes beyond the predicted order".
TEST(AcousticHoldout, WithUnmodelledEchoesTheStartFollowsTheWalkerAndALostTrackStartsAgain) {
  const auto summaries = testing::RunExtendedExample(
      "acoustic_holdout.yaml",
      "measurements: {max_order: 3}\nmethod: {restart_lost_track: true}\n"
      "grid:\n  - {method.restart_lost_track: [false, true]}\n",
      20);
  ASSERT_EQ(summaries.size(), 2u);
  EXPECT_LE(summaries[0].overall.diverged_runs, 8);  // without the restart: the moving box alone
  EXPECT_LE(summaries[1].overall.diverged_runs, 3);  // with it
}

}  // namespace
}  // namespace mirage::pipeline
