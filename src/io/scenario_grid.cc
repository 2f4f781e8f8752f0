// SPDX-License-Identifier: MIT
#include "mirage/io/scenario_grid.h"

#include <fmt/format.h>

#include "mirage/io/input_error.h"

namespace mirage::io {
namespace {

// One step of a key path: a map key, optionally followed by a list index.
struct PathStep {
  std::string key;
  int index = -1;
};

std::vector<PathStep> ParsePath(const std::string& path) {
  std::vector<PathStep> steps;
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t end = path.find('.', begin);
    std::string part = path.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    PathStep step;
    if (const auto open = part.find('['); open != std::string::npos && part.back() == ']') {
      try {
        step.index = std::stoi(part.substr(open + 1, part.size() - open - 2));
      } catch (const std::exception&) {
        step.index = -2;  // reported by the caller
      }
      part = part.substr(0, open);
    }
    step.key = part;
    steps.push_back(step);
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return steps;
}

// The node at `path` in `document`, or an invalid node; creates nothing. (A yaml-cpp handle is
// moved with reset(): assigning to it would overwrite the node it refers to.)
YAML::Node Find(const YAML::Node& document, const std::vector<PathStep>& steps) {
  YAML::Node node;
  node.reset(document);
  for (const PathStep& step : steps) {
    const YAML::Node& here = node;  // const lookup: non-const operator[] would insert
    if (!here.IsMap() || step.key.empty() || step.index < -1 || !here[step.key]) return YAML::Node(YAML::NodeType::Undefined);
    node.reset(here[step.key]);
    if (step.index >= 0) {
      if (!node.IsSequence() || static_cast<std::size_t>(step.index) >= node.size()) return YAML::Node(YAML::NodeType::Undefined);
      YAML::Node element = node[static_cast<std::size_t>(step.index)];
      node.reset(element);
    }
  }
  return node;
}

// A new map or list with the same entries as `node`, shared, not cloned: yaml-cpp keeps the
// file's line only in the nodes it parsed (YAML::Clone and every new node lose it), so what a
// variant does not change keeps its lines for messages. The copy keeps the flow or block style,
// so that a variant equal to another also prints equal (repeats are found by their text).
YAML::Node ShallowCopy(const YAML::Node& node) {
  YAML::Node copy(node.IsMap() ? YAML::NodeType::Map : YAML::NodeType::Sequence);
  if (node.IsMap()) {
    for (const auto& kv : node) copy.force_insert(kv.first, kv.second);
  } else {
    for (const auto& element : node) copy.push_back(element);
  }
  copy.SetStyle(node.Style());
  return copy;
}

// Puts `value` under `key` of `map` in place of the old value, with the same key node and in the
// same place, so that a variant equal to the base also prints equal.
void Replace(YAML::Node& map, const std::string& key, const YAML::Node& value) {
  std::vector<std::pair<YAML::Node, YAML::Node>> entries;
  for (const auto& kv : map) entries.emplace_back(kv.first, kv.first.Scalar() == key ? value : kv.second);
  for (const auto& [k, v] : entries) map.remove(k);
  for (const auto& [k, v] : entries) map.force_insert(k, v);
}

// Sets the value at `steps` in `document`, a variant's own root map whose entries the other
// variants share: copy on write, every map and list on the path is replaced by a shallow copy of
// its own before it changes, and nothing off the path is copied (so it keeps its lines). Stops
// without a change where the path does not lead through maps and lists (an earlier key of the
// same grid entry replaced a part of it); reading the variant then reports what it finds.
void SetValue(YAML::Node& document, const std::vector<PathStep>& steps, const YAML::Node& value) {
  YAML::Node map;  // moved with reset(): assigning to a yaml-cpp handle overwrites its node
  map.reset(document);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const PathStep& step = steps[i];
    const bool last = i + 1 == steps.size();
    const YAML::Node& const_map = map;  // const lookup: non-const operator[] would insert
    const YAML::Node child = const_map[step.key];
    YAML::Node next, descend;
    if (step.index < 0) {
      if (!last && !child.IsMap()) return;
      next.reset(last ? value : ShallowCopy(child));
      descend.reset(next);
    } else {
      if (!child.IsSequence() || static_cast<std::size_t>(step.index) >= child.size()) return;
      const YAML::Node element = child[static_cast<std::size_t>(step.index)];
      if (!last && !element.IsMap()) return;
      descend.reset(last ? value : ShallowCopy(element));
      YAML::Node list(YAML::NodeType::Sequence);
      for (std::size_t e = 0; e < child.size(); ++e) {
        list.push_back(static_cast<int>(e) == step.index ? descend : child[e]);
      }
      list.SetStyle(child.Style());
      next.reset(list);
    }
    Replace(map, step.key, next);
    map.reset(descend);
  }
}

std::string Text(const YAML::Node& value) {
  if (value.IsScalar()) return value.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << value;
  return out.c_str();
}

}  // namespace

std::vector<GridVariant> ExpandGrid(const YAML::Node& document, const std::shared_ptr<const YamlOrigins>& origins) {
  if (!document["grid"]) return {{"", {}, document, origins}};
  YAML::Node base = ShallowCopy(document);
  base.remove("grid");
  YamlMap root(document, "", origins);
  const std::string file = origins->FileOf("grid");
  const YAML::Node grid = document["grid"];
  if (!grid.IsSequence() || grid.size() == 0) root.Fail("grid", "expected a non-empty list of entries {key.path: [values], ...}");
  std::vector<GridVariant> variants;
  std::vector<std::string> seen;
  for (std::size_t n = 0; n < grid.size(); ++n) {
    const YAML::Node entry = grid[n];
    const auto fail = [&](const YAML::Node& at, const std::string& message) {
      throw InputError(fmt::format("{}:{}: grid[{}]: {}", file, at.Mark().line + 1, n, message));
    };
    if (!entry.IsMap() || entry.size() == 0) fail(entry, "expected a map {key.path: [values], ...}");
    std::vector<std::pair<std::string, YAML::Node>> axes;
    std::size_t count = 1;
    for (const auto& kv : entry) {
      const std::string path = kv.first.Scalar();
      if (path == "grid" || path == "name" || path.rfind("grid.", 0) == 0) fail(kv.first, "'" + path + "' cannot vary");
      if (!Find(document, ParsePath(path))) {
        fail(kv.first, "'" + path + "' names no key the scenario sets; set its base value in the scenario and list the "
                                    "variants' values here");
      }
      if (!kv.second.IsSequence() || kv.second.size() == 0) fail(kv.second, "'" + path + "': expected a non-empty list of values");
      count *= kv.second.size();
      if (variants.size() + count > kMaxGridVariants) fail(kv.first, fmt::format("the grid gives more than {} variants", kMaxGridVariants));
      axes.emplace_back(path, kv.second);
    }
    for (std::size_t k = 0; k < count; ++k) {
      GridVariant v;
      v.document = ShallowCopy(base);
      auto variant_origins = std::make_shared<YamlOrigins>(*origins);
      std::size_t rest = k;
      std::vector<std::size_t> at(axes.size());
      for (std::size_t a = axes.size(); a-- > 0;) {
        at[a] = rest % axes[a].second.size();
        rest /= axes[a].second.size();
      }
      for (std::size_t a = 0; a < axes.size(); ++a) {
        const YAML::Node value = axes[a].second[at[a]];
        // The grid entry's own node: messages about the value name its line.
        SetValue(v.document, ParsePath(axes[a].first), value);
        variant_origins->Set(axes[a].first, file);
        v.overrides.emplace_back(axes[a].first, Text(value));
        v.name += (v.name.empty() ? "" : ", ") + axes[a].first + "=" + Text(value);
      }
      v.origins = std::move(variant_origins);
      YAML::Emitter emitted;
      emitted << v.document;
      const std::string text = emitted.c_str();
      if (std::find(seen.begin(), seen.end(), text) != seen.end()) continue;
      seen.push_back(text);
      variants.push_back(std::move(v));
    }
  }
  return variants;
}

}  // namespace mirage::io
