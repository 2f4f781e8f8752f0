// SPDX-License-Identifier: MIT
// The ch. 8 example end to end: with the floor echoes the height is pinned (VDOP about 1, median
// height error of a centimetre), without them the TDOA rows lose it (VDOP several times larger),
// and a sending time estimated by the vote is absorbed by the height when no echo rows hold it.
// The height RMSE stays within 1.3 sigma c VDOP (Sec. 8.3) for every variant of the file's
// first three grid lines, the VDOP being that of the information used (for the vote's t_0 as a
// prior: the rows plus the vote's t_0 at its sigma), and the vote's sigma is checked against the
// simulated emission times.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "e2e/find_variant.h"
#include "e2e/extended_example.h"

#include "mirage/io/scenario.h"
#include "mirage/methods/acoustic/ground_echo_fix.h"
#include "mirage/pipeline/acoustic_source.h"
#include "mirage/pipeline/experiment.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

TEST(AcousticHeight, FloorEchoesPinTheHeight) {
  io::ScenarioOverrides overrides;
  overrides.runs = 2;
  overrides.threads = 0;
  const io::Scenario scenario = io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/acoustic_height.yaml", overrides);
  const auto result = RunExperiment(scenario.variants);
  const auto summaries = Summarize(scenario.variants, result);
  for (const auto& v : summaries) {
    SCOPED_TRACE(v.name);
    ASSERT_TRUE(v.overall.height_error.has_value());
    ASSERT_TRUE(v.overall.vdop.has_value());
  }
  const auto& estimated = summaries.front();  // echoes, t_0 from the vote
  const auto& known = testing::FindVariant(summaries, "method.ground_echo.echoes=true, method.ground_echo.sending_time=known");
  const auto& tdoa = testing::FindVariant(summaries, "method.ground_echo.echoes=true, method.ground_echo.sending_time=unknown");
  const auto& known_without = testing::FindVariant(summaries, "method.ground_echo.echoes=false, method.ground_echo.sending_time=known");
  const auto& tdoa_without = testing::FindVariant(summaries, "method.ground_echo.echoes=false, method.ground_echo.sending_time=unknown");
  const auto& estimated_without = testing::FindVariant(summaries, "method.ground_echo.echoes=false");
  // Sec. 8.5: VDOP with echoes at most ~1.2, the median height error about a centimetre.
  for (const auto* v : {&estimated, &known, &tdoa}) {
    SCOPED_TRACE(v->name);
    EXPECT_LE(v->overall.vdop->max, 1.3);
    EXPECT_LT(v->overall.height_error->p50, 0.03);
  }
  EXPECT_LT(tdoa.overall.height_error->p50, 0.03);
  // Sec. 8.3's bound, the criterion: with the floor echoes and the sending time known,
  // the height RMSE within 1.3 sigma c VDOP (RMS over the fixes), false alarms, misses and the
  // heavy tail included: the wrong picks among the echoes are caught by the geometry.
  const double sigma_range_m = 0.044e-3 * 331.3 * std::sqrt(1.0 + 20.0 / 273.15);  // the example's sigma, 20 C
  EXPECT_LE(known.overall.height_error->rmse, 1.3 * sigma_range_m * known.overall.vdop->rms);
  // The same bound with the sending time from the vote (a prior on a solved offset) or solved
  // (TDOA), and on the LOS rows alone with it known or solved: one wrong fix a metre off exceeds it (three nearly collinear microphones and a
  // false alarm fit a point on a circle around their line, below the floor or beside the sender,
  // as closely as four true stamps fit the sender; two microphones with their floor mirrors
  // leave a position and an offset undetermined).
  for (const auto* v : {&estimated, &tdoa, &known_without, &tdoa_without, &estimated_without}) {
    SCOPED_TRACE(v->name);
    EXPECT_LE(v->overall.height_error->rmse, 1.3 * sigma_range_m * v->overall.vdop->rms);
  }
  // Without echoes the vote's t_0 as a prior beats the solved offset alone (Table 8.2's order:
  // 0.141 m estimated, 0.289 m TDOA): its sigma is honest once an emission off the others' t_0
  // and rows beyond 3 sigma are left out of it and the scatter scales it (measured, 2 runs:
  // 0.057 against 0.064 m; 0.066 m, worse than TDOA, with the plain least-squares t_0, whose
  // error was 3.2 of its sigmas rms).
  EXPECT_LT(estimated_without.overall.height_error->rmse, 0.95 * tdoa_without.overall.height_error->rmse);
  // Without echoes: TDOA's VDOP several times larger, the estimated t_0 lands in the height.
  EXPECT_GT(tdoa_without.overall.vdop->p50, 4.0 * tdoa.overall.vdop->p50);
  EXPECT_GT(tdoa_without.overall.height_error->p50, 3.0 * tdoa.overall.height_error->p50);
  EXPECT_GT(estimated_without.overall.height_error->p50, 3.0 * estimated.overall.height_error->p50);
  EXPECT_GT(known_without.overall.height_error->p50, known.overall.height_error->p50);
  // Second-order echoes in the world: the floor-ceiling echo, paired with the LOS, looks like
  // the floor echo of a higher sender; modelled in the vote and the fix (floor_ceiling_echoes)
  // the voted t_0 holds as a known one does, within the same bound. Measured, 2 runs: height p95
  // 11.1 / 9.9 mm (voted / known), RMSE 5.6 / 5.0 mm (bound 7.0 / 6.6 mm); not modelled (the
  // ablation) p95 14.7 mm, RMSE 27 mm. Before a microphone whose floor echo the body shadowed
  // could be read from its floor-ceiling echo alone (sending_time_vote.h, alternatives), the
  // voted RMSE was 15 mm: such microphones, read as floor echoes, made a sender 0.4 m higher.
  // The bound on the voted t_0 holds at this file's seed; over 10 runs at seed 3 one fix 0.39 m
  // off (a ceiling echo first at blocked microphones) still exceeds it (ratio 1.72).
  const auto& second_estimated =
      testing::FindVariant(summaries, "measurements.max_order=2, method.ground_echo.sending_time=estimated");
  const auto& second_known = testing::FindVariant(summaries, "measurements.max_order=2, method.ground_echo.sending_time=known");
  const auto& second_unmodelled =
      testing::FindVariant(summaries, "measurements.max_order=2, method.ground_echo.floor_ceiling_echoes=false");
  EXPECT_LT(second_estimated.overall.height_error->p95, 1.5 * second_known.overall.height_error->p95);
  EXPECT_LT(second_estimated.overall.height_error->p95, 0.03);
  EXPECT_LT(second_estimated.overall.height_error->p95, second_unmodelled.overall.height_error->p95);
  EXPECT_LT(second_estimated.overall.height_error->rmse, 0.7 * second_unmodelled.overall.height_error->rmse);
  EXPECT_LE(second_known.overall.height_error->rmse, 1.3 * sigma_range_m * second_known.overall.vdop->rms);
  EXPECT_LE(second_estimated.overall.height_error->rmse, 1.3 * sigma_range_m * second_estimated.overall.vdop->rms);
}

// The vote's sigma against its error on the example's stamps (false alarms, misses, the heavy
// tail, the 20 ppm clock), without the floor echoes, where the vote's t_0 enters the height
// almost 1:1 and its sigma makes the DOP of the "estimated" variant: a sigma too large would
// loosen that bound, one too small understates the fix's covariance. The z-score's RMS over
// three runs (1290 emissions): measured 1.25, 2.6 % beyond 3 sigma (1.29 and 2.9 % before the
// vote's clusters tested each pair with its own tolerance; 1.15 and 1.4 % without the
// floor-ceiling model, whose chance rows join here); 1.71 and 7.5 % before the delay bound of a
// floor echo left out pairs of a false alarm and a later stamp (3.2 before the robust vote). The bounds fail with the sigma halved or inflated 1.5 times.
TEST(AcousticHeight, TheVotesSigmaDescribesTheErrorOfItsSendingTime) {
  io::ScenarioOverrides overrides;
  overrides.runs = 3;
  const io::Scenario scenario = io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/acoustic_height.yaml", overrides);
  const Experiment& experiment = scenario.variants.front().experiment;
  ASSERT_TRUE(experiment.acoustic.emission_time_known);  // the records carry the truth
  std::vector<Vec3> mics_m;
  for (const auto& anchor : experiment.anchors) mics_m.push_back(anchor.position_m);
  const double c_mps = experiment.medium.speed_mps;
  methods::acoustic::GroundEchoOptions options;
  options.sending_time = "estimated";
  options.echoes = false;
  double sum_z2 = 0.0;
  int votes = 0;
  int beyond_3_sigma = 0;
  int without_sigma = 0;
  for (int run = 0; run < experiment.runs; ++run) {
    methods::acoustic::GroundEchoFixer fixer(mics_m, experiment.plan.floor_z_m(), c_mps,
                                             experiment.acoustic.stamp_sigma_s * c_mps,
                                             experiment.trajectories.front().dt_s, experiment.acoustic.clock_drift_ppm,
                                             options, experiment.plan.ceiling_z_m());
    AcousticSource source(experiment, 0, run);
    while (const auto step = source.Next()) {
      const core::Epoch& epoch = step->epoch;
      if (epoch.toas.empty() || !epoch.toas.front().emission_s) continue;
      const auto fix = fixer.Process(epoch);
      if (!fix.voted_sending_time_s) continue;
      if (!(fix.voted_sending_time_sigma_s > 0.0)) {
        ++without_sigma;  // the vote's refinement gave no sigma
        continue;
      }
      const double z = (*fix.voted_sending_time_s - *epoch.toas.front().emission_s) / fix.voted_sending_time_sigma_s;
      sum_z2 += z * z;
      beyond_3_sigma += std::abs(z) > 3.0;
      ++votes;
    }
  }
  ASSERT_GT(votes, 1000);
  EXPECT_LT(without_sigma, 0.01 * votes);
  const double z_rms = std::sqrt(sum_z2 / votes);
  EXPECT_GT(z_rms, 0.8);
  EXPECT_LT(z_rms, 1.5);
  EXPECT_LT(beyond_3_sigma, 0.05 * votes);
}

// The TDOA variant with floor echoes over all ten runs of the example: once in them a cluster of
// LOS / wall-echo pairs at four microphones fits a sender 0.68 m higher (a solved offset absorbs
// the rest) as closely as the LOS / floor-echo pairs fit the sender; the stamps of the whole
// emission tell them apart (ties between fixes of as many microphones). And two microphones with
// their floor mirrors do not fix a position and an offset: the consensus starts from three.
TEST(AcousticHeight, TdoaWithFloorEchoesStaysWithinItsBoundInEveryRun) {
  const auto summaries = testing::RunExtendedExample(
      "acoustic_height.yaml",
      "method: {ground_echo: {echoes: true, sending_time: unknown}}\n"
      "grid:\n  - {measurements.false_alarm_rate: [0.5]}\n",
      10);
  ASSERT_EQ(summaries.size(), 1u);
  const auto& overall = summaries.front().overall;
  ASSERT_TRUE(overall.height_error.has_value());
  ASSERT_TRUE(overall.vdop.has_value());
  const double sigma_range_m = 0.044e-3 * 331.3 * std::sqrt(1.0 + 20.0 / 273.15);
  // Measured: RMSE 0.0070 m, bound 0.0082 m, VDOP max 0.76 (without the tie-break 0.0157 m; with
  // two-microphone sets 0.0121 m and VDOP max 4.46).
  EXPECT_LE(overall.height_error->rmse, 1.3 * sigma_range_m * overall.vdop->rms);
  EXPECT_LE(overall.vdop->max, 1.3);
}

// Seed 3 of the example: a walker on the room's symmetry line (y = 5.5 m, between two walls and
// two rows of microphones) sends LOS / wall-echo pairs at the four corner microphones that share
// one K like LOS / floor-echo pairs, and where the floor echo or the direct path of other
// microphones is missed they form the vote's cluster. Measured (10 runs): TDOA RMSE 0.0070 m
// against its bound 0.0082 m, the voted t_0 0.0070 m. Both changes are needed: with the centre
// pair's tolerance in the vote (the true cluster not found) TDOA 0.0119 m, 0.54 m at worst; with
// only the vote's clusters of as many microphones fitted and ranked by microphones rather than by
// all of the emission's stamps (the true cluster, one microphone short, never fitted) 0.0115 and
// 0.0115 m, 0.59 m at worst; with neither 0.0151 and 0.0141 m.
// Seed 2 is at 1.30 of its bound (one emission whose direct paths are blocked at four
// microphones: their (ceiling echo, floor echo) pairs win; docs/results/acoustic.md).
TEST(AcousticHeight, ASenderOnTheRoomsSymmetryLineIsNotReadFromItsWallEchoes) {
  const auto summaries = testing::RunExtendedExample(
      "acoustic_height.yaml",
      "seed: 3\n"
      "grid:\n  - {method.ground_echo.sending_time: [unknown, estimated]}\n",
      10);
  ASSERT_EQ(summaries.size(), 2u);
  const double sigma_range_m = 0.044e-3 * 331.3 * std::sqrt(1.0 + 20.0 / 273.15);
  for (const auto& summary : summaries) {
    SCOPED_TRACE(summary.name);
    const auto& overall = summary.overall;
    ASSERT_TRUE(overall.height_error.has_value());
    ASSERT_TRUE(overall.vdop.has_value());
    EXPECT_LE(overall.height_error->rmse, 1.3 * sigma_range_m * overall.vdop->rms);
    EXPECT_LT(overall.height_error->max, 0.1);
  }
}

}  // namespace
}  // namespace mirage::pipeline
