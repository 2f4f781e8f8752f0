// SPDX-License-Identifier: MIT
#include "mirage/io/recorded_scenario.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "mirage/io/output_file.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {

void WriteRecordedScenario(const Scenario& scenario, int trajectory, const std::string& dir, const std::string& name) {
  const YAML::Node& doc = scenario.document;
  const pipeline::Experiment& e = scenario.variants.front().experiment;
  YAML::Node out(YAML::NodeType::Map);
  out["name"] = name;
  for (const auto& entry : doc) {
    const std::string key = entry.first.Scalar();
    // Recorded data bring their own anchors and trajectory and are a single run; the simulators'
    // options describe how the recording was made, not how to read it.
    if (key == "name" || key == "anchors" || key == "trajectories" || key == "run_grid" || key == "runs" ||
        key == "perturb_initial_position" || key == "measurements" || key == "extends" || key == "grid" ||
        key == "agents" || key == "steps") {
      continue;
    }
    out[key] = entry.second;
  }
  const pipeline::TrajectorySpec& walked = e.trajectories[static_cast<std::size_t>(trajectory)];
  YAML::Node measurements(YAML::NodeType::Map);
  measurements["model"] = "recorded";
  const bool stamps = e.measurement_model == pipeline::MeasurementModel::kAcoustic;
  const bool tdoa = e.measurement_model == pipeline::MeasurementModel::kUwbTdoa;
  measurements[stamps ? "mics" : "anchors"] = stamps ? "mics.csv" : "anchors.csv";
  if (tdoa) {
    measurements["tdoa"] = "tdoa.csv";
  } else {
    measurements[stamps ? "toa" : "ranges"] = stamps ? "toa.csv" : "ranges.csv";
  }
  measurements["truth"] = "truth.csv";
  // The shortest text that reads back as the same double ("0.1", not "0.10000000000000001").
  if (e.measurement_model == pipeline::MeasurementModel::kRanging) {
    measurements["range_sigma_m"] = fmt::format("{}", e.ranging.range_sigma_m);
  }
  if (stamps) {
    // The facts the acoustic estimators' defaults derive from in the simulation
    // (pipeline::PhysicalKeysOf), and the sender's nominal height they take as known.
    measurements["height_m"] = fmt::format("{}", walked.height_m);
    measurements["stamp_sigma_s"] = fmt::format("{}", e.acoustic.stamp_sigma_s);
    measurements["detection_probability"] = fmt::format("{}", e.acoustic.detection_probability);
    measurements["false_alarm_rate"] = fmt::format("{}", e.acoustic.false_alarm_rate);
    measurements["dt_s"] = fmt::format("{}", walked.dt_s);
  }
  if (tdoa) {
    // The facts the TDOA filter's defaults derive from (pipeline::PhysicalKeysOf).
    if (e.uwb_tdoa.sigma_m > 0.0) measurements["tdoa_sigma_m"] = fmt::format("{}", e.uwb_tdoa.sigma_m);
    measurements["detection_probability"] = fmt::format("{}", e.uwb_tdoa.detection_probability);
    measurements["dt_s"] = fmt::format("{}", walked.dt_s);
  }
  measurements["speed_mps"] = fmt::format("{}", walked.speed_mps);
  out["measurements"] = measurements;

  YAML::Emitter emitter;
  emitter.SetDoublePrecision(17);
  emitter << out;
  const std::string path = dir + "/scenario.yaml";
  OutputFile output(path);
  output.stream() << "# Written by `mirage simulate " << scenario.file << "`: runs the recording in this directory.\n"
                  << "# Without the `truth:` line the estimator starts itself from the first epochs (no error figures).\n"
                  << emitter.c_str() << "\n";
  output.Commit();
}

}  // namespace mirage::io
