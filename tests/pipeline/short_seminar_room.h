// SPDX-License-Identifier: MIT
// Test fixture: the seminar-room example (examples/seminar_room.yaml) with its trajectories cut
// to their first metres, so that a pipeline run takes milliseconds instead of seconds.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/io/scenario.h"

namespace mirage::pipeline::testing {

inline std::string ExamplePath(const std::string& name) { return std::string(MIRAGE_SOURCE_DIR) + "/examples/" + name; }

// The first length_m of the polyline (at least its first leg's start and one more point).
inline std::vector<Vec2> TruncatePolyline(const std::vector<Vec2>& waypoints_m, double length_m) {
  std::vector<Vec2> out{waypoints_m.front()};
  double left_m = length_m;
  for (std::size_t i = 1; i < waypoints_m.size() && left_m > 0.0; ++i) {
    const Vec2 leg = waypoints_m[i] - waypoints_m[i - 1];
    const double leg_m = leg.norm();
    if (leg_m <= left_m) {
      out.push_back(waypoints_m[i]);
      left_m -= leg_m;
    } else {
      out.push_back(waypoints_m[i - 1] + leg * (left_m / leg_m));
      left_m = 0.0;
    }
  }
  return out;
}

// An example scenario with `runs` runs per trajectory, each trajectory cut to length_m (2 m = 40
// steps of 5 cm), on `threads` threads.
inline io::Scenario ShortExample(const std::string& file, int runs, double length_m = 2.0, int threads = 1) {
  io::ScenarioOverrides overrides;
  overrides.runs = runs;
  overrides.threads = threads;
  io::Scenario scenario = io::LoadScenario(ExamplePath(file), overrides);
  for (auto& v : scenario.variants) {
    for (auto& t : v.experiment.trajectories) t.waypoints_m = TruncatePolyline(t.waypoints_m, length_m);
  }
  return scenario;
}

// The seminar room (MINT) cut short.
inline io::Scenario ShortSeminarRoom(int runs, double length_m = 2.0, int threads = 1) {
  return ShortExample("seminar_room.yaml", runs, length_m, threads);
}

}  // namespace mirage::pipeline::testing
