// SPDX-License-Identifier: MIT
// Scenario files with UWB TDOA measurements: `measurements: {model: uwb_tdoa, ...}` (the
// simulator's options and box obstacles, six blocking faces each) and `measurements: {model:
// recorded, anchors, tdoa}` (tdoa.csv), and the pairing of the tdoa_ekf method with them. Bad
// input is an InputError naming the file, the line (as ":<n>:") and the key: a box without
// volume, a 2-D box corner, a repeated box name, an unknown key in a box, a trajectory through a
// box, a sound medium; a method that does not consume differences given them and tdoa_ekf given
// anything else or fewer than 4 anchors; a recording of differences mixed with ranges or stamps.
// The tdoa_ekf's derived tdoa_sigma_m follows the measurements' noise.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "io/scenario_errors.h"

#include "mirage/io/input_error.h"
#include "mirage/io/scenario.h"
#include "mirage/methods/registry.h"
#include "mirage/methods/tdoa_ekf/tdoa_ekf.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using testing::ExpectError;
using testing::WithLines;
using pipeline::Experiment;
using pipeline::MeasurementModel;

// A valid UWB TDOA scenario after examples/uwb_tdoa_3d.yaml (no grid, one run); the line numbers
// in the comments are the ones the messages give.
const char* const kTdoa =
    "name: tdoa\n"                                                                                // 1
    "seed: 7\n"                                                                                   // 2
    "runs: 1\n"                                                                                   // 3
    "floor_plan:\n"                                                                               // 4
    "  ceiling_z_m: 3.0\n"                                                                        // 5
    "  walls:\n"                                                                                  // 6
    "    - {polyline_m: [[0.0, 0.0], [7.0, 0.0], [7.0, 7.0], [0.0, 7.0]], closed: true}\n"        // 7
    "anchors:\n"                                                                                  // 8
    "  - {id: A0, position_m: [0.3, 0.3, 0.2]}\n"                                                 // 9
    "  - {id: A1, position_m: [3.5, 0.2, 2.5]}\n"                                                 // 10
    "  - {id: A2, position_m: [6.7, 0.3, 0.2]}\n"                                                 // 11
    "  - {id: A3, position_m: [6.8, 3.5, 2.5]}\n"                                                 // 12
    "  - {id: A4, position_m: [6.7, 6.7, 0.2]}\n"                                                 // 13
    "  - {id: A5, position_m: [3.5, 6.8, 2.5]}\n"                                                 // 14
    "  - {id: A6, position_m: [0.3, 6.7, 0.2]}\n"                                                 // 15
    "  - {id: A7, position_m: [0.2, 3.5, 2.5]}\n"                                                 // 16
    "trajectories:\n"                                                                             // 17
    "  - name: laps\n"                                                                            // 18
    "    waypoints_m: [[1.5, 1.5], [5.5, 1.5], [5.5, 5.5], [1.5, 5.5]]\n"                         // 19
    "    speed_mps: 1.5\n"                                                                        // 20
    "    dt_s: 0.05\n"                                                                            // 21
    "    height_m: 1.2\n"                                                                         // 22
    "    height_amplitude_m: 0.6\n"                                                               // 23
    "    height_period_s: 7.0\n"                                                                  // 24
    "measurements:\n"                                                                             // 25
    "  model: uwb_tdoa\n"                                                                         // 26
    "  rate_hz: 100\n"                                                                            // 27
    "  sigma_m: 0.12\n"                                                                           // 28
    "  pair_selection: round_robin\n"                                                             // 29
    "  boxes:\n"                                                                                  // 30
    "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5, 1.5]}\n"                       // 31
    "method:\n"                                                                                   // 32
    "  name: tdoa_ekf\n";                                                                         // 33

const Experiment& ExperimentOf(const Scenario& s) { return s.variants.front().experiment; }

const methods::tdoa_ekf::TdoaEkfOptions& TdoaEkf(const Experiment& e) {
  if (e.method.name != "tdoa_ekf" || !e.method.options) {
    throw std::logic_error("the experiment's method is '" + e.method.name + "', not 'tdoa_ekf'");
  }
  return *static_cast<const methods::tdoa_ekf::TdoaEkfOptions*>(e.method.options.get());
}

class UwbTdoaScenario : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("mirage_uwb_tdoa_test_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Writes `text` to dir/name and returns the path.
  std::string Write(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  // Writes kTdoa with the given lines replaced and expects its error at `line` with the fragments.
  void ExpectBad(const std::string& name, const std::map<int, std::string>& lines, int line,
                 const std::vector<std::string>& fragments) const {
    const std::string path = Write(name, WithLines(kTdoa, lines));
    ExpectError(ErrorOf(path), path, line, fragments);
  }

  // A small recording of differences in the test's directory: anchors.csv (five anchors, with
  // z_m) and tdoa.csv (five rows, one per time stamp).
  void WriteRecording() const {
    Write("anchors.csv",
          "anchor_id,x_m,y_m,z_m\n"
          "A0,0,0,0.2\n"
          "A1,4,0,2.4\n"
          "A2,4,4,0.2\n"
          "A3,0,4,2.4\n"
          "A4,2,2,2.6\n");
    Write("tdoa.csv",
          "t_s,id_i,id_j,tdoa_m\n"
          "0,A0,A1,0.25\n"
          "0.01,A1,A2,-0.30\n"
          "0.02,A2,A3,0.10\n"
          "0.03,A3,A4,-0.40\n"
          "0.04,A4,A0,0.50\n");
  }

  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// The simulated model
// ---------------------------------------------------------------------------------------------

TEST_F(UwbTdoaScenario, LoadsTheSimulatedModelWithItsOptionsAndTheBoxFaces) {
  const Scenario s = LoadScenario(Write("tdoa.yaml", kTdoa));
  const Experiment& e = ExperimentOf(s);

  EXPECT_EQ(e.measurement_model, MeasurementModel::kUwbTdoa);
  EXPECT_EQ(e.method.name, "tdoa_ekf");
  EXPECT_EQ(e.method.input, methods::MethodInput::kTdoa);
  ASSERT_EQ(e.anchors.size(), 8u);
  EXPECT_EQ(e.anchors[1].position_m, Vec3(3.5, 0.2, 2.5));
  // The options read, the rest at their defaults.
  EXPECT_DOUBLE_EQ(e.uwb_tdoa.rate_hz, 100.0);
  EXPECT_DOUBLE_EQ(e.uwb_tdoa.sigma_m, 0.12);
  EXPECT_EQ(e.uwb_tdoa.pair_selection, channel::UwbPairSelection::kRoundRobin);
  const channel::UwbTdoaOptions defaults;
  EXPECT_DOUBLE_EQ(e.uwb_tdoa.nlos_bias_min_m, defaults.nlos_bias_min_m);
  EXPECT_DOUBLE_EQ(e.uwb_tdoa.outlier_probability, defaults.outlier_probability);
  // One box: its six faces, blocking, over [2.5, 4.5]^2 x [0, 1.5].
  ASSERT_EQ(e.reflectors.size(), 6u);
  const std::vector<std::string> names{"crate bottom", "crate top", "crate y-", "crate x+", "crate y+", "crate x-"};
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(e.reflectors[k].name, names[k]);
    EXPECT_TRUE(e.reflectors[k].blocks);
  }
  EXPECT_EQ(e.reflectors[0].origin_m, Vec3(3.5, 3.5, 0.0));
  EXPECT_EQ(e.reflectors[1].origin_m, Vec3(3.5, 3.5, 1.5));
  EXPECT_DOUBLE_EQ(e.reflectors[0].u_half_m, 1.0);
  EXPECT_DOUBLE_EQ(e.reflectors[0].v_half_m, 1.0);
  EXPECT_DOUBLE_EQ(e.reflectors[3].origin_m.x(), 4.5);
  EXPECT_DOUBLE_EQ(e.reflectors[5].origin_m.x(), 2.5);
}

TEST_F(UwbTdoaScenario, LoadsWithoutBoxesAndWithSeveralBoxes) {
  const Experiment none = ExperimentOf(LoadScenario(Write("none.yaml", WithLines(kTdoa, {{30, ""}, {31, ""}}))));
  EXPECT_TRUE(none.reflectors.empty());
  EXPECT_DOUBLE_EQ(none.uwb_tdoa.rate_hz, 100.0);

  const Experiment two = ExperimentOf(LoadScenario(
      Write("two.yaml", WithLines(kTdoa, {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5, 1.5]}\n"
                                               "    - {name: shelf, min_m: [6.0, 2.0, 0.0], max_m: [6.5, 5.0, 2.0]}"}}))));
  ASSERT_EQ(two.reflectors.size(), 12u);
  EXPECT_EQ(two.reflectors[6].name, "shelf bottom");
  EXPECT_EQ(two.reflectors[11].name, "shelf x-");
  EXPECT_EQ(two.reflectors[7].origin_m, Vec3(6.25, 3.5, 2.0));
}

TEST_F(UwbTdoaScenario, TheDerivedTdoaSigmaFollowsTheSimulatedNoise) {
  const Experiment e = ExperimentOf(LoadScenario(Write("tdoa.yaml", kTdoa)));
  const core::PhysicalKeys keys = pipeline::PhysicalKeysOf(e);
  ASSERT_TRUE(keys.range_sigma_m.has_value());
  EXPECT_DOUBLE_EQ(*keys.range_sigma_m, 0.12);
  EXPECT_DOUBLE_EQ(TdoaEkf(e).tdoa_sigma_m, 0.12);

  const Experiment other = ExperimentOf(LoadScenario(Write("other.yaml", WithLines(kTdoa, {{28, "  sigma_m: 0.3"}}))));
  EXPECT_DOUBLE_EQ(TdoaEkf(other).tdoa_sigma_m, 0.3);

  // A value stated in the method wins over the derived one.
  const Experiment stated =
      ExperimentOf(LoadScenario(Write("stated.yaml", WithLines(kTdoa, {{33, "  name: tdoa_ekf\n  tdoa_sigma_m: 0.2"}}))));
  EXPECT_DOUBLE_EQ(TdoaEkf(stated).tdoa_sigma_m, 0.2);
}

TEST_F(UwbTdoaScenario, RejectsABoxWithoutVolumeOrWithATwoDimensionalCorner) {
  ExpectBad("flat.yaml", {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5, 0.0]}"}}, 31,
            {"max_m", "must exceed min_m", "no volume"});
  ExpectBad("inverted.yaml", {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [2.0, 4.5, 1.5]}"}}, 31,
            {"max_m", "must exceed min_m"});
  ExpectBad("two_d_max.yaml", {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5]}"}}, 31,
            {"max_m", "[x, y, z]"});
  ExpectBad("two_d_min.yaml", {{31, "    - {name: crate, min_m: [2.5, 2.5], max_m: [4.5, 4.5, 1.5]}"}}, 31,
            {"min_m", "[x, y, z]"});
}

TEST_F(UwbTdoaScenario, RejectsDuplicateBoxNamesAndUnknownKeysInABox) {
  ExpectBad("duplicate.yaml",
            {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5, 1.5]}\n"
                  "    - {name: crate, min_m: [6.0, 2.0, 0.0], max_m: [6.5, 5.0, 2.0]}"}},
            32, {"name", "duplicate box name 'crate'"});
  ExpectBad("unknown.yaml", {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5, 1.5], colour: red}"}}, 31,
            {"colour"});
}

TEST_F(UwbTdoaScenario, RejectsATrajectoryThroughABox) {
  // Straight through the crate at a constant 1.2 m (the box is 1.5 m high).
  ExpectBad("through.yaml", {{19, "    waypoints_m: [[1.0, 3.5], [6.0, 3.5]]"}, {23, ""}, {24, ""}}, 29,
            {"boxes", "trajectory 'laps' passes through box 'crate'"});
  // The same line above the box (at 1.6 m) is fine.
  EXPECT_NO_THROW(LoadScenario(
      Write("above.yaml", WithLines(kTdoa, {{19, "    waypoints_m: [[1.0, 3.5], [6.0, 3.5]]"}, {22, "    height_m: 1.6"},
                                            {23, ""}, {24, ""}}))));
}

TEST_F(UwbTdoaScenario, RejectsABoxOutsideTheRoomAboveTheCeilingOrAroundAnAnchor) {
  ExpectBad("outside.yaml", {{31, "    - {name: crate, min_m: [5.0, 5.0, 0.0], max_m: [8.0, 8.0, 1.5]}"}}, 31,
            {"max_m", "box 'crate' corner", "outside the floor plan"});
  ExpectBad("ceiling.yaml", {{31, "    - {name: crate, min_m: [2.5, 2.5, 0.0], max_m: [4.5, 4.5, 3.5]}"}}, 31,
            {"max_m", "between the floor"});
  ExpectBad("anchor.yaml", {{31, "    - {name: crate, min_m: [0.1, 0.1, 0.0], max_m: [0.5, 0.5, 0.5]}"}}, 31,
            {"anchor 'A0' is inside box 'crate'"});
}

TEST_F(UwbTdoaScenario, RejectsATrajectoryThatCrossesABoxOnlyAtARunGridOffset) {
  // Along the crate's edge at y = 2.5 (the crate starts at 2.55): clear as written, through the
  // crate for the run shifted by the grid's corner +0.1 m.
  const std::map<int, std::string> along = {{19, "    waypoints_m: [[1.0, 2.5], [6.0, 2.5]]"},
                                            {23, ""},
                                            {24, ""},
                                            {31, "    - {name: crate, min_m: [2.5, 2.55, 0.0], max_m: [4.5, 4.5, 1.5]}"}};
  EXPECT_NO_THROW(LoadScenario(Write("along.yaml", WithLines(kTdoa, along))));
  auto shifted = along;
  shifted[3] = "runs: 1\nrun_grid: {nx: 1, ny: 2, spacing_m: 0.2}";
  ExpectBad("shifted.yaml", shifted, 30, {"passes through box 'crate'", "shifted by the run grid's corner [0, 0.1] m"});
}

TEST_F(UwbTdoaScenario, RejectsATagBelowTheFloorAndStepsShorterThanASlot) {
  ExpectBad("below.yaml", {{22, "    height_m: 0.5"}}, 26, {"trajectory 'laps' leaves the space between floor and ceiling"});
  ExpectBad("short.yaml", {{21, "    dt_s: 0.005"}}, 27, {"rate_hz", "give dt_s >= 1 / rate_hz"});
}

TEST_F(UwbTdoaScenario, RejectsASoundMedium) {
  ExpectBad("sound.yaml", {{3, "runs: 1\nmedium: {kind: sound}"}}, 27, {"model", "medium: {kind: radio}"});
}

TEST_F(UwbTdoaScenario, RejectsAMethodThatDoesNotConsumeDifferences) {
  ExpectBad("range_ekf.yaml", {{33, "  name: range_ekf"}}, 26,
            {"measurements", "pairwise differences", "'range_ekf' does not consume"});
}

TEST_F(UwbTdoaScenario, RejectsTdoaEkfWithoutDifferences) {
  // Height motion is simulated by uwb_tdoa and acoustic only: dropped with the model.
  ExpectBad("ranging.yaml", {{23, ""}, {24, ""}, {26, "  model: ranging"}, {27, ""}, {28, ""}, {29, ""}, {30, ""}, {31, ""}},
            24, {"measurements", "'tdoa_ekf' consumes pairwise differences"});
}

TEST_F(UwbTdoaScenario, RejectsTdoaEkfWithThreeAnchors) {
  const std::string path = Write("three.yaml", WithLines(kTdoa, {{12, ""}, {13, ""}, {14, ""}, {15, ""}, {16, ""}}));
  ExpectError(ErrorOf(path), path, 0, {"anchors", "at least 4 anchors"});
}

// ---------------------------------------------------------------------------------------------
// Recorded differences
// ---------------------------------------------------------------------------------------------

TEST_F(UwbTdoaScenario, LoadsARecordingOfDifferences) {
  WriteRecording();
  const std::string path =
      Write("rec.yaml",
            "name: rec\n"
            "method: {name: tdoa_ekf}\n"
            "measurements: {model: recorded, anchors: anchors.csv, tdoa: tdoa.csv, tdoa_sigma_m: 0.1}\n");

  const Experiment e = ExperimentOf(LoadScenario(path));

  EXPECT_EQ(e.measurement_model, MeasurementModel::kRecorded);
  ASSERT_NE(e.recording, nullptr);
  EXPECT_TRUE(e.recording->tdoa);
  EXPECT_FALSE(e.recording->toa_stamps);
  ASSERT_EQ(e.anchors.size(), 5u);
  EXPECT_EQ(e.anchors[4].position_m, Vec3(2.0, 2.0, 2.6));
  EXPECT_EQ(e.recording->steps.size(), 5u);
  const core::PhysicalKeys keys = pipeline::PhysicalKeysOf(e);
  ASSERT_TRUE(keys.range_sigma_m.has_value());
  EXPECT_DOUBLE_EQ(*keys.range_sigma_m, 0.1);
  EXPECT_DOUBLE_EQ(TdoaEkf(e).tdoa_sigma_m, 0.1);  // derived from it
}

TEST_F(UwbTdoaScenario, RejectsARecordingOfDifferencesMixedWithRangesStampsOrTheirKeys) {
  WriteRecording();
  const std::string head =
      "name: rec\n"                                            // 1
      "method: {name: tdoa_ekf}\n"                             // 2
      "measurements:\n"                                        // 3
      "  model: recorded\n"                                    // 4
      "  anchors: anchors.csv\n"                               // 5
      "  tdoa: tdoa.csv\n";                                    // 6
  const auto load = [&](const std::string& name, const std::string& keys) { return ErrorOf(Write(name, head + keys)); };
  ExpectError(load("ranges.yaml", "  ranges: ranges.csv\n"), "ranges.yaml", 7,
              {"measurements.ranges", "anchors and tdoa (pairwise differences)"});
  ExpectError(load("toa.yaml", "  toa: toa.csv\n"), "toa.yaml", 7, {"measurements.toa", "either anchors and tdoa"});
  ExpectError(load("mics.yaml", "  mics: mics.csv\n"), "mics.yaml", 7, {"measurements.mics", "either anchors and tdoa"});
  ExpectError(load("height.yaml", "  height_m: 1.2\n"), "height.yaml", 7,
              {"measurements.height_m", "not used with tdoa", "tdoa_sigma_m"});
  ExpectError(load("range_sigma.yaml", "  range_sigma_m: 0.1\n"), "range_sigma.yaml", 7,
              {"measurements.range_sigma_m", "not used with tdoa"});
  // And a range method given the differences.
  const std::string range_ekf = head + "  tdoa_sigma_m: 0.1\n";
  std::string text = range_ekf;
  text.replace(text.find("tdoa_ekf"), 8, "range_ekf");
  ExpectError(ErrorOf(Write("range_ekf.yaml", text)), "range_ekf.yaml", 0, {"pairwise differences", "'range_ekf'"});
}

TEST_F(UwbTdoaScenario, RejectsTdoaSigmaOnARecordingOfRanges) {
  Write("anchors.csv", "anchor_id,x_m,y_m\nA1,0,0\nA2,4,0\nA3,4,4\n");
  Write("ranges.csv", "t_s,anchor_id,range_m\n0,A1,1.0\n0,A2,2.0\n");
  const std::string path = Write("ranges.yaml",
                                 "name: rec\n"
                                 "method: {name: range_ekf}\n"
                                 "measurements:\n"
                                 "  model: recorded\n"
                                 "  anchors: anchors.csv\n"
                                 "  ranges: ranges.csv\n"
                                 "  tdoa_sigma_m: 0.1\n");
  ExpectError(ErrorOf(path), path, 7, {"measurements.tdoa_sigma_m", "only for"});
}

}  // namespace
}  // namespace mirage::io
