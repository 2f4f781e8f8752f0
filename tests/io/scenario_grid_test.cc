// SPDX-License-Identifier: MIT
// A scenario's `grid:` (io/scenario_grid.h): each entry is the Cartesian product of its lists with
// the last key varying fastest, the grid is the union of its entries in order without repeats,
// a key path may index lists, every variant is named "key=value, ..." and is its own document (the
// others and the base are untouched), a value set by the grid keeps its line and what the grid does
// not change keeps its own, and a bad grid is an InputError naming grid[i] and its line.
#include "mirage/io/scenario_grid.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"

namespace mirage::io {
namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

// A document with the values the grids below vary; the comments give the lines.
const char* const kBase =
    "name: base\n"                                       // 1
    "agents: 2\n"                                        // 2
    "method:\n"                                          // 3
    "  name: coop\n"                                     // 4
    "  wall_update: true\n"                              // 5
    "  variance: {window_max_m: 0.3}\n"                  // 6
    "trajectories:\n"                                    // 7
    "  - {name: a, speed_mps: 0.5, waypoints_m: [[0, 0], [1, 0]]}\n"  // 8
    "  - {name: b, speed_mps: 0.25, waypoints_m: [[0, 1], [1, 1]]}\n";  // 9

std::vector<GridVariant> Expand(const std::string& text) {
  const auto origins = std::make_shared<YamlOrigins>("grid.yaml");
  return ExpandGrid(LoadYamlString(text, "grid.yaml"), origins);
}

// The InputError message of expanding `text` (fails the test when it expands).
std::string ErrorOf(const std::string& text) {
  try {
    Expand(text);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the grid expanded without an error:\n" << text;
  return {};
}

std::vector<std::string> Names(const std::vector<GridVariant>& variants) {
  std::vector<std::string> names;
  for (const auto& v : variants) names.push_back(v.name);
  return names;
}

TEST(ExpandGrid, WithoutAGridGivesTheDocumentAsOneUnnamedVariant) {
  const YAML::Node document = LoadYamlString(kBase, "grid.yaml");

  const auto variants = ExpandGrid(document, std::make_shared<YamlOrigins>("grid.yaml"));

  ASSERT_EQ(variants.size(), 1u);
  EXPECT_EQ(variants[0].name, "");
  EXPECT_TRUE(variants[0].overrides.empty());
  EXPECT_TRUE(variants[0].document.is(document));
  EXPECT_NE(variants[0].origins, nullptr);
}

TEST(ExpandGrid, CrossesTheListsOfAnEntryWithTheLastKeyVaryingFastest) {
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - {agents: [1, 2], method.wall_update: [false, true], method.variance.window_max_m: [0.2, 0.4]}\n");

  ASSERT_EQ(variants.size(), 8u);
  EXPECT_EQ(variants[0].name, "agents=1, method.wall_update=false, method.variance.window_max_m=0.2");
  EXPECT_EQ(variants[1].name, "agents=1, method.wall_update=false, method.variance.window_max_m=0.4");
  EXPECT_EQ(variants[2].name, "agents=1, method.wall_update=true, method.variance.window_max_m=0.2");
  EXPECT_EQ(variants[4].name, "agents=2, method.wall_update=false, method.variance.window_max_m=0.2");
  EXPECT_EQ(variants[7].name, "agents=2, method.wall_update=true, method.variance.window_max_m=0.4");
  // The documents carry the values the names say.
  EXPECT_EQ(variants[1].document["agents"].as<int>(), 1);
  EXPECT_FALSE(variants[1].document["method"]["wall_update"].as<bool>());
  EXPECT_EQ(variants[1].document["method"]["variance"]["window_max_m"].as<double>(), 0.4);
  EXPECT_EQ(variants[6].document["agents"].as<int>(), 2);
  EXPECT_TRUE(variants[6].document["method"]["wall_update"].as<bool>());
  EXPECT_EQ(variants[6].document["method"]["variance"]["window_max_m"].as<double>(), 0.2);
}

TEST(ExpandGrid, IsTheUnionOfItsEntriesInOrder) {
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - {agents: [1, 3]}\n"
                               "  - {method.wall_update: [false]}\n");

  EXPECT_EQ(Names(variants), (std::vector<std::string>{"agents=1", "agents=3", "method.wall_update=false"}));
  // An entry varies its own keys only: the last variant has the base's agents.
  EXPECT_EQ(variants[2].document["agents"].as<int>(), 2);
}

TEST(ExpandGrid, DropsAVariantEqualToAnEarlierOne) {
  // The first variant is the base itself; the third entry's agents=2 is the base too, and its
  // agents=1 repeats the second entry.
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - {method.wall_update: [true, false], agents: [2]}\n"
                               "  - {agents: [1]}\n"
                               "  - {agents: [2, 1, 3]}\n");

  EXPECT_EQ(Names(variants), (std::vector<std::string>{"method.wall_update=true, agents=2",
                                                       "method.wall_update=false, agents=2", "agents=1", "agents=3"}));
}

TEST(ExpandGrid, RecordsEachVariantsOverridesAsWritten) {
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - method.variance.window_max_m: [0.5e-1]\n"
                               "    trajectories[1].waypoints_m: [[[0, 2], [2, 2]]]\n");

  ASSERT_EQ(variants.size(), 1u);
  EXPECT_EQ(variants[0].overrides,
            (Overrides{{"method.variance.window_max_m", "0.5e-1"}, {"trajectories[1].waypoints_m", "[[0, 2], [2, 2]]"}}));
  EXPECT_EQ(variants[0].name, "method.variance.window_max_m=0.5e-1, trajectories[1].waypoints_m=[[0, 2], [2, 2]]");
}

TEST(ExpandGrid, SetsAListElementByItsIndexAndKeepsTheOtherElements) {
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - trajectories[1].speed_mps: [0.1, 0.2]\n");

  ASSERT_EQ(variants.size(), 2u);
  EXPECT_EQ(variants[0].name, "trajectories[1].speed_mps=0.1");
  const YAML::Node& trajectories = variants[1].document["trajectories"];
  ASSERT_EQ(trajectories.size(), 2u);
  EXPECT_EQ(trajectories[1]["speed_mps"].as<double>(), 0.2);
  EXPECT_EQ(trajectories[1]["name"].as<std::string>(), "b");
  EXPECT_EQ(trajectories[0]["speed_mps"].as<double>(), 0.5);
  EXPECT_EQ(trajectories[0]["name"].as<std::string>(), "a");
}

TEST(ExpandGrid, GivesEveryVariantADocumentOfItsOwnAndLeavesTheBaseAlone) {
  const YAML::Node document = LoadYamlString(std::string(kBase) +
                                                 "grid:\n"
                                                 "  - method.wall_update: [false]\n"
                                                 "    trajectories[0].speed_mps: [0.1]\n"
                                                 "  - {method.variance.window_max_m: [0.7]}\n",
                                             "grid.yaml");

  const auto variants = ExpandGrid(document, std::make_shared<YamlOrigins>("grid.yaml"));

  ASSERT_EQ(variants.size(), 2u);
  // Variant 0's values are not in variant 1 (a shared map or list changed in place would leak).
  EXPECT_TRUE(variants[1].document["method"]["wall_update"].as<bool>());
  EXPECT_EQ(variants[1].document["trajectories"][0]["speed_mps"].as<double>(), 0.5);
  EXPECT_EQ(variants[0].document["method"]["variance"]["window_max_m"].as<double>(), 0.3);
  // The scenario's own document keeps its values and its grid; the variants have no grid.
  EXPECT_TRUE(document["method"]["wall_update"].as<bool>());
  EXPECT_EQ(document["trajectories"][0]["speed_mps"].as<double>(), 0.5);
  EXPECT_EQ(document["method"]["variance"]["window_max_m"].as<double>(), 0.3);
  EXPECT_TRUE(document["grid"].IsDefined());
  for (const auto& v : variants) EXPECT_FALSE(v.document["grid"].IsDefined()) << v.name;
}

TEST(ExpandGrid, KeepsTheLinesOfWhatAVariantDoesNotChange) {
  // Messages name lines: a grid must not lose them for the lists and maps it leaves alone (the
  // trajectories of a coop file with a grid once had none). Lines are 0-based in yaml-cpp.
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - agents: [3]\n"
                               "    trajectories[0].speed_mps: [0.1]\n");

  ASSERT_EQ(variants.size(), 1u);
  const YAML::Node& d = variants[0].document;
  EXPECT_EQ(d["trajectories"][1].Mark().line, 8);
  EXPECT_EQ(d["trajectories"][1]["waypoints_m"].Mark().line, 8);
  EXPECT_EQ(d["trajectories"][0]["waypoints_m"].Mark().line, 7);
  EXPECT_EQ(d["method"].Mark().line, 3);
  EXPECT_EQ(d["method"]["variance"].Mark().line, 5);
}

TEST(ExpandGrid, GivesAValueItSetsTheLineOfTheGridEntry) {
  const auto variants = Expand(std::string(kBase) +
                               "grid:\n"
                               "  - {agents: [4]}\n"
                               "  - trajectories[0].waypoints_m: [[[0, 0], [2, 0]]]\n");

  ASSERT_EQ(variants.size(), 2u);
  EXPECT_EQ(variants[0].document["agents"].Mark().line, 10);
  EXPECT_EQ(variants[1].document["trajectories"][0]["waypoints_m"].Mark().line, 11);
}

TEST(ExpandGrid, NamesTheFileOfTheGridForTheValuesItSets) {
  // Arrange: the document as merged from base.yaml and a child that adds the grid.
  auto origins = std::make_shared<YamlOrigins>("base.yaml");
  origins->Set("grid", "child.yaml");
  const YAML::Node document = LoadYamlString(std::string(kBase) + "grid:\n  - trajectories[1].speed_mps: [0.1]\n", "x");

  // Act
  const auto variants = ExpandGrid(document, origins);

  // Assert: the value set comes from the child; its neighbours and the base stay the base's.
  ASSERT_EQ(variants.size(), 1u);
  ASSERT_NE(variants[0].origins, nullptr);
  EXPECT_EQ(variants[0].origins->FileOf("trajectories[1].speed_mps"), "child.yaml");
  EXPECT_EQ(variants[0].origins->FileOf("trajectories[1].name"), "base.yaml");
  EXPECT_EQ(variants[0].origins->FileOf("agents"), "base.yaml");
  EXPECT_EQ(origins->FileOf("trajectories[1].speed_mps"), "base.yaml");
}

// ---------------------------------------------------------------------------------------------
// Bad grids: grid[i] and the line
// ---------------------------------------------------------------------------------------------

TEST(ExpandGrid, NamesAKeyPathTheScenarioDoesNotSet) {
  const std::string message = ErrorOf(std::string(kBase) +
                                      "grid:\n"
                                      "  - {agents: [1]}\n"
                                      "  - {method.wall_sigma_m: [0.01]}\n");

  EXPECT_NE(message.find("grid.yaml:12: grid[1]: 'method.wall_sigma_m' names no key the scenario sets"),
            std::string::npos)
      << message;
}

TEST(ExpandGrid, NamesAListIndexBeyondTheList) {
  const std::string message = ErrorOf(std::string(kBase) +
                                      "grid:\n"
                                      "  - trajectories[2].speed_mps: [0.1]\n");

  EXPECT_NE(message.find("grid.yaml:11: grid[0]: 'trajectories[2].speed_mps' names no key"), std::string::npos)
      << message;
}

TEST(ExpandGrid, NamesAnIndexIntoAKeyThatIsNoList) {
  const std::string message = ErrorOf(std::string(kBase) +
                                      "grid:\n"
                                      "  - method[0].wall_update: [false]\n");

  EXPECT_NE(message.find("grid[0]: 'method[0].wall_update' names no key"), std::string::npos) << message;
}

TEST(ExpandGrid, NamesAnEmptyListOfValues) {
  const std::string message = ErrorOf(std::string(kBase) +
                                      "grid:\n"
                                      "  - {agents: [1]}\n"
                                      "  - {agents: []}\n");

  EXPECT_NE(message.find("grid.yaml:12: grid[1]: 'agents': expected a non-empty list of values"), std::string::npos)
      << message;
}

TEST(ExpandGrid, NamesAValueThatIsNotAList) {
  const std::string message = ErrorOf(std::string(kBase) +
                                      "grid:\n"
                                      "  - {agents: 3}\n");

  EXPECT_NE(message.find("grid.yaml:11: grid[0]: 'agents': expected a non-empty list of values"), std::string::npos)
      << message;
}

TEST(ExpandGrid, NamesAGridThatIsNotAListOfMaps) {
  EXPECT_NE(ErrorOf(std::string(kBase) + "grid: {agents: [1]}\n").find("grid.yaml:10: grid: expected a non-empty list"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kBase) + "grid: []\n").find("grid: expected a non-empty list"), std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kBase) + "grid:\n  - agents\n").find("grid.yaml:11: grid[0]: expected a map"),
            std::string::npos);
}

TEST(ExpandGrid, RefusesToVaryTheNameOrTheGridItself) {
  EXPECT_NE(ErrorOf(std::string(kBase) + "grid:\n  - {name: [x, y]}\n").find("grid[0]: 'name' cannot vary"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kBase) + "grid:\n  - {grid: [[]]}\n").find("grid[0]: 'grid' cannot vary"),
            std::string::npos);
}

TEST(ExpandGrid, NamesAGridOfMoreThanTheMostVariants) {
  // 10 x 10 x 11 = 1100 > kMaxGridVariants.
  const std::string ten = "[0, 1, 2, 3, 4, 5, 6, 7, 8, 9]";
  const std::string message = ErrorOf(std::string(kBase) + "grid:\n  - {agents: " + ten + ", method.wall_update: " + ten +
                                      ", method.variance.window_max_m: [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10]}\n");

  EXPECT_NE(message.find("grid[0]: the grid gives more than 1000 variants"), std::string::npos) << message;
}

}  // namespace
}  // namespace mirage::io
