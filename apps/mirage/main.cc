// SPDX-License-Identifier: MIT
// The mirage command-line tool.
//   mirage run SCENARIO.yaml [--runs N] [--seed S] [--threads T] [--json FILE] [--csv DIR] [--plot FILE]
//     (a `method: coop` scenario runs its grid of cooperative variants instead)
//   mirage simulate SCENARIO.yaml --out DIR [--seed S] [--trajectory NAME] [--run R]
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "mirage/io/coop_report.h"
#include "mirage/io/coop_scenario.h"
#include "mirage/io/input_error.h"
#include "mirage/io/plot.h"
#include "mirage/io/recorded_data.h"
#include "mirage/io/recorded_scenario.h"
#include "mirage/io/report.h"
#include "mirage/io/scenario.h"
#include "mirage/pipeline/coop_experiment.h"
#include "mirage/pipeline/coop_summary.h"
#include "mirage/pipeline/mint_experiment.h"
#include "mirage/pipeline/mint_summary.h"
#include "mirage/pipeline/run_simulator.h"

namespace {

struct RunArgs {
  std::string scenario;
  std::optional<int> runs;
  std::optional<std::uint64_t> seed;
  std::optional<int> threads;
  std::string json;
  std::string csv;
  std::string plot;
  bool quiet = false;
};

struct SimulateArgs {
  std::string scenario;
  std::string out;
  std::optional<std::uint64_t> seed;
  std::string trajectory;
  int run = 0;
  bool quiet = false;
};

std::string PlotScript() {
  // Next to the binary's source tree (build/bin/mirage -> tools/plot_run.py), or $MIRAGE_PLOT_SCRIPT.
  if (const char* env = std::getenv("MIRAGE_PLOT_SCRIPT"); env != nullptr && *env != '\0') return env;
  return std::string(MIRAGE_SOURCE_DIR) + "/tools/plot_run.py";
}

std::string CoopPlotScript() {
  if (const char* env = std::getenv("MIRAGE_COOP_PLOT_SCRIPT"); env != nullptr && *env != '\0') return env;
  return std::string(MIRAGE_SOURCE_DIR) + "/tools/plot_coop.py";
}

// A cooperative grid (issue 5): every variant `runs` times on both cores, with a progress bar.
int RunCoop(const RunArgs& args, const mirage::io::ScenarioOverrides& overrides) {
  const auto scenario = mirage::io::LoadCoopScenario(args.scenario, overrides);
  const auto& config = scenario.config;
  const bool show_progress = !args.quiet && isatty(STDERR_FILENO) != 0;
  std::mutex progress_mutex;
  const auto progress = [&](int done, int total) {
    if (!show_progress) return;
    const std::lock_guard<std::mutex> lock(progress_mutex);
    constexpr int kWidth = 40;
    const int filled = done * kWidth / std::max(1, total);
    std::fprintf(stderr, "\r[%s%s] %d/%d", std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), done, total);
    if (done == total) std::fprintf(stderr, "\n");
  };
  const auto result = mirage::pipeline::RunCoopExperiment(config, progress);
  const auto summary = mirage::pipeline::SummarizeCoop(result);
  if (!args.quiet) std::cout << mirage::io::FormatCoopTable(config, summary) << std::flush;
  if (!args.json.empty()) {
    mirage::io::WriteJson(args.json, mirage::io::MakeCoopJson(args.scenario, config, result, summary));
  }
  if (!args.csv.empty()) mirage::io::WriteCoopCsv(args.csv, summary);
  if (!args.plot.empty()) {
    mirage::io::RenderPlot(args.plot, CoopPlotScript(), mirage::io::CoopPlotData(config, result, summary));
  }
  return 0;
}

int Run(const RunArgs& args) {
  mirage::io::ScenarioOverrides overrides;
  overrides.runs = args.runs;
  overrides.seed = args.seed;
  overrides.threads = args.threads;
  if (mirage::io::IsCoopScenario(args.scenario)) return RunCoop(args, overrides);
  const auto scenario = mirage::io::LoadScenario(args.scenario, overrides);

  const bool show_progress = !args.quiet && isatty(STDERR_FILENO) != 0;
  std::mutex progress_mutex;
  const auto progress = [&](int done, int total) {
    if (!show_progress) return;
    const std::lock_guard<std::mutex> lock(progress_mutex);
    std::fprintf(stderr, "\rrun %d/%d", done, total);
    if (done == total) std::fprintf(stderr, "\n");
  };
  const auto result = mirage::pipeline::RunMintExperiment(scenario.mint, progress);
  const auto summary = mirage::pipeline::Summarize(scenario.mint, result);

  if (!args.quiet) std::cout << mirage::io::FormatResultTable(scenario, summary) << std::flush;
  if (!args.json.empty()) mirage::io::WriteJson(args.json, mirage::io::MakeJsonReport(scenario, result, summary));
  if (!args.csv.empty()) mirage::io::WriteCsv(args.csv, scenario, result);
  if (!args.plot.empty()) mirage::io::WritePlot(args.plot, PlotScript(), scenario, result, summary);
  return 0;
}

// Writes one simulated run as recorded data (anchors.csv, ranges.csv, truth.csv) plus a
// scenario.yaml that runs it, so that `mirage run DIR/scenario.yaml` replays exactly the ranges
// the Monte-Carlo driver's tracker sees in that run.
int Simulate(const SimulateArgs& args) {
  mirage::io::ScenarioOverrides overrides;
  overrides.seed = args.seed;
  if (mirage::io::IsCoopScenario(args.scenario)) {
    throw mirage::io::InputError(args.scenario + ": method coop has no recorded-data form; use mirage run");
  }
  const auto scenario = mirage::io::LoadScenario(args.scenario, overrides);
  const auto& config = scenario.mint;
  if (config.measurement_model == mirage::pipeline::MeasurementModel::kRecorded) {
    throw mirage::io::InputError(args.scenario + ": measurements.model is recorded; there is nothing to simulate");
  }
  int trajectory = 0;
  if (!args.trajectory.empty()) {
    trajectory = -1;
    std::string names;
    for (std::size_t t = 0; t < config.trajectories.size(); ++t) {
      if (config.trajectories[t].name == args.trajectory) trajectory = static_cast<int>(t);
      names += (names.empty() ? "" : ", ") + config.trajectories[t].name;
    }
    if (trajectory < 0) {
      throw mirage::io::InputError(fmt::format("--trajectory: no trajectory '{}' in {} (available: {})",
                                               args.trajectory, args.scenario, names));
    }
  }
  if (args.run < 0 || args.run >= config.runs) {
    throw mirage::io::InputError(
        fmt::format("--run: {} is out of range, expected [0, {}] (the scenario's runs)", args.run, config.runs - 1));
  }
  const auto recording = mirage::pipeline::SimulateRecording(config, trajectory, args.run);
  mirage::io::WriteRecording(args.out, recording);
  mirage::io::WriteRecordedScenario(args.scenario, args.out, config.name + " (recorded)");
  if (!args.quiet) {
    std::size_t rows = 0;
    for (const auto& step : recording.steps) {
      for (const auto& anchor : step.anchors) rows += anchor.ranges.size();
    }
    std::cout << fmt::format("mirage simulate: {} trajectory '{}' run {} (seed {}): {} steps, {} ranges -> {}/"
                             "{{anchors,ranges,truth}}.csv and scenario.yaml\n",
                             config.name, config.trajectories[static_cast<std::size_t>(trajectory)].name, args.run,
                             config.seed, recording.steps.size(), rows, args.out);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mirage: multipath-assisted, NLOS-robust indoor localization"};
  app.require_subcommand(1);
  RunArgs args;
  auto* run = app.add_subcommand("run", "simulate (or read) the scenario, run its method, report the result");
  run->add_option("scenario", args.scenario, "scenario file (YAML)")->required();
  run->add_option("--runs", args.runs, "Monte-Carlo runs per trajectory (overrides the scenario)");
  run->add_option("--seed", args.seed, "master seed (overrides the scenario)");
  run->add_option("--threads", args.threads, "worker threads, 0 = all cores (results do not depend on it)");
  run->add_option("--json", args.json, "write the JSON report to this file");
  run->add_option("--csv", args.csv, "write tracks.csv, runs.csv, paths.csv, virtual_anchors.csv into this directory");
  run->add_option("--plot", args.plot, "write a picture (PNG, PDF or SVG) of the run");
  run->add_flag("--quiet", args.quiet, "print nothing but errors");

  SimulateArgs sim;
  auto* simulate = app.add_subcommand("simulate", "simulate one run and write it as recorded data (CSV) with a scenario that runs it");
  simulate->add_option("scenario", sim.scenario, "scenario file (YAML)")->required();
  simulate->add_option("--out", sim.out, "output directory")->required();
  simulate->add_option("--seed", sim.seed, "master seed (overrides the scenario)");
  simulate->add_option("--trajectory", sim.trajectory, "trajectory name (default: the first)");
  simulate->add_option("--run", sim.run, "Monte-Carlo run index (start offset and random streams), default 0");
  simulate->add_flag("--quiet", sim.quiet, "print nothing but errors");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (run->parsed()) return Run(args);
    if (simulate->parsed()) return Simulate(sim);
  } catch (const mirage::io::InputError& e) {
    std::cerr << "mirage: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mirage: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
