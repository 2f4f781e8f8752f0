// SPDX-License-Identifier: MIT
// Section readers shared by the scenario parsers (io/scenario.cc for MINT and SLAM,
// io/coop_scenario.cc for cooperative tracking), so that a section written the same way in both
// kinds of file is read, checked and reported the same way (docs/scenario.md).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/io/scenario.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {

/// Upper bound of values that only have to be positive: large enough for any room, small enough
/// that products of two such values stay finite.
inline constexpr double kHuge = 1e9;
/// Monte-Carlo runs: below the stride of the MINT seed streams (trajectory * 1000003 + run).
inline constexpr int kMaxRuns = 1'000'000;
/// Worker threads.
inline constexpr int kMaxThreads = 1024;
/// Virtual anchors (image paths) per anchor or link: keeps a valid-looking file from exhausting
/// the machine.
inline constexpr double kMaxVirtualAnchorsPerAnchor = 2e5;

/// The run grid's extreme offsets (the zero offset first): where every shifted run's path lies.
std::vector<Vec2> GridCorners(const pipeline::RunGrid& grid);

/// True if the name can go into a CSV field unquoted (no commas, quotes or line breaks).
bool IsPlainName(const std::string& name);

/// Fails at `key` when `walls` walls up to reflection order `order` give more than
/// kMaxVirtualAnchorsPerAnchor virtual anchors.
void CheckVirtualAnchorCount(YamlMap& section, const std::string& key, std::size_t walls, int order);

/// Runs a component's Validate() and reports the first problem against the section's key path
/// (Validate() problems start with the key they are about).
template <typename Options>
void Check(const Options& options, const YamlMap& section) {
  const auto problems = Validate(options);
  if (!problems.empty()) section.FailProblem(problems.front());
}

/// The `materials` table: name -> amplitude reflection coefficient in (0, 1].
std::map<std::string, double> ReadMaterials(YamlMap table);

/// The `floor_plan` section (walls and obstacles). With `in_plan` non-null every wall entry may
/// carry `in_plan: false` (default true) and in_plan receives one flag per wall segment, in the
/// order of the plan's walls; with it null the key is unknown.
geometry::FloorPlan ReadFloorPlan(YamlMap m, const std::map<std::string, double>& materials,
                                  std::vector<bool>* in_plan = nullptr);


/// Fails at `key` when p is not enclosed by the plan's walls or lies inside an obstacle; `what`
/// names the point in the message ("anchor 'A1'").
/// Applies the command-line overrides --runs, --seed, --threads with the ranges of the file's
/// keys; InputError naming the option otherwise.
void ApplyOverrides(const ScenarioOverrides& overrides, int& runs, std::uint64_t& seed, int& threads);

void CheckInside(const geometry::FloorPlan& plan, const Vec2& p, YamlMap& where, const std::string& key,
                 const std::string& what);

}  // namespace mirage::io
