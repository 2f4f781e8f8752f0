// SPDX-License-Identifier: MIT
#include "mirage/io/scenario_measurements.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "mirage/channel/acoustic_stamps.h"
#include "mirage/channel/uwb_tdoa_simulator.h"
#include "mirage/geometry/reflector_3d.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/io/options_yaml.h"
#include "mirage/io/scenario_sections.h"

namespace mirage::io {

using pipeline::Experiment;

void ReadAcousticModel(YamlMap& m, Experiment& e, const core::PhysicalKeys& keys) {
  if (e.medium.kind != core::MediumKind::kSound) m.Fail("model", "the acoustic model needs medium: {kind: sound}");
  if (e.plan.walls().empty() || !std::isfinite(e.plan.ceiling_z_m())) {
    m.Fail("model", "the acoustic model needs a floor_plan with walls and ceiling_z_m (the hall's reflectors)");
  }
  e.reflectors = geometry::ReflectorsFromPlan(e.plan);
  const auto check_name = [&](YamlMap& r, const std::string& name) {
    for (const auto& other : e.reflectors) {
      if (other.name == name) r.Fail("name", "duplicate reflector name '" + name + "'");
    }
  };
  for (auto& p : m.Has("partitions") ? m.MapList("partitions", true) : std::vector<YamlMap>()) {
    const std::string name = p.String("name");
    check_name(p, name);
    const auto ends = p.Points("ends_m", 2);
    if (ends.size() != 2 || (ends[0] - ends[1]).norm() <= 0.0) p.Fail("ends_m", "give two different points [[x, y], [x, y]]");
    const double z0 = p.NumberInRange("z_min_m", e.plan.floor_z_m(), e.plan.floor_z_m(), e.plan.ceiling_z_m(), "m");
    const double z1 = p.NumberInRange("z_max_m", 2.0, z0, e.plan.ceiling_z_m(), "m");
    if (!(z1 > z0)) p.Fail("z_max_m", "must be above z_min_m");
    const double coeff = p.NumberInRange("reflection_coeff", 0.9, 0.0, 1.0, "");
    p.RejectUnknownKeys();
    e.reflectors.push_back(geometry::VerticalReflector(name, ends[0], ends[1], z0, z1, coeff));
  }
  for (auto& t : m.Has("tables") ? m.MapList("tables", true) : std::vector<YamlMap>()) {
    const std::string name = t.String("name");
    check_name(t, name);
    const auto corners = t.Points("corners_m", 2);
    if (corners.size() != 2) t.Fail("corners_m", "give two opposite corners [[x, y], [x, y]]");
    const Vec2 lo = corners[0].cwiseMin(corners[1]), hi = corners[0].cwiseMax(corners[1]);
    if (!((hi - lo).minCoeff() > 0.0)) t.Fail("corners_m", "the table has no area");
    const double z = t.NumberInRange("z_m", 0.75, e.plan.floor_z_m(), e.plan.ceiling_z_m(), "m");
    const double coeff = t.NumberInRange("reflection_coeff", 0.9, 0.0, 1.0, "");
    t.RejectUnknownKeys();
    e.reflectors.push_back(geometry::HorizontalReflector(name, 0.5 * (lo + hi), 0.5 * (hi - lo).x(), 0.5 * (hi - lo).y(), z, coeff));
  }
  for (auto& f : m.Has("facing") ? m.MapList("facing", true) : std::vector<YamlMap>()) {
    channel::FacingEpisode episode;
    episode.t_start_s = f.NumberInRange("t_start_s", 0.0, 0.0, kHuge, "s");
    episode.t_end_s = f.NumberInRange("t_end_s", 0.0, episode.t_start_s, kHuge, "s");
    if (!(episode.t_end_s > episode.t_start_s)) f.Fail("t_end_s", "must be after t_start_s");
    episode.reflector = f.String("reflector");
    if (std::none_of(e.reflectors.begin(), e.reflectors.end(), [&](const auto& r) { return r.name == episode.reflector; })) {
      std::string names;
      for (const auto& r : e.reflectors) names += (names.empty() ? "" : ", ") + r.name;
      f.Fail("reflector", "no reflector named '" + episode.reflector + "' (available: " + names + ")");
    }
    f.RejectUnknownKeys();
    e.acoustic.facing.push_back(episode);
  }
  if (m.Has("imu")) {
    YamlMap imu = m.Map("imu");
    const std::string model = imu.String("model");
    if (model == "imu") {
      e.inertial = pipeline::InertialModel::kImu;
      ReadOptions(imu, channel::ImuOptionsDescriptor(), keys, e.imu);
    } else if (model == "constant_heading_error") {
      e.inertial = pipeline::InertialModel::kConstantHeadingError;
      ReadOptions(imu, estimation::ConstantHeadingErrorOptionsDescriptor(), keys, e.heading_error);
    } else {
      imu.Fail("model", "unknown inertial model '" + model + "' (available: imu, constant_heading_error)");
    }
  }
  ReadOptions(m, channel::AcousticStampOptionsDescriptor(), keys, e.acoustic);
  for (const auto& t : e.trajectories) {
    if (t.height_m - t.height_amplitude_m <= e.plan.floor_z_m() || t.height_m + t.height_amplitude_m >= e.plan.ceiling_z_m()) {
      m.Fail("model", "trajectory '" + t.name + "' leaves the space between floor and ceiling (height_m +- height_amplitude_m)");
    }
  }
}

void ReadUwbTdoaModel(YamlMap& m, Experiment& e, const core::PhysicalKeys& keys) {
  if (e.medium.kind != core::MediumKind::kRadio) m.Fail("model", "the uwb_tdoa model needs medium: {kind: radio}");
  const double floor_z = e.plan.floor_z_m(), ceiling_z = e.plan.ceiling_z_m();
  struct Box {
    std::string name;
    Vec3 lo_m, hi_m;
    std::vector<geometry::Reflector3> faces;
  };
  std::vector<Box> boxes;
  std::set<std::string> names;
  for (auto& b : m.Has("boxes") ? m.MapList("boxes", true) : std::vector<YamlMap>()) {
    const std::string name = b.String("name");
    if (!names.insert(name).second) b.Fail("name", "duplicate box name '" + name + "'");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Vec3 lo = b.Point3("min_m", nan), hi = b.Point3("max_m", nan);
    if (!std::isfinite(lo.z())) b.Fail("min_m", "give the corner as [x, y, z] (m)");
    if (!std::isfinite(hi.z())) b.Fail("max_m", "give the corner as [x, y, z] (m)");
    if (!((hi - lo).minCoeff() > 0.0)) b.Fail("max_m", "must exceed min_m in x, y and z (the box has no volume)");
    if (lo.z() < floor_z || hi.z() > ceiling_z) {
      b.Fail(lo.z() < floor_z ? "min_m" : "max_m", fmt::format("the box must stand between the floor ({} m) and the ceiling", FormatValue(floor_z)));
    }
    if (!e.plan.walls().empty()) {
      for (const Vec2& corner : {Vec2(lo.x(), lo.y()), Vec2(hi.x(), lo.y()), Vec2(hi.x(), hi.y()), Vec2(lo.x(), hi.y())}) {
        CheckInside(e.plan, corner, b, "max_m", "box '" + name + "' corner");
      }
    }
    for (const auto& a : e.anchors) {
      if ((a.position_m - lo).minCoeff() > 0.0 && (hi - a.position_m).minCoeff() > 0.0) {
        b.Fail("min_m", "anchor '" + a.id + "' is inside box '" + name + "' (every leg to it would be blocked)");
      }
    }
    b.RejectUnknownKeys();
    boxes.push_back({name, lo, hi, geometry::BoxReflectors(name, lo, hi)});
    e.reflectors.insert(e.reflectors.end(), boxes.back().faces.begin(), boxes.back().faces.end());
  }
  ReadOptions(m, channel::UwbTdoaOptionsDescriptor(), keys, e.uwb_tdoa);
  for (const auto& t : e.trajectories) {
    // One slot or more per epoch: a shorter step gives epochs without a row by construction.
    if (t.dt_s * e.uwb_tdoa.rate_hz < 1.0 - 1e-9) {
      m.Fail("rate_hz", fmt::format("trajectory '{}' steps every {} s, more often than one slot (1 / rate_hz = {} s): "
                                    "give dt_s >= 1 / rate_hz",
                                    t.name, FormatValue(t.dt_s), FormatValue(1.0 / e.uwb_tdoa.rate_hz)));
    }
    if (t.height_m - t.height_amplitude_m <= floor_z || t.height_m + t.height_amplitude_m >= ceiling_z) {
      m.Fail("model", "trajectory '" + t.name + "' leaves the space between floor and ceiling (height_m +- height_amplitude_m)");
    }
    // A tag inside a box would have every leg blocked by the box it sits in, not behind it: no
    // leg between consecutive samples (of every run's shifted path) may cross a face or start
    // inside.
    for (const Vec2& offset : GridCorners(e.run_grid)) {
      const auto samples = geometry::SampleTrajectory(t.waypoints_m, t.speed_mps, t.dt_s, offset, t.turn_radius_m, t.stops);
      for (std::size_t k = 0; k < samples.size(); ++k) {
        const Vec3 p = pipeline::TrajectoryPositionAt(t, samples[k]);
        const Vec3 previous = k > 0 ? pipeline::TrajectoryPositionAt(t, samples[k - 1]) : p;
        for (const Box& box : boxes) {
          const bool inside = (p - box.lo_m).minCoeff() > 0.0 && (box.hi_m - p).minCoeff() > 0.0;
          if (inside || !geometry::IsSegmentClear(box.faces, previous, p)) {
            m.Fail("boxes", fmt::format("trajectory '{}' passes through box '{}' at t = {} s{}", t.name, box.name,
                                        FormatValue(samples[k].t_s),
                                        offset.norm() > 0.0 ? fmt::format(" (shifted by the run grid's corner [{}, {}] m)",
                                                                          FormatValue(offset.x() + 0.0), FormatValue(offset.y() + 0.0))
                                                            : std::string()));
          }
        }
      }
    }
  }
}

}  // namespace mirage::io
