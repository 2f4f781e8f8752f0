// SPDX-License-Identifier: MIT
// Scenario files in the one schema (docs/scenario.md): the examples load with the values they
// state, every method's options are read through its descriptor, `extends:` merges files (a
// method of another name replaces the base's method section), a grid gives one experiment per
// variant, files in the layout before the one schema are told how to write it now, and every kind
// of bad input throws an InputError whose message names the file, the line (as ":<n>:") and the
// key path (STYLE.md Sec. 9). The grid's own rules are in scenario_grid_test.cc.
#include "mirage/io/scenario.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "io/scenario_errors.h"

#include "mirage/io/input_error.h"
#include "mirage/methods/acoustic/acoustic_options.h"
#include "mirage/methods/coop/coop_tracker.h"
#include "mirage/methods/mint/mint_tracker.h"
#include "mirage/methods/range_ekf/range_ekf.h"
#include "mirage/methods/registry.h"
#include "mirage/methods/slam/slam_tracker.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;
using testing::ErrorOf;
using testing::ExpectError;
using testing::WithLines;
using pipeline::Experiment;
using pipeline::MeasurementModel;

std::string Example(const std::string& name) { return std::string(MIRAGE_SOURCE_DIR) + "/examples/" + name; }

const Experiment& ExperimentOf(const Scenario& s) { return s.variants.front().experiment; }

// The method options the loader bound, as the method's own struct (`method` guards the cast).
template <typename Options>
const Options& OptionsOf(const Experiment& e, std::string_view method) {
  if (e.method.name != method || !e.method.options) {
    throw std::logic_error("the experiment's method is '" + e.method.name + "', not '" + std::string(method) + "'");
  }
  return *static_cast<const Options*>(e.method.options.get());
}

const methods::mint::MintOptions& Mint(const Experiment& e) { return OptionsOf<methods::mint::MintOptions>(e, "mint"); }
const methods::slam::SlamOptions& Slam(const Experiment& e) { return OptionsOf<methods::slam::SlamOptions>(e, "slam"); }
const methods::coop::CoopOptions& Coop(const Experiment& e) { return OptionsOf<methods::coop::CoopOptions>(e, "coop"); }
const methods::range_ekf::RangeEkfOptions& RangeEkf(const Experiment& e) {
  return OptionsOf<methods::range_ekf::RangeEkfOptions>(e, "range_ekf");
}

// A small valid MINT scenario; the line numbers in the comments are the ones the messages give.
const char* const kTiny =
    "name: tiny\n"                                                                          // 1
    "materials:\n"                                                                          // 2
    "  concrete: 0.5\n"                                                                     // 3
    "floor_plan:\n"                                                                         // 4
    "  walls:\n"                                                                            // 5
    "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, material: concrete}\n"  // 6
    "  obstacles:\n"                                                                        // 7
    "    - {center_m: [2.0, 2.0], radius_m: 0.3}\n"                                         // 8
    "anchors:\n"                                                                            // 9
    "  - {id: A1, position_m: [0.5, 3.5]}\n"                                                // 10
    "  - {id: A2, position_m: [3.5, 0.5]}\n"                                                // 11
    "trajectories:\n"                                                                       // 12
    "  - name: walk\n"                                                                      // 13
    "    waypoints_m: [[0.5, 0.5], [0.5, 3.0]]\n"                                           // 14
    "    dt_s: 0.1\n"                                                                       // 15
    "channel:\n"                                                                            // 16
    "  sample_period_s: 0.125e-9\n"                                                         // 17
    "  pulse:\n"                                                                            // 18
    "    duration_s: 0.5e-9\n"                                                              // 19
    "method:\n"                                                                             // 20
    "  name: mint\n"                                                                        // 21
    "  variance:\n"                                                                         // 22
    "    window_min_m: 0.9\n"                                                               // 23
    "    window_max_m: 1.0\n";                                                              // 24

// A small valid cooperative scenario with a grid. Walls: 0-2 the polyline (labelled concrete),
// 3 north, 4 a pin board the filter does not know.
const char* const kCoop =
    "name: coop_room\n"                                                                     // 1
    "seed: 7\n"                                                                             // 2
    "runs: 5\n"                                                                             // 3
    "steps: 50\n"                                                                           // 4
    "agents: 2\n"                                                                           // 5
    "materials:\n"                                                                          // 6
    "  concrete: 0.6\n"                                                                     // 7
    "floor_plan:\n"                                                                         // 8
    "  walls:\n"                                                                            // 9
    "    - {polyline_m: [[0, 4], [0, 0], [6, 0], [6, 4]], material: concrete}\n"            // 10
    "    - {start_m: [6, 4], end_m: [0, 4], label: north}\n"                                // 11
    "    - {start_m: [5, 1], end_m: [5, 2], label: pinboard, in_plan: false}\n"             // 12
    "  obstacles:\n"                                                                        // 13
    "    - {center_m: [1.5, 3.0], radius_m: 0.2}\n"                                         // 14
    "floor_plan_error: {biased_wall: north, bias_m: -0.1, wall_shift_m: 0.002}\n"           // 15
    "trajectories:\n"                                                                       // 16
    "  - {name: a1, waypoints_m: [[1, 1], [2, 1]], speed_mps: 0.02, dt_s: 1.0}\n"           // 17
    "  - {name: a2, waypoints_m: [[4, 2], [4, 1]], dt_s: 1.0}\n"                            // 18
    "  - {name: a3, waypoints_m: [[2, 2], [2.5, 2.5]], speed_mps: 0.01, dt_s: 1.0}\n"       // 19
    "anchors:\n"                                                                            // 20
    "  - {id: A, position_m: [0.5, 0.5]}\n"                                                 // 21
    "channel:\n"                                                                            // 22
    "  max_order: 3\n"                                                                      // 23
    "  self_coupling_db: -30\n"                                                             // 24
    "  window_length_s: 80e-9\n"                                                            // 25
    "  pulse: {rolloff: 0.4, duration_s: 0.5e-9}\n"                                         // 26
    "mpc: {relative_threshold_db: -60}\n"                                                   // 27
    "method:\n"                                                                             // 28
    "  name: coop\n"                                                                        // 29
    "  agent_sigma_m: 0.05\n"                                                               // 30
    "  max_order: 1\n"                                                                      // 31
    "  variance: {window_max_m: 0.3}\n"                                                     // 32
    "  antenna_spacing_m: 0.04\n"                                                           // 33
    "  wall_sigma_m: 0.01\n"                                                                // 34
    "  anchor_links: false\n"                                                               // 35
    "grid:\n"                                                                               // 36
    "  - {agents: [2, 3], method.anchor_links: [false, true]}\n"                            // 37
    "  - {channel.pulse.duration_s: [1.0e-9, 0.5e-9], agents: [2]}\n";                      // 38

std::string TinyWithLine(int line, const std::string& text) { return WithLines(kTiny, {{line, text}}); }

class ScenarioFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("mirage_scenario_test_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
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

  // A file that extends an example and sets the given keys.
  std::string Extend(const std::string& name, const std::string& example, const std::string& text) const {
    return Write(name, "extends: " + Example(example) + "\n" + text);
  }
  std::string Override(const std::string& name, const std::string& text) const {
    return Extend(name, "seminar_room.yaml", text);
  }
  std::string OverrideSlam(const std::string& name, const std::string& text) const {
    return Extend(name, "seminar_room_slam.yaml", text);
  }

  // Writes `base` with the given lines replaced and expects its error at `line` with the fragments.
  void ExpectBad(const std::string& name, const char* base, const std::map<int, std::string>& lines, int line,
                 const std::vector<std::string>& fragments) const {
    const std::string path = Write(name, WithLines(base, lines));
    ExpectError(ErrorOf(path), path, line, fragments);
  }

  fs::path dir_;
};

using CoopScenarioFiles = ScenarioFiles;

// ---------------------------------------------------------------------------------------------
// The examples
// ---------------------------------------------------------------------------------------------

TEST(LoadScenario, ReadsTheSeminarRoomExampleWithTheValuesItStates) {
  // Act
  const Scenario s = LoadScenario(Example("seminar_room.yaml"));
  const Experiment& c = ExperimentOf(s);
  const auto& mint = Mint(c);

  // Assert
  ASSERT_NE(s.method, nullptr);
  EXPECT_EQ(s.method->name, "mint");
  EXPECT_FALSE(s.has_grid());
  ASSERT_EQ(s.variants.size(), 1u);
  EXPECT_EQ(s.variants[0].name, "seminar_room");
  EXPECT_FALSE(s.recording_files.has_value());
  EXPECT_EQ(c.name, "seminar_room");
  EXPECT_EQ(c.seed, 1u);
  EXPECT_EQ(c.runs, 25);
  EXPECT_EQ(c.threads, 0);
  EXPECT_FALSE(c.perturb_initial_position);
  EXPECT_EQ(c.run_grid.nx, 5);
  EXPECT_EQ(c.run_grid.ny, 5);
  EXPECT_DOUBLE_EQ(c.run_grid.spacing_m, 0.01);
  EXPECT_DOUBLE_EQ(c.medium.speed_mps, core::Medium::Radio().speed_mps);
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
  EXPECT_EQ(c.in_plan, std::vector<bool>(29, true));  // the estimator is given every wall
  EXPECT_EQ(c.plan_error.biased_wall, -1);
  EXPECT_DOUBLE_EQ(c.plan_error.wall_shift_m, 0.0);
  ASSERT_EQ(c.anchors.size(), 2u);
  EXPECT_EQ(c.anchors[0].id, "A1");
  EXPECT_EQ(c.anchors[1].id, "A2");
  EXPECT_EQ(c.anchors[0].position_m, Vec3(0.5, 7.0, 0.0));
  EXPECT_EQ(c.anchors[1].position_m, Vec3(5.2, 2.3, 0.0));
  ASSERT_EQ(c.trajectories.size(), 2u);
  EXPECT_EQ(c.trajectories[0].name, "trajectory_1");
  EXPECT_EQ(c.trajectories[0].waypoints_m.size(), 4u);
  EXPECT_EQ(c.trajectories[0].waypoints_m[3], Vec2(3.4, 2.2));
  EXPECT_DOUBLE_EQ(c.trajectories[0].speed_mps, 0.5);
  EXPECT_DOUBLE_EQ(c.trajectories[0].dt_s, 0.1);
  EXPECT_DOUBLE_EQ(c.trajectories[0].height_m, 0.0);
  EXPECT_EQ(c.trajectories[1].name, "trajectory_2");
  EXPECT_EQ(c.trajectories[1].waypoints_m.size(), 5u);
  EXPECT_EQ(c.measurement_model, MeasurementModel::kCir);
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
  EXPECT_EQ(c.method.name, "mint");
  EXPECT_FALSE(c.method.joint);
  EXPECT_EQ(c.method.input, methods::MethodInput::kRangeSets);
  EXPECT_DOUBLE_EQ(c.method.start_sigma_m, 0.1);  // the method's initial_position_sigma_m
  EXPECT_DOUBLE_EQ(mint.cutoff_m, 0.15);
  EXPECT_DOUBLE_EQ(mint.range_sigma_m, 0.07);
  EXPECT_EQ(mint.max_order, 2);
  EXPECT_TRUE(mint.reassociate);
  EXPECT_DOUBLE_EQ(mint.innovation_gate_chi2, 9.0);
  EXPECT_TRUE(mint.constrain_to_room);
  EXPECT_DOUBLE_EQ(mint.motion.accel_sigma_mps2, 1.0);
  EXPECT_TRUE(mint.variance.enabled);
  EXPECT_DOUBLE_EQ(mint.variance.window_min_m, 0.9);
  EXPECT_DOUBLE_EQ(mint.variance.window_max_m, 1.0);
  EXPECT_EQ(mint.variance.min_samples, 15);
  EXPECT_DOUBLE_EQ(mint.variance.default_sigma_m, 0.07);
  EXPECT_DOUBLE_EQ(mint.variance.max_variance_factor, 10.0);
  EXPECT_DOUBLE_EQ(mint.variance.min_sigma_m, 0.01);
  EXPECT_DOUBLE_EQ(mint.variance.overlap_distance_m, 0.15);
  EXPECT_TRUE(mint.relocalization.enabled);
  EXPECT_EQ(mint.relocalization.min_visible, 4);
  EXPECT_EQ(mint.relocalization.lost_steps, 3);
  EXPECT_DOUBLE_EQ(mint.relocalization.search_radius_m, 1.5);
  EXPECT_DOUBLE_EQ(mint.relocalization.found_score, 0.6);
  EXPECT_DOUBLE_EQ(c.divergence.threshold_m, 0.5);
  EXPECT_DOUBLE_EQ(c.divergence.last_fraction, 0.2);
  // The report's copy of the effective options is the same struct.
  EXPECT_NE(c.method.options_json.find("\"cutoff_m\":0.15"), std::string::npos) << c.method.options_json;
}

TEST(LoadScenario, ReadsTheSlamExamplesWithTheValuesTheyState) {
  // Act
  const Scenario anchors_only = LoadScenario(Example("seminar_room_slam.yaml"));
  const Scenario known = LoadScenario(Example("seminar_room_slam_known.yaml"));
  const auto& o = Slam(ExperimentOf(anchors_only));
  const auto& k = Slam(ExperimentOf(known));

  // Assert: the anchors-only example, every key it sets. Most of its values are also the
  // SlamOptions defaults, so only the method, the name, prior_visibility, motion (0.5 against the
  // base file's MINT 1.0) and the known-VA example's own keys below show that a key was read; the
  // rest pins what the example states (README numbers depend on it).
  EXPECT_EQ(anchors_only.method->name, "slam");
  EXPECT_EQ(ExperimentOf(anchors_only).name, "seminar_room_slam");
  EXPECT_DOUBLE_EQ(o.cutoff_m, 0.15);
  EXPECT_EQ(o.prior_max_order, 0);
  EXPECT_FALSE(o.prior_visibility);
  EXPECT_TRUE(o.reassociate);
  EXPECT_DOUBLE_EQ(o.innovation_gate_chi2, 9.0);
  EXPECT_DOUBLE_EQ(o.no_visibility_model_gate_chi2, 4.0);
  EXPECT_DOUBLE_EQ(o.motion.accel_sigma_mps2, 0.5);  // its own, not the base file's MINT 1.0
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
  EXPECT_DOUBLE_EQ(o.max_speed_mps, 1.5);
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

  // The known-VA example extends it: its own keys, the rest inherited (the same method merges).
  EXPECT_EQ(known.method->name, "slam");
  EXPECT_EQ(ExperimentOf(known).name, "seminar_room_slam_known");
  EXPECT_EQ(k.prior_max_order, 2);
  EXPECT_DOUBLE_EQ(k.prior_va_sigma_m, 0.05);
  EXPECT_TRUE(k.prior_visibility);
  EXPECT_FALSE(k.discovery.enabled);
  EXPECT_EQ(k.recovery.min_margin_floor_plan, 4);
  EXPECT_DOUBLE_EQ(k.recovery.floor_plan_watch_s, 1.0);
  EXPECT_DOUBLE_EQ(k.motion.accel_sigma_mps2, 0.5);
  EXPECT_DOUBLE_EQ(k.los_reacquire_m, 0.4);
  EXPECT_EQ(k.recovery.min_margin, 2);
}

TEST(LoadScenario, ReadsTheOneNanosecondExampleAsTheSeminarRoomWithALongerPulse) {
  // Act
  const Experiment base = ExperimentOf(LoadScenario(Example("seminar_room.yaml")));
  const Experiment one_ns = ExperimentOf(LoadScenario(Example("seminar_room_1ns.yaml")));

  // Assert
  EXPECT_EQ(one_ns.name, "seminar_room_1ns");
  EXPECT_DOUBLE_EQ(one_ns.channel.pulse.duration_s, 1.0e-9);
  EXPECT_DOUBLE_EQ(one_ns.channel.pulse.rolloff, base.channel.pulse.rolloff);
  EXPECT_DOUBLE_EQ(one_ns.channel.sample_period_s, base.channel.sample_period_s);
  ASSERT_EQ(one_ns.anchors.size(), base.anchors.size());
  EXPECT_EQ(one_ns.anchors[1].position_m, base.anchors[1].position_m);
  EXPECT_EQ(one_ns.plan.walls().size(), base.plan.walls().size());
  EXPECT_EQ(one_ns.trajectories.size(), base.trajectories.size());
  EXPECT_EQ(Mint(one_ns).relocalization.search_step_m, Mint(base).relocalization.search_step_m);
}

TEST(LoadScenario, ReadsTheRangesExampleWithItsMeasurementModel) {
  const Experiment e = ExperimentOf(LoadScenario(Example("seminar_room_ranges.yaml")));

  EXPECT_EQ(e.measurement_model, MeasurementModel::kRangeLevel);
  EXPECT_DOUBLE_EQ(e.range_level.detection_probability, 0.95);
  EXPECT_DOUBLE_EQ(e.range_level.clutter_rate, 1.0);
  EXPECT_DOUBLE_EQ(e.range_level.min_sinr_db, -10.0);
  EXPECT_DOUBLE_EQ(e.range_level.resolution_m, 0.075);
  EXPECT_DOUBLE_EQ(e.range_level.max_range_sigma_m, 0.22);
  EXPECT_EQ(e.method.name, "mint");
}

TEST(LoadScenario, ReadsTheThreeDimensionalRangingExample) {
  const Scenario s = LoadScenario(Example("rtls_room_3d.yaml"));
  const Experiment& e = ExperimentOf(s);

  EXPECT_EQ(s.method->name, "range_ekf");
  EXPECT_TRUE(e.plan.walls().empty());  // no floor plan
  EXPECT_TRUE(e.in_plan.empty());
  EXPECT_EQ(e.measurement_model, MeasurementModel::kRanging);
  EXPECT_DOUBLE_EQ(e.ranging.range_sigma_m, 0.1);
  EXPECT_DOUBLE_EQ(e.ranging.detection_probability, 1.0);
  EXPECT_DOUBLE_EQ(e.ranging.clutter_rate, 0.0);
  EXPECT_FALSE(e.ranging.multipath);
  ASSERT_EQ(e.anchors.size(), 4u);
  EXPECT_EQ(e.anchors[2].position_m, Vec3(7.7, 5.7, 2.9));
  ASSERT_EQ(e.trajectories.size(), 2u);
  EXPECT_DOUBLE_EQ(e.trajectories[0].height_m, 0.6);
  EXPECT_DOUBLE_EQ(e.trajectories[1].speed_mps, 1.2);
  EXPECT_EQ(RangeEkf(e).mode, "3d");
  EXPECT_DOUBLE_EQ(e.divergence.threshold_m, 0.5);
}

TEST(LoadScenario, ReadsTheHoldoutExampleWithAWallTheEstimatorIsNotGiven) {
  const Experiment e = ExperimentOf(LoadScenario(Example("slam_holdout.yaml")));

  ASSERT_EQ(e.plan.walls().size(), 4u);
  EXPECT_EQ(e.in_plan, std::vector<bool>(4, false));
  EXPECT_EQ(e.measurement_model, MeasurementModel::kRanging);
  EXPECT_TRUE(e.ranging.multipath);
  EXPECT_DOUBLE_EQ(e.ranging.max_range_m, 30.0);
  EXPECT_EQ(e.channel_max_order, 1);
  EXPECT_EQ(e.run_grid.nx, 1);
  EXPECT_FALSE(Slam(e).prior_visibility);
}

TEST(LoadScenario, ReadsTheCoopRoomExampleWithOneExperimentPerGridVariant) {
  const Scenario s = LoadScenario(Example("coop_room.yaml"));

  ASSERT_EQ(s.method->name, "coop");
  EXPECT_TRUE(s.has_grid());
  // 6 + 2 + 6 + 1 + 3: the second entry's 0.5 ns and the fifth entry's 3 mm repeat earlier variants.
  ASSERT_EQ(s.variants.size(), 18u);
  EXPECT_EQ(s.variants[0].name, "agents=2, method.anchor_links=false");
  EXPECT_EQ(s.variants[5].name, "agents=4, method.anchor_links=true");
  EXPECT_EQ(s.variants[6].name, "channel.pulse.duration_s=1.0e-9");
  EXPECT_EQ(s.variants[17].name, "floor_plan_error.bias_m=0.1, method.wall_sigma_m=0.01");
  for (const auto& v : s.variants) {
    const Experiment& e = v.experiment;
    EXPECT_EQ(e.name, "coop_room") << v.name;
    EXPECT_TRUE(e.method.joint) << v.name;
    EXPECT_EQ(e.method.input, methods::MethodInput::kLinkCirs) << v.name;
    EXPECT_EQ(e.trajectories.size(), 4u) << v.name;
    EXPECT_EQ(e.steps, 200) << v.name;
    EXPECT_EQ(e.in_plan.size(), e.plan.walls().size()) << v.name;
    EXPECT_EQ(e.plan.walls()[static_cast<std::size_t>(e.plan_error.biased_wall)].label, "door_south") << v.name;
    EXPECT_DOUBLE_EQ(Coop(e).antenna_spacing_m, 0.05) << v.name;
  }
  EXPECT_EQ(s.variants[5].experiment.agents, 4);
  EXPECT_TRUE(Coop(s.variants[5].experiment).anchor_links);
  EXPECT_DOUBLE_EQ(s.variants[6].experiment.channel.pulse.duration_s, 1.0e-9);
  EXPECT_EQ(s.variants[6].experiment.agents, 2);
  EXPECT_DOUBLE_EQ(s.variants[17].experiment.plan_error.bias_m, 0.1);
  EXPECT_DOUBLE_EQ(Coop(s.variants[17].experiment).wall_sigma_m, 0.01);
  EXPECT_TRUE(Coop(s.variants[17].experiment).wall_update);
}

TEST(LoadScenario, ReadsTheRecordedExampleWithItsFiles) {
  const Scenario s = LoadScenario(Example("recorded/scenario.yaml"));
  const Experiment& e = ExperimentOf(s);

  ASSERT_TRUE(s.recording_files.has_value());
  EXPECT_EQ(s.recording_files->anchors, Example("recorded/anchors.csv"));
  EXPECT_EQ(s.recording_files->ranges, Example("recorded/ranges.csv"));
  ASSERT_TRUE(s.recording_files->truth.has_value());
  EXPECT_EQ(*s.recording_files->truth, Example("recorded/truth.csv"));
  EXPECT_EQ(e.measurement_model, MeasurementModel::kRecorded);
  ASSERT_NE(e.recording, nullptr);
  EXPECT_FALSE(e.recording->steps.empty());
  EXPECT_EQ(e.runs, 1);
  ASSERT_EQ(e.anchors.size(), 2u);  // from anchors.csv
  EXPECT_EQ(e.anchors[0].id, "A1");
  EXPECT_TRUE(e.trajectories.empty());
  ASSERT_TRUE(e.recorded_speed_mps.has_value());
  EXPECT_DOUBLE_EQ(*e.recorded_speed_mps, 0.5);
  EXPECT_FALSE(e.recorded_range_sigma_m.has_value());
  EXPECT_EQ(s.method->name, "mint");
}

TEST(LoadScenario, ReadsTheRecordedAcousticExampleWithItsStampsAndPhysicalKeys) {
  const Scenario s = LoadScenario(Example("recorded_acoustic/scenario.yaml"));
  const Experiment& e = ExperimentOf(s);

  ASSERT_TRUE(s.recording_files.has_value());
  EXPECT_TRUE(s.recording_files->toa_stamps());
  EXPECT_EQ(s.recording_files->mics, Example("recorded_acoustic/mics.csv"));
  EXPECT_EQ(s.recording_files->toa, Example("recorded_acoustic/toa.csv"));
  ASSERT_NE(e.recording, nullptr);
  EXPECT_TRUE(e.recording->toa_stamps);
  ASSERT_EQ(e.anchors.size(), 8u);  // the microphones, from mics.csv
  EXPECT_EQ(e.anchors[7].position_m, Vec3(0.6, 4.5, 3.3));
  ASSERT_FALSE(e.recording->steps.empty());
  EXPECT_EQ(e.recording->steps.front().toas.size(), 8u);
  EXPECT_EQ(e.recorded_height_m, 1.3);
  // The physical keys as a simulation derives them: a stamp's noise as a range at the assumed
  // speed of sound, the stated emission interval (not the median between earliest stamps).
  const core::PhysicalKeys keys = pipeline::PhysicalKeysOf(e);
  ASSERT_TRUE(keys.range_sigma_m && keys.dt_s && keys.speed_mps && keys.detection_probability && keys.clutter_rate);
  EXPECT_EQ(*keys.range_sigma_m, e.medium.speed_mps * 0.15e-3);
  EXPECT_EQ(*keys.dt_s, 0.15);
  EXPECT_EQ(*keys.speed_mps, 1.0);
  EXPECT_EQ(*keys.detection_probability, 0.9);
  EXPECT_EQ(*keys.clutter_rate, 1.0);
  const auto& options = OptionsOf<methods::acoustic::AcousticOptions>(e, "acoustic");
  EXPECT_EQ(options.range_sigma_m, *keys.range_sigma_m);
  EXPECT_EQ(options.emission_interval_s, 0.15);
}

TEST_F(ScenarioFiles, RejectsRecordedStampsMixedWithRangesOrLackingTheirKeys) {
  const std::string mics = Example("recorded_acoustic/mics.csv");
  const std::string toa = Example("recorded_acoustic/toa.csv");
  const std::string head = "name: s\nmedium: {kind: sound}\nmethod: {name: acoustic}\nmeasurements:\n  model: recorded\n";
  const auto load = [&](const std::string& name, const std::string& keys) { return ErrorOf(Write(name, head + keys)); };
  ExpectError(load("mixed.yaml", "  mics: " + mics + "\n  toa: " + toa + "\n  height_m: 1\n  anchors: a.csv\n"), "mixed.yaml", 9,
              {"measurements.anchors: a recording has either anchors and ranges"});
  ExpectError(load("no_toa.yaml", "  mics: " + mics + "\n  height_m: 1\n"), "no_toa.yaml", 0,
              {"measurements.toa: missing", "needs both mics (mics.csv) and toa (toa.csv)"});
  ExpectError(load("sigma.yaml", "  mics: " + mics + "\n  toa: " + toa + "\n  height_m: 1\n  range_sigma_m: 0.1\n"),
              "sigma.yaml", 9, {"measurements.range_sigma_m: not used with toa", "stamp_sigma_s"});
  ExpectError(load("stamp_keys.yaml", "  anchors: a.csv\n  ranges: r.csv\n  stamp_sigma_s: 0.001\n"), "stamp_keys.yaml", 8,
              {"measurements.stamp_sigma_s: only for a recording of arrival-time stamps"});
}

TEST(LoadScenario, AppliesCommandLineOverridesToEveryVariant) {
  // Arrange
  ScenarioOverrides overrides;
  overrides.runs = 3;
  overrides.seed = 77;
  overrides.threads = 2;

  // Act
  const Scenario plain = LoadScenario(Example("seminar_room.yaml"), overrides);
  const Scenario grid = LoadScenario(Example("coop_room.yaml"), overrides);

  // Assert
  EXPECT_EQ(ExperimentOf(plain).runs, 3);
  EXPECT_EQ(ExperimentOf(plain).seed, 77u);
  EXPECT_EQ(ExperimentOf(plain).threads, 2);
  for (const auto& v : grid.variants) {
    EXPECT_EQ(v.experiment.runs, 3) << v.name;
    EXPECT_EQ(v.experiment.seed, 77u) << v.name;
    EXPECT_EQ(v.experiment.threads, 2) << v.name;
  }
}

TEST(LoadScenario, RejectsInvalidCommandLineOverrides) {
  ScenarioOverrides runs;
  runs.runs = 0;
  ScenarioOverrides threads;
  threads.threads = -1;
  ScenarioOverrides recorded_runs;
  recorded_runs.runs = 2;
  EXPECT_NE(ErrorOf(Example("seminar_room.yaml"), runs).find("--runs: 0 is out of range"), std::string::npos);
  EXPECT_NE(ErrorOf(Example("coop_room.yaml"), runs).find("--runs"), std::string::npos);
  EXPECT_NE(ErrorOf(Example("seminar_room.yaml"), threads).find("--threads: -1 is out of range"), std::string::npos);
  EXPECT_NE(ErrorOf(Example("recorded/scenario.yaml"), recorded_runs).find("--runs: recorded data are one run"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Small files: what the schema reads
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, RejectsAKnownSendingTimeWithoutEmissionTimesInTheRecords) {
  // examples/acoustic_height.yaml's "known" variants read the emission times the simulator
  // writes into the records; without them the fixer would find no sending time at any emission.
  const std::string without = Write("no_emission_times.yaml", "extends: " + Example("acoustic_height.yaml") +
                                                               "\nmeasurements: {emission_time_known: false}\n");
  ExpectError(ErrorOf(without), "acoustic_height.yaml", 0,
              {"method.ground_echo.sending_time", "'known' needs the emission times", "emission_time_known: true"});
  EXPECT_NO_THROW(LoadScenario(Example("acoustic_height.yaml")));
}

TEST(ScenarioDocument, StaysIntactAfterTheGridIsExpanded) {
  // `mirage simulate` writes its recorded scenario from the document; the grid's variants share
  // and rearrange its nodes, after which yaml-cpp 0.7 crashed emitting it (the loader now keeps
  // a deep copy).
  const Scenario scenario = LoadScenario(Example("uwb_tdoa_3d.yaml"));
  ASSERT_TRUE(scenario.has_grid());
  YAML::Emitter out;
  out << scenario.document;
  const std::string text = out.c_str();
  EXPECT_NE(text.find("grid"), std::string::npos);
  EXPECT_NE(text.find("update: rekf"), std::string::npos) << "the base value, not a variant's";
}

TEST_F(ScenarioFiles, LoadsTheTinyScenarioWithDefaultsForWhatItLeavesOut) {
  // The bad-input variants below change one line of this file; it must be valid itself.
  const Scenario s = LoadScenario(Write("tiny.yaml", kTiny));
  const Experiment& e = ExperimentOf(s);

  EXPECT_EQ(e.name, "tiny");
  EXPECT_EQ(e.plan.walls().size(), 4u);
  EXPECT_EQ(e.anchors.size(), 2u);
  EXPECT_EQ(e.trajectories[0].waypoints_m[1], Vec2(0.5, 3.0));
  EXPECT_EQ(e.runs, 25);
  EXPECT_EQ(e.seed, 1u);
  EXPECT_DOUBLE_EQ(e.trajectories[0].speed_mps, 0.5);
  EXPECT_EQ(e.measurement_model, MeasurementModel::kCir);
  EXPECT_EQ(e.channel_max_order, 2);
  EXPECT_DOUBLE_EQ(e.map_cutoff_m, 0.5);
  EXPECT_DOUBLE_EQ(e.plan.floor_z_m(), 0.0);
  EXPECT_EQ(e.plan.ceiling_z_m(), geometry::kNoCeiling_m);
  EXPECT_DOUBLE_EQ(Mint(e).cutoff_m, methods::mint::MintOptions{}.cutoff_m);
  EXPECT_DOUBLE_EQ(Mint(e).variance.window_min_m, 0.9);
}

TEST_F(ScenarioFiles, ReadsEveryMethodsOptionsThroughItsDescriptor) {
  // One non-default value of each method, nested sections included.
  const std::string mint = Write("mint.yaml", WithLines(kTiny, {{22, "  relocalization: {search_step_m: 0.2}"},
                                                               {23, "  motion: {accel_sigma_mps2: 2.5}"},
                                                               {24, ""}}));
  const std::string slam =
      Write("slam.yaml", WithLines(kTiny, {{21, "  name: slam"}, {22, "  discovery:"}, {23, "    sweep: {gate_m: 0.03}"},
                                           {24, "  prior_visibility: false"}}));
  const std::string ekf = Write("ekf.yaml", WithLines(kTiny, {{21, "  name: range_ekf"}, {22, "  mode: planar"},
                                                              {23, "  gate_chi2: 16"}, {24, ""}}));

  EXPECT_DOUBLE_EQ(Mint(ExperimentOf(LoadScenario(mint))).relocalization.search_step_m, 0.2);
  EXPECT_DOUBLE_EQ(Mint(ExperimentOf(LoadScenario(mint))).motion.accel_sigma_mps2, 2.5);
  EXPECT_DOUBLE_EQ(Slam(ExperimentOf(LoadScenario(slam))).discovery.sweep.gate_m, 0.03);
  EXPECT_FALSE(Slam(ExperimentOf(LoadScenario(slam))).prior_visibility);
  EXPECT_EQ(RangeEkf(ExperimentOf(LoadScenario(ekf))).mode, "planar");
  EXPECT_DOUBLE_EQ(RangeEkf(ExperimentOf(LoadScenario(ekf))).gate_chi2, 16.0);
}

TEST_F(ScenarioFiles, ReadsTheSweepKeys) {
  // Every value differs from its default, so each key must have been read.
  const std::string path = OverrideSlam("sweep.yaml",
                                         "method:\n  discovery:\n    sweep:\n      enabled: false\n"
                                         "      window_s: 4.0\n      every_steps: 10\n"
                                         "      min_baseline_m: 1.5\n      gate_m: 0.03\n"
                                         "      min_support_fraction: 0.7\n");
  const Scenario scenario = LoadScenario(path);  // kept: the options live in it
  const auto& sweep = Slam(ExperimentOf(scenario)).discovery.sweep;
  EXPECT_FALSE(sweep.enabled);
  EXPECT_DOUBLE_EQ(sweep.window_s, 4.0);
  EXPECT_EQ(sweep.every_steps, 10);
  EXPECT_DOUBLE_EQ(sweep.min_baseline_m, 1.5);
  EXPECT_DOUBLE_EQ(sweep.gate_m, 0.03);
  EXPECT_DOUBLE_EQ(sweep.min_support_fraction, 0.7);
}

TEST_F(ScenarioFiles, ReadsTheSlamGateAndVarianceKeys) {
  // Every value differs from its default and from the others, so each key must have been read
  // into its own option.
  const std::string path = OverrideSlam("gates.yaml",
                                         "method:\n  innovation_gate_chi2: 6\n  no_visibility_model_gate_chi2: 2.5\n"
                                         "  amplitude_gate_probability: 0.01\n  blocked_amplitude_probability: 0.2\n"
                                         "  nis_window_updates: 7\n  discovered_va_walk_m_per_sqrt_s: 0.004\n"
                                         "  startup_amplitude_k_factor: 3\n");
  const Scenario scenario = LoadScenario(path);  // kept: the options live in it
  const auto& slam = Slam(ExperimentOf(scenario));
  EXPECT_DOUBLE_EQ(slam.innovation_gate_chi2, 6.0);
  EXPECT_DOUBLE_EQ(slam.no_visibility_model_gate_chi2, 2.5);
  EXPECT_DOUBLE_EQ(slam.amplitude_gate_probability, 0.01);
  EXPECT_DOUBLE_EQ(slam.blocked_amplitude_probability, 0.2);
  EXPECT_EQ(slam.nis_window_updates, 7);
  EXPECT_DOUBLE_EQ(slam.discovered_va_walk_m_per_sqrt_s, 0.004);
  EXPECT_DOUBLE_EQ(slam.startup_amplitude_k_factor, 3.0);
}

TEST_F(ScenarioFiles, ReadsTheRecoverySpeedLimitAndNamesABadOne) {
  const std::string good = OverrideSlam("speed.yaml", "method:\n  recovery:\n    max_speed_mps: 2.5\n");
  EXPECT_DOUBLE_EQ(Slam(ExperimentOf(LoadScenario(good))).recovery.max_speed_mps, 2.5);
  const std::string path = OverrideSlam("speed_bad.yaml", "method:\n  recovery:\n    max_speed_mps: 0\n");
  ExpectError(ErrorOf(path), path, 4, {"method.recovery.max_speed_mps", "out of range"});
}

TEST_F(ScenarioFiles, ReadsTheMediumTheFloorPlanHeightsAndThreeDimensionalAnchors) {
  const std::string path = Write("heights.yaml", WithLines(kTiny, {{1, "name: tiny\nmedium: {kind: radio}"},
                                                                   {5, "  floor_z_m: -0.5\n  ceiling_z_m: 2.5\n  walls:"},
                                                                   {10, "  - {id: A1, position_m: [0.5, 3.5, 1.2]}"},
                                                                   {11, "  - {id: A2, position_m: [3.5, 0.5, 1.2]}"},
                                                                   {15, "    dt_s: 0.1\n    height_m: 1.2"}}));

  const Experiment e = ExperimentOf(LoadScenario(path));

  EXPECT_DOUBLE_EQ(e.medium.speed_mps, core::Medium::Radio().speed_mps);
  EXPECT_DOUBLE_EQ(e.channel.medium.speed_mps, e.medium.speed_mps);
  EXPECT_DOUBLE_EQ(e.plan.floor_z_m(), -0.5);
  EXPECT_DOUBLE_EQ(e.plan.ceiling_z_m(), 2.5);
  EXPECT_EQ(e.anchors[0].position_m, Vec3(0.5, 3.5, 1.2));
  EXPECT_DOUBLE_EQ(e.trajectories[0].height_m, 1.2);
}

TEST_F(ScenarioFiles, ReadsInPlanFlagsForEveryMethod) {
  // A MINT scenario whose plan lacks an inner wall the signals reflect on.
  const std::string path =
      Write("in_plan.yaml", TinyWithLine(6, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true}\n"
                                            "    - {start_m: [3.0, 2.5], end_m: [3.0, 3.5], in_plan: false}"));

  const Experiment e = ExperimentOf(LoadScenario(path));

  EXPECT_EQ(e.in_plan, (std::vector<bool>{true, true, true, true, false}));
}

TEST_F(ScenarioFiles, ReadsAScenarioWithoutFloorPlan) {
  const std::string path = Write("no_plan.yaml",
                                 "name: open\n"
                                 "anchors: [{id: A, position_m: [0, 0, 3]}, {id: B, position_m: [9, 0, 3]},"
                                 " {id: C, position_m: [0, 9, 3]}]\n"
                                 "trajectories: [{name: t, waypoints_m: [[1, 1], [5, 5]], speed_mps: 1}]\n"
                                 "measurements: {model: ranging, range_sigma_m: 0.2}\n"
                                 "method: {name: range_ekf}\n");

  const Experiment e = ExperimentOf(LoadScenario(path));

  EXPECT_TRUE(e.plan.walls().empty());
  EXPECT_DOUBLE_EQ(e.ranging.range_sigma_m, 0.2);
  EXPECT_EQ(e.anchors.size(), 3u);
}

TEST_F(ScenarioFiles, ReadsTheEvaluationSection) {
  const std::string path =
      Override("evaluation.yaml", "evaluation:\n  map_cutoff_m: 0.3\n  divergence: {threshold_m: 1.0, last_fraction: 0.5}\n");

  const Experiment e = ExperimentOf(LoadScenario(path));

  EXPECT_DOUBLE_EQ(e.map_cutoff_m, 0.3);
  EXPECT_DOUBLE_EQ(e.divergence.threshold_m, 1.0);
  EXPECT_DOUBLE_EQ(e.divergence.last_fraction, 0.5);
}

TEST_F(ScenarioFiles, ReadsAJointMethodsAgentsAndSteps) {
  const std::string path = Write("coop.yaml", WithLines(kCoop, {{36, ""}, {37, ""}, {38, ""}}));

  const Scenario s = LoadScenario(path);

  EXPECT_FALSE(s.has_grid());
  EXPECT_EQ(ExperimentOf(s).agents, 2);
  EXPECT_EQ(ExperimentOf(s).steps, 50);
}

// ---------------------------------------------------------------------------------------------
// extends
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, MergesAFileOverTheOneItExtends) {
  // Arrange: the child changes a nested number, the name, adds runs, replaces the anchor list and
  // sets one method option.
  Write("base.yaml", kTiny);
  const std::string child = Write("variants/child.yaml",
                                  "extends: ../base.yaml\n"
                                  "name: child\n"
                                  "runs: 4\n"
                                  "channel:\n"
                                  "  pulse:\n"
                                  "    duration_s: 1.0e-9\n"
                                  "anchors:\n"
                                  "  - {id: B, position_m: [3.0, 3.0]}\n"
                                  "method:\n"
                                  "  variance: {window_max_m: 1.2}\n");

  // Act
  const Scenario s = LoadScenario(child);
  const Experiment& e = ExperimentOf(s);

  // Assert
  EXPECT_EQ(s.file, child);
  EXPECT_EQ(e.name, "child");
  EXPECT_EQ(e.runs, 4);
  EXPECT_DOUBLE_EQ(e.channel.pulse.duration_s, 1.0e-9);
  EXPECT_DOUBLE_EQ(e.channel.sample_period_s, 0.125e-9);  // sibling key from the base
  ASSERT_EQ(e.anchors.size(), 1u);                        // lists are replaced
  EXPECT_EQ(e.anchors[0].id, "B");
  EXPECT_EQ(e.trajectories.size(), 1u);
  EXPECT_EQ(s.method->name, "mint");  // the method's name from the base
  EXPECT_DOUBLE_EQ(Mint(e).variance.window_max_m, 1.2);
  EXPECT_DOUBLE_EQ(Mint(e).variance.window_min_m, 0.9);  // the same method's sections merge
}

TEST_F(ScenarioFiles, ReplacesTheBasesMethodSectionWhenExtendingWithAnotherMethod) {
  // Arrange: the base's MINT relocalization is no SLAM key; merged, it would be an unknown key.
  Write("base.yaml", WithLines(kTiny, {{22, "  relocalization: {search_step_m: 0.2}"}, {23, ""}, {24, ""}}));
  const std::string child = Write("slam.yaml", "extends: base.yaml\nmethod:\n  name: slam\n  prior_visibility: false\n");

  // Act
  const Scenario s = LoadScenario(child);

  // Assert
  EXPECT_EQ(s.method->name, "slam");
  EXPECT_FALSE(Slam(ExperimentOf(s)).prior_visibility);
  EXPECT_DOUBLE_EQ(Slam(ExperimentOf(s)).cutoff_m, methods::slam::SlamOptions{}.cutoff_m);
}

TEST_F(ScenarioFiles, FollowsAChainOfExtends) {
  // Arrange
  Write("a.yaml", kTiny);
  Write("b.yaml", "extends: a.yaml\nruns: 7\n");
  const std::string c = Write("c.yaml", "extends: b.yaml\nseed: 9\n");

  // Act
  const Experiment e = ExperimentOf(LoadScenario(c));

  // Assert
  EXPECT_EQ(e.runs, 7);
  EXPECT_EQ(e.seed, 9u);
  EXPECT_EQ(e.name, "tiny");
}

TEST_F(ScenarioFiles, DetectsACycleOfExtends) {
  const std::string a = Write("cycle_a.yaml", "extends: cycle_b.yaml\nname: a\n");
  Write("cycle_b.yaml", "extends: cycle_a.yaml\nname: b\n");
  ExpectError(ErrorOf(a), "cycle_", 0, {"extends", "cycle"});
}

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
  const std::string base = Write("bad_base.yaml", TinyWithLine(15, "    dt_s: -0.1"));
  const std::string child = Write("good_child.yaml", "extends: bad_base.yaml\nname: child\n");

  // Act
  const std::string message = ErrorOf(child);

  // Assert
  ExpectError(message, base, 15, {"trajectories[0].dt_s"});
}

TEST_F(ScenarioFiles, NamesTheOverridingFileAndLineForAnUnknownKey) {
  const std::string path = Override("unknown_override.yaml", "channel:\n  pulse:\n    durations_s: 1.0e-9\n");
  ExpectError(ErrorOf(path), path, 4, {"channel.pulse.durations_s", "unknown key"});
}

TEST_F(ScenarioFiles, NamesTheOverridingFileForABadMaterial) {
  const std::string path = Override("bad_material.yaml", "materials:\n  glass: 1.5\n");
  ExpectError(ErrorOf(path), path, 3, {"materials.glass", "(0, 1]"});
}

TEST_F(ScenarioFiles, NamesTheFileOfTheGridForABadValueItSets) {
  // The key's base value is in the example; the bad value, and so the message, in this file.
  const std::string path = Override("bad_grid_value.yaml", "grid:\n  - trajectories[1].speed_mps: [0.5, -1]\n");
  ExpectError(ErrorOf(path), path, 3, {"trajectories[1].speed_mps", "-1 m/s must be > 0 m/s"});
}

TEST_F(ScenarioFiles, NamesTheOverridingFileForABadMethodOption) {
  const std::string path = Override("bad_method.yaml", "method:\n  motion:\n    accel_sigma_mps2: 0\n");
  ExpectError(ErrorOf(path), path, 4, {"method.motion.accel_sigma_mps2", "out of range"});
}

// ---------------------------------------------------------------------------------------------
// Files in the layout before the one schema: how to write them now
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, TellsAFileWithTheMethodAsAStringHowToWriteItNow) {
  const std::string path = Write("string.yaml", WithLines(kTiny, {{20, "method: mint"}, {21, "mint:"}}));
  ExpectError(ErrorOf(path), path, 20, {"method: the scenario layout changed", "method: {name: mint, ...}"});
}

TEST_F(ScenarioFiles, TellsAFileWithATopLevelMethodSectionHowToWriteItNow) {
  for (const std::string method : {"mint", "slam", "coop"}) {
    SCOPED_TRACE(method);
    const std::string path = Write(method + ".yaml", WithLines(kTiny, {{20, method + ":"}, {21, "  cutoff_m: 0.1"}}));
    // The line of the section's value (its first key), as for every value.
    ExpectError(ErrorOf(path), path, 21,
                {method + ": the scenario layout changed", "method: {name: " + method + ", ...}", "top-level `" + method + ":`"});
  }
}

TEST_F(ScenarioFiles, TellsAFileWithVariantsHowToWriteItsGridNow) {
  const std::string variants = Write("variants.yaml", std::string(kTiny) + "variants:\n  - {agents: [2, 3]}\n");
  const std::string defaults = Write("defaults.yaml", std::string(kTiny) + "variant_defaults: {wall_sigma_mm: 3}\n");
  ExpectError(ErrorOf(variants), variants, 26, {"variants: the scenario layout changed", "grid:"});
  ExpectError(ErrorOf(defaults), defaults, 25, {"variant_defaults: the scenario layout changed", "grid:"});
}

TEST_F(ScenarioFiles, TellsAFileWithTheOtherFormerKeysHowToWriteThemNow) {
  const std::string agents =
      Write("agents.yaml", std::string(kTiny) + "agents:\n  - {name: a1, waypoints_m: [[1, 1], [2, 1]]}\n");
  const std::string anchor = Write("anchor.yaml", std::string(kTiny) + "anchor: {id: A, position_m: [1, 1]}\n");
  const std::string bias = Write("bias.yaml", std::string(kTiny) + "wall_bias: {wall: north, offset_m: 0.1}\n");
  const std::string spacing = Write("spacing.yaml", std::string(kTiny) + "antenna_spacing_m: 0.04\n");
  ExpectError(ErrorOf(agents), agents, 26, {"agents: the scenario layout changed", "trajectories:"});
  ExpectError(ErrorOf(anchor), anchor, 25, {"anchor: the scenario layout changed", "anchors:"});
  ExpectError(ErrorOf(bias), bias, 25, {"wall_bias: the scenario layout changed", "floor_plan_error:"});
  ExpectError(ErrorOf(spacing), spacing, 25, {"antenna_spacing_m: the scenario layout changed", "method.antenna_spacing_m"});
}

TEST_F(ScenarioFiles, TellsAFileThatExtendsAnOldOneHowToWriteItNow) {
  // The old layout is found in the merged document, so a file that changes one key of an old base
  // is told too (naming the base, which holds the old section).
  const std::string base = Write("old_base.yaml", WithLines(kTiny, {{20, "mint:"}, {21, "  cutoff_m: 0.1"}}));
  const std::string child = Write("child.yaml", "extends: old_base.yaml\nruns: 3\n");
  ExpectError(ErrorOf(child), base, 21, {"mint: the scenario layout changed"});
}

// ---------------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, NamesTheMissingFile) {
  const std::string path = (dir_ / "nowhere.yaml").string();
  ExpectError(ErrorOf(path), "nowhere.yaml", 0, {"file not found"});
}

TEST_F(ScenarioFiles, NamesTheLineOfAYamlSyntaxError) {
  // Line 14's flow sequence is never closed; yaml-cpp notices on the next line.
  const std::string path = Write("syntax.yaml", TinyWithLine(14, "    waypoints_m: [[0.5, 0.5], [0.5, 3.0]"));
  const std::string message = ErrorOf(path);
  ExpectError(message, path, 0, {"YAML syntax error"});
  EXPECT_TRUE(message.find(path + ":14:") != std::string::npos || message.find(path + ":15:") != std::string::npos)
      << message;
}

TEST_F(ScenarioFiles, NamesAMissingName) {
  const std::string path = Write("no_name.yaml", TinyWithLine(1, ""));
  ExpectError(ErrorOf(path), path, 0, {"name", "missing (required)"});
}

TEST_F(ScenarioFiles, NamesAMissingMethodAndAMethodWithoutName) {
  const std::string none = Write("no_method.yaml", WithLines(kTiny, {{20, ""}, {21, ""}, {22, ""}, {23, ""}, {24, ""}}));
  const std::string nameless = Write("nameless.yaml", TinyWithLine(21, ""));
  ExpectError(ErrorOf(none), none, 0, {"method: missing (required)"});
  ExpectError(ErrorOf(nameless), nameless, 21, {"method.name: missing (required)"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMethodWithTheKnownOnes) {
  const std::string path = Write("method.yaml", TinyWithLine(21, "  name: magic"));
  ExpectError(ErrorOf(path), path, 21, {"method.name", "unknown method 'magic'", "mint, slam, coop, range_ekf"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMethodOptionWithTheKnownOnes) {
  const std::string path = Write("option.yaml", TinyWithLine(22, "  cutof_m: 0.1\n  variance:"));
  ExpectError(ErrorOf(path), path, 22, {"method.cutof_m", "unknown key", "cutoff_m", "relocalization"});
}

TEST_F(ScenarioFiles, NamesAnotherMethodsOptionAsUnknown) {
  // relocalization is MINT's: for SLAM it is an unknown key, not silently ignored.
  const std::string path = Write("other.yaml", WithLines(kTiny, {{21, "  name: slam"}, {22, "  relocalization: {enabled: false}"},
                                                                 {23, ""}, {24, ""}}));
  ExpectError(ErrorOf(path), path, 22, {"method.relocalization", "unknown key"});
}

TEST_F(ScenarioFiles, NamesAnUnknownTopLevelKey) {
  const std::string path = Write("top_typo.yaml", TinyWithLine(1, "name: tiny\nsed: 3"));
  ExpectError(ErrorOf(path), path, 2, {"sed", "unknown key"});
}

TEST_F(ScenarioFiles, NamesAnUnknownNestedKeyWithItsPath) {
  const std::string path = Write("nested_typo.yaml", TinyWithLine(19, "    durations_s: 0.5e-9"));
  ExpectError(ErrorOf(path), path, 19, {"channel.pulse.durations_s", "unknown key", "duration_s"});
}

TEST_F(ScenarioFiles, NamesABadMotionKeyOfEitherTrackerWithItsPath) {
  const std::string mint_path = Override("mint_motion.yaml", "method:\n  motion:\n    accel_sigma_mps2: 0\n");
  ExpectError(ErrorOf(mint_path), mint_path, 4, {"method.motion.accel_sigma_mps2"});
  const std::string slam_path = OverrideSlam("slam_motion.yaml", "method:\n  motion:\n    accel_sigma: 0.5\n");
  ExpectError(ErrorOf(slam_path), slam_path, 4, {"method.motion.accel_sigma", "unknown key", "accel_sigma_mps2"});
}

TEST_F(ScenarioFiles, NamesABadSlamGateWithItsPathAndLine) {
  const std::string path = OverrideSlam("gates_bad.yaml", "method:\n  no_visibility_model_gate_chi2: -1\n");
  ExpectError(ErrorOf(path), path, 3, {"method.no_visibility_model_gate_chi2", "out of range"});
}

TEST_F(ScenarioFiles, NamesABadSweepKeyWithItsPathAndLine) {
  const std::string path =
      OverrideSlam("sweep_bad.yaml", "method:\n  discovery:\n    sweep:\n      min_support_fraction: 1.5\n");
  ExpectError(ErrorOf(path), path, 5, {"method.discovery.sweep.min_support_fraction", "out of range"});
}

TEST_F(ScenarioFiles, NamesAWindowMaxBelowWindowMin) {
  const std::string path = Write("window.yaml", TinyWithLine(24, "    window_max_m: 0.5"));
  ExpectError(ErrorOf(path), path, 24, {"method.variance.window_max_m", "window_min_m"});
}

TEST_F(ScenarioFiles, NamesAMethodOrderTooHighForThePlan) {
  // 4 walls: order 6 is fine for the counting, so use the seminar room's 29.
  const std::string path = Override("order.yaml", "method:\n  max_order: 6\n");
  ExpectError(ErrorOf(path), path, 3, {"method.max_order", "virtual anchors per anchor"});
}

TEST_F(ScenarioFiles, NamesAZeroLengthWall) {
  const std::string path =
      Write("zero_wall.yaml", TinyWithLine(6, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true}\n"
                                              "    - {start_m: [1.0, 1.0], end_m: [1.0, 1.0]}"));
  ExpectError(ErrorOf(path), path, 7, {"floor_plan.walls[1].end_m", "zero length"});
}

TEST_F(ScenarioFiles, NamesACeilingBelowTheFloor) {
  const std::string path = Write("ceiling.yaml", TinyWithLine(5, "  floor_z_m: 2\n  ceiling_z_m: 1\n  walls:"));
  ExpectError(ErrorOf(path), path, 6, {"floor_plan.ceiling_z_m", "above floor_z_m"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMedium) {
  const std::string path = Write("medium.yaml", TinyWithLine(1, "name: tiny\nmedium: {kind: water}"));
  ExpectError(ErrorOf(path), path, 2, {"medium.kind", "unknown medium 'water'", "radio, sound"});
}

TEST_F(ScenarioFiles, NamesANanValue) {
  const std::string path = Write("nan.yaml", TinyWithLine(17, "  sample_period_s: .nan"));
  ExpectError(ErrorOf(path), path, 17, {"channel.sample_period_s", "expected a number in [1e-15, 0.001] s", "'.nan'"});
}

TEST_F(ScenarioFiles, NamesANonNumberWhereANumberIsExpected) {
  const std::string path = Write("not_a_number.yaml", TinyWithLine(15, "    dt_s: fast"));
  ExpectError(ErrorOf(path), path, 15, {"trajectories[0].dt_s", "expected a number", "fast"});
}

TEST_F(ScenarioFiles, NamesAnAnchorOutsideTheFloorPlan) {
  const std::string path = Write("anchor_outside.yaml", TinyWithLine(11, "  - {id: A2, position_m: [4.5, 0.5]}"));
  ExpectError(ErrorOf(path), path, 11, {"anchors[1].position_m", "outside the floor plan"});
}

TEST_F(ScenarioFiles, NamesAnAnchorInsideThePillar) {
  const std::string path = Write("anchor_in_pillar.yaml", TinyWithLine(11, "  - {id: A2, position_m: [2.1, 2.0]}"));
  ExpectError(ErrorOf(path), path, 11, {"anchors[1].position_m", "inside an obstacle"});
}

TEST_F(ScenarioFiles, NamesAnAnchorPositionOfOneOrFourNumbers) {
  const std::string one = Write("one.yaml", TinyWithLine(11, "  - {id: A2, position_m: [3.5]}"));
  const std::string four = Write("four.yaml", TinyWithLine(11, "  - {id: A2, position_m: [3.5, 0.5, 0, 1]}"));
  ExpectError(ErrorOf(one), one, 11, {"anchors[1].position_m", "3 numbers [x, y, z] or 2 numbers [x, y]"});
  ExpectError(ErrorOf(four), four, 11, {"anchors[1].position_m", "a list of 4"});
}

TEST_F(ScenarioFiles, NamesACirScenarioWithAnchorsAboveTheTrajectoriesPlane) {
  // The cir and ranges models simulate the plane; ranging is the 3-D model.
  const std::string cir = Write("cir.yaml", TinyWithLine(11, "  - {id: A2, position_m: [3.5, 0.5, 2.0]}"));
  ExpectError(ErrorOf(cir), cir, 10, {"anchors", "anchor 'A2' at z = 2 m", "trajectory 'walk' at height 0 m", "ranging"});
  const std::string ranging =
      Write("ranging.yaml", TinyWithLine(11, "  - {id: A2, position_m: [3.5, 0.5, 2.0]}\nmeasurements: {model: ranging}"));
  EXPECT_EQ(ExperimentOf(LoadScenario(ranging)).anchors[1].position_m.z(), 2.0);
}

TEST_F(ScenarioFiles, NamesARangeMethodWithoutAnchors) {
  const std::string path = Write("no_anchors.yaml", WithLines(kTiny, {{9, ""}, {10, ""}, {11, ""}}));
  ExpectError(ErrorOf(path), path, 0, {"anchors: method 'mint' needs at least one anchor"});
  const std::string empty = Write("empty_anchors.yaml", WithLines(kTiny, {{9, "anchors: []"}, {10, ""}, {11, ""}}));
  ExpectError(ErrorOf(empty), empty, 9, {"anchors: method 'mint' needs at least one anchor"});
}

TEST_F(ScenarioFiles, NamesANegativeTimeStep) {
  const std::string path = Write("negative_dt.yaml", TinyWithLine(15, "    dt_s: -0.1"));
  ExpectError(ErrorOf(path), path, 15, {"trajectories[0].dt_s", "> 0"});
}

TEST_F(ScenarioFiles, NamesATrajectoryShorterThanOneStep) {
  const std::string path = Write("short.yaml", TinyWithLine(14, "    waypoints_m: [[0.5, 0.5], [0.5, 0.52]]"));
  ExpectError(ErrorOf(path), path, 14, {"trajectories[0].waypoints_m", "shorter than one step"});
}

TEST_F(ScenarioFiles, ReadsSelfStartAndATurnRadius) {
  const std::string path = Write("self_start.yaml", TinyWithLine(15, "    dt_s: 0.1\n    turn_radius_m: 0.2\nself_start: true"));
  const Experiment e = ExperimentOf(LoadScenario(path));
  EXPECT_TRUE(e.self_start);
  EXPECT_DOUBLE_EQ(e.trajectories[0].turn_radius_m, 0.2);
  // The defaults: start from the truth, turn at the waypoints.
  const Experiment tiny = ExperimentOf(LoadScenario(Write("tiny.yaml", kTiny)));
  EXPECT_FALSE(tiny.self_start);
  EXPECT_DOUBLE_EQ(tiny.trajectories[0].turn_radius_m, 0.0);
}

TEST_F(ScenarioFiles, NamesABadSelfStartAndANegativeTurnRadius) {
  const std::string start = Write("self_start.yaml", TinyWithLine(15, "    dt_s: 0.1\nself_start: maybe"));
  ExpectError(ErrorOf(start), start, 16, {"self_start", "expected true or false"});
  const std::string radius = Write("radius.yaml", TinyWithLine(15, "    dt_s: 0.1\n    turn_radius_m: -0.5"));
  ExpectError(ErrorOf(radius), radius, 16, {"trajectories[0].turn_radius_m", "out of range"});
}

TEST_F(ScenarioFiles, NamesATrajectoryLegThroughAnObstacle) {
  const std::string path = Write("leg_through_pillar.yaml", TinyWithLine(14, "    waypoints_m: [[0.5, 2.0], [3.5, 2.0]]"));
  ExpectError(ErrorOf(path), path, 14, {"trajectories[0].waypoints_m", "crosses a wall or an obstacle"});
}

TEST_F(ScenarioFiles, NamesATrajectoryLegThroughAWall) {
  // An inner wall from (2, 2.5) to (2, 4) after line 6, and a leg (now line 15) crossing it at y = 3.
  std::string text = TinyWithLine(6, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, material: concrete}\n"
                                     "    - {start_m: [2.0, 2.5], end_m: [2.0, 4.0]}");
  const std::string old_leg = "    waypoints_m: [[0.5, 0.5], [0.5, 3.0]]";
  text.replace(text.find(old_leg), old_leg.size(), "    waypoints_m: [[0.5, 3.0], [3.5, 3.0]]");
  const std::string path = Write("leg_through_wall.yaml", text);
  ExpectError(ErrorOf(path), path, 15, {"trajectories[0].waypoints_m", "crosses a wall"});
}

TEST_F(ScenarioFiles, NamesARunGridCornerThatPushesATrajectoryThroughAWall) {
  // The 5 x 5 grid 0.3 m apart shifts the start (0.5, 0.5) by (-0.6, -0.6): outside the room.
  const std::string path = Write("run_grid.yaml", TinyWithLine(1, "name: tiny\nrun_grid: {spacing_m: 0.3}"));
  ExpectError(ErrorOf(path), path, 15, {"trajectories[0].waypoints_m", "shifted by the run grid's corner"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMaterial) {
  const std::string path =
      Write("unknown_material.yaml",
            TinyWithLine(6, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, material: marble}"));
  ExpectError(ErrorOf(path), path, 6, {"floor_plan.walls[0].material", "unknown material 'marble'"});
}

TEST_F(ScenarioFiles, NamesAZeroReflectionCoefficientOfAWall) {
  const std::string path = Write(
      "zero_reflection.yaml", TinyWithLine(6, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, reflection_coeff: 0}"));
  ExpectError(ErrorOf(path), path, 6, {"floor_plan.walls[0].reflection_coeff", "(0, 1]"});
}

TEST_F(ScenarioFiles, NamesAReflectionCoefficientAboveOne) {
  const std::string path = Write(
      "big_reflection.yaml", TinyWithLine(6, "    - {polyline_m: [[0, 0], [4, 0], [4, 4], [0, 4]], closed: true, reflection_coeff: 1.2}"));
  ExpectError(ErrorOf(path), path, 6, {"floor_plan.walls[0].reflection_coeff", "1.2", "out of range"});
}

TEST_F(ScenarioFiles, NamesAMaterialWithAReflectionCoefficientOfZero) {
  const std::string path = Write("zero_material.yaml", TinyWithLine(3, "  concrete: 0"));
  ExpectError(ErrorOf(path), path, 3, {"materials", "concrete", "(0, 1]"});
}

TEST_F(ScenarioFiles, NamesTheLineAndKeyOfTheBadMaterialEntry) {
  // The bad coefficient is the second entry, on line 4.
  const std::string path = Write("second_material.yaml", TinyWithLine(3, "  concrete: 0.5\n  glass: 1.5"));
  ExpectError(ErrorOf(path), path, 4, {"materials.glass", "(0, 1]"});
}

TEST_F(ScenarioFiles, NamesADuplicateAnchorId) {
  const std::string path = Write("duplicate_id.yaml", TinyWithLine(11, "  - {id: A1, position_m: [3.5, 0.5]}"));
  ExpectError(ErrorOf(path), path, 11, {"anchors[1].id", "duplicate anchor id 'A1'"});
}

TEST_F(ScenarioFiles, NamesASamplePeriodAboveNyquist) {
  // The 0.5 ns RC pulse with roll-off 0.5 reaches 1.5 GHz: T_s must be <= 1 / 3 GHz = 0.333 ns.
  const std::string path = Write("nyquist.yaml", TinyWithLine(17, "  sample_period_s: 0.5e-9"));
  ExpectError(ErrorOf(path), path, 17, {"channel.sample_period_s", "Nyquist"});
}

TEST_F(ScenarioFiles, StatesTheNyquistLimitInTheMessage) {
  const std::string path = Write("nyquist_value.yaml", TinyWithLine(17, "  sample_period_s: 0.5e-9"));
  const std::string message = ErrorOf(path);
  EXPECT_NE(message.find("3.33333e-10 s"), std::string::npos) << message;
}

TEST_F(ScenarioFiles, NamesAWindowShorterThanEightPulses) {
  // 2 ns pulse, 10 ns window: the window check of the channel, not the LOS one (which needs more).
  const std::string path = Write("short_window.yaml", TinyWithLine(19, "    duration_s: 2e-9\n  window_length_s: 10e-9"));
  ExpectError(ErrorOf(path), path, 20, {"channel.window_length_s", "must be at least 8 pulse durations"});
}

TEST_F(ScenarioFiles, NamesAWindowThatEndsBeforeTheLatestLineOfSight) {
  const std::string path = Write("los_window.yaml", TinyWithLine(17, "  sample_period_s: 0.125e-9\n  window_length_s: 8e-9"));
  ExpectError(ErrorOf(path), path, 18, {"channel.window_length_s", "latest LOS delay"});
}

TEST_F(ScenarioFiles, NamesAMapWhereAListIsExpected) {
  std::string text = kTiny;
  const auto from = text.find("anchors:\n");
  text.replace(from, text.find("trajectories:\n") - from, "anchors: {id: A1}\n");
  const std::string path = Write("anchors_map.yaml", text);
  ExpectError(ErrorOf(path), path, 9, {"anchors", "expected a list"});
}

TEST_F(ScenarioFiles, NamesAnUnknownMeasurementModel) {
  const std::string path = Write("model.yaml", TinyWithLine(1, "name: tiny\nmeasurements: {model: telepathy}"));
  ExpectError(ErrorOf(path), path, 2, {"measurements.model", "unknown measurement model 'telepathy'", "ranging"});
}

TEST_F(ScenarioFiles, NamesAKeyOfAnotherMeasurementModel) {
  // detection_probability is a key of the range models, not of the CIR model.
  const std::string path = Write("model_key.yaml", TinyWithLine(1, "name: tiny\nmeasurements: {detection_probability: 0.9}"));
  ExpectError(ErrorOf(path), path, 2, {"measurements.detection_probability", "unknown key"});
}

TEST_F(ScenarioFiles, NamesAJointMethodsKeysInASingleAgentScenario) {
  const std::string path = Write("agents.yaml", TinyWithLine(1, "name: tiny\nagents: 2"));
  ExpectError(ErrorOf(path), path, 2, {"agents", "unknown key"});
}

// ---------------------------------------------------------------------------------------------
// Recorded data
// ---------------------------------------------------------------------------------------------

TEST_F(ScenarioFiles, NamesTheKeysRecordedDataReplace) {
  for (const std::string key : {"anchors: [{id: A1, position_m: [0.5, 7.0]}]",
                                "trajectories: [{name: t, waypoints_m: [[1, 1], [1, 2]]}]", "run_grid: {nx: 1}",
                                "perturb_initial_position: true"}) {
    SCOPED_TRACE(key);
    const std::string path = Extend("recorded.yaml", "recorded/scenario.yaml", key + "\n");
    ExpectError(ErrorOf(path), path, 2, {key.substr(0, key.find(':')) + ": not used with measurements.model recorded"});
  }
}

TEST_F(ScenarioFiles, NamesRecordedDataOfMoreThanOneRun) {
  const std::string path = Extend("runs.yaml", "recorded/scenario.yaml", "runs: 25\n");
  ExpectError(ErrorOf(path), path, 2, {"runs", "out of range, expected an integer in [1, 1]"});
}

TEST_F(ScenarioFiles, LoadsRecordedDataWithoutTruthOrStartForTheMethodsThatStartThemselves) {
  const std::string recorded = Example("recorded/");
  const std::string text = "name: no_start\n"
                           "measurements: {model: recorded, anchors: " + recorded + "anchors.csv, ranges: " + recorded +
                           "ranges.csv}\n"
                           "method: {name: METHOD}\n";
  const auto with = [&](const std::string& method) {
    std::string t = text;
    t.replace(t.find("METHOD"), 6, method);
    return t;
  };

  // MINT, SLAM and range_ekf start themselves from the first epochs: no start point needed.
  for (const std::string method : {"mint", "slam", "range_ekf"}) {
    SCOPED_TRACE(method);
    ASSERT_TRUE(methods::FindMethod(method)->self_initializes);
    EXPECT_FALSE(ExperimentOf(LoadScenario(Write(method + ".yaml", with(method)))).start_m.has_value());
  }
  // A start given is taken.
  std::string with_start = with("mint");
  with_start.replace(with_start.find("ranges.csv}"), 11, "ranges.csv, start_m: [1.0, 1.4]}");
  const Experiment e = ExperimentOf(LoadScenario(Write("start.yaml", with_start)));
  ASSERT_TRUE(e.start_m.has_value());
  EXPECT_EQ(*e.start_m, Vec3(1.0, 1.4, 0.0));
}

TEST_F(ScenarioFiles, NamesARecordedAnchorOutsideTheFloorPlan) {
  // The recorded anchors (A1 at y = 7) lie outside a 4 m room.
  const std::string recorded = Example("recorded/");
  const std::string path = Write("outside.yaml", WithLines(kTiny, {{9, "measurements: {model: recorded, anchors: " + recorded +
                                                                            "anchors.csv, ranges: " + recorded + "ranges.csv, "
                                                                            "truth: " + recorded + "truth.csv}"},
                                                                   {10, ""}, {11, ""}, {12, ""}, {13, ""}, {14, ""}, {15, ""}}));
  ExpectError(ErrorOf(path), "anchors.csv", 0, {"anchor 'A1'", "outside the floor plan of " + path});
}

// ---------------------------------------------------------------------------------------------
// Cooperative (joint) scenarios
// ---------------------------------------------------------------------------------------------

TEST_F(CoopScenarioFiles, LoadsTheSmallScenarioWithTheValuesItStates) {
  // Arrange
  const std::string path = Write("coop.yaml", kCoop);

  // Act
  const Scenario s = LoadScenario(path);

  // Assert
  ASSERT_EQ(s.method->name, "coop");
  const Experiment& c = ExperimentOf(s);
  EXPECT_EQ(s.file, path);
  EXPECT_EQ(c.name, "coop_room");
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.runs, 5);
  EXPECT_EQ(c.threads, 0);
  EXPECT_EQ(c.steps, 50);
  ASSERT_EQ(c.plan.walls().size(), 5u);
  EXPECT_DOUBLE_EQ(c.plan.walls()[0].reflection_coeff, 0.6);
  EXPECT_EQ(c.plan.walls()[3].label, "north");
  EXPECT_EQ(c.plan.obstacles().size(), 1u);
  EXPECT_EQ(c.in_plan, (std::vector<bool>{true, true, true, true, false}));
  ASSERT_EQ(c.trajectories.size(), 3u);
  EXPECT_EQ(c.trajectories[1].name, "a2");
  EXPECT_EQ(c.trajectories[1].waypoints_m.size(), 2u);
  EXPECT_DOUBLE_EQ(c.trajectories[0].speed_mps, 0.02);
  EXPECT_DOUBLE_EQ(c.trajectories[1].speed_mps, pipeline::TrajectorySpec{}.speed_mps);
  EXPECT_DOUBLE_EQ(c.trajectories[1].dt_s, 1.0);
  ASSERT_EQ(c.anchors.size(), 1u);
  EXPECT_EQ(c.anchors[0].id, "A");
  EXPECT_DOUBLE_EQ(c.anchors[0].position_m.x(), 0.5);
  EXPECT_EQ(c.plan_error.biased_wall, 3);
  EXPECT_DOUBLE_EQ(c.plan_error.bias_m, -0.1);
  EXPECT_DOUBLE_EQ(c.plan_error.wall_shift_m, 0.002);
  EXPECT_EQ(c.channel_max_order, 3);
  EXPECT_DOUBLE_EQ(c.self_coupling_db, -30.0);
  EXPECT_DOUBLE_EQ(c.channel.window_length_s, 80e-9);
  EXPECT_DOUBLE_EQ(c.channel.pulse.rolloff, 0.4);
  EXPECT_DOUBLE_EQ(c.channel.pulse.duration_s, 0.5e-9);
  EXPECT_DOUBLE_EQ(c.mpc.relative_threshold_db, -60.0);
  EXPECT_TRUE(c.method.joint);
  EXPECT_DOUBLE_EQ(c.method.start_sigma_m, 0.05);  // the method's agent_sigma_m
  const auto& coop = Coop(c);
  EXPECT_DOUBLE_EQ(coop.agent_sigma_m, 0.05);
  EXPECT_EQ(coop.max_order, 1);
  EXPECT_DOUBLE_EQ(coop.antenna_spacing_m, 0.04);
  EXPECT_DOUBLE_EQ(coop.wall_sigma_m, 0.01);
  const methods::coop::CoopOptions defaults;
  EXPECT_DOUBLE_EQ(coop.velocity_sigma_mps, defaults.velocity_sigma_mps);
  EXPECT_DOUBLE_EQ(coop.variance.window_max_m, 0.3);
  // The other variance keys keep the cooperative defaults, not MINT's.
  EXPECT_DOUBLE_EQ(coop.variance.window_min_m, defaults.variance.window_min_m);
  EXPECT_EQ(coop.variance.min_samples, defaults.variance.min_samples);
  EXPECT_DOUBLE_EQ(coop.variance.default_sigma_m, defaults.variance.default_sigma_m);
  EXPECT_NE(coop.variance.min_samples, methods::mint::MintOptions{}.variance.min_samples);
}

TEST_F(CoopScenarioFiles, GivesOneExperimentPerGridVariantInGridOrder) {
  // Grid entry 1 in the order agents, anchor_links (the last fastest); entry 2's 0.5 ns variant
  // repeats entry 1's first and is dropped.
  const Scenario s = LoadScenario(Write("coop.yaml", kCoop));

  ASSERT_EQ(s.variants.size(), 5u);
  const std::vector<std::string> names = {"agents=2, method.anchor_links=false", "agents=2, method.anchor_links=true",
                                          "agents=3, method.anchor_links=false", "agents=3, method.anchor_links=true",
                                          "channel.pulse.duration_s=1.0e-9, agents=2"};
  const std::vector<int> agents = {2, 2, 3, 3, 2};
  const std::vector<bool> anchor_links = {false, true, false, true, false};
  const std::vector<double> pulse_s = {0.5e-9, 0.5e-9, 0.5e-9, 0.5e-9, 1e-9};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const Experiment& e = s.variants[i].experiment;
    EXPECT_EQ(s.variants[i].name, names[i]);
    EXPECT_EQ(e.agents, agents[i]) << i;
    EXPECT_EQ(Coop(e).anchor_links, anchor_links[i]) << i;
    EXPECT_DOUBLE_EQ(e.channel.pulse.duration_s, pulse_s[i]) << i;
    // What the grid does not vary is the base's in every variant.
    EXPECT_DOUBLE_EQ(Coop(e).wall_sigma_m, 0.01) << i;
    EXPECT_DOUBLE_EQ(e.plan_error.bias_m, -0.1) << i;
    EXPECT_EQ(e.seed, 7u) << i;
  }
  EXPECT_EQ(s.variants[1].overrides,
            (std::vector<std::pair<std::string, std::string>>{{"agents", "2"}, {"method.anchor_links", "true"}}));
  // Every variant keeps its own effective options for the report.
  EXPECT_NE(s.variants[1].experiment.method.options_json.find("\"anchor_links\":true"), std::string::npos);
  EXPECT_NE(s.variants[0].experiment.method.options_json.find("\"anchor_links\":false"), std::string::npos);
}

TEST_F(CoopScenarioFiles, WithoutAGridIsOneVariantNamedAfterTheScenario) {
  const Scenario s = LoadScenario(Write("plain.yaml", WithLines(kCoop, {{36, ""}, {37, ""}, {38, ""}})));

  ASSERT_EQ(s.variants.size(), 1u);
  EXPECT_FALSE(s.has_grid());
  EXPECT_EQ(s.variants[0].name, "coop_room");
  EXPECT_TRUE(s.variants[0].overrides.empty());
  EXPECT_FALSE(Coop(ExperimentOf(s)).anchor_links);
}

TEST_F(CoopScenarioFiles, MergesAFileOverTheOneItExtends) {
  Write("base.yaml", kCoop);
  const std::string path = Write("child.yaml", "extends: base.yaml\nruns: 2\nmethod: {wall_sigma_m: 0.001}\n");

  const Scenario s = LoadScenario(path);

  EXPECT_EQ(s.method->name, "coop");  // inherited through extends
  EXPECT_EQ(s.variants.size(), 5u);   // the base's grid too
  for (const auto& v : s.variants) {
    EXPECT_EQ(v.experiment.runs, 2) << v.name;
    EXPECT_DOUBLE_EQ(Coop(v.experiment).wall_sigma_m, 0.001) << v.name;
    EXPECT_DOUBLE_EQ(Coop(v.experiment).agent_sigma_m, 0.05) << v.name;
  }
}

TEST_F(CoopScenarioFiles, RunsWithoutAnchorsWhenItHasNoAnchorLinks) {
  // Kulmer's anchorless case: no anchors at all.
  const Scenario s = LoadScenario(Write("anchorless.yaml", WithLines(kCoop, {{20, ""}, {21, ""}, {36, ""}, {37, ""}, {38, ""}})));

  EXPECT_TRUE(ExperimentOf(s).anchors.empty());
}

TEST_F(CoopScenarioFiles, NamesAnchorLinksWithoutAnAnchor) {
  // The grid's anchor variant (its value's line), and the scenario's own anchor_links (lines 20-21 removed).
  ExpectBad("no_anchor.yaml", kCoop, {{20, ""}, {21, ""}}, 35, {"method.anchor_links", "need an anchor"});
  ExpectBad("no_anchor_base.yaml", kCoop, {{20, ""}, {21, ""}, {35, "  anchor_links: true"}, {36, ""}, {37, ""}, {38, ""}}, 33,
            {"method.anchor_links", "need an anchor"});
}

TEST_F(CoopScenarioFiles, NamesAnUnknownKey) {
  ExpectBad("typo.yaml", kCoop, {{30, "  agent_sigma: 0.05"}}, 30, {"method.agent_sigma", "unknown key", "agent_sigma_m"});
}

TEST_F(CoopScenarioFiles, NamesAnUnknownTopLevelKey) {
  ExpectBad("top_typo.yaml", kCoop, {{4, "steps: 50\nstep_count: 3"}}, 5, {"step_count", "unknown key"});
}

TEST_F(CoopScenarioFiles, NamesAGridKeyPathTheScenarioDoesNotSet) {
  ExpectBad("axis_typo.yaml", kCoop, {{38, "  - {agent: [2]}"}}, 38, {"grid[1]", "'agent' names no key the scenario sets"});
}

TEST_F(CoopScenarioFiles, NamesMoreAgentsThanTheScenarioHas) {
  // The grid's value keeps its line: the message names the grid entry's.
  ExpectBad("many_agents.yaml", kCoop, {{37, "  - {agents: [2, 4], method.anchor_links: [false, true]}"}}, 37,
            {"agents", "4 is out of range, expected an integer in [0, 3]"});
}

TEST_F(CoopScenarioFiles, NamesAFractionalAgentCount) {
  ExpectBad("half_agent.yaml", kCoop, {{5, "agents: 2.5"}, {36, ""}, {37, ""}, {38, ""}}, 5, {"agents", "expected an integer"});
}

TEST_F(CoopScenarioFiles, NamesTrajectoriesOfDifferentTimeSteps) {
  ExpectBad("dt.yaml", kCoop, {{18, "  - {name: a2, waypoints_m: [[4, 2], [4, 1]], dt_s: 0.5}"}}, 17,
            {"trajectories", "give every trajectory the same dt_s"});
}

TEST_F(CoopScenarioFiles, NamesAChannelOrderAboveTheLinksThree) {
  ExpectBad("sim_order.yaml", kCoop, {{23, "  max_order: 4"}}, 23, {"channel.max_order", "4 is above 3"});
}

TEST_F(CoopScenarioFiles, NamesAMeasurementModelOtherThanCir) {
  ExpectBad("ranges.yaml", kCoop, {{27, "mpc: {relative_threshold_db: -60}\nmeasurements: {model: ranges}"}}, 28,
            {"measurements", "method 'coop' consumes CIRs: measurements.model must be cir"});
}

TEST_F(CoopScenarioFiles, NamesABiasWithoutItsWall) {
  ExpectBad("no_wall.yaml", kCoop, {{15, "floor_plan_error: {bias_m: -0.1}"}}, 15,
            {"floor_plan_error.bias_m", "a bias needs the wall it moves: set biased_wall"});
}

TEST_F(CoopScenarioFiles, NamesAnUnknownBiasedWallLabel) {
  ExpectBad("bias_label.yaml", kCoop, {{15, "floor_plan_error: {biased_wall: ceiling}"}}, 15,
            {"floor_plan_error.biased_wall", "no wall labelled 'ceiling'"});
}

TEST_F(CoopScenarioFiles, NamesABiasedWallLabelOfSeveralSegments) {
  ExpectBad("bias_many.yaml", kCoop, {{15, "floor_plan_error: {biased_wall: concrete}"}}, 15,
            {"floor_plan_error.biased_wall", "'concrete' names more than one wall segment"});
}

TEST_F(CoopScenarioFiles, NamesABiasOnAWallTheFilterDoesNotKnow) {
  ExpectBad("bias_pinboard.yaml", kCoop, {{15, "floor_plan_error: {biased_wall: pinboard}"}}, 15,
            {"floor_plan_error.biased_wall", "in_plan: false"});
}

TEST_F(CoopScenarioFiles, NamesABiasOutOfRange) {
  ExpectBad("bias_offset.yaml", kCoop, {{15, "floor_plan_error: {biased_wall: north, bias_m: 15}"}}, 15,
            {"floor_plan_error.bias_m", "out of range"});
}

TEST_F(CoopScenarioFiles, NamesAWallShiftOutOfRange) {
  ExpectBad("wall_shift.yaml", kCoop, {{15, "floor_plan_error: {wall_shift_m: -0.001}"}}, 15,
            {"floor_plan_error.wall_shift_m", "out of range"});
}

TEST_F(CoopScenarioFiles, NamesANonBooleanInPlan) {
  ExpectBad("in_plan.yaml", kCoop, {{12, "    - {start_m: [5, 1], end_m: [5, 2], in_plan: maybe}"}}, 12,
            {"floor_plan.walls[2].in_plan", "true or false"});
}

TEST_F(CoopScenarioFiles, NamesAWaypointOutsideThePlan) {
  ExpectBad("outside.yaml", kCoop, {{18, "  - {name: a2, waypoints_m: [[4, 2], [7, 1]], dt_s: 1.0}"}}, 18,
            {"trajectories[1].waypoints_m", "waypoint 1", "outside the floor plan"});
}

TEST_F(CoopScenarioFiles, NamesAWaypointInsideAnObstacle) {
  ExpectBad("pillar.yaml", kCoop, {{18, "  - {name: a2, waypoints_m: [[1.5, 3.1], [3, 3]], dt_s: 1.0}"}}, 18,
            {"trajectories[1].waypoints_m", "inside an obstacle"});
}

TEST_F(CoopScenarioFiles, NamesALegThroughTheWallTheFilterDoesNotKnow) {
  ExpectBad("leg.yaml", kCoop, {{18, "  - {name: a2, waypoints_m: [[4, 1.5], [5.5, 1.5]], dt_s: 1.0}"}}, 18,
            {"trajectories[1].waypoints_m", "crosses a wall or an obstacle"});
}

TEST_F(CoopScenarioFiles, NamesANegativeSpeed) {
  ExpectBad("speed.yaml", kCoop, {{17, "  - {name: a1, waypoints_m: [[1, 1], [2, 1]], speed_mps: -0.02, dt_s: 1.0}"}}, 17,
            {"trajectories[0].speed_mps", "-0.02", "> 0"});
}

TEST_F(CoopScenarioFiles, NamesADuplicateAgentName) {
  ExpectBad("same_name.yaml", kCoop, {{18, "  - {name: a1, waypoints_m: [[4, 2], [4, 1]], dt_s: 1.0}"}}, 18,
            {"trajectories[1].name", "duplicate"});
}

TEST_F(CoopScenarioFiles, NamesAFilterOrderAboveTwo) {
  ExpectBad("order.yaml", kCoop, {{31, "  max_order: 3"}}, 31, {"method.max_order", "3 is out of range"});
}

TEST_F(CoopScenarioFiles, NamesASelfGateBelowTheAntennaSpacing) {
  ExpectBad("gate.yaml", kCoop, {{31, "  max_order: 1\n  self_gate_m: 0.03"}}, 32, {"method.self_gate_m", "antenna_spacing_m"});
}

TEST_F(CoopScenarioFiles, NamesABadGridValueAtTheGridEntrysLine) {
  // Values set by the grid keep the grid's line, with the key path they set.
  ExpectBad("zero_pulse.yaml", kCoop, {{38, "  - {channel.pulse.duration_s: [1.0e-9, 0], agents: [2]}"}}, 38,
            {"channel.pulse.duration_s", "out of range"});
  ExpectBad("zero_sigma.yaml", kCoop, {{38, "  - {method.wall_sigma_m: [0.003, 0]}"}}, 38,
            {"method.wall_sigma_m", "out of range"});
  ExpectBad("flag.yaml", kCoop, {{37, "  - {agents: [2, 3], method.anchor_links: [false, yes please]}"}}, 37,
            {"method.anchor_links", "true or false"});
}

TEST_F(CoopScenarioFiles, NamesASamplePeriodTooLongForAGridVariantsPulse) {
  // 0.1 ns at roll-off 0.4 needs samples below 36 ps; the default is 125 ps.
  // sample_period_s is not in the file: the message names the line of its section.
  const std::string path = Write("nyquist.yaml", WithLines(kCoop, {{38, "  - {channel.pulse.duration_s: [0.1e-9], agents: [2]}"}}));
  ExpectError(ErrorOf(path), path, 22, {"channel.sample_period_s", "Nyquist"});
}

TEST_F(CoopScenarioFiles, KeepsTheLinesOfListsAndMapsTheGridDoesNotChange) {
  // The trajectories and anchors are no grid values: their errors name their own lines.
  ExpectBad("anchor_outside.yaml", kCoop, {{21, "  - {id: A, position_m: [6.5, 0.5]}"}}, 21,
            {"anchors[0].position_m", "outside the floor plan"});
  ExpectBad("leg_grid.yaml", kCoop, {{19, "  - {name: a3, waypoints_m: [[2, 2], [2, 5]], speed_mps: 0.01, dt_s: 1.0}"}}, 19,
            {"trajectories[2].waypoints_m", "outside the floor plan"});
}

}  // namespace
}  // namespace mirage::io
