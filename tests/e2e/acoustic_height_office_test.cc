// SPDX-License-Identifier: MIT
// End-to-end regression of examples/acoustic_height_office.yaml, the hold-out of the acoustic
// height methods: an office whose rooms return echoes to order 2, the body and partitions
// blocking direct paths, the phone swinging at 1.1-1.5 m, two stops. The 3-D REKF that predicts
// the echoes to order 2 (the default) keeps the height within centimetres; predicting first-order
// echoes only, it pairs the floor-ceiling double echoes with first-order paths and holds a height
// 0.2-0.3 m off (the reason for the default). 4 runs per variant with the file's seed; the ch. 8
// snapshot variants are not run here (their failure is documented in docs/results/acoustic.md).
// The order-2 REKF also runs started by itself (`self_start`, the fix over all stamps of
// multipath_fix.h searched over the whole office's volume).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "e2e/find_variant.h"
#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

TEST(AcousticHeightOffice, SecondOrderEchoesPredictedKeepTheHeightFirstOrderOnlyBiasesIt) {
  io::ScenarioOverrides overrides;
  overrides.runs = 4;
  overrides.threads = 0;
  const io::Scenario scenario =
      io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/acoustic_height_office.yaml", overrides);
  std::vector<Variant> filters;
  for (const auto& v : scenario.variants) {
    if (v.name.find("estimator=rekf") != std::string::npos) filters.push_back(v);
  }
  ASSERT_EQ(filters.size(), 2u);
  filters.push_back(filters.front());  // the order-2 REKF started by itself from the first emissions
  filters.back().name = "self start";
  filters.back().experiment.self_start = true;
  const auto summaries = Summarize(filters, RunExperiment(filters));

  const auto& order2 = testing::FindVariant(summaries, "method.estimator=rekf").overall;
  ASSERT_TRUE(order2.height_error.has_value());
  EXPECT_LT(order2.height_error->p50, 0.03);   // measured 0.013 m over 20 runs
  EXPECT_LT(order2.height_error->rmse, 0.05);  // 0.025 m
  EXPECT_EQ(order2.diverged_runs, 0);

  // Started without the truth: the fix over all stamps in the whole office's volume.
  const auto& self_start = testing::FindVariant(summaries, "self start").overall;
  ASSERT_TRUE(self_start.height_error.has_value());
  EXPECT_LT(self_start.height_error->p50, 0.03);
  EXPECT_EQ(self_start.diverged_runs, 0);

  const auto& order1 = testing::FindVariant(summaries, "method.estimator=rekf, method.echo_order=1").overall;
  ASSERT_TRUE(order1.height_error.has_value());
  EXPECT_GT(order1.height_error->p50, 0.1);  // measured 0.25 m over 20 runs
}

}  // namespace
}  // namespace mirage::pipeline
