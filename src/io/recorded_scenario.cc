// SPDX-License-Identifier: MIT
#include "mirage/io/recorded_scenario.h"

#include <yaml-cpp/yaml.h>

#include "mirage/io/output_file.h"
#include "mirage/io/yaml_reader.h"

namespace mirage::io {

void WriteRecordedScenario(const std::string& scenario_path, const std::string& dir, const std::string& name) {
  YamlOrigins origins(scenario_path);
  YAML::Node doc = LoadYamlWithExtends(scenario_path, origins);
  YAML::Node out(YAML::NodeType::Map);
  out["name"] = name;
  for (const auto& entry : doc) {
    const std::string key = entry.first.Scalar();
    // Recorded data bring their own anchors and trajectory and are a single run; the
    // range-level simulator's options describe how the recording was made, not how to read it.
    if (key == "name" || key == "anchors" || key == "trajectories" || key == "run_grid" || key == "runs" ||
        key == "perturb_initial_position" || key == "measurements" || key == "extends") {
      continue;
    }
    out[key] = entry.second;
  }
  YAML::Node measurements(YAML::NodeType::Map);
  measurements["model"] = "recorded";
  measurements["anchors"] = "anchors.csv";
  measurements["ranges"] = "ranges.csv";
  measurements["truth"] = "truth.csv";
  out["measurements"] = measurements;

  YAML::Emitter emitter;
  emitter << out;
  const std::string path = dir + "/scenario.yaml";
  OutputFile output(path);
  auto& file = output.stream();
  file << "# Written by `mirage simulate " << scenario_path << "`: runs the recording in this directory.\n"
       << emitter.c_str() << "\n";
  output.Commit();
}

}  // namespace mirage::io
