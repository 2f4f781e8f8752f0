// SPDX-License-Identifier: MIT
#include "mirage/io/scenario_sections.h"

#include <utility>

#include <fmt/format.h>

namespace mirage::io {
namespace {

// Upper bound of the number of VAs per anchor up to `order` with `walls` walls.
double VirtualAnchorCount(std::size_t walls, int order) {
  double count = 1.0, level = 1.0;
  for (int k = 1; k <= order; ++k) {
    level *= k == 1 ? static_cast<double>(walls) : static_cast<double>(walls) - 1.0;
    count += level;
  }
  return count;
}

}  // namespace

std::vector<Vec2> GridCorners(const pipeline::RunGrid& grid) {
  const double hx = 0.5 * (grid.nx - 1) * grid.spacing_m;
  const double hy = 0.5 * (grid.ny - 1) * grid.spacing_m;
  return {Vec2::Zero(), Vec2(-hx, -hy), Vec2(hx, -hy), Vec2(-hx, hy), Vec2(hx, hy)};
}

bool IsPlainName(const std::string& name) { return name.find_first_of(",\"\n\r") == std::string::npos; }

void CheckVirtualAnchorCount(YamlMap& section, const std::string& key, std::size_t walls, int order) {
  const double count = VirtualAnchorCount(walls, order);
  if (count > kMaxVirtualAnchorsPerAnchor) {
    section.Fail(key, fmt::format("order {} with {} walls gives up to {:.3g} virtual anchors per anchor, more than {:g}",
                                  order, walls, count, kMaxVirtualAnchorsPerAnchor));
  }
}

std::map<std::string, double> ReadMaterials(YamlMap table) {
  std::map<std::string, double> materials;
  for (const auto& [name, value] : table.NumberTable()) {
    if (!(value > 0.0 && value <= 1.0)) {
      table.Fail(name, fmt::format("reflection coefficient {} must be in (0, 1]", FormatValue(value)));
    }
    materials[name] = value;
  }
  return materials;
}

geometry::FloorPlan ReadFloorPlan(YamlMap m, const std::map<std::string, double>& materials, std::vector<bool>* in_plan) {
  std::vector<geometry::Wall> walls;
  if (in_plan != nullptr) in_plan->clear();
  for (auto& w : m.MapList("walls", false)) {
    // A wall entry is either one segment (start_m, end_m) or a polyline (polyline_m, closed).
    std::vector<Vec2> points;
    bool closed = false;
    if (w.Has("polyline_m")) {
      points = w.Points("polyline_m", 2);
      closed = w.Boolean("closed", false);
      if (closed && points.size() < 3) w.Fail("closed", "a closed polyline needs at least 3 points");
    } else {
      points = {w.Point("start_m"), w.Point("end_m")};
    }
    double coeff = geometry::Wall{}.reflection_coeff;
    std::string label;
    if (w.Has("material")) {
      label = w.String("material");
      const auto it = materials.find(label);
      if (it == materials.end()) w.Fail("material", "unknown material '" + label + "' (define it under materials:)");
      coeff = it->second;
    }
    if (w.Has("reflection_coeff")) coeff = w.NumberInRange("reflection_coeff", coeff, 0.0, 1.0, "");
    if (!(coeff > 0.0)) w.Fail("reflection_coeff", "must be in (0, 1], got 0");
    label = w.String("label", label);
    // Only read when the caller has somewhere to put it, so that the key stays unknown (an
    // error) in files whose method has no provided-plan / true-plan distinction.
    const bool entry_in_plan = in_plan != nullptr ? w.Boolean("in_plan", true) : true;
    const std::size_t segments = closed ? points.size() : points.size() - 1;
    for (std::size_t i = 0; i < segments; ++i) {
      const Vec2& a = points[i];
      const Vec2& b = points[(i + 1) % points.size()];
      if ((b - a).norm() < 1e-6) {
        w.Fail(w.Has("polyline_m") ? "polyline_m" : "end_m",
               fmt::format("wall segment {} has zero length (from [{}, {}] to [{}, {}] m)", i, FormatValue(a.x()),
                           FormatValue(a.y()), FormatValue(b.x()), FormatValue(b.y())));
      }
      for (const auto& other : walls) {
        const bool same = ((other.start_m - a).norm() < 1e-6 && (other.end_m - b).norm() < 1e-6) ||
                          ((other.start_m - b).norm() < 1e-6 && (other.end_m - a).norm() < 1e-6);
        if (same) {
          w.Fail(w.Has("polyline_m") ? "polyline_m" : "end_m",
                 fmt::format("wall segment {} from [{}, {}] to [{}, {}] m repeats an earlier wall", i, FormatValue(a.x()),
                             FormatValue(a.y()), FormatValue(b.x()), FormatValue(b.y())));
        }
      }
      walls.push_back({a, b, coeff, label});
      if (in_plan != nullptr) in_plan->push_back(entry_in_plan);
    }
    w.RejectUnknownKeys();
  }
  std::vector<geometry::CircleObstacle> obstacles;
  if (m.Has("obstacles")) {
    for (auto& o : m.MapList("obstacles", true)) {
      geometry::CircleObstacle obstacle;
      obstacle.center_m = o.Point("center_m");
      obstacle.radius_m = o.Number("radius_m");
      if (!(obstacle.radius_m > 0.0)) o.Fail("radius_m", FormatValue(obstacle.radius_m) + " m must be > 0 m");
      obstacle.label = o.String("label", std::string());
      o.RejectUnknownKeys();
      obstacles.push_back(obstacle);
    }
  }
  // Walls are vertical and span floor to ceiling (2.5-D); a plan without heights reaches up without
  // end, which keeps every planar scenario as it was.
  const double floor_z_m = m.NumberInRange("floor_z_m", 0.0, -kHuge, kHuge, "m");
  double ceiling_z_m = geometry::kNoCeiling_m;
  if (m.Has("ceiling_z_m")) {
    ceiling_z_m = m.NumberInRange("ceiling_z_m", 0.0, -kHuge, kHuge, "m");
    if (!(ceiling_z_m > floor_z_m)) m.Fail("ceiling_z_m", fmt::format("{} m must be above floor_z_m ({} m)", FormatValue(ceiling_z_m), FormatValue(floor_z_m)));
  }
  m.RejectUnknownKeys();
  return geometry::FloorPlan(std::move(walls), std::move(obstacles), floor_z_m, ceiling_z_m);
}

void CheckInside(const geometry::FloorPlan& plan, const Vec2& p, YamlMap& where, const std::string& key,
                 const std::string& what) {
  if (!plan.Encloses(p)) {
    where.Fail(key, fmt::format("{} at [{}, {}] m is outside the floor plan (not enclosed by walls)", what,
                                FormatValue(p.x()), FormatValue(p.y())));
  }
  if (plan.InsideObstacle(p)) {
    where.Fail(key, fmt::format("{} at [{}, {}] m is inside an obstacle", what, FormatValue(p.x()), FormatValue(p.y())));
  }
}

void ApplyOverrides(const ScenarioOverrides& overrides, int& runs, std::uint64_t& seed, int& threads) {
  if (overrides.runs) {
    if (*overrides.runs < 1 || *overrides.runs > kMaxRuns) {
      throw InputError(fmt::format("--runs: {} is out of range, expected [1, {}]", *overrides.runs, kMaxRuns));
    }
    runs = *overrides.runs;
  }
  if (overrides.seed) seed = *overrides.seed;
  if (overrides.threads) {
    if (*overrides.threads < 0 || *overrides.threads > kMaxThreads) {
      throw InputError(fmt::format("--threads: {} is out of range, expected [0, {}]", *overrides.threads, kMaxThreads));
    }
    threads = *overrides.threads;
  }
}

}  // namespace mirage::io
