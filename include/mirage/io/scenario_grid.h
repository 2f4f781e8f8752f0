// SPDX-License-Identifier: MIT
// A scenario's `grid:` (docs/scenario.md): a list of entries, each a map from a key path of the
// scenario ("method.wall_update", "channel.pulse.duration_s", "trajectories[0].speed_mps") to a
// list of values. An entry gives the Cartesian product of its lists (the last key varying
// fastest), the grid the union of its entries in order; a variant equal to an earlier one is
// dropped. A key path must name a key the scenario sets (its base value): a grid varies values,
// it does not add keys.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mirage/io/yaml_reader.h"

namespace mirage::io {

/// One variant: the scenario's document with the variant's values set and `grid` removed.
struct GridVariant {
  std::string name;  ///< "key=value, key=value" (empty without a grid)
  std::vector<std::pair<std::string, std::string>> overrides;
  YAML::Node document;
  /// Which file each key path of `document` came from: the scenario's, with the values the
  /// variant sets from the file that wrote the grid (messages name it with the grid's line).
  std::shared_ptr<const YamlOrigins> origins;
};

/// Most variants a grid may give (a valid-looking file must not exhaust the machine).
inline constexpr std::size_t kMaxGridVariants = 1000;

/// The variants of `document` (one, unchanged but for `grid`, without a grid). Throws
/// InputError at the grid entry for an unknown key path, an empty list or too many variants.
std::vector<GridVariant> ExpandGrid(const YAML::Node& document, const std::shared_ptr<const YamlOrigins>& origins);

}  // namespace mirage::io
