// SPDX-License-Identifier: MIT
#include "mirage/io/coop_scenario.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "mirage/geometry/trajectory.h"
#include "mirage/io/scenario_sections.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {
namespace {

using pipeline::CoopAgent;
using pipeline::CoopAnchor;
using pipeline::CoopExperimentConfig;
using pipeline::CoopVariant;

constexpr int kMaxSteps = 100'000;
constexpr double kMaxSpeed_m_per_step = 0.1;
constexpr int kMaxSimulatedOrder = 3;
constexpr int kMaxFilterOrder = 2;
// Expanded variants over all grids (before duplicates are dropped): the paper's grids have a few
// dozen; the limit keeps a short file from asking for an unbounded amount of work.
constexpr std::size_t kMaxVariants = 1000;
constexpr double kMaxPulseDuration_ns = 10.0;
constexpr double kMaxWallError_mm = 500.0;
constexpr double kMaxWallSigma_mm = 1000.0;
constexpr double kNsPerS = 1e9;
constexpr double kMmPerM = 1e3;
// Marks an absent number: the file cannot contain it, ToNumber rejects non-finite values.
constexpr double kAbsent = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Agents, anchor, wall bias
// ---------------------------------------------------------------------------------------------

// The agent's centre and both antennas (TX at p + s/2 e_x, RX at p - s/2 e_x, coop_link.h) must
// stay inside the room and never cross a wall or an obstacle: the simulator places paths at the
// antennas. Checking the antennas' own legs and the centre's covers every wall that crosses the
// thin band the antenna pair sweeps, except one that ends inside it.
void CheckAgentPath(const geometry::FloorPlan& plan, const std::vector<Vec2>& waypoints_m,
                    const methods::coop::AntennaLayout& antennas, YamlMap& a) {
  struct Point {
    Vec2 offset_m;
    std::string what;
  };
  std::vector<Point> points = {{Vec2::Zero(), ""}};
  if (antennas.spacing_m > 0.0) {
    points.push_back({antennas.tx_offset(), " (its TX antenna, antenna_spacing_m / 2 along +x)"});
    points.push_back({antennas.rx_offset(), " (its RX antenna, antenna_spacing_m / 2 along -x)"});
  }
  for (const Point& point : points) {
    for (std::size_t i = 0; i < waypoints_m.size(); ++i) {
      CheckInside(plan, waypoints_m[i] + point.offset_m, a, "waypoints_m", fmt::format("waypoint {}{}", i, point.what));
      if (i > 0 && !plan.IsLegClear(waypoints_m[i - 1] + point.offset_m, waypoints_m[i] + point.offset_m)) {
        a.Fail("waypoints_m",
               fmt::format("the leg from waypoint {} to {}{} crosses a wall or an obstacle", i - 1, i, point.what));
      }
    }
  }
}

std::vector<CoopAgent> ReadAgents(YamlMap& root, const CoopExperimentConfig& config) {
  std::vector<CoopAgent> agents;
  std::set<std::string> names;
  for (auto& a : root.MapList("agents", false)) {
    CoopAgent agent;
    agent.name = a.String("name");
    if (!names.insert(agent.name).second) a.Fail("name", "duplicate agent name '" + agent.name + "'");
    if (!IsPlainName(agent.name)) a.Fail("name", "must not contain commas, quotes or line breaks (it goes into CSV files)");
    agent.waypoints_m = a.Points("waypoints_m", 2);
    if (geometry::PolylineLength(agent.waypoints_m) < 1e-6) {
      a.Fail("waypoints_m", "all waypoints are the same point; an agent needs at least 2 distinct points");
    }
    agent.speed_m_per_step = a.Number("speed_m_per_step", agent.speed_m_per_step);
    if (!(agent.speed_m_per_step > 0.0 && agent.speed_m_per_step <= kMaxSpeed_m_per_step)) {
      a.Fail("speed_m_per_step", fmt::format("{} m per step is out of range, expected (0, {}] m per step",
                                             FormatValue(agent.speed_m_per_step), FormatValue(kMaxSpeed_m_per_step)));
    }
    CheckAgentPath(config.true_plan, agent.waypoints_m, config.antennas, a);
    a.RejectUnknownKeys();
    agents.push_back(std::move(agent));
  }
  if (agents.size() < 2) {
    root.Fail("agents", fmt::format("cooperative tracking needs at least 2 agents, got {}", agents.size()));
  }
  return agents;
}

CoopAnchor ReadAnchor(YamlMap a, const geometry::FloorPlan& plan) {
  CoopAnchor anchor;
  anchor.id = a.String("id", anchor.id);
  if (anchor.id.empty() || !IsPlainName(anchor.id)) {
    a.Fail("id", "must be a non-empty name without commas, quotes or line breaks (it goes into CSV files)");
  }
  anchor.position_m = a.Point("position_m");
  CheckInside(plan, anchor.position_m, a, "position_m", "anchor '" + anchor.id + "'");
  a.RejectUnknownKeys();
  return anchor;
}

pipeline::WallBias ReadWallBias(YamlMap b, const geometry::FloorPlan& plan, const std::vector<bool>& in_plan) {
  pipeline::WallBias bias;
  const std::string label = b.String("wall");
  const auto& walls = plan.walls();
  std::vector<int> matches;
  std::set<std::string> labels;
  for (std::size_t s = 0; s < walls.size(); ++s) {
    if (walls[s].label == label) matches.push_back(static_cast<int>(s));
    if (!walls[s].label.empty()) labels.insert(walls[s].label);
  }
  if (matches.empty()) {
    std::string known;
    for (const auto& l : labels) known += (known.empty() ? "" : ", ") + l;
    b.Fail("wall", fmt::format("no wall segment is labelled '{}' (labels in floor_plan: {})", label,
                               known.empty() ? "none" : known));
  }
  if (matches.size() > 1) {
    // Labels default to the material name and a polyline gives all its segments its label.
    b.Fail("wall", fmt::format("'{}' labels {} wall segments; the biased wall must be exactly one segment (give it a "
                               "label of its own)",
                               label, matches.size()));
  }
  bias.wall = matches.front();
  if (!in_plan[static_cast<std::size_t>(bias.wall)]) {
    b.Fail("wall", fmt::format("wall '{}' has in_plan: false; the filter does not know it, so it cannot be biased", label));
  }
  bias.offset_m = b.NumberInRange("offset_m", bias.offset_m, -1.0, 1.0, "m");
  b.RejectUnknownKeys();
  return bias;
}

// ---------------------------------------------------------------------------------------------
// Channel, filter
// ---------------------------------------------------------------------------------------------

// The pulse duration is left to the variants; Validate(ChannelOptions) is run per variant pulse
// later (CheckChannelPerPulse), since the Nyquist limit and the window's minimum depend on it.
void ReadCoopChannel(YamlMap& m, CoopExperimentConfig& config) {
  channel::ChannelOptions& o = config.channel;
  config.simulated_max_order = m.Integer("simulated_max_order", config.simulated_max_order, 1, kMaxSimulatedOrder);
  CheckVirtualAnchorCount(m, "simulated_max_order", config.true_plan.walls().size(), config.simulated_max_order);
  config.self_coupling_db = m.NumberInRange("self_coupling_db", config.self_coupling_db, -100.0, 40.0, "dB");
  o.sample_period_s = m.NumberInRange("sample_period_s", o.sample_period_s, 1e-15, 1e-3, "s");
  o.window_length_s = m.NumberInRange("window_length_s", o.window_length_s, 1e-12, 1.0, "s");
  o.snr_at_1m_db = m.NumberInRange("snr_at_1m_db", o.snr_at_1m_db, -100.0, 200.0, "dB");
  YamlMap pulse = m.OptionalMap("pulse");
  if (pulse.Has("duration_s")) {
    pulse.Fail("duration_s", "not used with method coop: the pulse duration is a variant axis (set "
                             "variant_defaults.pulse_duration_ns or list it in variants)");
  }
  o.pulse = ReadPulse(pulse);
  o.diffuse = ReadDiffuse(m.OptionalMap("diffuse"));
  m.RejectUnknownKeys();
  // A second-order path between two points of a convex room is at most twice the diagonal of
  // its bounding box long (the image point lies within two room lengths per axis); the window
  // starts at 0 s, so its length must reach that far.
  const auto [lo_m, hi_m] = config.true_plan.Bounds();
  const double needed_m = 2.0 * (hi_m - lo_m).norm();
  if (o.window_length_s * o.medium.speed_mps < needed_m) {
    m.Fail("window_length_s",
           fmt::format("{} s ({:.4g} m) does not cover the longest paths of interest: it must reach twice the "
                       "diagonal of the floor plan's bounding box, {:.4g} m = {:.6g} s",
                       FormatValue(o.window_length_s), o.window_length_s * o.medium.speed_mps, needed_m,
                       needed_m / o.medium.speed_mps));
  }
}

// Validate(ChannelOptions) once per pulse duration of the grid (the channel is used with each).
void CheckChannelPerPulse(const YamlMap& m, const CoopExperimentConfig& config) {
  std::vector<double> durations_s = {config.channel.pulse.duration_s};
  for (const auto& v : config.variants) {
    if (std::find(durations_s.begin(), durations_s.end(), v.pulse_duration_s) == durations_s.end()) {
      durations_s.push_back(v.pulse_duration_s);
    }
  }
  for (const double duration_s : durations_s) {
    channel::ChannelOptions o = config.channel;
    o.pulse.duration_s = duration_s;
    const auto problems = Validate(o);
    if (!problems.empty()) {
      const std::string& p = problems.front();
      const auto space = p.find(' ');
      m.Fail(p.substr(0, space), fmt::format("{} (with the pulse duration {} ns of the variant grid)", p.substr(space + 1),
                                             FormatValue(duration_s * kNsPerS)));
    }
  }
}

dsp::MpcExtractorOptions ReadCoopMpc(YamlMap m) {
  if (m.Has("max_components")) {
    m.Fail("max_components", "not used with method coop: the filter extracts round(coop.extraction_factor |K|) "
                             "components per link, |K| the paths it expects on the link");
  }
  return ReadMpc(m);
}

methods::coop::CoopOptions ReadCoop(YamlMap m, const CoopExperimentConfig& config) {
  methods::coop::CoopOptions o = config.coop;
  for (const char* axis : {"wall_update", "wall_sigma_m"}) {
    if (m.Has(axis)) {
      m.Fail(axis, "a variant axis, not a filter option here: set it under variant_defaults or variants "
                   "(wall_update, wall_sigma_mm)");
    }
  }
  o.agent_sigma_m = m.NumberInRange("agent_sigma_m", o.agent_sigma_m, 1e-9, kHuge, "m");
  o.velocity_sigma_mps = m.NumberInRange("velocity_sigma_mps", o.velocity_sigma_mps, 1e-9, kHuge, "m/s");
  o.max_speed_mps = m.NumberInRange("max_speed_mps", o.max_speed_mps, 1e-9, kHuge, "m/s");
  o.max_order = m.Integer("max_order", o.max_order, 1, kMaxFilterOrder);
  CheckVirtualAnchorCount(m, "max_order", config.true_plan.walls().size(), o.max_order);
  o.cutoff_m = m.NumberInRange("cutoff_m", o.cutoff_m, 0.0, kHuge, "m");
  o.extraction_factor = m.NumberInRange("extraction_factor", o.extraction_factor, 1.0, 100.0, "");
  o.self_gate_m = m.NumberInRange("self_gate_m", o.self_gate_m, 0.0, kHuge, "m");
  o.innovation_gate_sigma = m.NumberInRange("innovation_gate_sigma", o.innovation_gate_sigma, 0.0, 100.0, "");
  // The coupling between an agent's own antennas arrives at the antenna spacing; a gate below
  // it would hand the coupling to the association as a wall reflection.
  if (config.antennas.spacing_m > 0.0 && !(o.self_gate_m > config.antennas.spacing_m)) {
    m.Fail("self_gate_m", fmt::format("{} m must exceed antenna_spacing_m ({} m), where the TX-RX coupling of a "
                                      "self link arrives",
                                      FormatValue(o.self_gate_m), FormatValue(config.antennas.spacing_m)));
  }
  // The defaults are the cooperative ones (the struct's, CoopOptions::DefaultVariance()), not
  // MINT's: the paper's window is 0.2 m of track.
  o.variance = ReadVariance(m.OptionalMap("variance"), o.variance);
  m.RejectUnknownKeys();
  return o;
}

// ---------------------------------------------------------------------------------------------
// Variant grid
// ---------------------------------------------------------------------------------------------

// Checks of one axis value in the file's unit; an empty string means valid.
using NumberCheck = std::function<std::string(double)>;
using FlagCheck = std::function<std::string(bool)>;

// The checks of every axis, which depend on the rest of the scenario.
struct AxisChecks {
  NumberCheck agents;
  FlagCheck anchor;
  NumberCheck pulse_duration_ns;
  NumberCheck wall_error_mm;
  FlagCheck biased_wall;
  NumberCheck wall_sigma_mm;
};

AxisChecks MakeAxisChecks(const CoopExperimentConfig& config) {
  const int agents = static_cast<int>(config.agents.size());
  const bool has_anchor = config.anchor.has_value();
  const bool has_bias = config.wall_bias.wall >= 0;
  AxisChecks c;
  c.agents = [agents](double v) -> std::string {
    if (v != std::floor(v)) return fmt::format("expected a whole number of agents, got {}", FormatValue(v));
    if (v < 2.0) return fmt::format("{} agents: cooperative tracking needs at least 2", FormatValue(v));
    if (v > agents) return fmt::format("{} agents, but the scenario defines {} under agents:", FormatValue(v), agents);
    return {};
  };
  c.anchor = [has_anchor](bool v) -> std::string {
    return v && !has_anchor ? "true needs an anchor: section (the fixed anchor's position_m)" : "";
  };
  c.pulse_duration_ns = [](double v) -> std::string {
    if (v > 0.0 && v <= kMaxPulseDuration_ns) return {};
    return fmt::format("{} ns is out of range, expected (0, {}] ns", FormatValue(v), FormatValue(kMaxPulseDuration_ns));
  };
  c.wall_error_mm = [](double v) -> std::string {
    if (v >= 0.0 && v <= kMaxWallError_mm) return {};
    return fmt::format("{} mm is out of range, expected [0, {}] mm", FormatValue(v), FormatValue(kMaxWallError_mm));
  };
  c.biased_wall = [has_bias](bool v) -> std::string {
    return v && !has_bias ? "true needs a wall_bias: section (which wall, and by how much)" : "";
  };
  c.wall_sigma_mm = [](double v) -> std::string {
    if (v > 0.0 && v <= kMaxWallSigma_mm) return {};
    return fmt::format("{} mm is out of range, expected (0, {}] mm", FormatValue(v), FormatValue(kMaxWallSigma_mm));
  };
  return c;
}

// A number of variant_defaults: kAbsent when the key is absent (the caller keeps its default
// in SI units, so that converting it back and forth cannot change it).
double ReadDefault(YamlMap& m, const std::string& key, const NumberCheck& check) {
  const double v = m.Number(key, kAbsent);
  if (std::isnan(v)) return v;
  if (const std::string problem = check(v); !problem.empty()) m.Fail(key, problem);
  return v;
}

bool ReadDefaultFlag(YamlMap& m, const std::string& key, bool fallback, const FlagCheck& check) {
  const bool v = m.Boolean(key, fallback);
  if (const std::string problem = check(v); !problem.empty()) m.Fail(key, problem);
  return v;
}

CoopVariant ReadVariantDefaults(YamlMap m, const AxisChecks& checks) {
  CoopVariant v;
  if (const double agents = ReadDefault(m, "agents", checks.agents); !std::isnan(agents)) {
    v.agents = static_cast<int>(agents);
  }
  v.anchor = ReadDefaultFlag(m, "anchor", v.anchor, checks.anchor);
  if (const double ns = ReadDefault(m, "pulse_duration_ns", checks.pulse_duration_ns); !std::isnan(ns)) {
    v.pulse_duration_s = ns / kNsPerS;
  }
  if (const double mm = ReadDefault(m, "wall_error_mm", checks.wall_error_mm); !std::isnan(mm)) {
    v.wall_error_m = mm / kMmPerM;
  }
  v.biased_wall = ReadDefaultFlag(m, "biased_wall", v.biased_wall, checks.biased_wall);
  v.wall_update = ReadDefaultFlag(m, "wall_update", v.wall_update, [](bool) { return std::string(); });
  if (const double mm = ReadDefault(m, "wall_sigma_mm", checks.wall_sigma_mm); !std::isnan(mm)) {
    v.wall_sigma_m = mm / kMmPerM;
  }
  m.RejectUnknownKeys();
  return v;
}

// One axis of a grid: its values divided by per_si (file unit -> SI), or {fallback} when the grid
// does not name it.
template <typename T>
std::vector<T> ReadAxis(YamlMap& g, const std::string& key, T fallback, const NumberCheck& check, double per_si) {
  const std::vector<double> values = g.NumberList(key);
  if (values.empty()) return {fallback};
  std::vector<T> out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (const std::string problem = check(values[i]); !problem.empty()) g.FailAt(key, i, problem);
    out.push_back(static_cast<T>(values[i] / per_si));
  }
  return out;
}

std::vector<bool> ReadFlagAxis(YamlMap& g, const std::string& key, bool fallback, const FlagCheck& check) {
  const std::vector<bool> values = g.BooleanList(key);
  if (values.empty()) return {fallback};
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (const std::string problem = check(values[i]); !problem.empty()) g.FailAt(key, i, problem);
  }
  return values;
}

// The grids in file order, each the cross product of its axes (agents, anchor, pulse duration,
// wall error, biased wall, wall update, wall sigma; the last varies fastest), without exact
// duplicates (the first one stays).
std::vector<CoopVariant> ReadVariants(YamlMap& root, const CoopVariant& defaults, const AxisChecks& checks) {
  if (!root.Has("variants")) return {defaults};
  std::vector<CoopVariant> variants;
  std::size_t expanded = 0;
  std::vector<YamlMap> grids = root.MapList("variants", false);
  for (std::size_t n = 0; n < grids.size(); ++n) {
    YamlMap& g = grids[n];
    const auto agents = ReadAxis<int>(g, "agents", defaults.agents, checks.agents, 1.0);
    const auto anchor = ReadFlagAxis(g, "anchor", defaults.anchor, checks.anchor);
    const auto pulse_s = ReadAxis<double>(g, "pulse_duration_ns", defaults.pulse_duration_s, checks.pulse_duration_ns, kNsPerS);
    const auto error_m = ReadAxis<double>(g, "wall_error_mm", defaults.wall_error_m, checks.wall_error_mm, kMmPerM);
    const auto biased = ReadFlagAxis(g, "biased_wall", defaults.biased_wall, checks.biased_wall);
    const auto update = ReadFlagAxis(g, "wall_update", defaults.wall_update, [](bool) { return std::string(); });
    const auto sigma_m = ReadAxis<double>(g, "wall_sigma_mm", defaults.wall_sigma_m, checks.wall_sigma_mm, kMmPerM);
    g.RejectUnknownKeys();

    const std::array<std::size_t, 7> sizes = {agents.size(), anchor.size(), pulse_s.size(), error_m.size(),
                                              biased.size(), update.size(), sigma_m.size()};
    // Counted before multiplying out, so that a grid of long lists is refused without the work.
    std::size_t count = 1;
    for (const std::size_t size : sizes) {
      count *= size;
      if (expanded + count > kMaxVariants) {
        root.FailAt("variants", n, fmt::format("the grids give more than {} variants", kMaxVariants));
      }
    }
    expanded += count;
    for (std::size_t k = 0; k < count; ++k) {
      std::array<std::size_t, 7> at{};
      std::size_t rest = k;
      for (std::size_t axis = sizes.size(); axis-- > 0;) {
        at[axis] = rest % sizes[axis];
        rest /= sizes[axis];
      }
      CoopVariant v;
      v.agents = agents[at[0]];
      v.anchor = anchor[at[1]];
      v.pulse_duration_s = pulse_s[at[2]];
      v.wall_error_m = error_m[at[3]];
      v.biased_wall = biased[at[4]];
      v.wall_update = update[at[5]];
      v.wall_sigma_m = sigma_m[at[6]];
      if (std::find(variants.begin(), variants.end(), v) == variants.end()) variants.push_back(v);
    }
  }
  return variants;
}

}  // namespace

CoopScenario LoadCoopScenario(const std::string& path, const ScenarioOverrides& overrides) {
  auto origins = std::make_shared<YamlOrigins>(path);
  YAML::Node doc = LoadYamlWithExtends(path, *origins);
  YamlMap root(doc, "", origins);

  CoopScenario scenario;
  scenario.file = path;
  CoopExperimentConfig& config = scenario.config;
  config.name = root.String("name");
  const std::string method = root.String("method");
  if (method != "coop") {
    root.Fail("method", "'" + method + "' in a cooperative scenario, expected coop (mint and slam scenarios have "
                                       "their own reader)");
  }
  config.seed = root.Unsigned("seed", config.seed);
  config.runs = root.Integer("runs", config.runs, 1, kMaxRuns);
  config.threads = root.Integer("threads", config.threads, 0, kMaxThreads);
  config.steps = root.Integer("steps", config.steps, 1, kMaxSteps);

  const std::map<std::string, double> materials = ReadMaterials(root.OptionalMap("materials"));
  config.true_plan = ReadFloorPlan(root.Map("floor_plan"), materials, &config.in_plan);
  // Before the agents: their antennas must be inside the plan too.
  config.antennas.spacing_m = root.NumberInRange("antenna_spacing_m", config.antennas.spacing_m, 0.0, 0.5, "m");
  config.agents = ReadAgents(root, config);
  if (root.Has("anchor")) config.anchor = ReadAnchor(root.Map("anchor"), config.true_plan);
  if (root.Has("wall_bias")) config.wall_bias = ReadWallBias(root.Map("wall_bias"), config.true_plan, config.in_plan);

  YamlMap channel = root.OptionalMap("channel");
  ReadCoopChannel(channel, config);
  config.mpc = ReadCoopMpc(root.OptionalMap("mpc"));
  config.coop = ReadCoop(root.OptionalMap("coop"), config);

  const AxisChecks checks = MakeAxisChecks(config);
  const CoopVariant defaults = ReadVariantDefaults(root.OptionalMap("variant_defaults"), checks);
  config.channel.pulse.duration_s = defaults.pulse_duration_s;
  config.variants = ReadVariants(root, defaults, checks);
  root.RejectUnknownKeys();
  CheckChannelPerPulse(channel, config);

  ApplyOverrides(overrides, config.runs, config.seed, config.threads);
  return scenario;
}

bool IsCoopScenario(const std::string& path) {
  try {
    YamlOrigins origins(path);
    const YAML::Node doc = LoadYamlWithExtends(path, origins);
    const YAML::Node method = doc["method"];
    return method && method.IsScalar() && method.Scalar() == "coop";
  } catch (const InputError&) {
    return false;  // LoadScenario reports it
  } catch (const YAML::Exception&) {
    return false;
  }
}

}  // namespace mirage::io
