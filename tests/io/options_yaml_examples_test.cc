// SPDX-License-Identifier: MIT
// ReadOptions (io/options_yaml.h) through the real descriptors reads every options section of
// every example to exactly the values the scenario loader binds (io/scenario.h): the method
// section (without `name`) to the options struct of pipeline::MethodSpec::options, and the
// channel, mpc, measurement-model and divergence sections to the experiment's structs, compared
// as the report's JSON of the effective options. Keys the loader reads from a section into
// something other than the section's struct (channel.max_order and self_coupling_db, the
// measurement model and a recording's files) are removed from a copy of the section first. For a
// grid, each section is compared with every variant that does not vary a key of it.
#include "mirage/io/options_yaml.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/options_json.h"
#include "mirage/io/scenario.h"
#include "mirage/methods/coop/coop_tracker.h"
#include "mirage/methods/mint/mint_tracker.h"
#include "mirage/methods/acoustic/acoustic_options.h"
#include "mirage/methods/range_ekf/range_ekf.h"
#include "mirage/methods/slam/slam_tracker.h"
#include "mirage/methods/tdoa_ekf/tdoa_ekf.h"

namespace mirage::io {
namespace {

using pipeline::Experiment;
using pipeline::MeasurementModel;

std::string Example(const std::string& name) { return std::string(MIRAGE_SOURCE_DIR) + "/examples/" + name; }

// Every *.yaml of examples/ and its subdirectories, sorted.
std::vector<std::string> Examples() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(Example(""))) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Reads the section at `keys` ({"evaluation", "divergence"}) of `file`, its `extends` resolved,
// without the keys `skip`, into a default-constructed T (an absent section is an empty map), with
// the physical keys the loader derived defaults from.
template <typename T>
T ReadSection(const std::string& file, const std::vector<std::string>& keys, const core::OptionsDescriptor<T>& descriptor,
              const std::vector<std::string>& skip = {}, const core::PhysicalKeys& physical = {}) {
  auto origins = std::make_shared<YamlOrigins>(file);
  const YAML::Node doc = LoadYamlWithExtends(file, *origins);
  YAML::Node node = YAML::Clone(doc);
  std::string path;
  for (const auto& key : keys) {
    const YAML::Node& parent = node;  // const lookup: non-const operator[] would insert
    const YAML::Node child = parent.IsMap() ? parent[key] : YAML::Node();
    node.reset(child ? child : YAML::Node(YAML::NodeType::Map));
    path += (path.empty() ? "" : ".") + key;
  }
  for (const auto& key : skip) node.remove(key);
  T options;
  ReadOptions(YamlMap(node, path, origins), descriptor, physical, options);
  return options;
}

template <typename T>
void ExpectSameOptions(const core::OptionsDescriptor<T>& descriptor, const T& read, const T& loaded) {
  EXPECT_EQ(OptionsToJson(descriptor, read).dump(2), OptionsToJson(descriptor, loaded).dump(2));
}

// The variants that vary no key under `section` ("method", "channel", ...): the ones whose value
// of the section is the file's.
std::vector<const pipeline::Variant*> VariantsKeeping(const Scenario& scenario, const std::string& section) {
  std::vector<const pipeline::Variant*> out;
  for (const auto& v : scenario.variants) {
    const bool varies = std::any_of(v.overrides.begin(), v.overrides.end(),
                                    [&](const auto& o) { return o.first == section || o.first.rfind(section + ".", 0) == 0; });
    if (!varies) out.push_back(&v);
  }
  return out;
}

// The method section read through the method's descriptor against the loader's bound options.
template <typename T>
void ExpectMethodOptions(const std::string& file, const Experiment& e, const core::OptionsDescriptor<T>& descriptor) {
  ASSERT_NE(e.method.options, nullptr);
  const T read = ReadSection(file, {"method"}, descriptor, {"name"}, pipeline::PhysicalKeysOf(e));
  ExpectSameOptions(descriptor, read, *static_cast<const T*>(e.method.options.get()));
}

void ExpectMethodOptions(const std::string& file, const Experiment& e) {
  if (e.method.name == "mint") return ExpectMethodOptions(file, e, methods::mint::MintOptionsDescriptor());
  if (e.method.name == "slam") return ExpectMethodOptions(file, e, methods::slam::SlamOptionsDescriptor());
  if (e.method.name == "coop") return ExpectMethodOptions(file, e, methods::coop::CoopOptionsDescriptor());
  if (e.method.name == "range_ekf") return ExpectMethodOptions(file, e, methods::range_ekf::RangeEkfOptionsDescriptor());
  if (e.method.name == "acoustic") return ExpectMethodOptions(file, e, methods::acoustic::AcousticOptionsDescriptor());
  if (e.method.name == "tdoa_ekf") return ExpectMethodOptions(file, e, methods::tdoa_ekf::TdoaEkfOptionsDescriptor());
  ADD_FAILURE() << "no options struct known for method '" << e.method.name << "': add it here";
}

TEST(ReadOptionsOnTheExamples, GivesTheMethodOptionsTheLoaderBinds) {
  const auto files = Examples();
  ASSERT_GE(files.size(), 10u);
  std::vector<std::string> methods_seen;
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const Scenario scenario = LoadScenario(file);
    const auto variants = VariantsKeeping(scenario, "method");
    ASSERT_FALSE(variants.empty()) << "every variant varies a method option";
    for (const auto* v : variants) {
      SCOPED_TRACE(v->name);
      ExpectMethodOptions(file, v->experiment);
    }
    methods_seen.push_back(scenario.method->name);
  }
  // Every registered method is exercised by some example.
  for (const auto& m : methods::Methods()) {
    EXPECT_NE(std::find(methods_seen.begin(), methods_seen.end(), m.name), methods_seen.end()) << m.name;
  }
}

TEST(ReadOptionsOnTheExamples, GivesTheChannelFrontEndMeasurementAndEvaluationOptionsTheLoaderReads) {
  for (const auto& file : Examples()) {
    SCOPED_TRACE(file);
    const Scenario scenario = LoadScenario(file);
    for (const auto* v : VariantsKeeping(scenario, "channel")) {
      const Experiment& e = v->experiment;
      ExpectSameOptions(channel::ChannelOptionsDescriptor(),
                        ReadSection(file, {"channel"}, channel::ChannelOptionsDescriptor(), {"max_order", "self_coupling_db"},
                                    pipeline::PhysicalKeysOf(e)),
                        e.channel);
    }
    for (const auto* v : VariantsKeeping(scenario, "mpc")) {
      ExpectSameOptions(dsp::MpcExtractorOptionsDescriptor(),
                        ReadSection(file, {"mpc"}, dsp::MpcExtractorOptionsDescriptor(), {}, pipeline::PhysicalKeysOf(v->experiment)),
                        v->experiment.mpc);
    }
    for (const auto* v : VariantsKeeping(scenario, "measurements")) {
      const Experiment& e = v->experiment;
      if (e.measurement_model == MeasurementModel::kRangeLevel) {
        ExpectSameOptions(channel::RangeLevelOptionsDescriptor(),
                          ReadSection(file, {"measurements"}, channel::RangeLevelOptionsDescriptor(), {"model"},
                                      pipeline::PhysicalKeysOf(e)),
                          e.range_level);
      } else if (e.measurement_model == MeasurementModel::kRanging) {
        ExpectSameOptions(channel::RangingOptionsDescriptor(),
                          ReadSection(file, {"measurements"}, channel::RangingOptionsDescriptor(), {"model"},
                                      pipeline::PhysicalKeysOf(e)),
                          e.ranging);
      }
    }
    for (const auto* v : VariantsKeeping(scenario, "evaluation")) {
      ExpectSameOptions(eval::DivergenceRuleDescriptor(),
                        ReadSection(file, {"evaluation", "divergence"}, eval::DivergenceRuleDescriptor(), {},
                                    pipeline::PhysicalKeysOf(v->experiment)),
                        v->experiment.divergence);
    }
  }
}

// The comparisons above are not between defaults only: the examples set non-default values,
// through `extends` (a method of another name replacing the base's section) too.
TEST(ReadOptionsOnTheExamples, ReadsTheValuesTheExamplesSet) {
  const auto slam = ReadSection(Example("seminar_room_slam.yaml"), {"method"}, methods::slam::SlamOptionsDescriptor(), {"name"});
  const auto coop = ReadSection(Example("coop_room.yaml"), {"method"}, methods::coop::CoopOptionsDescriptor(), {"name"});
  const auto ekf = ReadSection(Example("rtls_room_3d.yaml"), {"method"}, methods::range_ekf::RangeEkfOptionsDescriptor(), {"name"});
  const auto mpc = ReadSection(Example("coop_room.yaml"), {"mpc"}, dsp::MpcExtractorOptionsDescriptor());
  const auto coop_channel =
      ReadSection(Example("coop_room.yaml"), {"channel"}, channel::ChannelOptionsDescriptor(), {"max_order", "self_coupling_db"});
  const auto ranging =
      ReadSection(Example("slam_holdout.yaml"), {"measurements"}, channel::RangingOptionsDescriptor(), {"model"});

  EXPECT_EQ(slam.motion.accel_sigma_mps2, 0.5);
  EXPECT_FALSE(slam.prior_visibility);
  EXPECT_EQ(coop.agent_sigma_m, 0.03);
  EXPECT_EQ(coop.self_gate_m, 0.3);
  EXPECT_EQ(ekf.mode, "3d");
  EXPECT_EQ(mpc.relative_threshold_db, -60.0);
  EXPECT_EQ(coop_channel.pulse.rolloff, 0.6);
  EXPECT_EQ(coop_channel.window_length_s, 100e-9);
  EXPECT_TRUE(ranging.multipath);
  EXPECT_EQ(ranging.detection_probability, 0.95);
}

}  // namespace
}  // namespace mirage::io
