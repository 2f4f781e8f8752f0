// SPDX-License-Identifier: MIT
// The simulated measurements of one run: every anchor draws from its own random streams, so
// adding an anchor leaves the other anchors' measurements unchanged (run_simulator.h).
#include "mirage/pipeline/run_simulator.h"

#include <vector>

#include <gtest/gtest.h>

#include "pipeline/short_seminar_room.h"

namespace mirage::pipeline {
namespace {

using testing::ShortSeminarRoom;

// The measurements of the first `anchors` anchors at every step of run 0 of trajectory 0.
std::vector<std::vector<core::AnchorRanges>> Measure(const MintExperimentConfig& config) {
  const SimulationContext context(config);
  RunSimulator simulator(context, 0, 0);
  std::vector<std::vector<core::AnchorRanges>> out;
  for (std::size_t k = 0; k < simulator.samples().size(); ++k) {
    simulator.Simulate(k);
    out.emplace_back();
    simulator.Measure(out.back());
  }
  return out;
}

void ExpectAddingAnAnchorKeepsTheOthersMeasurements(MeasurementModel model) {
  // Arrange: the seminar room, and the same room with a third anchor in the middle.
  auto two = ShortSeminarRoom(1, 1.0);
  two.mint.measurement_model = model;
  auto three = two;
  three.mint.anchor_ids.push_back("A3");
  three.mint.anchors_m.emplace_back(3.0, 4.0);
  three.mint.known_anchors_m = three.mint.anchors_m;

  // Act
  const auto a = Measure(two.mint);
  const auto b = Measure(three.mint);

  // Assert: anchors 0 and 1 see bit-identical ranges and amplitudes at every step.
  ASSERT_EQ(a.size(), b.size());
  std::size_t compared = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(b[k].size(), 3u);
    for (std::size_t anchor = 0; anchor < 2; ++anchor) {
      const auto& ra = a[k][anchor].ranges;
      const auto& rb = b[k][anchor].ranges;
      ASSERT_EQ(ra.size(), rb.size()) << "step " << k << " anchor " << anchor;
      for (std::size_t i = 0; i < ra.size(); ++i) {
        EXPECT_EQ(ra[i].range_m, rb[i].range_m) << "step " << k << " anchor " << anchor;
        EXPECT_EQ(ra[i].amplitude, rb[i].amplitude) << "step " << k << " anchor " << anchor;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100u);
}

TEST(RunSimulator, RangeLevelNoiseOfOneAnchorDoesNotDependOnTheOtherAnchors) {
  ExpectAddingAnAnchorKeepsTheOthersMeasurements(MeasurementModel::kRangeLevel);
}

TEST(RunSimulator, CirNoiseOfOneAnchorDoesNotDependOnTheOtherAnchors) {
  ExpectAddingAnAnchorKeepsTheOthersMeasurements(MeasurementModel::kCir);
}

}  // namespace
}  // namespace mirage::pipeline
