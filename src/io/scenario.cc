// SPDX-License-Identifier: MIT
#include "mirage/io/scenario.h"

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "mirage/geometry/segment.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/io/scenario_sections.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {
namespace {

// Work limit that keeps a valid-looking file from exhausting the machine (the others are in
// scenario_sections.h).
constexpr double kMaxStepsPerTrajectory = 1e6;

// The run grid's extreme offsets (the zero offset first).
std::vector<Vec2> GridCorners(const pipeline::RunGrid& grid) {
  const double hx = 0.5 * (grid.nx - 1) * grid.spacing_m;
  const double hy = 0.5 * (grid.ny - 1) * grid.spacing_m;
  return {Vec2::Zero(), Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(-hx, hy), Vec2(hx, hy)};
}

// The CIR window must contain every LOS delay the trajectories produce, with room after it.
void CheckWindowCoversLos(YamlMap& m, const pipeline::MintExperimentConfig& config) {
  double min_m = std::numeric_limits<double>::infinity(), max_m = 0.0;
  for (const auto& spec : config.trajectories) {
    for (const Vec2& offset : GridCorners(config.run_grid)) {
      for (std::size_t i = 0; i < spec.waypoints_m.size(); ++i) {
        for (const Vec2& anchor : config.anchors_m) {
          // The distance to a point is convex along a segment: its maximum is at a waypoint.
          max_m = std::max(max_m, (spec.waypoints_m[i] + offset - anchor).norm());
          if (i > 0) {
            min_m = std::min(min_m, geometry::DistanceToSegment(anchor, spec.waypoints_m[i - 1] + offset,
                                                                spec.waypoints_m[i] + offset));
          }
        }
      }
    }
  }
  const auto& o = config.channel;
  if (o.window_start_s > min_m / o.medium.speed_mps) {
    m.Fail("window_start_s", fmt::format("{} s starts after the earliest LOS delay along the trajectories ({:.6g} s)",
                                         FormatValue(o.window_start_s), min_m / o.medium.speed_mps));
  }
  const double needed_s = max_m / o.medium.speed_mps + 8.0 * o.pulse.duration_s;
  if (o.window_start_s + o.window_length_s < needed_s) {
    m.Fail("window_length_s", fmt::format("the window ends at {:.6g} s, before the latest LOS delay along the "
                                          "trajectories plus 8 pulse durations ({:.6g} s)",
                                          o.window_start_s + o.window_length_s, needed_s));
  }
}

void ReadChannel(YamlMap m, pipeline::MintExperimentConfig& config) {
  channel::ChannelOptions& o = config.channel;
  config.channel_max_order = m.Integer("max_order", config.channel_max_order, 0, geometry::kMaxVirtualAnchorOrder);
  CheckVirtualAnchorCount(m, "max_order", config.plan.walls().size(), config.channel_max_order);
  o.sample_period_s = m.NumberInRange("sample_period_s", o.sample_period_s, 1e-15, 1e-3, "s");
  o.window_start_s = m.NumberInRange("window_start_s", o.window_start_s, 0.0, 1.0, "s");
  o.window_length_s = m.NumberInRange("window_length_s", o.window_length_s, 1e-12, 1.0, "s");
  o.snr_at_1m_db = m.NumberInRange("snr_at_1m_db", o.snr_at_1m_db, -100.0, 200.0, "dB");
  o.pulse = ReadPulse(m.OptionalMap("pulse"));
  o.diffuse = ReadDiffuse(m.OptionalMap("diffuse"));
  m.RejectUnknownKeys();
  Check(o, m);
  CheckWindowCoversLos(m, config);
}

// The keys MINT and SLAM share, with the same meaning and limits.
template <typename TrackerOptions>
void ReadTrackerCommon(YamlMap& m, TrackerOptions& o) {
  o.cutoff_m = m.NumberInRange("cutoff_m", o.cutoff_m, 1e-9, kHuge, "m");
  o.range_sigma_m = m.NumberInRange("range_sigma_m", o.range_sigma_m, 1e-9, kHuge, "m");
  o.initial_position_sigma_m =
      m.NumberInRange("initial_position_sigma_m", o.initial_position_sigma_m, 1e-9, kHuge, "m");
  o.initial_velocity_sigma_mps =
      m.NumberInRange("initial_velocity_sigma_mps", o.initial_velocity_sigma_mps, 1e-9, kHuge, "m/s");
}

methods::mint::MintOptions ReadMint(YamlMap m, std::size_t walls) {
  methods::mint::MintOptions o;
  ReadTrackerCommon(m, o);
  o.max_order = m.Integer("max_order", o.max_order, 0, geometry::kMaxVirtualAnchorOrder);
  CheckVirtualAnchorCount(m, "max_order", walls, o.max_order);
  o.reassociate = m.Boolean("reassociate", o.reassociate);
  o.constrain_to_room = m.Boolean("constrain_to_room", o.constrain_to_room);
  o.innovation_gate_chi2 = m.NumberInRange("innovation_gate_chi2", o.innovation_gate_chi2, 0.0, 1e6, "");
  o.motion = ReadMotion(m.OptionalMap("motion"), o.motion);
  o.variance = ReadVariance(m.OptionalMap("variance"));
  {
    YamlMap r = m.OptionalMap("relocalization");
    auto& ro = o.relocalization;
    ro.enabled = r.Boolean("enabled", ro.enabled);
    ro.match_tolerance_m = r.NumberInRange("match_tolerance_m", ro.match_tolerance_m, 1e-6, 10.0, "m");
    ro.max_order = r.Integer("max_order", ro.max_order, 0, geometry::kMaxVirtualAnchorOrder);
    ro.min_visible = r.Integer("min_visible", ro.min_visible, 1, 10000);
    ro.lost_score = r.NumberInRange("lost_score", ro.lost_score, 0.0, 1.0, "");
    ro.lost_steps = r.Integer("lost_steps", ro.lost_steps, 1, 100000);
    ro.search_radius_m = r.NumberInRange("search_radius_m", ro.search_radius_m, 1e-3, 100.0, "m");
    ro.search_step_m = r.NumberInRange("search_step_m", ro.search_step_m, 1e-3, 100.0, "m");
    ro.found_score = r.NumberInRange("found_score", ro.found_score, 0.0, 1.0, "");
    r.RejectUnknownKeys();
  }
  m.RejectUnknownKeys();
  Check(o, m);
  return o;
}

methods::slam::TrackRecoveryOptions ReadRecovery(YamlMap m) {
  methods::slam::TrackRecoveryOptions o;
  o.enabled = m.Boolean("enabled", o.enabled);
  o.match_tolerance_m = m.NumberInRange("match_tolerance_m", o.match_tolerance_m, 1e-9, kHuge, "m");
  o.los_candidates = m.Integer("los_candidates", o.los_candidates, 1, 100);
  o.min_margin = m.Integer("min_margin", o.min_margin, 1, 1000);
  o.min_margin_floor_plan = m.Integer("min_margin_floor_plan", o.min_margin_floor_plan, 1, 1000);
  o.floor_plan_watch_steps = m.Integer("floor_plan_watch_steps", o.floor_plan_watch_steps, 0, 1000000);
  o.lost_steps = m.Integer("lost_steps", o.lost_steps, 1, 1000000);
  o.follow_gate_m = m.NumberInRange("follow_gate_m", o.follow_gate_m, 1e-9, kHuge, "m");
  o.max_jump_m = m.NumberInRange("max_jump_m", o.max_jump_m, 1e-9, kHuge, "m");
  o.max_speed_mps = m.NumberInRange("max_speed_mps", o.max_speed_mps, 1e-9, kHuge, "m/s");
  m.RejectUnknownKeys();
  return o;
}

methods::slam::SweepOptions ReadSweep(YamlMap m) {
  methods::slam::SweepOptions o;
  o.enabled = m.Boolean("enabled", o.enabled);
  o.window_steps = m.Integer("window_steps", o.window_steps, 3, 100000);
  o.every_steps = m.Integer("every_steps", o.every_steps, 1, 100000);
  o.min_baseline_m = m.NumberInRange("min_baseline_m", o.min_baseline_m, 1e-9, kHuge, "m");
  o.gate_m = m.NumberInRange("gate_m", o.gate_m, 1e-9, kHuge, "m");
  o.min_support_fraction = m.NumberInRange("min_support_fraction", o.min_support_fraction, 1e-9, 1.0, "");
  m.RejectUnknownKeys();
  return o;
}

methods::slam::DiscoveryOptions ReadDiscovery(YamlMap m) {
  methods::slam::DiscoveryOptions o;
  o.enabled = m.Boolean("enabled", o.enabled);
  o.max_agent_sigma_m = m.NumberInRange("max_agent_sigma_m", o.max_agent_sigma_m, 1e-9, kHuge, "m");
  o.group_gate_m = m.NumberInRange("group_gate_m", o.group_gate_m, 1e-9, kHuge, "m");
  o.group_max_gap_steps = m.Integer("group_max_gap_steps", o.group_max_gap_steps, 0, 100000);
  o.group_size = m.Integer("group_size", o.group_size, 3, 100000);
  o.min_group_baseline_m = m.NumberInRange("min_group_baseline_m", o.min_group_baseline_m, 0.0, kHuge, "m");
  o.max_fit_rms_m = m.NumberInRange("max_fit_rms_m", o.max_fit_rms_m, 1e-9, kHuge, "m");
  o.rls_initial_sigma_m = m.NumberInRange("rls_initial_sigma_m", o.rls_initial_sigma_m, 1e-9, kHuge, "m");
  o.rls_range_sigma_m = m.NumberInRange("rls_range_sigma_m", o.rls_range_sigma_m, 1e-9, kHuge, "m");
  o.min_measurements = m.Integer("min_measurements", o.min_measurements, 1, 100000);
  o.resolve_misses = m.Integer("resolve_misses", o.resolve_misses, 1, 100000);
  o.min_turn_m = m.NumberInRange("min_turn_m", o.min_turn_m, 0.0, kHuge, "m");
  o.merge_hypotheses_m = m.NumberInRange("merge_hypotheses_m", o.merge_hypotheses_m, 1e-9, kHuge, "m");
  o.candidate_timeout_steps = m.Integer("candidate_timeout_steps", o.candidate_timeout_steps, 1, 1000000);
  o.candidate_max_age_steps = m.Integer("candidate_max_age_steps", o.candidate_max_age_steps, 1, 1000000);
  o.duplicate_radius_m = m.NumberInRange("duplicate_radius_m", o.duplicate_radius_m, 0.0, kHuge, "m");
  o.verify = m.Boolean("verify", o.verify);
  o.verify_fit_rms_m = m.NumberInRange("verify_fit_rms_m", o.verify_fit_rms_m, 1e-9, kHuge, "m");
  o.verify_min_inlier_fraction =
      m.NumberInRange("verify_min_inlier_fraction", o.verify_min_inlier_fraction, 1e-9, 1.0, "");
  o.verify_mirror_ratio = m.NumberInRange("verify_mirror_ratio", o.verify_mirror_ratio, 1.0, kHuge, "");
  o.verify_max_sigma_m = m.NumberInRange("verify_max_sigma_m", o.verify_max_sigma_m, 1e-9, kHuge, "m");
  o.verify_far_sigma_per_m = m.NumberInRange("verify_far_sigma_per_m", o.verify_far_sigma_per_m, 0.0, kHuge, "");
  o.verify_far_fit_rms_m = m.NumberInRange("verify_far_fit_rms_m", o.verify_far_fit_rms_m, 1e-9, kHuge, "m");
  o.sweep = ReadSweep(m.OptionalMap("sweep"));
  m.RejectUnknownKeys();
  Check(o, m);
  return o;
}

methods::slam::SlamOptions ReadSlam(YamlMap m, std::size_t walls) {
  methods::slam::SlamOptions o;
  ReadTrackerCommon(m, o);
  o.prior_max_order = m.Integer("prior_max_order", o.prior_max_order, 0, geometry::kMaxVirtualAnchorOrder);
  CheckVirtualAnchorCount(m, "prior_max_order", walls, o.prior_max_order);
  o.prior_va_sigma_m = m.NumberInRange("prior_va_sigma_m", o.prior_va_sigma_m, 1e-9, kHuge, "m");
  o.prior_visibility = m.Boolean("prior_visibility", o.prior_visibility);
  o.reassociate = m.Boolean("reassociate", o.reassociate);
  o.innovation_gate_chi2 = m.NumberInRange("innovation_gate_chi2", o.innovation_gate_chi2, 0.0, 1e6, "");
  o.no_visibility_model_gate_chi2 = m.NumberInRange("no_visibility_model_gate_chi2", o.no_visibility_model_gate_chi2, 0.0, 1e6, "");
  o.va_filter = m.Boolean("va_filter", o.va_filter);
  o.va_filter_sigma_m = m.NumberInRange("va_filter_sigma_m", o.va_filter_sigma_m, 1e-9, kHuge, "m");
  o.va_filter_keeps_associating = m.Boolean("va_filter_keeps_associating", o.va_filter_keeps_associating);
  o.va_filter_anchors = m.Boolean("va_filter_anchors", o.va_filter_anchors);
  o.joseph_update = m.Boolean("joseph_update", o.joseph_update);
  o.amplitude_gate_probability =
      m.NumberInRange("amplitude_gate_probability", o.amplitude_gate_probability, 0.0, 0.5, "");
  o.motion = ReadMotion(m.OptionalMap("motion"), o.motion);
  o.variance = ReadVariance(m.OptionalMap("variance"));
  o.discovery = ReadDiscovery(m.OptionalMap("discovery"));
  o.blocked_amplitude_probability =
      m.NumberInRange("blocked_amplitude_probability", o.blocked_amplitude_probability, 0.0, 0.5, "");
  o.startup_amplitude_k_factor =
      m.NumberInRange("startup_amplitude_k_factor", o.startup_amplitude_k_factor, 0.0, 1e6, "");
  o.shadow_cone_deg = m.NumberInRange("shadow_cone_deg", o.shadow_cone_deg, 0.0, 180.0, "deg");
  o.shadow_sigma_m = m.NumberInRange("shadow_sigma_m", o.shadow_sigma_m, 1e-9, kHuge, "m");
  o.los_reacquire_m = m.NumberInRange("los_reacquire_m", o.los_reacquire_m, 0.0, kHuge, "m");
  o.nis_window_updates = m.Integer("nis_window_updates", o.nis_window_updates, 0, 100000);
  o.max_speed_mps = m.NumberInRange("max_speed_mps", o.max_speed_mps, 0.0, kHuge, "m/s");
  o.discovered_va_walk_m_per_sqrt_s =
      m.NumberInRange("discovered_va_walk_m_per_sqrt_s", o.discovered_va_walk_m_per_sqrt_s, 0.0, kHuge, "m/sqrt(s)");
  o.recovery = ReadRecovery(m.OptionalMap("recovery"));
  m.RejectUnknownKeys();
  Check(o, m);
  return o;
}

void ReadMeasurements(YamlMap m, Scenario& scenario) {
  auto& config = scenario.mint;
  const std::string model = m.String("model", std::string("cir"));
  if (model == "cir") {
    config.measurement_model = pipeline::MeasurementModel::kCir;
  } else if (model == "ranges") {
    config.measurement_model = pipeline::MeasurementModel::kRangeLevel;
  } else if (model == "recorded") {
    config.measurement_model = pipeline::MeasurementModel::kRecorded;
    RecordingFiles files;
    files.anchors = m.FilePath("anchors");
    files.ranges = m.FilePath("ranges");
    if (m.Has("truth")) files.truth = m.FilePath("truth");
    if (m.Has("start_m")) config.start_m = m.Point("start_m");
    if (!files.truth && !config.start_m) {
      m.Fail("start_m", "missing: without a truth file the tracker needs its start position [x, y] (m)");
    }
    scenario.recording_files = files;
  } else {
    m.Fail("model", "unknown measurement model '" + model + "' (available: cir, ranges, recorded)");
  }
  auto& o = config.range_level;
  o.detection_probability = m.NumberInRange("detection_probability", o.detection_probability, 0.0, 1.0, "");
  o.clutter_rate = m.NumberInRange("clutter_rate", o.clutter_rate, 0.0, 1000.0, "");
  o.min_sinr_db = m.NumberInRange("min_sinr_db", o.min_sinr_db, -200.0, 200.0, "dB");
  o.resolution_m = m.NumberInRange("resolution_m", o.resolution_m, 0.0, kHuge, "m");
  o.max_range_sigma_m = m.NumberInRange("max_range_sigma_m", o.max_range_sigma_m, 1e-9, kHuge, "m");
  m.RejectUnknownKeys();
  Check(o, m);
}

// Whether the document's measurements.model is "recorded" (a malformed section is reported later
// by ReadMeasurements).
bool IsRecorded(const YAML::Node& doc) {
  const YAML::Node m = doc["measurements"];
  if (!m || !m.IsMap()) return false;
  const YAML::Node model = m["model"];
  return model && model.IsScalar() && model.Scalar() == "recorded";
}

// Reads the recording named by the scenario; its anchors become the scenario's.
void LoadRecordedData(Scenario& scenario) {
  auto& config = scenario.mint;
  const RecordingFiles& files = *scenario.recording_files;
  auto recording = std::make_shared<pipeline::Recording>(LoadRecording(files));
  for (std::size_t a = 0; a < recording->anchors_m.size(); ++a) {
    const Vec2& p = recording->anchors_m[a];
    if (!config.plan.Encloses(p) || config.plan.InsideObstacle(p)) {
      throw InputError(fmt::format("{}: anchor '{}' at [{}, {}] m is outside the floor plan of {} (or inside an obstacle)",
                                   files.anchors, recording->anchor_ids[a], FormatValue(p.x()), FormatValue(p.y()),
                                   scenario.file));
    }
  }
  const Vec2 start_m = config.start_m ? *config.start_m : *recording->TruthAt(recording->steps.front().t_s);
  if (!config.plan.Encloses(start_m)) {
    throw InputError(fmt::format("{}: the start [{}, {}] m is outside the floor plan", config.start_m ? scenario.file
                                                                                                       : *files.truth,
                                 FormatValue(start_m.x()), FormatValue(start_m.y())));
  }
  config.anchor_ids = recording->anchor_ids;
  config.anchors_m = recording->anchors_m;
  config.known_anchors_m = config.anchors_m;
  pipeline::TrajectorySpec spec;
  spec.name = "recorded";
  config.trajectories = {spec};
  config.runs = 1;
  config.recording = std::move(recording);
}

}  // namespace

Scenario LoadScenario(const std::string& path, const ScenarioOverrides& overrides) {
  auto origins = std::make_shared<YamlOrigins>(path);
  YAML::Node doc = LoadYamlWithExtends(path, *origins);
  YamlMap root(doc, "", origins);

  Scenario scenario;
  scenario.file = path;
  auto& config = scenario.mint;
  config.name = root.String("name");
  scenario.method = root.String("method");
  if (scenario.method == "mint") {
    config.method = pipeline::Method::kMint;
  } else if (scenario.method == "slam") {
    config.method = pipeline::Method::kSlam;
  } else {
    root.Fail("method", "unknown method '" + scenario.method + "' (available: mint, slam)");
  }
  // Recorded data are one run with their own anchors and trajectory (checked before the keys
  // that would otherwise be required).
  const bool recorded = IsRecorded(doc);
  if (recorded) {
    config.runs = 1;
    for (const char* key : {"anchors", "trajectories", "run_grid", "perturb_initial_position"}) {
      if (root.Has(key)) {
        root.Fail(key, "not used with measurements.model recorded (the recording has the anchors and the "
                       "trajectory); remove it");
      }
    }
  }
  config.seed = root.Unsigned("seed", config.seed);
  config.runs = root.Integer("runs", config.runs, 1, recorded ? 1 : kMaxRuns);
  config.threads = root.Integer("threads", config.threads, 0, kMaxThreads);
  config.perturb_initial_position = root.Boolean("perturb_initial_position", config.perturb_initial_position);
  {
    YamlMap grid = root.OptionalMap("run_grid");
    config.run_grid.nx = grid.Integer("nx", config.run_grid.nx, 1, 1000);
    config.run_grid.ny = grid.Integer("ny", config.run_grid.ny, 1, 1000);
    config.run_grid.spacing_m = grid.NumberInRange("spacing_m", config.run_grid.spacing_m, 0.0, 10.0, "m");
    grid.RejectUnknownKeys();
  }

  const std::map<std::string, double> materials = ReadMaterials(root.OptionalMap("materials"));
  config.plan = ReadFloorPlan(root.Map("floor_plan"), materials);
  config.known_plan = config.plan;

  std::set<std::string> ids;
  for (auto& a : recorded ? std::vector<YamlMap>() : root.MapList("anchors", false)) {
    const std::string id = a.String("id");
    if (!ids.insert(id).second) a.Fail("id", "duplicate anchor id '" + id + "'");
    if (!IsPlainName(id)) a.Fail("id", "must not contain commas, quotes or line breaks (it goes into CSV files)");
    const Vec2 p = a.Point("position_m");
    CheckInside(config.plan, p, a, "position_m", "anchor '" + id + "'");
    a.RejectUnknownKeys();
    config.anchor_ids.push_back(id);
    config.anchors_m.push_back(p);
  }
  config.known_anchors_m = config.anchors_m;

  for (auto& t : recorded ? std::vector<YamlMap>() : root.MapList("trajectories", false)) {
    pipeline::TrajectorySpec spec;
    spec.name = t.String("name");
    spec.waypoints_m = t.Points("waypoints_m", 2);
    spec.speed_mps = t.Number("speed_mps", spec.speed_mps);
    if (!(spec.speed_mps > 0.0)) t.Fail("speed_mps", FormatValue(spec.speed_mps) + " m/s must be > 0 m/s");
    spec.dt_s = t.Number("dt_s", spec.dt_s);
    if (!(spec.dt_s > 0.0)) t.Fail("dt_s", FormatValue(spec.dt_s) + " s must be > 0 s (time steps go forward)");
    if (!IsPlainName(spec.name)) t.Fail("name", "must not contain commas, quotes or line breaks (it goes into CSV files)");
    for (const auto& other : config.trajectories) {
      if (other.name == spec.name) t.Fail("name", "duplicate trajectory name '" + spec.name + "' (names label the CSV rows)");
    }
    const double length_m = geometry::PolylineLength(spec.waypoints_m);
    if (length_m < spec.speed_mps * spec.dt_s) {
      t.Fail("waypoints_m", "the trajectory is shorter than one step (speed_mps * dt_s)");
    }
    if (length_m / (spec.speed_mps * spec.dt_s) > kMaxStepsPerTrajectory) {
      t.Fail("speed_mps", fmt::format("speed_mps * dt_s gives more than {:g} steps for this trajectory", kMaxStepsPerTrajectory));
    }
    // Every run walks the trajectory shifted by its grid offset: check the grid's corners too.
    for (const Vec2& offset : GridCorners(config.run_grid)) {
      const std::string shifted =
          offset.norm() > 0.0 ? fmt::format(" (shifted by the run grid's corner [{}, {}] m)", FormatValue(offset.x()),
                                            FormatValue(offset.y()))
                              : std::string();
      for (std::size_t i = 0; i < spec.waypoints_m.size(); ++i) {
        CheckInside(config.plan, spec.waypoints_m[i] + offset, t, "waypoints_m", fmt::format("waypoint {}{}", i, shifted));
        if (i > 0 && !config.plan.IsLegClear(spec.waypoints_m[i - 1] + offset, spec.waypoints_m[i] + offset)) {
          t.Fail("waypoints_m",
                 fmt::format("the leg from waypoint {} to {}{} crosses a wall or an obstacle", i - 1, i, shifted));
        }
      }
    }
    t.RejectUnknownKeys();
    config.trajectories.push_back(std::move(spec));
  }

  ReadChannel(root.OptionalMap("channel"), config);
  config.mpc = ReadMpc(root.OptionalMap("mpc"));
  config.mint = ReadMint(root.OptionalMap("mint"), config.plan.walls().size());
  config.slam = ReadSlam(root.OptionalMap("slam"), config.plan.walls().size());
  ReadMeasurements(root.OptionalMap("measurements"), scenario);
  {
    YamlMap evaluation = root.OptionalMap("evaluation");
    YamlMap divergence = evaluation.OptionalMap("divergence");
    config.divergence.threshold_m = divergence.NumberInRange("threshold_m", config.divergence.threshold_m, 1e-9, kHuge, "m");
    config.divergence.last_fraction =
        divergence.NumberInRange("last_fraction", config.divergence.last_fraction, 1e-9, 1.0, "");
    divergence.RejectUnknownKeys();
    config.map_cutoff_m = evaluation.NumberInRange("map_cutoff_m", config.map_cutoff_m, 1e-9, kHuge, "m");
    evaluation.RejectUnknownKeys();
  }
  root.RejectUnknownKeys();
  if (recorded) LoadRecordedData(scenario);

  if (recorded && overrides.runs && *overrides.runs != 1) {
    throw InputError("--runs: recorded data are one run (got " + std::to_string(*overrides.runs) + ")");
  }
  ApplyOverrides(overrides, config.runs, config.seed, config.threads);
  return scenario;
}

}  // namespace mirage::io
