// SPDX-License-Identifier: MIT
#include "mirage/io/yaml_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include <fmt/format.h>

namespace mirage::io {
namespace {

std::string JoinPath(const std::string& base, const std::string& key) {
  if (base.empty()) return key;
  if (!key.empty() && key.front() == '[') return base + key;
  return base + "." + key;
}

std::string ScalarText(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return fmt::format("a list of {}", node.size());
  if (node.IsMap()) return "a map";
  return "nothing";
}

InputError SyntaxError(const std::string& file, const YAML::ParserException& e) {
  return InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", file, e.mark.line + 1, e.mark.column + 1, e.msg));
}

YAML::Node LoadFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path + ": file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": not a regular file");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::ParserException& e) {
    throw SyntaxError(path, e);
  } catch (const YAML::BadFile&) {
    throw InputError(path + ": cannot read file");
  }
}

// Map keys must be plain scalars and appear once (yaml-cpp accepts duplicates silently and keeps
// one of them, which one depending on how the node is read).
void CheckKeys(const YAML::Node& map, const std::string& path, const std::string& file) {
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const std::string where = fmt::format("{}:{}", file, kv.first.Mark().line + 1);
    if (!kv.first.IsScalar()) {
      throw InputError(fmt::format("{}: {}: keys must be plain names, got {}", where, path.empty() ? "document" : path,
                                   ScalarText(kv.first)));
    }
    if (!seen.insert(kv.first.Scalar()).second) {
      throw InputError(fmt::format("{}: {}: duplicate key", where, JoinPath(path, kv.first.Scalar())));
    }
  }
}

void Merge(YAML::Node base, const YAML::Node& over, const std::string& path, const std::string& file,
           YamlOrigins& origins) {
  CheckKeys(over, path, file);
  for (const auto& kv : over) {
    const auto key = kv.first.as<std::string>();
    const std::string key_path = JoinPath(path, key);
    if (key == "extends" && path.empty()) continue;
    const YAML::Node& const_base = base;  // const lookup: non-const operator[] would insert
    // A scenario that switches to another method does not inherit the base's method options:
    // `method` maps with different names replace each other instead of merging.
    const bool other_method = path.empty() && key == "method" && kv.second.IsMap() && const_base[key] &&
                              const_base[key].IsMap() && kv.second["name"] && const_base[key]["name"] &&
                              kv.second["name"].Scalar() != const_base[key]["name"].Scalar();
    if (kv.second.IsMap() && const_base[key] && const_base[key].IsMap() && !other_method) {
      Merge(base[key], kv.second, key_path, file, origins);
    } else if (const_base[key]) {
      base[key] = kv.second;
      origins.Set(key_path, file);
    } else {
      // A new key keeps its own node, and with it the line it was written on.
      base.force_insert(kv.first, kv.second);
      origins.Set(key_path, file);
    }
  }
}

}  // namespace

const std::string& YamlOrigins::FileOf(const std::string& path) const {
  std::string prefix = path;
  while (true) {
    const auto it = files_.find(prefix);
    if (it != files_.end()) return it->second;
    const auto cut = prefix.find_last_of(".[");
    if (cut == std::string::npos) return default_file_;
    prefix = prefix.substr(0, cut);
  }
}

namespace {

// chain: the files being loaded, to detect `extends` cycles.
YAML::Node LoadWithExtends(const std::string& path, YamlOrigins& origins, std::vector<std::string>& chain) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec).string();
  for (const auto& seen : chain) {
    if (seen == canonical) throw InputError(path + ": extends: the files extend each other in a cycle");
  }
  chain.push_back(canonical);
  YAML::Node doc = LoadFile(path);
  if (!doc.IsMap()) throw InputError(path + ":1: the document must be a map of keys");
  if (!doc["extends"]) return doc;
  const YAML::Node extends = doc["extends"];
  if (!extends.IsScalar()) {
    throw InputError(fmt::format("{}:{}: extends: expected a file name", path, extends.Mark().line + 1));
  }
  const auto base_path = (std::filesystem::path(path).parent_path() / extends.as<std::string>()).string();
  YamlOrigins base_origins(base_path);
  YAML::Node base = LoadWithExtends(base_path, base_origins, chain);
  // The merged document's default origin is the base file; every key this file sets is recorded.
  origins = base_origins;
  Merge(base, doc, "", path, origins);
  return base;
}

}  // namespace

YAML::Node LoadYamlWithExtends(const std::string& path, YamlOrigins& origins) {
  std::vector<std::string> chain;
  return LoadWithExtends(path, origins, chain);
}

YAML::Node LoadYamlString(const std::string& text, const std::string& name) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw SyntaxError(name, e);
  }
}

namespace {

// The line of the key node of `key` in `map` (null when there is none).
YAML::Mark KeyMark(const YAML::Node& map, const std::string& key) {
  if (!map.IsMap()) return YAML::Mark::null_mark();
  for (const auto& kv : map) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) return kv.first.Mark();
  }
  return YAML::Mark::null_mark();
}

// The node's line, else `fallback`. yaml-cpp keeps lines only in the nodes it parsed: the maps
// and lists a grid variant copies (scenario_grid.cc) and the empty map of an absent optional
// section have none, and a message then names the line of their key or of the enclosing map.
YAML::Mark MarkOr(const YAML::Mark& mark, const YAML::Mark& fallback) { return mark.is_null() ? fallback : mark; }
YAML::Mark MarkOr(const YAML::Node& node, const YAML::Mark& fallback) { return MarkOr(node.Mark(), fallback); }

}  // namespace

YamlMap::YamlMap(YAML::Node node, std::string path, std::shared_ptr<const YamlOrigins> origins)
    : YamlMap(std::move(node), std::move(path), std::move(origins), YAML::Mark::null_mark()) {}

YamlMap::YamlMap(YAML::Node node, std::string path, std::shared_ptr<const YamlOrigins> origins, const YAML::Mark& fallback)
    : node_(std::move(node)), path_(std::move(path)), origins_(std::move(origins)), mark_(MarkOr(node_, fallback)) {
  if (!node_.IsMap()) {
    throw InputError(fmt::format("{}: {}: expected a map of keys, got {}", Where(node_, path_),
                                 path_.empty() ? "document" : path_, ScalarText(node_)));
  }
  CheckKeys(node_, path_, origins_->FileOf(path_));
}

bool YamlMap::Has(const std::string& key) const { return static_cast<bool>(node_[key]); }

std::string YamlMap::KeyPath(const std::string& key) const { return JoinPath(path_, key); }

YAML::Mark YamlMap::ChildMark(const YAML::Node& value, const std::string& key) const {
  return MarkOr(value, MarkOr(KeyMark(node_, key), mark_));
}

std::string YamlMap::Where(const YAML::Node& node, const std::string& key_path) const {
  const std::string& file = origins_->FileOf(key_path);
  const auto mark = MarkOr(node, mark_);
  if (mark.is_null()) return file;
  return fmt::format("{}:{}", file, mark.line + 1);
}

void YamlMap::Fail(const std::string& key, const std::string& message) const {
  // A dotted key ("relocalization.search_step_m", from a nested Validate()) names a node in a
  // sub-map; point at the deepest node that exists so file and line belong together.
  // Node::reset rebinds; operator= would overwrite the referenced node inside the document.
  YAML::Node at;
  at.reset(node_);
  YAML::Mark mark = mark_;
  std::size_t begin = 0;
  while (begin <= key.size()) {
    const auto dot = std::min(key.find('.', begin), key.size());
    const YAML::Node& map = at;  // const lookup: non-const operator[] would insert
    const std::string part = key.substr(begin, dot - begin);
    const YAML::Node child = map.IsMap() ? map[part] : YAML::Node();
    if (!child) break;
    mark = MarkOr(child, MarkOr(KeyMark(map, part), mark));
    at.reset(child);
    begin = dot + 1;
  }
  const std::string& file = origins_->FileOf(KeyPath(key));
  const std::string where = mark.is_null() ? file : fmt::format("{}:{}", file, mark.line + 1);
  throw InputError(fmt::format("{}: {}: {}", where, KeyPath(key), message));
}

void YamlMap::FailProblem(const std::string& problem) const {
  const auto space = problem.find(' ');
  std::string key = problem.substr(0, space);
  if (!key.empty() && key.back() == ':') key.pop_back();
  Fail(key, space == std::string::npos ? std::string("invalid") : problem.substr(space + 1));
}

YAML::Node YamlMap::Get(const std::string& key) {
  used_.insert(key);
  return node_[key];
}

std::optional<double> YamlMap::ParseNumber(const YAML::Node& node) {
  if (!node.IsScalar()) return std::nullopt;
  try {
    return node.as<double>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

double YamlMap::ToNumber(const YAML::Node& node, const std::string& key_path) const {
  const std::optional<double> value = ParseNumber(node);
  if (!value) throw InputError(fmt::format("{}: {}: expected a number, got {}", Where(node, key_path), key_path, ScalarText(node)));
  if (!std::isfinite(*value)) {
    throw InputError(fmt::format("{}: {}: expected a finite number, got {}", Where(node, key_path), key_path, ScalarText(node)));
  }
  return *value;
}

std::optional<double> YamlMap::FiniteNumber(const std::string& key, const std::string& expected) {
  const YAML::Node n = Get(key);
  if (!n) return std::nullopt;
  const std::optional<double> value = ParseNumber(n);
  if (!value || !std::isfinite(*value)) Fail(key, fmt::format("expected {}, got {}", expected, ScalarText(n)));
  return value;
}

double YamlMap::Number(const std::string& key, double fallback) {
  const YAML::Node n = Get(key);
  if (!n) return fallback;
  return ToNumber(n, KeyPath(key));
}

double YamlMap::Number(const std::string& key) {
  const YAML::Node n = Get(key);
  if (!n) Fail(key, "missing (required)");
  return ToNumber(n, KeyPath(key));
}

double YamlMap::NumberInRange(const std::string& key, double fallback, double lo, double hi, const std::string& unit) {
  const double v = Number(key, fallback);
  if (v < lo || v > hi) {
    const std::string u = unit.empty() ? "" : " " + unit;
    Fail(key, fmt::format("{}{} is out of range, expected [{}, {}]{}", FormatValue(v), u, FormatValue(lo),
                          FormatValue(hi), u));
  }
  return v;
}

int YamlMap::Integer(const std::string& key, int fallback, int lo, int hi) {
  const YAML::Node n = Get(key);
  if (!n) return fallback;
  const double v = ToNumber(n, KeyPath(key));
  if (v != std::floor(v)) Fail(key, "expected an integer, got " + ScalarText(n));
  if (v < lo || v > hi) Fail(key, fmt::format("{} is out of range, expected an integer in [{}, {}]", FormatValue(v), lo, hi));
  return static_cast<int>(v);
}

std::uint64_t YamlMap::Unsigned(const std::string& key, std::uint64_t fallback) {
  const YAML::Node n = Get(key);
  if (!n) return fallback;
  try {
    if (!n.IsScalar() || n.Scalar().empty() || n.Scalar().front() == '-') throw YAML::Exception({}, "");
    return n.as<std::uint64_t>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected a non-negative integer, got " + ScalarText(n));
  }
}

bool YamlMap::Boolean(const std::string& key, bool fallback) {
  const YAML::Node n = Get(key);
  if (!n) return fallback;
  try {
    if (!n.IsScalar()) throw YAML::Exception({}, "");
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected true or false, got " + ScalarText(n));
  }
}

std::string YamlMap::String(const std::string& key, const std::optional<std::string>& fallback) {
  const YAML::Node n = Get(key);
  if (!n) {
    if (!fallback) Fail(key, "missing (required)");
    return *fallback;
  }
  if (!n.IsScalar()) Fail(key, "expected a string, got " + ScalarText(n));
  return n.Scalar();
}

std::string YamlMap::FilePath(const std::string& key) {
  const std::string value = String(key);
  if (value.empty()) Fail(key, "expected a file name, got an empty string");
  const std::filesystem::path path(value);
  if (path.is_absolute()) return value;
  // Relative to the file that set the key (a scenario may extend one in another directory).
  return (std::filesystem::path(origins_->FileOf(KeyPath(key))).parent_path() / path).lexically_normal().string();
}

Vec2 YamlMap::Point(const std::string& key) {
  const YAML::Node n = Get(key);
  if (!n) Fail(key, "missing (required), expected [x, y] in metres");
  if (!n.IsSequence() || n.size() != 2) Fail(key, "expected 2 numbers [x, y], got " + ScalarText(n));
  return {ToNumber(n[0], KeyPath(key) + "[0]"), ToNumber(n[1], KeyPath(key) + "[1]")};
}

Vec3 YamlMap::Point3(const std::string& key, double default_z_m) {
  const YAML::Node n = Get(key);
  if (!n) Fail(key, "missing (required), expected [x, y, z] or [x, y] in metres");
  if (!n.IsSequence() || (n.size() != 2 && n.size() != 3)) {
    Fail(key, "expected 3 numbers [x, y, z] or 2 numbers [x, y], got " + ScalarText(n));
  }
  const std::string path = KeyPath(key);
  return Vec3(ToNumber(n[0], path + "[0]"), ToNumber(n[1], path + "[1]"),
              n.size() == 3 ? ToNumber(n[2], path + "[2]") : default_z_m);
}

std::vector<Vec2> YamlMap::Points(const std::string& key, std::size_t min_count) {
  const YAML::Node n = Get(key);
  if (!n) Fail(key, "missing (required), expected a list of [x, y] points in metres");
  if (!n.IsSequence()) Fail(key, "expected a list of [x, y] points, got " + ScalarText(n));
  if (n.size() < min_count) Fail(key, fmt::format("expected at least {} points, got {}", min_count, n.size()));
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const YAML::Node p = n[i];
    const std::string p_path = fmt::format("{}[{}]", KeyPath(key), i);
    if (!p.IsSequence() || p.size() != 2) {
      throw InputError(fmt::format("{}: {}: expected 2 numbers [x, y], got {}", Where(p, p_path), p_path, ScalarText(p)));
    }
    points.emplace_back(ToNumber(p[0], p_path + "[0]"), ToNumber(p[1], p_path + "[1]"));
  }
  return points;
}

YamlMap YamlMap::Map(const std::string& key) {
  const YAML::Node n = Get(key);
  if (!n) Fail(key, "missing (required)");
  return YamlMap(n, KeyPath(key), origins_, ChildMark(n, key));
}

YamlMap YamlMap::OptionalMap(const std::string& key) {
  const YAML::Node n = Get(key);
  if (!n) return YamlMap(YAML::Node(YAML::NodeType::Map), KeyPath(key), origins_, mark_);
  return YamlMap(n, KeyPath(key), origins_, ChildMark(n, key));
}

std::vector<YamlMap> YamlMap::MapList(const std::string& key, bool allow_empty) {
  const YAML::Node n = Get(key);
  if (!n) Fail(key, "missing (required)");
  if (!n.IsSequence()) Fail(key, "expected a list, got " + ScalarText(n));
  if (!allow_empty && n.size() == 0) Fail(key, "expected at least one entry");
  std::vector<YamlMap> maps;
  const YAML::Mark list_mark = ChildMark(n, key);
  for (std::size_t i = 0; i < n.size(); ++i) {
    maps.push_back(YamlMap(n[i], fmt::format("{}[{}]", KeyPath(key), i), origins_, list_mark));
  }
  return maps;
}

// An absent key gives an empty sequence: callers fall back to their default.
YAML::Node YamlMap::OptionalNonEmptyList(const std::string& key) {
  const YAML::Node n = Get(key);
  if (!n) return YAML::Node(YAML::NodeType::Sequence);
  if (!n.IsSequence()) Fail(key, "expected a list, got " + ScalarText(n));
  if (n.size() == 0) Fail(key, "expected at least one entry");
  return n;
}

std::vector<double> YamlMap::NumberList(const std::string& key) {
  const YAML::Node n = OptionalNonEmptyList(key);
  std::vector<double> values;
  for (std::size_t i = 0; i < n.size(); ++i) values.push_back(ToNumber(n[i], fmt::format("{}[{}]", KeyPath(key), i)));
  return values;
}

std::vector<bool> YamlMap::BooleanList(const std::string& key) {
  const YAML::Node n = OptionalNonEmptyList(key);
  std::vector<bool> values;
  for (std::size_t i = 0; i < n.size(); ++i) {
    const YAML::Node entry = n[i];
    bool ok = entry.IsScalar();
    bool value = false;
    if (ok) {
      try {
        value = entry.as<bool>();
      } catch (const YAML::Exception&) {
        ok = false;
      }
    }
    if (!ok) FailAt(key, i, "expected true or false, got " + ScalarText(entry));
    values.push_back(value);
  }
  return values;
}

void YamlMap::FailAt(const std::string& key, std::size_t index, const std::string& message) const {
  const std::string key_path = fmt::format("{}[{}]", KeyPath(key), index);
  const YAML::Node& map = node_;  // const lookup: non-const operator[] would insert
  const YAML::Node list = map[key];
  // Fall back to the map's line when the entry does not exist (a caller's wrong index).
  const YAML::Node at = list && list.IsSequence() && index < list.size() ? list[index] : node_;
  throw InputError(fmt::format("{}: {}: {}", Where(at, key_path), key_path, message));
}

std::vector<std::pair<std::string, double>> YamlMap::NumberTable() {
  std::vector<std::pair<std::string, double>> table;
  for (const auto& kv : node_) {
    const auto name = kv.first.as<std::string>();
    used_.insert(name);
    table.emplace_back(name, ToNumber(kv.second, KeyPath(name)));
  }
  return table;
}

void YamlMap::RejectUnknownKeys() const {
  for (const auto& kv : node_) {
    const auto key = kv.first.as<std::string>();
    if (used_.count(key) != 0 || (path_.empty() && key == "extends")) continue;
    std::string allowed;
    for (const auto& k : used_) {
      if (!allowed.empty()) allowed += ", ";
      allowed += k;
    }
    throw InputError(fmt::format("{}: {}: unknown key (known keys here: {})", Where(kv.first, KeyPath(key)), KeyPath(key),
                                 allowed.empty() ? "none" : allowed));
  }
}

std::string FormatValue(double value) { return fmt::format("{:.6g}", value); }

}  // namespace mirage::io
