// SPDX-License-Identifier: MIT
// ReadOptions (io/options_yaml.h) through the real descriptors reads every options section of
// every example to exactly the values the scenario loaders give (io/scenario.h,
// io/coop_scenario.h), compared as the report's JSON of the effective options: the examples keep
// their meaning when the loaders switch to the descriptors. Keys a loader reads from a section
// into something other than the section's struct (channel.max_order, the measurement model, the
// cooperative channel's simulated order and coupling) are removed from a copy of the section first.
#include "mirage/io/options_yaml.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/coop_scenario.h"
#include "mirage/io/options_json.h"
#include "mirage/io/scenario.h"

namespace mirage::io {
namespace {

std::string Example(const std::string& name) { return std::string(MIRAGE_SOURCE_DIR) + "/examples/" + name; }

// The examples a scenario loader of each kind reads (every *.yaml of examples/ and its
// subdirectories), sorted.
std::vector<std::string> Examples(bool coop) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(Example(""))) {
    if (entry.path().extension() != ".yaml") continue;
    if (IsCoopScenario(entry.path().string()) == coop) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Reads the section at `keys` ({"evaluation", "divergence"}) of `file`, its `extends` resolved,
// without the keys `skip`, into a default-constructed T (an absent section is an empty map).
template <typename T>
T ReadSection(const std::string& file, const std::vector<std::string>& keys, const core::OptionsDescriptor<T>& descriptor,
              const std::vector<std::string>& skip = {}) {
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
  ReadOptions(YamlMap(node, path, origins), descriptor, {}, options);
  return options;
}

template <typename T>
void ExpectSameOptions(const core::OptionsDescriptor<T>& descriptor, const T& read, const T& loaded) {
  EXPECT_EQ(OptionsToJson(descriptor, read).dump(2), OptionsToJson(descriptor, loaded).dump(2));
}

TEST(ReadOptionsOnTheExamples, GivesTheMintAndSlamLoadersValues) {
  const auto files = Examples(false);
  ASSERT_GE(files.size(), 6u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const pipeline::MintExperimentConfig loaded = LoadScenario(file).mint;

    ExpectSameOptions(channel::ChannelOptionsDescriptor(),
                      ReadSection(file, {"channel"}, channel::ChannelOptionsDescriptor(), {"max_order"}),
                      loaded.channel);
    ExpectSameOptions(dsp::MpcExtractorOptionsDescriptor(),
                      ReadSection(file, {"mpc"}, dsp::MpcExtractorOptionsDescriptor()), loaded.mpc);
    ExpectSameOptions(methods::mint::MintOptionsDescriptor(),
                      ReadSection(file, {"mint"}, methods::mint::MintOptionsDescriptor()), loaded.mint);
    ExpectSameOptions(methods::slam::SlamOptionsDescriptor(),
                      ReadSection(file, {"slam"}, methods::slam::SlamOptionsDescriptor()), loaded.slam);
    ExpectSameOptions(channel::RangeLevelOptionsDescriptor(),
                      ReadSection(file, {"measurements"}, channel::RangeLevelOptionsDescriptor(),
                                  {"model", "anchors", "ranges", "truth", "start_m"}),
                      loaded.range_level);
    ExpectSameOptions(eval::DivergenceRuleDescriptor(),
                      ReadSection(file, {"evaluation", "divergence"}, eval::DivergenceRuleDescriptor()),
                      loaded.divergence);
  }
}

TEST(ReadOptionsOnTheExamples, GivesTheCoopLoadersValues) {
  const auto files = Examples(true);
  ASSERT_GE(files.size(), 1u);
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const pipeline::CoopExperimentConfig loaded = LoadCoopScenario(file).config;

    ExpectSameOptions(channel::ChannelOptionsDescriptor(),
                      ReadSection(file, {"channel"}, channel::ChannelOptionsDescriptor(),
                                  {"simulated_max_order", "self_coupling_db"}),
                      loaded.channel);
    ExpectSameOptions(dsp::MpcExtractorOptionsDescriptor(),
                      ReadSection(file, {"mpc"}, dsp::MpcExtractorOptionsDescriptor()), loaded.mpc);
    ExpectSameOptions(methods::coop::CoopOptionsDescriptor(),
                      ReadSection(file, {"coop"}, methods::coop::CoopOptionsDescriptor()), loaded.coop);
  }
}

// The comparisons above are not between defaults only: the examples set non-default values,
// through `extends` too.
TEST(ReadOptionsOnTheExamples, ReadsTheValuesTheExamplesSet) {
  const auto slam = ReadSection(Example("seminar_room_slam.yaml"), {"slam"}, methods::slam::SlamOptionsDescriptor());
  const auto mpc = ReadSection(Example("coop_room.yaml"), {"mpc"}, dsp::MpcExtractorOptionsDescriptor());
  const auto coop_channel = ReadSection(Example("coop_room.yaml"), {"channel"}, channel::ChannelOptionsDescriptor(),
                                        {"simulated_max_order", "self_coupling_db"});

  EXPECT_EQ(slam.motion.accel_sigma_mps2, 0.5);
  EXPECT_FALSE(slam.prior_visibility);
  EXPECT_EQ(mpc.relative_threshold_db, -60.0);
  EXPECT_EQ(coop_channel.pulse.rolloff, 0.6);
  EXPECT_EQ(coop_channel.window_length_s, 100e-9);
}

}  // namespace
}  // namespace mirage::io
