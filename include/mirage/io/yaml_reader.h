// SPDX-License-Identifier: MIT
// Strict, position-aware reading of YAML documents: every value is read through a YamlMap that
// knows its file, line and key path, checks types and ranges, and rejects unknown keys, so that a
// typo never passes silently (STYLE.md Sec. 4, 9). The only place besides the scenario parsers
// (scenario.cc, coop_scenario.cc) that sees yaml-cpp.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mirage/core/types.h"
#include "mirage/io/input_error.h"

namespace mirage::io {

/// Which file each key path came from (documents merged with `extends:`).
class YamlOrigins {
 public:
  explicit YamlOrigins(std::string default_file) : default_file_(std::move(default_file)) {}
  /// Records that the value at `path` (and below) came from `file`.
  void Set(const std::string& path, const std::string& file) { files_[path] = file; }
  /// The file that provided `path`: the longest recorded prefix, else the default file.
  [[nodiscard]] const std::string& FileOf(const std::string& path) const;

 private:
  std::string default_file_;
  std::map<std::string, std::string> files_;
};

/// Loads a YAML file; a top-level `extends: other.yaml` (relative to the file) loads that file
/// first and merges this one over it (maps recursively, everything else replaced; a `method` map
/// naming another method replaces the base's instead of merging with it).
/// Throws InputError for missing files and syntax errors.
YAML::Node LoadYamlWithExtends(const std::string& path, YamlOrigins& origins);

/// Parses YAML text (tests, options given on a command line); `name` stands for the file in
/// messages. Throws InputError for syntax errors.
YAML::Node LoadYamlString(const std::string& text, const std::string& name);

/// One YAML mapping being read.
class YamlMap {
 public:
  /// @param node    must be a map (else InputError).
  /// @param path    key path for messages, e.g. "channel.pulse" ("" for the root).
  YamlMap(YAML::Node node, std::string path, std::shared_ptr<const YamlOrigins> origins);

  [[nodiscard]] bool Has(const std::string& key) const;
  [[nodiscard]] const std::string& path() const { return path_; }

  /// A finite number; `fallback` when the key is absent.
  double Number(const std::string& key, double fallback);
  /// A required finite number.
  double Number(const std::string& key);
  /// A finite number, or empty when the key is absent. Anything else fails with "expected
  /// <expected>, got ..." (`expected` names the range and unit: "a number > 0 m/s^2").
  std::optional<double> FiniteNumber(const std::string& key, const std::string& expected);
  /// A number in [lo, hi] (inclusive), with the unit for the message.
  double NumberInRange(const std::string& key, double fallback, double lo, double hi, const std::string& unit);
  /// An integer; `fallback` when absent.
  int Integer(const std::string& key, int fallback, int lo, int hi);
  /// An unsigned 64-bit integer (seeds).
  std::uint64_t Unsigned(const std::string& key, std::uint64_t fallback);
  /// true/false.
  bool Boolean(const std::string& key, bool fallback);
  /// A string; required when fallback is empty-optional.
  std::string String(const std::string& key, const std::optional<std::string>& fallback = std::nullopt);
  /// A file name (required), resolved relative to the directory of the file that set the key.
  std::string FilePath(const std::string& key);
  /// A point [x, y] (m).
  Vec2 Point(const std::string& key);
  /// A point [x, y, z] or [x, y] (m); the missing z is `default_z_m`.
  Vec3 Point3(const std::string& key, double default_z_m);
  /// A list of points [[x, y], ...] with at least min_count entries.
  std::vector<Vec2> Points(const std::string& key, std::size_t min_count);
  /// A nested map (required).
  YamlMap Map(const std::string& key);
  /// A nested map, or an empty one when the key is absent.
  YamlMap OptionalMap(const std::string& key);
  /// A list of maps (required, possibly empty when allow_empty).
  std::vector<YamlMap> MapList(const std::string& key, bool allow_empty);
  /// A non-empty list of finite numbers ([1, 2.5]; a single number is not a list), or an empty
  /// vector when the key is absent.
  std::vector<double> NumberList(const std::string& key);
  /// A non-empty list of true/false, or an empty vector when the key is absent.
  std::vector<bool> BooleanList(const std::string& key);
  /// This map read as name -> number (e.g. materials); marks every key as known.
  std::vector<std::pair<std::string, double>> NumberTable();

  /// Throws for every key that was never read.
  void RejectUnknownKeys() const;

  /// Throws an InputError "file:line: path.key: message".
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const;
  /// Throws an InputError for a problem returned by a Validate() function, "key.path: message"
  /// (or, in the older form, "key.path message"), at the key it names.
  [[noreturn]] void FailProblem(const std::string& problem) const;
  /// Throws an InputError "file:line: path.key[index]: message" at the line of entry `index` of
  /// the list at `key` (for checks on single entries of NumberList and BooleanList).
  [[noreturn]] void FailAt(const std::string& key, std::size_t index, const std::string& message) const;

 private:
  [[nodiscard]] YAML::Node Get(const std::string& key);
  [[nodiscard]] std::string KeyPath(const std::string& key) const;
  [[nodiscard]] std::string Where(const YAML::Node& node, const std::string& key_path) const;
  [[nodiscard]] double ToNumber(const YAML::Node& node, const std::string& key_path) const;
  // The node's number (possibly not finite), or empty when it is not a number.
  [[nodiscard]] static std::optional<double> ParseNumber(const YAML::Node& node);
  [[nodiscard]] YAML::Node OptionalNonEmptyList(const std::string& key);
  // `fallback`: where the map is when its node has no line of its own (an absent optional map,
  // or a map a grid variant copied).
  YamlMap(YAML::Node node, std::string path, std::shared_ptr<const YamlOrigins> origins, const YAML::Mark& fallback);
  // The line of the value at `key` (its own, else its key's, else this map's) for a child map.
  [[nodiscard]] YAML::Mark ChildMark(const YAML::Node& value, const std::string& key) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const YamlOrigins> origins_;
  YAML::Mark mark_;  ///< the map's line for messages: its node's, else the fallback it was given
  std::set<std::string> used_;
};

/// Formats a number for messages (up to 6 significant digits).
std::string FormatValue(double value);

}  // namespace mirage::io
