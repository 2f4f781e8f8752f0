// SPDX-License-Identifier: MIT
// Cooperative scenario files (method: coop): a small file loads with the values it states (units
// converted, the variant grids multiplied out in order without duplicates, in_plan flags, the
// biased wall's index), and every kind of bad input throws an InputError whose message names the
// file, the line (as ":<n>:") and the key path (docs/scenario.md, "Cooperative scenarios").
#include "mirage/io/coop_scenario.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"
#include "mirage/io/scenario.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;

using pipeline::CoopVariant;

// A small valid cooperative scenario; the line numbers in the comments are the ones the error
// messages give. Walls: 0 west, 1 south, 2 east (one polyline, labelled concrete), 3 north,
// 4 a pin board the filter does not know.
const char* const kCoop =
    "name: coop_room\n"                                                                      // 1
    "method: coop\n"                                                                         // 2
    "seed: 7\n"                                                                              // 3
    "runs: 5\n"                                                                              // 4
    "steps: 50\n"                                                                            // 5
    "materials:\n"                                                                           // 6
    "  concrete: 0.6\n"                                                                      // 7
    "floor_plan:\n"                                                                          // 8
    "  walls:\n"                                                                             // 9
    "    - {polyline_m: [[0, 4], [0, 0], [6, 0], [6, 4]], material: concrete}\n"             // 10
    "    - {start_m: [6, 4], end_m: [0, 4], label: north}\n"                                 // 11
    "    - {start_m: [5, 1], end_m: [5, 2], label: pinboard, in_plan: false}\n"              // 12
    "  obstacles:\n"                                                                         // 13
    "    - {center_m: [1.5, 3.0], radius_m: 0.2}\n"                                          // 14
    "agents:\n"                                                                              // 15
    "  - {name: a1, waypoints_m: [[1, 1], [2, 1]], speed_m_per_step: 0.02}\n"                // 16
    "  - {name: a2, waypoints_m: [[4, 2], [4, 1]]}\n"                                        // 17
    "  - {name: a3, waypoints_m: [[2, 2], [2.5, 2.5]], speed_m_per_step: 0.01}\n"            // 18
    "anchor: {id: A, position_m: [0.5, 0.5]}\n"                                              // 19
    "wall_bias: {wall: north, offset_m: -0.1}\n"                                             // 20
    "antenna_spacing_m: 0.04\n"                                                              // 21
    "channel:\n"                                                                             // 22
    "  simulated_max_order: 3\n"                                                             // 23
    "  self_coupling_db: -30\n"                                                              // 24
    "  window_length_s: 80e-9\n"                                                             // 25
    "  pulse: {rolloff: 0.4}\n"                                                              // 26
    "mpc: {relative_threshold_db: -60}\n"                                                    // 27
    "coop:\n"                                                                                // 28
    "  agent_sigma_m: 0.05\n"                                                                // 29
    "  max_order: 1\n"                                                                       // 30
    "  variance: {window_max_m: 0.3}\n"                                                      // 31
    "variant_defaults:\n"                                                                    // 32
    "  wall_error_mm: 2\n"                                                                   // 33
    "  wall_sigma_mm: 10\n"                                                                  // 34
    "variants:\n"                                                                            // 35
    "  - {agents: [2, 3], anchor: [false, true]}\n"                                          // 36
    "  - {pulse_duration_ns: [1, 0.5], agents: [2]}\n";                                      // 37

// kCoop with the given lines (1-based) replaced by their text (several lines allowed, "" removes
// the line).
std::string CoopWith(const std::map<int, std::string>& lines) {
  std::string out;
  const std::string text = kCoop;
  std::size_t start = 0;
  for (int n = 1; start < text.size(); ++n) {
    const std::size_t end = text.find('\n', start);
    const auto it = lines.find(n);
    if (it == lines.end()) {
      out += text.substr(start, end - start + 1);
    } else if (!it->second.empty()) {
      out += it->second + "\n";
    }
    start = end + 1;
  }
  return out;
}

CoopVariant Variant(int agents, bool anchor, double pulse_duration_s) {
  CoopVariant v;
  v.agents = agents;
  v.anchor = anchor;
  v.pulse_duration_s = pulse_duration_s;
  v.wall_error_m = 0.002;
  v.wall_sigma_m = 0.01;
  return v;
}

class CoopScenarioFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("mirage_coop_scenario_test_" + std::to_string(::getpid()) + "_" + info->name());
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

  // The InputError message of loading `path` (fails the test if it loads).
  static std::string ErrorOf(const std::string& path, const ScenarioOverrides& overrides = {}) {
    try {
      LoadCoopScenario(path, overrides);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << path << " loaded without an error";
    return {};
  }

  // Expects the error to name the file, the line as ":<line>:" and every fragment.
  static void ExpectError(const std::string& message, const std::string& file, int line,
                          const std::vector<std::string>& fragments) {
    EXPECT_NE(message.find(file), std::string::npos) << "no file name in: " << message;
    if (line > 0) {
      EXPECT_NE(message.find(file + ":" + std::to_string(line) + ":"), std::string::npos)
          << "no '" << file << ":" << line << ":' in: " << message;
    }
    for (const auto& f : fragments) EXPECT_NE(message.find(f), std::string::npos) << "no '" << f << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  }

  // Writes kCoop with the replacements and expects its error at `line` with the fragments.
  void ExpectBad(const std::string& name, const std::map<int, std::string>& lines, int line,
                 const std::vector<std::string>& fragments) const {
    const std::string path = Write(name, CoopWith(lines));
    ExpectError(ErrorOf(path), path, line, fragments);
  }

  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// Valid files
// ---------------------------------------------------------------------------------------------

TEST_F(CoopScenarioFiles, LoadsTheSmallScenarioWithTheValuesItStates) {
  // Arrange
  const std::string path = Write("coop.yaml", kCoop);

  // Act
  const CoopScenario s = LoadCoopScenario(path);

  // Assert
  const auto& c = s.config;
  EXPECT_EQ(s.file, path);
  EXPECT_EQ(c.name, "coop_room");
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.runs, 5);
  EXPECT_EQ(c.threads, 0);
  EXPECT_EQ(c.steps, 50);
  ASSERT_EQ(c.true_plan.walls().size(), 5u);
  EXPECT_DOUBLE_EQ(c.true_plan.walls()[0].reflection_coeff, 0.6);
  EXPECT_EQ(c.true_plan.walls()[3].label, "north");
  EXPECT_EQ(c.true_plan.obstacles().size(), 1u);
  EXPECT_EQ(c.in_plan, (std::vector<bool>{true, true, true, true, false}));
  ASSERT_EQ(c.agents.size(), 3u);
  EXPECT_EQ(c.agents[1].name, "a2");
  EXPECT_EQ(c.agents[1].waypoints_m.size(), 2u);
  EXPECT_DOUBLE_EQ(c.agents[0].speed_m_per_step, 0.02);
  EXPECT_DOUBLE_EQ(c.agents[1].speed_m_per_step, pipeline::CoopAgent{}.speed_m_per_step);
  ASSERT_TRUE(c.anchor.has_value());
  EXPECT_EQ(c.anchor->id, "A");
  EXPECT_DOUBLE_EQ(c.anchor->position_m.x(), 0.5);
  EXPECT_EQ(c.wall_bias.wall, 3);
  EXPECT_DOUBLE_EQ(c.wall_bias.offset_m, -0.1);
  EXPECT_DOUBLE_EQ(c.antennas.spacing_m, 0.04);
  EXPECT_EQ(c.simulated_max_order, 3);
  EXPECT_DOUBLE_EQ(c.self_coupling_db, -30.0);
  EXPECT_DOUBLE_EQ(c.channel.window_length_s, 80e-9);
  EXPECT_DOUBLE_EQ(c.channel.pulse.rolloff, 0.4);
  EXPECT_DOUBLE_EQ(c.channel.pulse.duration_s, 0.5e-9);  // from the variant defaults
  EXPECT_DOUBLE_EQ(c.mpc.relative_threshold_db, -60.0);
  EXPECT_DOUBLE_EQ(c.coop.agent_sigma_m, 0.05);
  EXPECT_EQ(c.coop.max_order, 1);
  const methods::coop::CoopOptions defaults;
  EXPECT_DOUBLE_EQ(c.coop.velocity_sigma_mps, defaults.velocity_sigma_mps);
  EXPECT_DOUBLE_EQ(c.coop.variance.window_max_m, 0.3);
  // The other variance keys keep the cooperative defaults, not MINT's.
  EXPECT_DOUBLE_EQ(c.coop.variance.window_min_m, defaults.variance.window_min_m);
  EXPECT_EQ(c.coop.variance.min_samples, defaults.variance.min_samples);
  EXPECT_DOUBLE_EQ(c.coop.variance.default_sigma_m, defaults.variance.default_sigma_m);
  // Grid 1 in the order agents, anchor (the last fastest); grid 2's 0.5 ns variant repeats grid
  // 1's first and is dropped.
  const std::vector<CoopVariant> expected = {Variant(2, false, 0.5e-9), Variant(2, true, 0.5e-9),
                                             Variant(3, false, 0.5e-9), Variant(3, true, 0.5e-9),
                                             Variant(2, false, 1e-9)};
  ASSERT_EQ(c.variants.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(c.variants[i].agents, expected[i].agents) << i;
    EXPECT_EQ(c.variants[i].anchor, expected[i].anchor) << i;
    EXPECT_DOUBLE_EQ(c.variants[i].pulse_duration_s, expected[i].pulse_duration_s) << i;
    EXPECT_DOUBLE_EQ(c.variants[i].wall_error_m, 0.002) << i;
    EXPECT_DOUBLE_EQ(c.variants[i].wall_sigma_m, 0.01) << i;
    EXPECT_FALSE(c.variants[i].biased_wall) << i;
    EXPECT_TRUE(c.variants[i].wall_update) << i;
  }
}

TEST_F(CoopScenarioFiles, CrossesAllSevenAxesWithTheLastVaryingFastest) {
  // Arrange
  const std::string path = Write(
      "axes.yaml", CoopWith({{36, "  - {agents: [3, 2], anchor: [true], pulse_duration_ns: [2], wall_error_mm: [0, 5],\n"
                                  "     biased_wall: [false, true], wall_update: [false], wall_sigma_mm: [1, 3]}"},
                             {37, ""}}));

  // Act
  const auto variants = LoadCoopScenario(path).config.variants;

  // Assert
  ASSERT_EQ(variants.size(), 16u);
  EXPECT_EQ(variants[0].agents, 3);
  EXPECT_TRUE(variants[0].anchor);
  EXPECT_DOUBLE_EQ(variants[0].pulse_duration_s, 2e-9);
  EXPECT_DOUBLE_EQ(variants[0].wall_error_m, 0.0);
  EXPECT_FALSE(variants[0].biased_wall);
  EXPECT_FALSE(variants[0].wall_update);
  EXPECT_DOUBLE_EQ(variants[0].wall_sigma_m, 0.001);
  EXPECT_DOUBLE_EQ(variants[1].wall_sigma_m, 0.003);  // the last axis varies fastest
  EXPECT_TRUE(variants[2].biased_wall);
  EXPECT_DOUBLE_EQ(variants[4].wall_error_m, 0.005);
  EXPECT_EQ(variants[7].agents, 3);
  EXPECT_EQ(variants[8].agents, 2);  // the first axis varies slowest, in the file's order
}

TEST_F(CoopScenarioFiles, WithoutVariantsTheGridIsTheDefaultVariant) {
  // Arrange
  const std::string path = Write("defaults.yaml", CoopWith({{32, "variant_defaults: {agents: 3, anchor: true, "
                                                                 "pulse_duration_ns: 1, biased_wall: true, wall_update: "
                                                                 "false}"},
                                                            {33, ""}, {34, ""}, {35, ""}, {36, ""}, {37, ""}}));

  // Act
  const auto config = LoadCoopScenario(path).config;

  // Assert
  ASSERT_EQ(config.variants.size(), 1u);
  const CoopVariant& v = config.variants[0];
  EXPECT_EQ(v.agents, 3);
  EXPECT_TRUE(v.anchor);
  EXPECT_DOUBLE_EQ(v.pulse_duration_s, 1e-9);
  EXPECT_TRUE(v.biased_wall);
  EXPECT_FALSE(v.wall_update);
  EXPECT_EQ(v.wall_error_m, CoopVariant{}.wall_error_m);  // untouched: no unit round trip
  EXPECT_EQ(v.wall_sigma_m, CoopVariant{}.wall_sigma_m);
  EXPECT_DOUBLE_EQ(config.channel.pulse.duration_s, 1e-9);
}

TEST(LoadCoopScenario, ReadsTheCoopRoomExample) {
  const std::string path = std::string(MIRAGE_SOURCE_DIR) + "/examples/coop_room.yaml";
  ASSERT_TRUE(IsCoopScenario(path));
  const auto config = LoadCoopScenario(path).config;
  EXPECT_EQ(config.name, "coop_room");
  EXPECT_GE(config.agents.size(), 2u);
  EXPECT_FALSE(config.variants.empty());
  EXPECT_EQ(config.in_plan.size(), config.true_plan.walls().size());
}

TEST_F(CoopScenarioFiles, AppliesCommandLineOverrides) {
  // Arrange
  const std::string path = Write("coop.yaml", kCoop);
  ScenarioOverrides overrides;
  overrides.runs = 2;
  overrides.seed = 11;
  overrides.threads = 3;

  // Act
  const auto config = LoadCoopScenario(path, overrides).config;

  // Assert
  EXPECT_EQ(config.runs, 2);
  EXPECT_EQ(config.seed, 11u);
  EXPECT_EQ(config.threads, 3);
}

TEST_F(CoopScenarioFiles, RejectsInvalidCommandLineOverrides) {
  const std::string path = Write("coop.yaml", kCoop);
  ScenarioOverrides runs;
  runs.runs = 0;
  EXPECT_NE(ErrorOf(path, runs).find("--runs"), std::string::npos);
  ScenarioOverrides threads;
  threads.threads = -1;
  EXPECT_NE(ErrorOf(path, threads).find("--threads"), std::string::npos);
}

TEST_F(CoopScenarioFiles, TellsCoopFilesFromOthers) {
  EXPECT_TRUE(IsCoopScenario(Write("coop.yaml", kCoop)));
  EXPECT_FALSE(IsCoopScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/seminar_room.yaml"));
  EXPECT_FALSE(IsCoopScenario(Write("broken.yaml", "name: [unclosed\nmethod: coop\n")));
  EXPECT_FALSE(IsCoopScenario(Write("list.yaml", "- method: coop\n")));
  EXPECT_FALSE(IsCoopScenario((dir_ / "missing.yaml").string()));
  EXPECT_FALSE(IsCoopScenario(Write("method_map.yaml", "method: {coop: 1}\n")));
  // `method` inherited through extends counts.
  Write("base.yaml", kCoop);
  EXPECT_TRUE(IsCoopScenario(Write("child.yaml", "extends: base.yaml\nruns: 2\n")));
}

TEST_F(CoopScenarioFiles, MergesAFileOverTheOneItExtends) {
  Write("base.yaml", kCoop);
  const std::string path = Write("child.yaml", "extends: base.yaml\nruns: 2\nvariant_defaults: {wall_sigma_mm: 1}\n");

  const auto config = LoadCoopScenario(path).config;

  EXPECT_EQ(config.runs, 2);
  EXPECT_DOUBLE_EQ(config.variants.front().wall_sigma_m, 0.001);
  EXPECT_DOUBLE_EQ(config.variants.front().wall_error_m, 0.002);
}

TEST_F(CoopScenarioFiles, TheMintReaderStillRejectsInPlan) {
  // in_plan only means something to the cooperative reader.
  const std::string path = Write("mint.yaml", "name: m\n"
                                              "method: mint\n"
                                              "floor_plan:\n"
                                              "  walls:\n"
                                              "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, in_plan: false}\n"
                                              "anchors: [{id: A, position_m: [1, 1]}]\n"
                                              "trajectories: [{name: t, waypoints_m: [[2, 2], [2, 3]]}]\n");
  std::string message;
  try {
    LoadScenario(path);
  } catch (const InputError& e) {
    message = e.what();
  }
  ExpectError(message, path, 5, {"floor_plan.walls[0].in_plan", "unknown key"});
}

// ---------------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------------

TEST_F(CoopScenarioFiles, NamesAnUnknownKey) {
  ExpectBad("typo.yaml", {{29, "  agent_sigma: 0.05"}}, 29, {"coop.agent_sigma", "unknown key", "agent_sigma_m"});
}

TEST_F(CoopScenarioFiles, NamesAnUnknownTopLevelKey) {
  ExpectBad("top_typo.yaml", {{5, "steps: 50\nstep_count: 3"}}, 6, {"step_count", "unknown key"});
}

TEST_F(CoopScenarioFiles, NamesAnUnknownAxisWithTheKnownOnes) {
  ExpectBad("axis_typo.yaml", {{37, "  - {agent: [2]}"}}, 37,
            {"variants[1].agent", "unknown key", "agents", "wall_sigma_mm"});
}

TEST_F(CoopScenarioFiles, NamesAnotherMethod) {
  ExpectBad("mint.yaml", {{2, "method: mint"}}, 2, {"method", "'mint'", "coop"});
}

TEST_F(CoopScenarioFiles, NamesFewerThanTwoAgentsInAGrid) {
  ExpectBad("one_agent.yaml", {{36, "  - {agents: [1, 3], anchor: [false, true]}"}}, 36,
            {"variants[0].agents[0]", "at least 2"});
}

TEST_F(CoopScenarioFiles, NamesMoreAgentsThanTheScenarioHas) {
  ExpectBad("many_agents.yaml", {{36, "  - {agents: [2, 4], anchor: [false, true]}"}}, 36,
            {"variants[0].agents[1]", "4 agents", "defines 3"});
}

TEST_F(CoopScenarioFiles, NamesAFractionalAgentCount) {
  ExpectBad("half_agent.yaml", {{32, "variant_defaults:\n  agents: 2.5"}, {33, ""}}, 33,
            {"variant_defaults.agents", "whole number"});
}

TEST_F(CoopScenarioFiles, NamesFewerThanTwoAgentsInTheScenario) {
  // The line of the list (its first entry), as for every value.
  ExpectBad("lonely.yaml", {{17, ""}, {18, ""}, {36, "  - {agents: [2]}"}}, 16, {"agents", "at least 2 agents, got 1"});
}

TEST_F(CoopScenarioFiles, NamesAnAnchorVariantWithoutAnAnchor) {
  // Without line 19 the grid is on line 35.
  ExpectBad("no_anchor.yaml", {{19, ""}}, 35, {"variants[0].anchor[1]", "needs an anchor: section"});
}

TEST_F(CoopScenarioFiles, NamesABiasedWallVariantWithoutAWallBias) {
  // Without line 20 the variant defaults move up one line.
  ExpectBad("no_bias.yaml", {{20, ""}, {34, "  wall_sigma_mm: 10\n  biased_wall: true"}}, 34,
            {"variant_defaults.biased_wall", "needs a wall_bias: section"});
}

TEST_F(CoopScenarioFiles, NamesAnUnknownWallBiasLabel) {
  ExpectBad("bias_label.yaml", {{20, "wall_bias: {wall: ceiling}"}}, 20,
            {"wall_bias.wall", "no wall segment is labelled 'ceiling'", "north"});
}

TEST_F(CoopScenarioFiles, NamesAWallBiasLabelOfSeveralSegments) {
  ExpectBad("bias_many.yaml", {{20, "wall_bias: {wall: concrete}"}}, 20,
            {"wall_bias.wall", "'concrete' labels 3 wall segments"});
}

TEST_F(CoopScenarioFiles, NamesABiasOnAWallTheFilterDoesNotKnow) {
  ExpectBad("bias_pinboard.yaml", {{20, "wall_bias: {wall: pinboard}"}}, 20, {"wall_bias.wall", "in_plan: false"});
}

TEST_F(CoopScenarioFiles, NamesAWallBiasOffsetOutOfRange) {
  ExpectBad("bias_offset.yaml", {{20, "wall_bias: {wall: north, offset_m: 1.5}"}}, 20,
            {"wall_bias.offset_m", "out of range"});
}

TEST_F(CoopScenarioFiles, NamesANonBooleanInPlan) {
  ExpectBad("in_plan.yaml", {{12, "    - {start_m: [5, 1], end_m: [5, 2], in_plan: maybe}"}}, 12,
            {"floor_plan.walls[2].in_plan", "true or false"});
}

TEST_F(CoopScenarioFiles, NamesAWaypointOutsideThePlan) {
  ExpectBad("outside.yaml", {{17, "  - {name: a2, waypoints_m: [[4, 2], [7, 1]]}"}}, 17,
            {"agents[1].waypoints_m", "waypoint 1", "outside the floor plan"});
}

TEST_F(CoopScenarioFiles, NamesAWaypointInsideAnObstacle) {
  ExpectBad("pillar.yaml", {{17, "  - {name: a2, waypoints_m: [[1.5, 3.1], [3, 3]]}"}}, 17,
            {"agents[1].waypoints_m", "inside an obstacle"});
}

TEST_F(CoopScenarioFiles, NamesAnAntennaThroughAWall) {
  // The centre stays 1 cm inside the west wall; the RX antenna 2 cm to the west does not.
  ExpectBad("antenna.yaml", {{17, "  - {name: a2, waypoints_m: [[0.01, 2], [0.01, 1]]}"}}, 17,
            {"agents[1].waypoints_m", "RX antenna"});
}

TEST_F(CoopScenarioFiles, NamesALegThroughTheInvisiblePinBoard) {
  ExpectBad("leg.yaml", {{17, "  - {name: a2, waypoints_m: [[4, 1.5], [5.5, 1.5]]}"}}, 17,
            {"agents[1].waypoints_m", "crosses a wall or an obstacle"});
}

TEST_F(CoopScenarioFiles, NamesANegativeSpeed) {
  ExpectBad("speed.yaml", {{16, "  - {name: a1, waypoints_m: [[1, 1], [2, 1]], speed_m_per_step: -0.02}"}}, 16,
            {"agents[0].speed_m_per_step", "-0.02", "(0, 0.1]"});
}

TEST_F(CoopScenarioFiles, NamesADuplicateAgentName) {
  ExpectBad("same_name.yaml", {{17, "  - {name: a1, waypoints_m: [[4, 2], [4, 1]]}"}}, 17,
            {"agents[1].name", "duplicate"});
}

TEST_F(CoopScenarioFiles, NamesMaxComponentsInMpc) {
  ExpectBad("mpc.yaml", {{27, "mpc: {relative_threshold_db: -60, max_components: 10}"}}, 27,
            {"mpc.max_components", "extraction_factor"});
}

TEST_F(CoopScenarioFiles, NamesAPulseDurationInTheChannel) {
  ExpectBad("pulse.yaml", {{26, "  pulse: {rolloff: 0.4, duration_s: 1e-9}"}}, 26,
            {"channel.pulse.duration_s", "pulse_duration_ns"});
}

TEST_F(CoopScenarioFiles, NamesAWallUpdateInTheFilterOptions) {
  ExpectBad("wall_update.yaml", {{30, "  max_order: 1\n  wall_update: false"}}, 31, {"coop.wall_update", "variant"});
}

TEST_F(CoopScenarioFiles, NamesAFilterOrderAboveTwo) {
  ExpectBad("order.yaml", {{30, "  max_order: 3"}}, 30, {"coop.max_order", "[1, 2]"});
}

TEST_F(CoopScenarioFiles, NamesASelfGateBelowTheAntennaSpacing) {
  ExpectBad("gate.yaml", {{30, "  max_order: 1\n  self_gate_m: 0.03"}}, 31, {"coop.self_gate_m", "antenna_spacing_m"});
}

TEST_F(CoopScenarioFiles, NamesAnEmptyAxisList) {
  ExpectBad("empty_axis.yaml", {{37, "  - {pulse_duration_ns: [], agents: [2]}"}}, 37,
            {"variants[1].pulse_duration_ns", "at least one entry"});
}

TEST_F(CoopScenarioFiles, NamesAnAxisThatIsNotAList) {
  ExpectBad("scalar_axis.yaml", {{37, "  - {agents: 2}"}}, 37, {"variants[1].agents", "expected a list"});
}

TEST_F(CoopScenarioFiles, NamesAPulseDurationOutOfRange) {
  ExpectBad("zero_pulse.yaml", {{37, "  - {pulse_duration_ns: [1, 0], agents: [2]}"}}, 37,
            {"variants[1].pulse_duration_ns[1]", "(0, 10] ns"});
}

TEST_F(CoopScenarioFiles, NamesAWallErrorOutOfRange) {
  ExpectBad("wall_error.yaml", {{33, "  wall_error_mm: -1"}}, 33, {"variant_defaults.wall_error_mm", "[0, 500] mm"});
}

TEST_F(CoopScenarioFiles, NamesAZeroWallSigma) {
  ExpectBad("wall_sigma.yaml", {{37, "  - {wall_sigma_mm: [3, 0]}"}}, 37, {"variants[1].wall_sigma_mm[1]", "(0, 1000] mm"});
}

TEST_F(CoopScenarioFiles, NamesANonBooleanAxisEntry) {
  ExpectBad("flag.yaml", {{36, "  - {agents: [2, 3], anchor: [false, yes please]}"}}, 36,
            {"variants[0].anchor[1]", "true or false"});
}

TEST_F(CoopScenarioFiles, NamesAWindowTooShortForThePlan) {
  // The plan's bounding box is 6 m x 4 m: twice its diagonal is 14.4 m, 48 ns.
  ExpectBad("window.yaml", {{25, "  window_length_s: 40e-9"}}, 25, {"channel.window_length_s", "diagonal"});
}

TEST_F(CoopScenarioFiles, NamesASamplePeriodTooLongForAVariantPulse) {
  // 0.1 ns at roll-off 0.4 needs samples below 36 ps; the default is 125 ps.
  const std::string path = Write("nyquist.yaml", CoopWith({{37, "  - {pulse_duration_ns: [0.1], agents: [2]}"}}));
  ExpectError(ErrorOf(path), path, 0, {"channel.sample_period_s", "Nyquist", "0.1 ns"});
}

TEST_F(CoopScenarioFiles, NamesASimulatedOrderOutOfRange) {
  ExpectBad("sim_order.yaml", {{23, "  simulated_max_order: 4"}}, 23, {"channel.simulated_max_order", "[1, 3]"});
}

TEST_F(CoopScenarioFiles, NamesAWindowStartWhichTheCooperativeChannelDoesNotHave) {
  ExpectBad("window_start.yaml", {{25, "  window_length_s: 80e-9\n  window_start_s: 1e-9"}}, 26,
            {"channel.window_start_s", "unknown key"});
}

}  // namespace
}  // namespace mirage::io
