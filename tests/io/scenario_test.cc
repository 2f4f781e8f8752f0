// SPDX-License-Identifier: MIT
// Scenario files: the seminar-room example loads with the values it states, `extends:` merges
// files, and every kind of bad input throws an InputError whose message names the file, the line
// (as ":<n>:") and the key path (STYLE.md Sec. 9, docs/scenario.md).
#include "mirage/io/scenario.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;

std::string Example(const std::string& name) { return std::string(MIRAGE_SOURCE_DIR) + "/examples/" + name; }

// A small valid scenario; the line numbers in the comments are the ones the error messages give.
const char* const kTiny =
    "name: tiny\n"                                                       // 1
    "method: mint\n"                                                     // 2
    "materials:\n"                                                       // 3
    "  concrete: 0.5\n"                                                  // 4
    "floor_plan:\n"                                                      // 5
    "  walls:\n"                                                         // 6
    "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, material: concrete}\n"  // 7
    "  obstacles:\n"                                                     // 8
    "    - {center_m: [2.0, 2.0], radius_m: 0.3}\n"                      // 9
    "anchors:\n"                                                         // 10
    "  - {id: A1, position_m: [0.5, 3.5]}\n"                             // 11
    "  - {id: A2, position_m: [3.5, 0.5]}\n"                             // 12
    "trajectories:\n"                                                    // 13
    "  - name: walk\n"                                                   // 14
    "    waypoints_m: [[0.5, 0.5], [0.5, 3.0]]\n"                        // 15
    "    dt_s: 0.1\n"                                                    // 16
    "channel:\n"                                                         // 17
    "  sample_period_s: 0.125e-9\n"                                      // 18
    "  pulse:\n"                                                         // 19
    "    duration_s: 0.5e-9\n"                                           // 20
    "mint:\n"                                                            // 21
    "  variance:\n"                                                      // 22
    "    window_min_m: 0.9\n"                                            // 23
    "    window_max_m: 1.0\n";                                           // 24

// kTiny with line `line` (1-based) replaced by `text` (several lines allowed, "" removes it).
std::string TinyWithLine(int line, const std::string& text) {
  std::string out;
  std::string tiny = kTiny;
  std::size_t start = 0;
  for (int n = 1; start < tiny.size(); ++n) {
    const std::size_t end = tiny.find('\n', start);
    const std::string current = tiny.substr(start, end - start + 1);
    if (n == line) {
      if (!text.empty()) out += text + "\n";
    } else {
      out += current;
    }
    start = end + 1;
  }
  return out;
}

class ScenarioFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("mirage_scenario_test_" + std::to_string(::getpid()) + "_" + info->name());
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
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.string();
  }

  // A file that extends the seminar-room example and sets the given keys.
  std::string Override(const std::string& name, const std::string& text) const {
    return Write(name, "extends: " + Example("seminar_room.yaml") + "\n" + text);
  }

  // A file that extends the anchors-only SLAM example and sets the given keys.
  std::string OverrideSlam(const std::string& name, const std::string& text) const {
    return Write(name, "extends: " + Example("seminar_room_slam.yaml") + "\n" + text);
  }

  // The InputError message of loading `path` (fails the test if it loads).
  static std::string ErrorOf(const std::string& path) {
    try {
      LoadScenario(path);
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

  fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// Valid files
// ---------------------------------------------------------------------------------------------

TEST(LoadScenario, ReadsTheSeminarRoomExampleWithTheValuesItStates) {
  // Act
  const Scenario s = LoadScenario(Example("seminar_room.yaml"));
  const auto& c = s.mint;

  // Assert
  EXPECT_EQ(s.method, "mint");
  EXPECT_EQ(c.name, "seminar_room");
  EXPECT_EQ(c.seed, 1u);
  EXPECT_EQ(c.runs, 25);
  EXPECT_EQ(c.threads, 0);
  EXPECT_FALSE(c.perturb_initial_position);
  EXPECT_EQ(c.run_grid.nx, 5);
  EXPECT_EQ(c.run_grid.ny, 5);
  EXPECT_DOUBLE_EQ(c.run_grid.spacing_m, 0.01);
  // 14 wall entries, polylines split into 29 segments; the first is concrete, the third glass.
  ASSERT_EQ(c.plan.walls().size(), 29u);
  EXPECT_EQ(c.plan.walls()[0].start_m, Vec2(-0.309, 0.0));
  EXPECT_EQ(c.plan.walls()[0].end_m, Vec2(5.775, 0.0));
  EXPECT_DOUBLE_EQ(c.plan.walls()[0].reflection_coeff, 0.5);
  EXPECT_EQ(c.plan.walls()[0].label, "concrete");
  EXPECT_DOUBLE_EQ(c.plan.walls()[3].reflection_coeff, 0.7);
  EXPECT_EQ(c.plan.walls()[3].label, "glass");
  ASSERT_EQ(c.plan.obstacles().size(), 1u);
  EXPECT_EQ(c.plan.obstacles()[0].center_m, Vec2(2.4, 4.2));
  EXPECT_DOUBLE_EQ(c.plan.obstacles()[0].radius_m, 0.3);
  EXPECT_EQ(c.plan.obstacles()[0].label, "pillar");
  EXPECT_EQ(c.known_plan.walls().size(), c.plan.walls().size());
  ASSERT_EQ(c.anchor_ids, (std::vector<std::string>{"A1", "A2"}));
  EXPECT_EQ(c.anchors_m[0], Vec2(0.5, 7.0));
  EXPECT_EQ(c.anchors_m[1], Vec2(5.2, 2.3));
  EXPECT_EQ(c.known_anchors_m, c.anchors_m);
  ASSERT_EQ(c.trajectories.size(), 2u);
  EXPECT_EQ(c.trajectories[0].name, "trajectory_1");
  EXPECT_EQ(c.trajectories[0].waypoints_m.size(), 4u);
  EXPECT_EQ(c.trajectories[0].waypoints_m[3], Vec2(3.4, 2.2));
  EXPECT_DOUBLE_EQ(c.trajectories[0].speed_mps, 0.5);
  EXPECT_DOUBLE_EQ(c.trajectories[0].dt_s, 0.1);
  EXPECT_EQ(c.trajectories[1].name, "trajectory_2");
  EXPECT_EQ(c.trajectories[1].waypoints_m.size(), 5u);
  EXPECT_EQ(c.channel_max_order, 2);
  EXPECT_DOUBLE_EQ(c.channel.sample_period_s, 0.125e-9);
  EXPECT_DOUBLE_EQ(c.channel.window_length_s, 128e-9);
  EXPECT_DOUBLE_EQ(c.channel.snr_at_1m_db, 35.0);
  EXPECT_DOUBLE_EQ(c.channel.pulse.carrier_hz, 7.0e9);
  EXPECT_DOUBLE_EQ(c.channel.pulse.rolloff, 0.5);
  EXPECT_DOUBLE_EQ(c.channel.pulse.duration_s, 0.5e-9);
  EXPECT_TRUE(c.channel.diffuse.enabled);
  EXPECT_DOUBLE_EQ(c.channel.diffuse.decay_s, 20e-9);
  EXPECT_DOUBLE_EQ(c.channel.diffuse.rise_weight, 0.98);
  EXPECT_EQ(c.mpc.max_components, 20);
  EXPECT_DOUBLE_EQ(c.mpc.relative_threshold_db, -30.0);
  EXPECT_DOUBLE_EQ(c.mint.cutoff_m, 0.15);
  EXPECT_DOUBLE_EQ(c.mint.range_sigma_m, 0.07);
  EXPECT_EQ(c.mint.max_order, 2);
  EXPECT_TRUE(c.mint.reassociate);
  EXPECT_DOUBLE_EQ(c.mint.innovation_gate_chi2, 9.0);
  EXPECT_TRUE(c.mint.constrain_to_room);
  EXPECT_DOUBLE_EQ(c.mint.motion.accel_sigma_mps2, 1.0);
  EXPECT_TRUE(c.mint.variance.enabled);
  EXPECT_DOUBLE_EQ(c.mint.variance.window_min_m, 0.9);
  EXPECT_DOUBLE_EQ(c.mint.variance.window_max_m, 1.0);
  EXPECT_EQ(c.mint.variance.min_samples, 15);
  EXPECT_DOUBLE_EQ(c.mint.variance.default_sigma_m, 0.07);
  EXPECT_DOUBLE_EQ(c.mint.variance.max_variance_factor, 10.0);
  EXPECT_DOUBLE_EQ(c.mint.variance.min_sigma_m, 0.01);
  EXPECT_DOUBLE_EQ(c.mint.variance.overlap_distance_m, 0.15);
  EXPECT_TRUE(c.mint.relocalization.enabled);
  EXPECT_EQ(c.mint.relocalization.min_visible, 4);
  EXPECT_EQ(c.mint.relocalization.lost_steps, 3);
  EXPECT_DOUBLE_EQ(c.mint.relocalization.search_radius_m, 1.5);
  EXPECT_DOUBLE_EQ(c.mint.relocalization.found_score, 0.6);
  EXPECT_DOUBLE_EQ(c.divergence.threshold_m, 0.5);
  EXPECT_DOUBLE_EQ(c.divergence.last_fraction, 0.2);
}

TEST(LoadScenario, ReadsTheSlamExamplesWithTheValuesTheyState) {
  // Act
  const Scenario anchors_only = LoadScenario(Example("seminar_room_slam.yaml"));
  const Scenario known = LoadScenario(Example("seminar_room_slam_known.yaml"));
  const auto& o = anchors_only.mint.slam;
  const auto& k = known.mint.slam;

  // Assert: the anchors-only example, every key it sets. Most of its values are also the
  // SlamOptions defaults, so only method, name, prior_visibility, slam.motion (0.5 against
  // mint.motion's 1.0) and the known-VA example's own keys below show that a key was read; the
  // rest pins what the example states (README numbers depend on it).
  EXPECT_EQ(anchors_only.method, "slam");
  EXPECT_EQ(anchors_only.mint.name, "seminar_room_slam");
  EXPECT_DOUBLE_EQ(o.cutoff_m, 0.15);
  EXPECT_EQ(o.prior_max_order, 0);
  EXPECT_FALSE(o.prior_visibility);
  EXPECT_TRUE(o.reassociate);
  EXPECT_DOUBLE_EQ(o.innovation_gate_chi2, 9.0);
  EXPECT_DOUBLE_EQ(o.no_visibility_model_gate_chi2, 4.0);
  EXPECT_DOUBLE_EQ(o.motion.accel_sigma_mps2, 0.5);  // slam.motion, not mint.motion's 1.0
  EXPECT_DOUBLE_EQ(anchors_only.mint.mint.motion.accel_sigma_mps2, 1.0);
  EXPECT_TRUE(o.va_filter);
  EXPECT_DOUBLE_EQ(o.va_filter_sigma_m, 0.0623);
  EXPECT_TRUE(o.va_filter_keeps_associating);
  EXPECT_DOUBLE_EQ(o.amplitude_gate_probability, 0.001);
  EXPECT_DOUBLE_EQ(o.blocked_amplitude_probability, 0.1);
  EXPECT_DOUBLE_EQ(o.startup_amplitude_k_factor, 10.0);
  EXPECT_DOUBLE_EQ(o.shadow_cone_deg, 0.0);
  EXPECT_DOUBLE_EQ(o.shadow_sigma_m, 0.05);
  EXPECT_DOUBLE_EQ(o.los_reacquire_m, 0.4);
  EXPECT_EQ(o.nis_window_updates, 20);
  EXPECT_TRUE(o.recovery.enabled);
  EXPECT_EQ(o.recovery.min_margin, 2);
  EXPECT_EQ(o.recovery.lost_steps, 3);
  EXPECT_DOUBLE_EQ(o.recovery.max_speed_mps, 1.5);
  EXPECT_TRUE(o.discovery.enabled);
  EXPECT_DOUBLE_EQ(o.discovery.max_agent_sigma_m, 0.1);
  EXPECT_DOUBLE_EQ(o.discovery.verify_far_sigma_per_m, 0.015);
  EXPECT_DOUBLE_EQ(o.discovery.verify_far_fit_rms_m, 0.025);
  EXPECT_EQ(o.discovery.group_size, 10);
  EXPECT_DOUBLE_EQ(o.discovery.min_group_baseline_m, 0.3);
  EXPECT_DOUBLE_EQ(o.discovery.max_fit_rms_m, 0.03);
  EXPECT_EQ(o.discovery.min_measurements, 10);
  EXPECT_EQ(o.discovery.resolve_misses, 3);
  EXPECT_TRUE(o.discovery.verify);
  EXPECT_TRUE(o.discovery.sweep.enabled);

  // The known-VA example extends it: its own keys, the rest inherited.
  EXPECT_EQ(known.method, "slam");
  EXPECT_EQ(known.mint.name, "seminar_room_slam_known");
  EXPECT_EQ(k.prior_max_order, 2);
  EXPECT_DOUBLE_EQ(k.prior_va_sigma_m, 0.05);
  EXPECT_TRUE(k.prior_visibility);
  EXPECT_FALSE(k.discovery.enabled);
  EXPECT_EQ(k.recovery.min_margin_floor_plan, 4);
  EXPECT_EQ(k.recovery.floor_plan_watch_steps, 10);
  EXPECT_DOUBLE_EQ(k.motion.accel_sigma_mps2, 0.5);
  EXPECT_DOUBLE_EQ(k.los_reacquire_m, 0.4);
  EXPECT_EQ(k.recovery.min_margin, 2);
}

TEST(LoadScenario, AppliesCommandLineOverrides) {
  // Arrange
  ScenarioOverrides overrides;
  overrides.runs = 3;
  overrides.seed = 77;
  overrides.threads = 2;

  // Act
  const Scenario s = LoadScenario(Example("seminar_room.yaml"), overrides);

  // Assert
  EXPECT_EQ(s.mint.runs, 3);
  EXPECT_EQ(s.mint.seed, 77u);
  EXPECT_EQ(s.mint.threads, 2);
}

TEST(LoadScenario, RejectsInvalidCommandLineOverrides) {
  ScenarioOverrides runs;
  runs.runs = 0;
  ScenarioOverrides threads;
  threads.threads = -1;
  try {
    LoadScenario(Example("seminar_room.yaml"), runs);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--runs"), std::string::npos) << e.what();
  }
  try {
    LoadScenario(Example("seminar_room.yaml"), threads);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--threads"), std::string::npos) << e.what();
  }
}

TEST(LoadScenario, ReadsTheOneNanosecondExampleAsTheSeminarRoomWithALongerPulse) {
  // Act
  const Scenario base = LoadScenario(Example("seminar_room.yaml"));
  const Scenario one_ns = LoadScenario(Example("seminar_room_1ns.yaml"));

  // Assert
  EXPECT_EQ(one_ns.mint.name, "seminar_room_1ns");
  EXPECT_DOUBLE_EQ(one_ns.mint.channel.pulse.duration_s, 1.0e-9);
  EXPECT_DOUBLE_EQ(one_ns.mint.channel.pulse.rolloff, base.mint.channel.pulse.rolloff);
  EXPECT_DOUBLE_EQ(one_ns.mint.channel.sample_period_s, base.mint.channel.sample_period_s);
  EXPECT_EQ(one_ns.mint.anchors_m, base.mint.anchors_m);
  EXPECT_EQ(one_ns.mint.plan.walls().size(), base.mint.plan.walls().size());
  EXPECT_EQ(one_ns.mint.trajectories.size(), base.mint.trajectories.size());
}

TEST_F(ScenarioFiles, LoadsTheTinyScenario) {
  // The bad-input variants below change one line of this file; it must be valid itself.
  const Scenario s = LoadScenario(Write("tiny.yaml", kTiny));
  EXPECT_EQ(s.mint.name, "tiny");
  EXPECT_EQ(s.mint.plan.walls().size(), 4u);
  EXPECT_EQ(s.mint.anchors_m.size(), 2u);
  EXPECT_EQ(s.mint.trajectories[0].waypoints_m[1], Vec2(0.5, 3.0));
  // Defaults for everything the file leaves out.
  EXPECT_EQ(s.mint.runs, 25);
  EXPECT_EQ(s.mint.seed, 1u);
  EXPECT_DOUBLE_EQ(s.mint.trajectories[0].speed_mps, 0.5);
}

TEST_F(ScenarioFiles, MergesAFileOverTheOneItExtends) {
  // Arrange: the child changes a nested number, the name, adds runs and replaces the anchor list.
  Write("base.yaml", kTiny);
  const std::string child = Write("variants/child.yaml",
                                  "extends: ../base.yaml\n"
                                  "name: child\n"
                                  "runs: 4\n"
                                  "channel:\n"
                                  "  pulse:\n"
                                  "    duration_s: 1.0e-9\n"
                                  "anchors:\n"
                                  "  - {id: B, position_m: [3.0, 3.0]}\n");

  // Act
  const Scenario s = LoadScenario(child);

  // Assert
  EXPECT_EQ(s.file, child);
  EXPECT_EQ(s.mint.name, "child");
  EXPECT_EQ(s.mint.runs, 4);
  EXPECT_DOUBLE_EQ(s.mint.channel.pulse.duration_s, 1.0e-9);
  EXPECT_DOUBLE_EQ(s.mint.channel.sample_period_s, 0.125e-9);  // sibling key from the base
  ASSERT_EQ(s.mint.anchor_ids, (std::vector<std::string>{"B"}));  // lists are replaced
  EXPECT_EQ(s.mint.trajectories.size(), 1u);
  EXPECT_EQ(s.method, "mint");
}

TEST_F(ScenarioFiles, FollowsAChainOfExtends) {
  // Arrange
  Write("a.yaml", kTiny);
  Write("b.yaml", "extends: a.yaml\nruns: 7\n");
  const std::string c = Write("c.yaml", "extends: b.yaml\nseed: 9\n");

  // Act
  const Scenario s = LoadScenario(c);

  // Assert
  EXPECT_EQ(s.mint.runs, 7);
  EXPECT_EQ(s.mint.seed, 9u);
  EXPECT_EQ(s.mint.name, "tiny");
}

// ---------------------------------------------------------------------------------------------
// Bad input: standalone files
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, NamesTheMissingFile) {
  const std::string path = (dir_ / "nowhere.yaml").string();
  ExpectError(ErrorOf(path), "nowhere.yaml", 0, {"file not found"});
}

TEST_F(ScenarioFiles, NamesTheLineOfAYamlSyntaxError) {
  // Line 15's flow sequence is never closed; yaml-cpp notices on the next line.
  const std::string path = Write("syntax.yaml", TinyWithLine(15, "    waypoints_m: [[0.5, 0.5], [0.5, 3.0]"));
  const std::string message = ErrorOf(path);
  ExpectError(message, path, 0, {"YAML syntax error"});
  EXPECT_TRUE(message.find(path + ":15:") != std::string::npos || message.find(path + ":16:") != std::string::npos)
      << message;
}

TEST_F(ScenarioFiles, NamesAMissingName) {
  const std::string path = Write("no_name.yaml", TinyWithLine(1, ""));
  ExpectError(ErrorOf(path), path, 0, {"name", "missing (required)"});
}

TEST_F(ScenarioFiles, NamesMissingAnchors) {
  // kTiny without lines 10-12 (the anchors block).
  std::string text = kTiny;
  const auto from = text.find("anchors:\n");
  text.erase(from, text.find("trajectories:\n") - from);
  const std::string path = Write("no_anchors.yaml", text);
  ExpectError(ErrorOf(path), path, 0, {"anchors", "missing (required)"});
}

TEST_F(ScenarioFiles, NamesAnUnknownTopLevelKey) {
  const std::string path = Write("top_typo.yaml", TinyWithLine(2, "method: mint\nsed: 3"));
  ExpectError(ErrorOf(path), path, 3, {"sed", "unknown key"});
}

TEST_F(ScenarioFiles, NamesAnUnknownNestedKeyWithItsPath) {
  const std::string path = Write("nested_typo.yaml", TinyWithLine(20, "    durations_s: 0.5e-9"));
  ExpectError(ErrorOf(path), path, 20, {"channel.pulse.durations_s", "unknown key", "duration_s"});
}

TEST_F(ScenarioFiles, NamesABadMotionKeyOfEitherTrackerWithItsPath) {
  const std::string mint_path = Override("mint_motion.yaml", "mint:\n  motion:\n    accel_sigma_mps2: 0\n");
  ExpectError(ErrorOf(mint_path), mint_path, 4, {"mint.motion.accel_sigma_mps2"});
  const std::string slam_path = Write("slam_motion.yaml", "extends: " + Example("seminar_room_slam.yaml") +
                                                              "\nslam:\n  motion:\n    accel_sigma: 0.5\n");
  ExpectError(ErrorOf(slam_path), slam_path, 4, {"slam.motion.accel_sigma", "unknown key", "accel_sigma_mps2"});
}

TEST_F(ScenarioFiles, ReadsTheSweepKeys) {
  // Every value differs from its default, so each key must have been read.
  const std::string path = OverrideSlam("sweep.yaml",
                                         "slam:\n  discovery:\n    sweep:\n      enabled: false\n"
                                         "      window_steps: 40\n      every_steps: 10\n"
                                         "      min_baseline_m: 1.5\n      gate_m: 0.03\n"
                                         "      min_support_fraction: 0.7\n");
  const auto& sweep = LoadScenario(path).mint.slam.discovery.sweep;
  EXPECT_FALSE(sweep.enabled);
  EXPECT_EQ(sweep.window_steps, 40);
  EXPECT_EQ(sweep.every_steps, 10);
  EXPECT_DOUBLE_EQ(sweep.min_baseline_m, 1.5);
  EXPECT_DOUBLE_EQ(sweep.gate_m, 0.03);
  EXPECT_DOUBLE_EQ(sweep.min_support_fraction, 0.7);
}

TEST_F(ScenarioFiles, ReadsTheSlamGateAndVarianceKeys) {
  // Every value differs from its default and from the others, so each key must have been read
  // into its own option.
  const std::string path = OverrideSlam("gates.yaml",
                                         "slam:\n  innovation_gate_chi2: 6\n  no_visibility_model_gate_chi2: 2.5\n"
                                         "  amplitude_gate_probability: 0.01\n  blocked_amplitude_probability: 0.2\n"
                                         "  nis_window_updates: 7\n  discovered_va_walk_m_per_sqrt_s: 0.004\n"
                                         "  startup_amplitude_k_factor: 3\n");
  const auto& slam = LoadScenario(path).mint.slam;
  EXPECT_DOUBLE_EQ(slam.innovation_gate_chi2, 6.0);
  EXPECT_DOUBLE_EQ(slam.no_visibility_model_gate_chi2, 2.5);
  EXPECT_DOUBLE_EQ(slam.amplitude_gate_probability, 0.01);
  EXPECT_DOUBLE_EQ(slam.blocked_amplitude_probability, 0.2);
  EXPECT_EQ(slam.nis_window_updates, 7);
  EXPECT_DOUBLE_EQ(slam.discovered_va_walk_m_per_sqrt_s, 0.004);
  EXPECT_DOUBLE_EQ(slam.startup_amplitude_k_factor, 3.0);
}

TEST_F(ScenarioFiles, ReadsTheRecoverySpeedLimitAndNamesABadOne) {
  const std::string good = OverrideSlam("speed.yaml", "slam:\n  recovery:\n    max_speed_mps: 2.5\n");
  EXPECT_DOUBLE_EQ(LoadScenario(good).mint.slam.recovery.max_speed_mps, 2.5);
  const std::string path = OverrideSlam("speed_bad.yaml", "slam:\n  recovery:\n    max_speed_mps: 0\n");
  ExpectError(ErrorOf(path), path, 4, {"slam.recovery.max_speed_mps", "out of range"});
}

TEST_F(ScenarioFiles, NamesABadSlamGateWithItsPathAndLine) {
  const std::string path = OverrideSlam("gates_bad.yaml", "slam:\n  no_visibility_model_gate_chi2: -1\n");
  ExpectError(ErrorOf(path), path, 3, {"slam.no_visibility_model_gate_chi2", "out of range"});
}

TEST_F(ScenarioFiles, NamesABadSweepKeyWithItsPathAndLine) {
  const std::string path =
      OverrideSlam("sweep_bad.yaml", "slam:\n  discovery:\n    sweep:\n      min_support_fraction: 1.5\n");
  ExpectError(ErrorOf(path), path, 5, {"slam.discovery.sweep.min_support_fraction", "out of range"});
}

TEST_F(ScenarioFiles, NamesAZeroLengthWall) {
  const std::string path =
      Write("zero_wall.yaml", TinyWithLine(7, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true}\n"
                                              "    - {start_m: [1.0, 1.0], end_m: [1.0, 1.0]}"));
  ExpectError(ErrorOf(path), path, 8, {"floor_plan.walls[1].end_m", "zero length"});
}

TEST_F(ScenarioFiles, NamesANanValue) {
  const std::string path = Write("nan.yaml", TinyWithLine(18, "  sample_period_s: .nan"));
  ExpectError(ErrorOf(path), path, 18, {"channel.sample_period_s", "finite"});
}

TEST_F(ScenarioFiles, NamesANonNumberWhereANumberIsExpected) {
  const std::string path = Write("not_a_number.yaml", TinyWithLine(16, "    dt_s: fast"));
  ExpectError(ErrorOf(path), path, 16, {"trajectories[0].dt_s", "expected a number", "fast"});
}

TEST_F(ScenarioFiles, NamesAnAnchorOutsideTheFloorPlan) {
  const std::string path = Write("anchor_outside.yaml", TinyWithLine(12, "  - {id: A2, position_m: [4.5, 0.5]}"));
  ExpectError(ErrorOf(path), path, 12, {"anchors[1].position_m", "outside the floor plan"});
}

TEST_F(ScenarioFiles, NamesAnAnchorInsideThePillar) {
  const std::string path = Write("anchor_in_pillar.yaml", TinyWithLine(12, "  - {id: A2, position_m: [2.1, 2.0]}"));
  ExpectError(ErrorOf(path), path, 12, {"anchors[1].position_m", "inside an obstacle"});
}

TEST_F(ScenarioFiles, NamesANegativeTimeStep) {
  const std::string path = Write("negative_dt.yaml", TinyWithLine(16, "    dt_s: -0.1"));
  ExpectError(ErrorOf(path), path, 16, {"trajectories[0].dt_s", "> 0"});
}

TEST_F(ScenarioFiles, NamesATrajectoryLegThroughAnObstacle) {
  const std::string path = Write("leg_through_pillar.yaml", TinyWithLine(15, "    waypoints_m: [[0.5, 2.0], [3.5, 2.0]]"));
  ExpectError(ErrorOf(path), path, 15, {"trajectories[0].waypoints_m", "crosses a wall or an obstacle"});
}

TEST_F(ScenarioFiles, NamesATrajectoryLegThroughAWall) {
  // An inner wall from (2, 2.5) to (2, 4) after line 7, and a leg (now line 16) crossing it at y = 3.
  std::string text = TinyWithLine(7, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, material: concrete}\n"
                                     "    - {start_m: [2.0, 2.5], end_m: [2.0, 4.0]}");
  const std::string old_leg = "    waypoints_m: [[0.5, 0.5], [0.5, 3.0]]";
  text.replace(text.find(old_leg), old_leg.size(), "    waypoints_m: [[0.5, 3.0], [3.5, 3.0]]");
  const std::string path = Write("leg_through_wall.yaml", text);
  ExpectError(ErrorOf(path), path, 16, {"trajectories[0].waypoints_m", "crosses a wall"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMaterial) {
  const std::string path =
      Write("unknown_material.yaml",
            TinyWithLine(7, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, material: marble}"));
  ExpectError(ErrorOf(path), path, 7, {"floor_plan.walls[0].material", "unknown material 'marble'"});
}

TEST_F(ScenarioFiles, NamesAZeroReflectionCoefficientOfAWall) {
  const std::string path = Write(
      "zero_reflection.yaml", TinyWithLine(7, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, reflection_coeff: 0}"));
  ExpectError(ErrorOf(path), path, 7, {"floor_plan.walls[0].reflection_coeff", "(0, 1]"});
}

TEST_F(ScenarioFiles, NamesAReflectionCoefficientAboveOne) {
  const std::string path = Write(
      "big_reflection.yaml", TinyWithLine(7, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, reflection_coeff: 1.2}"));
  ExpectError(ErrorOf(path), path, 7, {"floor_plan.walls[0].reflection_coeff", "1.2", "out of range"});
}

TEST_F(ScenarioFiles, NamesAMaterialWithAReflectionCoefficientOfZero) {
  const std::string path = Write("zero_material.yaml", TinyWithLine(4, "  concrete: 0"));
  const std::string message = ErrorOf(path);
  ExpectError(message, path, 0, {"materials", "concrete", "(0, 1]"});
  EXPECT_NE(message.find(path + ":4:"), std::string::npos) << message;
}

TEST_F(ScenarioFiles, NamesTheLineAndKeyOfTheBadMaterialEntry) {
  // The bad coefficient is the second entry, on line 5.
  const std::string path = Write("second_material.yaml", TinyWithLine(4, "  concrete: 0.5\n  glass: 1.5"));
  const std::string message = ErrorOf(path);
  ExpectError(message, path, 5, {"materials.glass", "(0, 1]"});
}

TEST_F(ScenarioFiles, NamesADuplicateAnchorId) {
  const std::string path = Write("duplicate_id.yaml", TinyWithLine(12, "  - {id: A1, position_m: [3.5, 0.5]}"));
  ExpectError(ErrorOf(path), path, 12, {"anchors[1].id", "duplicate anchor id 'A1'"});
}

TEST_F(ScenarioFiles, NamesASamplePeriodAboveNyquist) {
  // The 0.5 ns RC pulse with roll-off 0.5 reaches 1.5 GHz: T_s must be <= 1 / 3 GHz = 0.333 ns.
  const std::string path = Write("nyquist.yaml", TinyWithLine(18, "  sample_period_s: 0.5e-9"));
  ExpectError(ErrorOf(path), path, 18, {"channel.sample_period_s", "Nyquist"});
}

TEST_F(ScenarioFiles, StatesTheNyquistLimitInTheMessage) {
  const std::string path = Write("nyquist_value.yaml", TinyWithLine(18, "  sample_period_s: 0.5e-9"));
  const std::string message = ErrorOf(path);
  EXPECT_NE(message.find("3.33333e-10 s"), std::string::npos) << message;
}

TEST_F(ScenarioFiles, NamesAWindowMaxBelowWindowMin) {
  const std::string path = Write("window.yaml", TinyWithLine(24, "    window_max_m: 0.5"));
  ExpectError(ErrorOf(path), path, 24, {"mint.variance.window_max_m", "window_min_m"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMethod) {
  const std::string path = Write("method.yaml", TinyWithLine(2, "method: magic"));
  ExpectError(ErrorOf(path), path, 2, {"method", "unknown method 'magic'", "mint"});
}

TEST_F(ScenarioFiles, NamesAMapWhereAListIsExpected) {
  std::string text = kTiny;
  const auto from = text.find("anchors:\n");
  text.replace(from, text.find("trajectories:\n") - from, "anchors: {id: A1}\n");
  const std::string path = Write("anchors_map.yaml", text);
  ExpectError(ErrorOf(path), path, 10, {"anchors", "expected a list"});
}

TEST_F(ScenarioFiles, DetectsACycleOfExtends) {
  const std::string a = Write("cycle_a.yaml", "extends: cycle_b.yaml\nname: a\n");
  Write("cycle_b.yaml", "extends: cycle_a.yaml\nname: b\n");
  ExpectError(ErrorOf(a), "cycle_", 0, {"extends", "cycle"});
}

// ---------------------------------------------------------------------------------------------
// Bad input in files that extend the seminar-room example: the error names the overriding file
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, NamesTheOverridingFileForABadNestedValue) {
  const std::string path = Override("bad_pulse.yaml", "channel:\n  pulse:\n    duration_s: -1.0e-9\n");
  ExpectError(ErrorOf(path), path, 4, {"channel.pulse.duration_s", "out of range"});
}

TEST_F(ScenarioFiles, NamesTheOverridingFileForABadList) {
  const std::string path =
      Override("bad_anchor.yaml", "anchors:\n  - {id: A1, position_m: [0.5, 7.0]}\n  - {id: A2, position_m: [7.2, 2.3]}\n");
  ExpectError(ErrorOf(path), path, 4, {"anchors[1].position_m", "outside the floor plan"});
}

TEST_F(ScenarioFiles, NamesTheBaseFileForAnErrorItContains) {
  // Arrange: the base has a negative dt_s, the child only changes the name.
  const std::string base = Write("bad_base.yaml", TinyWithLine(16, "    dt_s: -0.1"));
  const std::string child = Write("good_child.yaml", "extends: bad_base.yaml\nname: child\n");

  // Act
  const std::string message = ErrorOf(child);

  // Assert
  ExpectError(message, base, 16, {"trajectories[0].dt_s"});
}

TEST_F(ScenarioFiles, NamesTheOverridingFileAndLineForAnUnknownKey) {
  const std::string path = Override("unknown_override.yaml", "channel:\n  pulse:\n    durations_s: 1.0e-9\n");
  const std::string message = ErrorOf(path);
  ExpectError(message, path, 4, {"channel.pulse.durations_s", "unknown key"});
}

TEST_F(ScenarioFiles, NamesTheOverridingFileForABadMaterial) {
  const std::string path = Override("bad_material.yaml", "materials:\n  glass: 1.5\n");
  const std::string message = ErrorOf(path);
  ExpectError(message, path, 3, {"materials.glass", "(0, 1]"});
}

}  // namespace
}  // namespace mirage::io
