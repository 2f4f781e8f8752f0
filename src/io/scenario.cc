// SPDX-License-Identifier: MIT
#include "mirage/io/scenario.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "mirage/channel/acoustic_stamps.h"
#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/range_level_simulator.h"
#include "mirage/channel/ranging_simulator.h"
#include "mirage/channel/uwb_tdoa_simulator.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/eval/error_stats.h"
#include "mirage/geometry/segment.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/io/options_json.h"
#include "mirage/io/options_yaml.h"
#include "mirage/io/scenario_grid.h"
#include "mirage/io/scenario_measurements.h"
#include "mirage/io/scenario_sections.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {
namespace {

using pipeline::Experiment;
using pipeline::MeasurementModel;

// Work limit that keeps a valid-looking file from exhausting the machine (the others are in
// scenario_sections.h).
constexpr double kMaxStepsPerTrajectory = 1e6;

// A file in the layout before the one schema: say how to write it now.
void RejectOldLayout(YamlMap& root, const YAML::Node& doc) {
  const auto how = [](const std::string& name) {
    return fmt::format("the scenario layout changed: write `method: {{name: {0}, ...}}` with the keys of the former "
                       "top-level `{0}:` section inside it (docs/scenario.md)",
                       name);
  };
  if (doc["method"] && doc["method"].IsScalar()) root.Fail("method", how(doc["method"].Scalar()));
  for (const char* old : {"mint", "slam", "coop"}) {
    if (doc[old]) root.Fail(old, how(old));
  }
  if (doc["variants"] || doc["variant_defaults"]) {
    root.Fail(doc["variants"] ? "variants" : "variant_defaults",
              "the scenario layout changed: the base values are the scenario's own keys, and `grid:` lists the "
              "variants as key paths with lists of values, e.g. `grid: [{method.wall_update: [false, true]}]` "
              "(docs/scenario.md)");
  }
  if (doc["agents"] && doc["agents"].IsSequence()) {
    root.Fail("agents", "the scenario layout changed: agents are `trajectories:` (name, waypoints_m, speed_mps, "
                        "dt_s); `agents: N` walks the first N of them together (docs/scenario.md)");
  }
  if (doc["anchor"]) root.Fail("anchor", "the scenario layout changed: list it under `anchors:` (docs/scenario.md)");
  if (doc["wall_bias"]) {
    root.Fail("wall_bias", "the scenario layout changed: write `floor_plan_error: {biased_wall: LABEL, bias_m: 0.1}` "
                           "(docs/scenario.md)");
  }
  if (doc["antenna_spacing_m"]) {
    root.Fail("antenna_spacing_m", "the scenario layout changed: it is the method option `method.antenna_spacing_m`");
  }
}

// The CIR window must contain every LOS delay the trajectories produce, with room after it.
void CheckWindowCoversLos(YamlMap& m, const Experiment& e) {
  double min_m = std::numeric_limits<double>::infinity(), max_m = 0.0;
  for (const auto& spec : e.trajectories) {
    for (const Vec2& offset : GridCorners(e.run_grid)) {
      for (std::size_t i = 0; i < spec.waypoints_m.size(); ++i) {
        for (const auto& anchor : e.anchors) {
          // The distance to a point is convex along a segment: its maximum is at a waypoint.
          const Vec2 a = anchor.position_m.head<2>();
          max_m = std::max(max_m, (spec.waypoints_m[i] + offset - a).norm());
          if (i > 0) {
            min_m = std::min(min_m, geometry::DistanceToSegment(a, spec.waypoints_m[i - 1] + offset, spec.waypoints_m[i] + offset));
          }
        }
      }
    }
  }
  if (!std::isfinite(min_m)) return;
  const auto& o = e.channel;
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

void ReadMedium(YamlMap m, Experiment& e) {
  const std::string kind = m.String("kind", std::string("radio"));
  if (kind == "radio") {
    e.medium = core::Medium::Radio();
  } else if (kind == "sound") {
    // The temperature the estimator assumes (C); 20 C gives 343.2 m/s (Bordoy 2020 Eq. 3.31).
    e.medium = core::Medium::Sound(m.NumberInRange("temperature_c", 20.0, -50.0, 60.0, "C"));
  } else {
    m.Fail("kind", "unknown medium '" + kind + "' (available: radio, sound)");
  }
  m.RejectUnknownKeys();
}

void ReadAnchors(YamlMap& root, bool recorded, Experiment& e) {
  std::set<std::string> ids;
  // Optional: an anchorless method (coop) needs none, and a method that does says so below.
  for (auto& a : recorded || !root.Has("anchors") ? std::vector<YamlMap>() : root.MapList("anchors", true)) {
    const std::string id = a.String("id");
    if (!ids.insert(id).second) a.Fail("id", "duplicate anchor id '" + id + "'");
    if (!IsPlainName(id)) a.Fail("id", "must not contain commas, quotes or line breaks (it goes into CSV files)");
    const Vec3 p = a.Point3("position_m", 0.0);
    if (!e.plan.walls().empty()) CheckInside(e.plan, p.head<2>(), a, "position_m", "anchor '" + id + "'");
    a.RejectUnknownKeys();
    e.anchors.push_back({id, p});
  }
}

void ReadTrajectories(YamlMap& root, bool recorded, Experiment& e) {
  for (auto& t : recorded ? std::vector<YamlMap>() : root.MapList("trajectories", false)) {
    pipeline::TrajectorySpec spec;
    spec.name = t.String("name");
    spec.waypoints_m = t.Points("waypoints_m", 2);
    spec.speed_mps = t.Number("speed_mps", spec.speed_mps);
    if (!(spec.speed_mps > 0.0)) t.Fail("speed_mps", FormatValue(spec.speed_mps) + " m/s must be > 0 m/s");
    spec.dt_s = t.Number("dt_s", spec.dt_s);
    if (!(spec.dt_s > 0.0)) t.Fail("dt_s", FormatValue(spec.dt_s) + " s must be > 0 s (time steps go forward)");
    spec.height_m = t.NumberInRange("height_m", spec.height_m, -kHuge, kHuge, "m");
    spec.turn_radius_m = t.NumberInRange("turn_radius_m", spec.turn_radius_m, 0.0, 100.0, "m");
    spec.height_amplitude_m = t.NumberInRange("height_amplitude_m", spec.height_amplitude_m, 0.0, 100.0, "m");
    if (t.Has("height_period_s")) {
      spec.height_period_s = t.Number("height_period_s", spec.height_period_s);
      if (!(spec.height_period_s > 0.0)) t.Fail("height_period_s", FormatValue(spec.height_period_s) + " s must be > 0 s");
    }
    for (auto& stop_map : t.Has("stops") ? t.MapList("stops", true) : std::vector<YamlMap>()) {
      geometry::Stop stop;
      // The walker slows down over kStopRamp_s before a stop and speeds up over it after.
      stop.at_s = stop_map.NumberInRange("at_s", 0.0, geometry::kStopRamp_s, kHuge, "s");
      stop.duration_s = stop_map.Number("duration_s");
      if (!(stop.duration_s > 0.0)) stop_map.Fail("duration_s", FormatValue(stop.duration_s) + " s must be > 0 s");
      if (!spec.stops.empty()) {
        const double earliest_s = spec.stops.back().at_s + spec.stops.back().duration_s + 2.0 * geometry::kStopRamp_s;
        if (stop.at_s < earliest_s) {
          stop_map.Fail("at_s", fmt::format("{} s is before {} s, the previous stop's end plus the time to speed up and slow "
                                            "down again ({} s each): stops are sorted and do not overlap",
                                            FormatValue(stop.at_s), FormatValue(earliest_s), FormatValue(geometry::kStopRamp_s)));
        }
      }
      // The stop must begin while the agent still walks (the path with its rounded corners).
      const double walk_s = geometry::PathLength(spec.waypoints_m, spec.turn_radius_m) / spec.speed_mps;
      if (geometry::WalkedTime(stop.at_s, spec.stops) >= walk_s) {
        stop_map.Fail("at_s", fmt::format("{} s is after the walk ends ({} s with the earlier stops)", FormatValue(stop.at_s),
                                          FormatValue(walk_s + (stop.at_s - geometry::WalkedTime(stop.at_s, spec.stops)))));
      }
      stop_map.RejectUnknownKeys();
      spec.stops.push_back(stop);
    }
    if (!IsPlainName(spec.name)) t.Fail("name", "must not contain commas, quotes or line breaks (it goes into CSV files)");
    for (const auto& other : e.trajectories) {
      if (other.name == spec.name) t.Fail("name", "duplicate trajectory name '" + spec.name + "' (names label the CSV rows)");
    }
    const double length_m = geometry::PolylineLength(spec.waypoints_m);
    if (length_m < spec.speed_mps * spec.dt_s) t.Fail("waypoints_m", "the trajectory is shorter than one step (speed_mps * dt_s)");
    if (length_m / (spec.speed_mps * spec.dt_s) > kMaxStepsPerTrajectory) {
      t.Fail("speed_mps", fmt::format("speed_mps * dt_s gives more than {:g} steps for this trajectory", kMaxStepsPerTrajectory));
    }
    double stopped_s = 0.0;  // with its ramps
    for (const auto& stop : spec.stops) stopped_s += stop.duration_s + geometry::kStopRamp_s;
    if ((length_m / spec.speed_mps + stopped_s) / spec.dt_s > kMaxStepsPerTrajectory) {
      t.Fail("stops", fmt::format("the stops make the trajectory longer than {:g} steps of dt_s", kMaxStepsPerTrajectory));
    }
    if (spec.turn_radius_m > 0.0 &&
        geometry::SampleTrajectory(spec.waypoints_m, spec.speed_mps, spec.dt_s, Vec2::Zero(), spec.turn_radius_m, spec.stops).size() < 2) {
      t.Fail("turn_radius_m", "with its corners rounded the trajectory is shorter than one step (speed_mps * dt_s)");
    }
    // Every run walks the trajectory shifted by its grid offset: check the grid's corners too.
    if (!e.plan.walls().empty()) {
      for (const Vec2& offset : GridCorners(e.run_grid)) {
        const std::string shifted = offset.norm() > 0.0 ? fmt::format(" (shifted by the run grid's corner [{}, {}] m)",
                                                                      FormatValue(offset.x()), FormatValue(offset.y()))
                                                        : std::string();
        for (std::size_t i = 0; i < spec.waypoints_m.size(); ++i) {
          CheckInside(e.plan, spec.waypoints_m[i] + offset, t, "waypoints_m", fmt::format("waypoint {}{}", i, shifted));
          if (i > 0 && !e.plan.IsLegClear(spec.waypoints_m[i - 1] + offset, spec.waypoints_m[i] + offset)) {
            t.Fail("waypoints_m", fmt::format("the leg from waypoint {} to {}{} crosses a wall or an obstacle", i - 1, i, shifted));
          }
        }
      }
    }
    t.RejectUnknownKeys();
    e.trajectories.push_back(std::move(spec));
  }
}

void ReadPlanError(YamlMap m, Experiment& e) {
  e.plan_error.wall_shift_m = m.NumberInRange("wall_shift_m", e.plan_error.wall_shift_m, 0.0, 10.0, "m");
  e.plan_error.bias_m = m.NumberInRange("bias_m", e.plan_error.bias_m, -10.0, 10.0, "m");
  if (m.Has("biased_wall")) {
    const std::string label = m.String("biased_wall");
    int found = -1;
    for (std::size_t s = 0; s < e.plan.walls().size(); ++s) {
      if (e.plan.walls()[s].label != label) continue;
      if (found >= 0) m.Fail("biased_wall", "the label '" + label + "' names more than one wall segment; give the wall a label of its own");
      found = static_cast<int>(s);
    }
    if (found < 0) m.Fail("biased_wall", "no wall labelled '" + label + "' in floor_plan");
    if (!e.in_plan[static_cast<std::size_t>(found)]) m.Fail("biased_wall", "the wall '" + label + "' is not in the given plan (in_plan: false)");
    e.plan_error.biased_wall = found;
  } else if (m.Has("bias_m") && e.plan_error.bias_m != 0.0) {
    m.Fail("bias_m", "a bias needs the wall it moves: set biased_wall");
  }
  m.RejectUnknownKeys();
}

void ReadChannel(YamlMap m, Experiment& e, const core::PhysicalKeys& keys) {
  e.channel_max_order = m.Integer("max_order", e.channel_max_order, 0, geometry::kMaxVirtualAnchorOrder);
  CheckVirtualAnchorCount(m, "max_order", e.plan.walls().size(), e.channel_max_order);
  e.self_coupling_db = m.NumberInRange("self_coupling_db", e.self_coupling_db, -300.0, 100.0, "dB");
  ReadOptions(m, channel::ChannelOptionsDescriptor(), keys, e.channel);
  e.channel.medium = e.medium;
  // The checks against the pulse (Nyquist limit, samples per pulse, window of 8 pulses) are not
  // in the descriptor (channel/cir_synthesizer.h): Validate() has them.
  Check(e.channel, m);
}

// `measurements: {model: recorded, anchors, tdoa, ...}`: pairwise differences (tdoa.csv) and the
// facts the TDOA filters' defaults derive from.
void ReadRecordedTdoa(YamlMap& m, Experiment& e, RecordingFiles& f) {
  for (const char* key : {"ranges", "mics", "toa"}) {
    if (m.Has(key)) m.Fail(key, "a recording has either anchors and tdoa (pairwise differences), anchors and ranges, or mics and toa");
  }
  if (!m.Has("anchors")) m.Fail("anchors", "missing: a recording of differences needs anchors (anchors.csv with z_m) and tdoa (tdoa.csv)");
  for (const char* key : {"epoch_window_s", "range_sigma_m", "height_m", "stamp_sigma_s", "false_alarm_rate"}) {
    if (m.Has(key)) m.Fail(key, "not used with tdoa (give the differences' noise as tdoa_sigma_m)");
  }
  if (e.medium.kind != core::MediumKind::kRadio) m.Fail("model", "a recording of UWB differences (tdoa) needs medium: {kind: radio}");
  f.anchors = m.FilePath("anchors");
  f.tdoa = m.FilePath("tdoa");
  if (m.Has("tdoa_sigma_m")) e.recorded_range_sigma_m = m.NumberInRange("tdoa_sigma_m", 0.15, 1e-9, kHuge, "m");
  if (m.Has("detection_probability")) {
    e.recorded_detection_probability = m.NumberInRange("detection_probability", 1.0, 0.0, 1.0, "");
  }
}

// `measurements: {model: recorded, mics, toa, ...}`: a sound sender's arrival-time stamps and the
// facts the acoustic methods need that the files cannot show (the sender's height, the stamps'
// noise as the physical range noise, detection and false alarms).
void ReadRecordedStamps(YamlMap& m, Experiment& e, RecordingFiles& f) {
  for (const char* key : {"anchors", "ranges"}) {
    if (m.Has(key)) {
      m.Fail(key, "a recording has either anchors and ranges (range sets) or mics and toa (arrival-time stamps), not both");
    }
  }
  for (const char* key : {"mics", "toa"}) {
    if (!m.Has(key)) m.Fail(key, "missing: a recording of arrival-time stamps needs both mics (mics.csv) and toa (toa.csv)");
  }
  if (m.Has("epoch_window_s")) m.Fail("epoch_window_s", "not used with toa: the rows of one emission share t_s");
  if (m.Has("range_sigma_m")) m.Fail("range_sigma_m", "not used with toa: give the stamps' noise as stamp_sigma_s (s)");
  if (e.medium.kind != core::MediumKind::kSound) m.Fail("model", "arrival-time stamps (mics, toa) need medium: {kind: sound}");
  f.mics = m.FilePath("mics");
  f.toa = m.FilePath("toa");
  if (!m.Has("height_m")) {
    m.Fail("height_m", "missing: the sender's height (m), which the planar acoustic estimators take as known");
  }
  e.recorded_height_m = m.NumberInRange("height_m", 0.0, -kHuge, kHuge, "m");
  // As for a simulated scenario (pipeline::PhysicalKeysOf): a stamp's noise as a range at the
  // speed the estimator assumes.
  if (m.Has("stamp_sigma_s")) e.recorded_range_sigma_m = e.medium.speed_mps * m.NumberInRange("stamp_sigma_s", 0.3e-3, 1e-12, kHuge, "s");
  if (m.Has("detection_probability")) {
    e.recorded_detection_probability = m.NumberInRange("detection_probability", 1.0, 0.0, 1.0, "");
  }
  if (m.Has("false_alarm_rate")) e.recorded_clutter_rate = m.NumberInRange("false_alarm_rate", 0.0, 0.0, kHuge, "");
}

// `measurements`: the model and its keys.
void ReadMeasurements(YamlMap m, Experiment& e, std::optional<RecordingFiles>& files, const core::PhysicalKeys& keys) {
  const std::string model = m.String("model", std::string("cir"));
  if (model == "cir") {
    e.measurement_model = MeasurementModel::kCir;
    m.RejectUnknownKeys();
  } else if (model == "ranges") {
    e.measurement_model = MeasurementModel::kRangeLevel;
    ReadOptions(m, channel::RangeLevelOptionsDescriptor(), keys, e.range_level);
  } else if (model == "ranging") {
    e.measurement_model = MeasurementModel::kRanging;
    ReadOptions(m, channel::RangingOptionsDescriptor(), keys, e.ranging);
  } else if (model == "acoustic") {
    e.measurement_model = MeasurementModel::kAcoustic;
    ReadAcousticModel(m, e, keys);
  } else if (model == "uwb_tdoa") {
    e.measurement_model = MeasurementModel::kUwbTdoa;
    ReadUwbTdoaModel(m, e, keys);
  } else if (model == "recorded") {
    e.measurement_model = MeasurementModel::kRecorded;
    RecordingFiles f;
    if (m.Has("tdoa")) {
      ReadRecordedTdoa(m, e, f);
    } else if (m.Has("mics") || m.Has("toa")) {
      ReadRecordedStamps(m, e, f);
    } else {
      for (const char* key : {"height_m", "stamp_sigma_s", "detection_probability", "false_alarm_rate", "tdoa_sigma_m"}) {
        if (m.Has(key)) m.Fail(key, "only for a recording of arrival-time stamps (mics, toa) or of differences (tdoa)");
      }
      f.anchors = m.FilePath("anchors");
      f.ranges = m.FilePath("ranges");
      e.epoch_window_s = m.NumberInRange("epoch_window_s", e.epoch_window_s, 0.0, 3600.0, "s");
      if (m.Has("range_sigma_m")) e.recorded_range_sigma_m = m.NumberInRange("range_sigma_m", 0.1, 1e-9, kHuge, "m");
    }
    if (m.Has("truth")) f.truth = m.FilePath("truth");
    if (m.Has("start_m")) e.start_m = m.Point3("start_m", 0.0);
    if (m.Has("speed_mps")) e.recorded_speed_mps = m.NumberInRange("speed_mps", 1.0, 0.0, kHuge, "m/s");
    if (m.Has("dt_s")) e.recorded_dt_s = m.NumberInRange("dt_s", 0.1, 1e-9, kHuge, "s");
    m.RejectUnknownKeys();
    files = f;
  } else {
    m.Fail("model", "unknown measurement model '" + model + "' (available: cir, ranges, ranging, acoustic, uwb_tdoa, recorded)");
  }
}

// The channel simulators are planar: every anchor at the trajectories' height.
void CheckPlanarChannel(YamlMap& root, const Experiment& e) {
  if (e.measurement_model != MeasurementModel::kCir && e.measurement_model != MeasurementModel::kRangeLevel) return;
  for (const auto& t : e.trajectories) {
    for (const auto& a : e.anchors) {
      if (a.position_m.z() != t.height_m) {
        root.Fail("anchors", fmt::format("anchor '{}' at z = {} m and trajectory '{}' at height {} m: the cir and ranges "
                                         "models simulate the plane (give all the same height), use measurements.model "
                                         "ranging for 3-D geometry",
                                         a.id, FormatValue(a.position_m.z()), t.name, FormatValue(t.height_m)));
      }
    }
  }
}

// Reads the recording named by the scenario; its anchors become the scenario's.
void LoadRecordedData(const std::string& scenario_file, const RecordingFiles& files, Experiment& e) {
  auto recording = std::make_shared<pipeline::Recording>(LoadRecording(files));
  for (std::size_t a = 0; a < recording->anchors_m.size(); ++a) {
    const Vec2 p = recording->anchors_m[a].head<2>();
    if (!e.plan.walls().empty() && (!e.plan.Encloses(p) || e.plan.InsideObstacle(p))) {
      throw InputError(fmt::format("{}: {} '{}' at [{}, {}] m is outside the floor plan of {} (or inside an obstacle)",
                                   files.toa_stamps() ? files.mics : files.anchors,
                                   files.toa_stamps() ? "microphone" : "anchor", recording->anchor_ids[a],
                                   FormatValue(p.x()), FormatValue(p.y()), scenario_file));
    }
    e.anchors.push_back({recording->anchor_ids[a], recording->anchors_m[a]});
  }
  std::optional<Vec3> start = e.start_m;
  if (!start) start = recording->TruthAt(recording->steps.front().t_s);
  if (start && !e.plan.walls().empty() && !e.plan.Encloses(start->head<2>())) {
    throw InputError(fmt::format("{}: the start [{}, {}] m is outside the floor plan", e.start_m ? scenario_file : *files.truth,
                                 FormatValue(start->x()), FormatValue(start->y())));
  }
  e.runs = 1;
  e.recording = std::move(recording);
}

// One experiment from a document (the scenario, or one variant of its grid).
Experiment ReadExperiment(YamlMap& root, const std::string& file, const methods::MethodInfo*& method,
                          std::optional<RecordingFiles>& files) {
  Experiment e;
  e.name = root.String("name");
  const bool recorded = [&] {
    if (!root.Has("measurements")) return false;
    YamlMap peek = root.OptionalMap("measurements");
    return peek.Has("model") && peek.String("model") == "recorded";
  }();
  if (recorded) {
    for (const char* key : {"anchors", "trajectories", "run_grid", "perturb_initial_position", "agents", "steps"}) {
      if (root.Has(key)) {
        root.Fail(key, "not used with measurements.model recorded (the recording has the anchors and the trajectory); remove it");
      }
    }
  }
  e.seed = root.Unsigned("seed", e.seed);
  e.runs = root.Integer("runs", e.runs, 1, recorded ? 1 : kMaxRuns);
  e.threads = root.Integer("threads", e.threads, 0, kMaxThreads);
  e.perturb_initial_position = root.Boolean("perturb_initial_position", e.perturb_initial_position);
  e.self_start = root.Boolean("self_start", e.self_start);
  {
    YamlMap grid = root.OptionalMap("run_grid");
    e.run_grid.nx = grid.Integer("nx", e.run_grid.nx, 1, 1000);
    e.run_grid.ny = grid.Integer("ny", e.run_grid.ny, 1, 1000);
    e.run_grid.spacing_m = grid.NumberInRange("spacing_m", e.run_grid.spacing_m, 0.0, 10.0, "m");
    grid.RejectUnknownKeys();
  }
  ReadMedium(root.OptionalMap("medium"), e);
  const std::map<std::string, double> materials = ReadMaterials(root.OptionalMap("materials"));
  if (root.Has("floor_plan")) e.plan = ReadFloorPlan(root.Map("floor_plan"), materials, &e.in_plan);
  ReadPlanError(root.OptionalMap("floor_plan_error"), e);
  ReadAnchors(root, recorded, e);
  ReadTrajectories(root, recorded, e);

  // The method first by name: whether it is joint decides which keys are known.
  YamlMap m = root.Map("method");
  const std::string name = m.String("name");
  method = methods::FindMethod(name);
  if (method == nullptr) m.Fail("name", "unknown method '" + name + "' (available: " + methods::MethodNames() + ")");
  if (method->joint && !recorded) {
    e.agents = root.Integer("agents", e.agents, 0, static_cast<int>(e.trajectories.size()));
    e.steps = root.Integer("steps", e.steps, 0, static_cast<int>(kMaxStepsPerTrajectory));
    for (const auto& t : e.trajectories) {
      if (t.dt_s != e.trajectories.front().dt_s) {
        root.Fail("trajectories", "the agents of a joint method walk in common steps: give every trajectory the same dt_s");
      }
    }
  }

  ReadMeasurements(root.OptionalMap("measurements"), e, files, pipeline::PhysicalKeysOf(e));
  if (files && !files->truth && !e.start_m && !method->self_initializes) {
    YamlMap measurements = root.OptionalMap("measurements");
    measurements.Fail("start_m", "missing: without a truth file method '" + method->name +
                                     "' needs its start position [x, y] (m); it cannot start itself");
  }
  if (files) LoadRecordedData(file, *files, e);
  if (e.measurement_model != MeasurementModel::kAcoustic && e.measurement_model != MeasurementModel::kUwbTdoa) {
    for (auto& t : recorded ? std::vector<YamlMap>() : root.MapList("trajectories", false)) {
      if (t.Has("height_amplitude_m") || t.Has("height_period_s")) {
        t.Fail(t.Has("height_amplitude_m") ? "height_amplitude_m" : "height_period_s",
               "height motion is simulated by measurements.model acoustic and uwb_tdoa only");
      }
    }
  }
  const core::PhysicalKeys keys = pipeline::PhysicalKeysOf(e);
  ReadChannel(root.OptionalMap("channel"), e, keys);
  ReadOptions(root.OptionalMap("mpc"), dsp::MpcExtractorOptionsDescriptor(), keys, e.mpc);
  if (e.measurement_model == MeasurementModel::kCir || e.measurement_model == MeasurementModel::kRangeLevel) {
    YamlMap channel = root.OptionalMap("channel");
    CheckWindowCoversLos(channel, e);
  }
  CheckPlanarChannel(root, e);
  {
    YamlMap evaluation = root.OptionalMap("evaluation");
    ReadOptions(evaluation.OptionalMap("divergence"), eval::DivergenceRuleDescriptor(), keys, e.divergence);
    e.map_cutoff_m = evaluation.NumberInRange("map_cutoff_m", e.map_cutoff_m, 1e-9, kHuge, "m");
    const std::string align = evaluation.String("align", std::string("none"));
    if (align != "none" && align != "rigid") evaluation.Fail("align", "'" + align + "' is not one of: none, rigid");
    e.align_rigid = align == "rigid";
    if (e.align_rigid && !(e.recording && e.recording->has_truth())) {
      evaluation.Fail("align", "rigid aligns a recording's estimates to its truth's frame (truth.csv from another "
                               "reference system); a simulation's truth, or a recording without truth, has none to align to");
    }
    if (e.align_rigid && !e.start_m && !method->self_initializes) {
      evaluation.Fail("align", "rigid: the truth's frame is not the anchors', so the run cannot start at the truth, and method '" +
                                   method->name + "' cannot start itself: give measurements.start_m");
    }
    evaluation.RejectUnknownKeys();
  }

  // The method's options through its descriptor; the plan bounds its virtual-anchor orders.
  std::shared_ptr<void> options = method->make_options();
  ReadOptionsObject(m, *method->descriptor, keys, options.get());
  for (const char* order_key : {"max_order", "prior_max_order"}) {
    const core::OptionField* field = method->descriptor->Find(order_key);
    if (field == nullptr || field->kind() != core::OptionKind::kInteger) continue;
    const auto order = static_cast<int>(std::get<std::int64_t>(field->Get(options.get())));
    CheckVirtualAnchorCount(m, order_key, e.plan.walls().size(), order);
  }
  const methods::MethodInfo* info = method;
  if (info->check) {
    methods::World world;
    for (const auto& a : e.anchors) world.anchors.push_back({a.id, a.position_m});
    world.floor_plan = e.plan;
    world.emission_times_known = e.measurement_model == MeasurementModel::kAcoustic && e.acoustic.emission_time_known;
    const auto problems = info->check(options.get(), world);
    if (!problems.empty()) m.FailProblem(problems.front());
  }
  e.method = pipeline::BindMethod(*info, options);
  e.method.options_json = OptionsObjectToJson(*info->descriptor, options.get()).dump();
  // Checks that need the world: a method that estimates with the anchors must be given some.
  if (info->input == methods::MethodInput::kRangeSets && e.anchors.empty()) {
    root.Fail("anchors", "method '" + info->name + "' needs at least one anchor");
  }
  const bool recorded_stamps = e.recording && e.recording->toa_stamps;
  if (info->input == methods::MethodInput::kToaStamps && e.measurement_model != MeasurementModel::kAcoustic &&
      !recorded_stamps) {
    root.Fail("measurements", "method '" + info->name + "' consumes arrival-time stamps: measurements.model must be acoustic, "
                              "or recorded with mics and toa");
  }
  if (info->input != methods::MethodInput::kToaStamps && recorded_stamps) {
    root.Fail("measurements", "the recording has arrival-time stamps (mics, toa), which method '" + info->name +
                                  "' does not consume (use an acoustic method)");
  }
  if (info->input != methods::MethodInput::kToaStamps && e.measurement_model == MeasurementModel::kAcoustic) {
    root.Fail("measurements", "measurements.model acoustic gives arrival-time stamps, which method '" + info->name +
                                  "' does not consume (use an acoustic method)");
  }
  const bool recorded_tdoa = e.recording && e.recording->tdoa;
  if (info->input == methods::MethodInput::kTdoa && e.measurement_model != MeasurementModel::kUwbTdoa && !recorded_tdoa) {
    root.Fail("measurements", "method '" + info->name + "' consumes pairwise differences: measurements.model must be "
                              "uwb_tdoa, or recorded with anchors and tdoa");
  }
  if (info->input != methods::MethodInput::kTdoa && (recorded_tdoa || e.measurement_model == MeasurementModel::kUwbTdoa)) {
    root.Fail("measurements", "the measurements are pairwise differences (uwb_tdoa, or tdoa.csv), which method '" +
                                  info->name + "' does not consume (use tdoa_ekf)");
  }
  if (info->input == methods::MethodInput::kLinkCirs && e.measurement_model != MeasurementModel::kCir) {
    root.Fail("measurements", "method '" + info->name + "' consumes CIRs: measurements.model must be cir");
  }
  if (info->input == methods::MethodInput::kLinkCirs && e.channel_max_order > 3) {
    YamlMap channel = root.OptionalMap("channel");
    channel.Fail("max_order", fmt::format("{} is above 3, the highest order of the links' image-source paths",
                                          e.channel_max_order));
  }
  return e;
}

}  // namespace

Scenario LoadScenario(const std::string& path, const ScenarioOverrides& overrides) {
  auto origins = std::make_shared<YamlOrigins>(path);
  Scenario scenario;
  scenario.file = path;
  const YAML::Node document = LoadYamlWithExtends(path, *origins);
  {
    YamlMap root(document, "", origins);
    RejectOldLayout(root, document);
  }
  // A deep copy for `mirage simulate`: the grid's variants share the document's nodes and
  // rearrange maps on the way to their values (scenario_grid.cc), after which yaml-cpp 0.7
  // crashes emitting the original.
  scenario.document = YAML::Clone(document);
  for (GridVariant& g : ExpandGrid(document, origins)) {
    YamlMap root(g.document, "", g.origins);
    std::optional<RecordingFiles> files;
    pipeline::Variant v;
    v.name = g.name;
    v.overrides = std::move(g.overrides);
    v.experiment = ReadExperiment(root, path, scenario.method, files);
    root.RejectUnknownKeys();
    if (files) scenario.recording_files = files;
    if (v.experiment.recording && overrides.runs && *overrides.runs != 1) {
      throw InputError("--runs: recorded data are one run (got " + std::to_string(*overrides.runs) + ")");
    }
    ApplyOverrides(overrides, v.experiment.runs, v.experiment.seed, v.experiment.threads);
    if (v.name.empty()) v.name = v.experiment.name;
    scenario.variants.push_back(std::move(v));
  }
  return scenario;
}

}  // namespace mirage::io
