// SPDX-License-Identifier: MIT
// The mirage command-line tool.
//   mirage run SCENARIO.yaml [--runs N] [--seed S] [--threads T] [--json FILE] [--csv DIR] [--plot FILE] [--quiet]
//   mirage describe [METHOD|SECTION] [--markdown]
//   mirage simulate SCENARIO.yaml --out DIR [--seed S] [--trajectory NAME] [--run R] [--quiet]
//   mirage --version
// Exit codes: 0 success, 2 bad input or usage, 3 internal error.
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/range_level_simulator.h"
#include "mirage/channel/acoustic_stamps.h"
#include "mirage/channel/uwb_tdoa_simulator.h"
#include "mirage/channel/imu_simulator.h"
#include "mirage/channel/ranging_simulator.h"
#include "mirage/estimation/imu/pdr.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/eval/error_stats.h"
#include "mirage/io/input_error.h"
#include "mirage/io/options_describe.h"
#include "mirage/io/output_file.h"
#include "mirage/io/plot.h"
#include "mirage/io/recorded_data.h"
#include "mirage/io/recorded_scenario.h"
#include "mirage/io/report.h"
#include "mirage/io/scenario.h"
#include "mirage/methods/registry.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/simulated_recording.h"
#include "mirage/pipeline/summary.h"

namespace {

struct RunArgs {
  std::string scenario;
  std::optional<int> runs;
  std::string seed;  // parsed by ParseSeed: CLI11 would wrap -1 around to 2^64 - 1
  std::optional<int> threads;
  std::string json;
  std::string csv;
  std::string plot;
  bool quiet = false;
};

struct SimulateArgs {
  std::string scenario;
  std::string out;
  std::string seed;
  std::string trajectory;
  int run = 0;
  bool quiet = false;
};

// The master seed of --seed: a decimal integer in [0, 2^64 - 1]; empty when the option is absent.
std::optional<std::uint64_t> ParseSeed(const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::uint64_t seed = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw mirage::io::InputError("--seed: expected an integer in [0, 18446744073709551615], got '" + text + "'");
  }
  return seed;
}

// The directory of the running binary (/proc/self/exe), so that its data files are found
// relative to it wherever the tree was built or installed.
std::filesystem::path BinaryDirectory() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path(".") : exe.parent_path();
}

// A plot script: $ENV_NAME if set, else bin/../share/mirage/NAME beside the binary (the build
// tree and an installed tree have the same layout).
std::string PlotScript(const char* env_name, const char* file_name) {
  if (const char* env = std::getenv(env_name); env != nullptr && *env != '\0') return env;
  return (BinaryDirectory().parent_path() / "share" / "mirage" / file_name).string();
}

// Progress of the Monte-Carlo jobs on stderr: a bar redrawn in place on a terminal; otherwise
// (a log file, CI) one line every few seconds, so that a long run is visibly alive.
class Progress {
 public:
  Progress(bool quiet, std::string what) : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0), what_(std::move(what)) {}
  void operator()(int done, int total) {
    if (quiet_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto now = Clock::now();
    if (tty_) {
      constexpr int kWidth = 40;
      const int filled = done * kWidth / std::max(1, total);
      std::fprintf(stderr, "\r[%s%s] %d/%d %s", std::string(static_cast<std::size_t>(filled), '#').c_str(),
                   std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), done, total, what_.c_str());
      if (done == total) std::fprintf(stderr, "\n");
      return;
    }
    if (done == total || now - last_ >= kInterval) {
      std::fprintf(stderr, "mirage: %d/%d %s done (%.0f s)\n", done, total, what_.c_str(),
                   std::chrono::duration<double>(now - start_).count());
      last_ = now;
    }
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kInterval{5};
  bool quiet_;
  bool tty_;
  std::string what_;
  std::mutex mutex_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_ = Clock::now();
};

// Checks every output path before the run starts, so that a typo does not cost the run.
void CheckOutputs(const std::string& json, const std::string& csv, const std::string& plot) {
  if (!json.empty()) mirage::io::CheckWritableFile(json, "--json");
  if (!csv.empty()) mirage::io::CheckWritableDirectory(csv, "--csv");
  if (!plot.empty()) mirage::io::CheckWritableFile(plot, "--plot");
}

// The closing line: which files the run wrote.
void PrintWritten(bool quiet, const std::vector<std::string>& files) {
  if (quiet || files.empty()) return;
  std::string list;
  for (const auto& f : files) list += (list.empty() ? "" : ", ") + f;
  std::fprintf(stderr, "mirage: wrote %s\n", list.c_str());
}

int Run(const RunArgs& args) {
  mirage::io::ScenarioOverrides overrides;
  overrides.runs = args.runs;
  overrides.seed = ParseSeed(args.seed);
  overrides.threads = args.threads;
  const auto scenario = mirage::io::LoadScenario(args.scenario, overrides);
  CheckOutputs(args.json, args.csv, args.plot);

  Progress progress(args.quiet, "jobs");
  const auto result = mirage::pipeline::RunExperiment(scenario.variants, std::ref(progress));
  const auto summaries = mirage::pipeline::Summarize(scenario.variants, result);
  const std::string table = mirage::io::FormatResultTable(scenario, result, summaries);

  if (!args.quiet) std::cout << table << std::flush;
  std::vector<std::string> written;
  if (!args.json.empty()) {
    mirage::io::WriteJson(args.json, mirage::io::MakeJsonReport(scenario, result, summaries));
    written.push_back(args.json);
  }
  if (!args.csv.empty()) {
    for (const auto& f : mirage::io::WriteCsv(args.csv, scenario, result, summaries)) written.push_back(f);
  }
  if (!args.plot.empty()) {
    mirage::io::RenderPlot(args.plot, PlotScript("MIRAGE_PLOT_SCRIPT", "plot_run.py"),
                           mirage::io::PlotData(scenario, result, summaries, table));
    written.push_back(args.plot);
  }
  PrintWritten(args.quiet, written);
  return 0;
}

// The scenario sections whose keys come from an options descriptor, by the name `mirage
// describe` takes: the front end and the evaluation, next to the methods.
struct DescribedSection {
  const char* name;      // `mirage describe NAME`
  const char* yaml_path;  // where its keys go in a scenario
  const char* summary;
  const mirage::core::OptionsDescriptorBase& descriptor;
};

std::vector<DescribedSection> DescribedSections() {
  return {
      {"channel", "channel", "the simulated UWB channel (measurements.model cir or ranges)",
       mirage::channel::ChannelOptionsDescriptor()},
      {"ranging", "measurements", "a ranging system's ranges (measurements.model ranging)",
       mirage::channel::RangingOptionsDescriptor()},
      {"ranges", "measurements", "range-level measurements with SINR-dependent noise (measurements.model ranges)",
       mirage::channel::RangeLevelOptionsDescriptor()},
      {"acoustic_stamps", "measurements", "arrival-time stamps of a sound sender at microphones (measurements.model acoustic)",
       mirage::channel::AcousticStampOptionsDescriptor()},
      {"uwb_tdoa", "measurements", "pairwise UWB TDOA of a tag among anchors (measurements.model uwb_tdoa)",
       mirage::channel::UwbTdoaOptionsDescriptor()},
      {"imu", "measurements.imu", "a smartphone IMU's samples (measurements.imu model imu)",
       mirage::channel::ImuOptionsDescriptor()},
      {"constant_heading_error", "measurements.imu",
       "the thesis's synthetic IMU: displacements rotated by a constant angle (measurements.imu model constant_heading_error)",
       mirage::estimation::ConstantHeadingErrorOptionsDescriptor()},
      {"mpc", "mpc", "multipath-component extraction from CIRs", mirage::dsp::MpcExtractorOptionsDescriptor()},
      {"divergence", "evaluation.divergence", "the rule that calls a run diverged", mirage::eval::DivergenceRuleDescriptor()},
  };
}

// Every option of a method or a section (or the list of both): key, unit, default or the
// formula it is derived from, valid range and meaning, from the options descriptor.
int Describe(const std::string& name, bool markdown) {
  if (name.empty()) {
    std::cout << "methods (mirage describe METHOD lists its options under `method:`):\n";
    for (const auto& m : mirage::methods::Methods()) {
      std::cout << fmt::format("  {:<10} {} ({})\n", m.name, m.summary, m.source);
    }
    std::cout << "scenario sections (mirage describe SECTION):\n";
    for (const auto& s : DescribedSections()) {
      std::cout << fmt::format("  {:<10} `{}`: {}\n", s.name, s.yaml_path, s.summary);
    }
    return 0;
  }
  if (const auto* info = mirage::methods::FindMethod(name)) {
    std::cout << (markdown ? mirage::io::DescribeMarkdown(*info->descriptor, "method")
                           : mirage::io::DescribeText(*info->descriptor, "method: {name: " + info->name + ", ...}"));
    return 0;
  }
  for (const auto& s : DescribedSections()) {
    if (name != s.name) continue;
    std::cout << (markdown ? mirage::io::DescribeMarkdown(s.descriptor, s.yaml_path)
                           : mirage::io::DescribeText(s.descriptor, s.yaml_path));
    return 0;
  }
  std::string sections;
  for (const auto& s : DescribedSections()) sections += std::string(sections.empty() ? "" : ", ") + s.name;
  throw mirage::io::InputError("describe: unknown method or section '" + name +
                               "' (methods: " + mirage::methods::MethodNames() + "; sections: " + sections + ")");
}

// The scalar text at a dotted key path ("measurements.sigma_m") of a scenario document, empty
// when the path leads to no scalar (a list index, a map, a missing key).
std::string BaseValueText(const YAML::Node& document, const std::string& path) {
  YAML::Node node;
  node.reset(document);
  std::size_t begin = 0;
  while (begin <= path.size()) {
    const std::size_t end = path.find('.', begin);
    const std::string key = path.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    const YAML::Node& here = node;  // const lookup: non-const operator[] would insert
    if (!here.IsMap() || !here[key]) return {};
    node.reset(here[key]);
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return node.IsScalar() ? node.Scalar() : std::string();
}

// Writes one simulated run as recorded data (anchors.csv, ranges.csv, truth.csv, or mics.csv,
// toa.csv, truth.csv for an acoustic scenario) plus a scenario.yaml that runs it, so that
// `mirage run DIR/scenario.yaml` replays exactly the ranges or stamps the Monte-Carlo driver's
// estimator sees in that run.
int Simulate(const SimulateArgs& args) {
  mirage::io::ScenarioOverrides overrides;
  overrides.seed = ParseSeed(args.seed);
  const auto scenario = mirage::io::LoadScenario(args.scenario, overrides);
  // A grid whose variants vary only the method (or restate the file's own values elsewhere, as
  // a first variant "the file as written" does) has one set of measurements: the recording is
  // the same for all, and its scenario runs the file's method.
  for (const auto& variant : scenario.variants) {
    for (const auto& [key, value] : variant.overrides) {
      if (key.rfind("method.", 0) != 0 && BaseValueText(scenario.document, key) != value) {
        throw mirage::io::InputError(args.scenario + ": the grid varies " + key +
                                     ", so its variants have different measurements; simulate one variant's scenario");
      }
    }
  }
  const auto& config = scenario.variants.front().experiment;
  if (config.measurement_model == mirage::pipeline::MeasurementModel::kRecorded) {
    throw mirage::io::InputError(args.scenario + ": measurements.model is recorded; there is nothing to simulate");
  }
  if (config.method.input == mirage::methods::MethodInput::kLinkCirs) {
    throw mirage::io::InputError(args.scenario + ": method " + config.method.name +
                                 " consumes CIRs, which have no recorded-data form; use mirage run");
  }
  if (config.inertial != mirage::pipeline::InertialModel::kNone) {
    throw mirage::io::InputError(args.scenario + ": measurements.imu: the inertial records have no recorded-data form "
                                 "(mics.csv, toa.csv hold the stamps only); remove it to simulate the stamps");
  }
  if (const auto options = nlohmann::json::parse(config.method.options_json);
      options.contains("inertial") && options["inertial"] == true) {
    throw mirage::io::InputError(args.scenario + ": method.inertial: the inertial records have no recorded-data form "
                                 "(mics.csv, toa.csv hold the stamps only); set it false to simulate the stamps");
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
  mirage::io::CheckWritableDirectory(args.out, "--out");
  const auto recording = mirage::pipeline::SimulateRecording(config, trajectory, args.run);
  mirage::io::WriteRecording(args.out, recording);
  mirage::io::WriteRecordedScenario(scenario, trajectory, args.out, config.name + " (recorded)");
  if (!args.quiet) {
    std::size_t rows = 0;
    for (const auto& step : recording.steps) {
      for (const auto& anchor : step.anchors) rows += anchor.ranges.size();
      for (const auto& mic : step.toas) rows += mic.toa_s.size();
      rows += step.tdoas.size();
    }
    const std::string kind = recording.tdoa ? "differences" : recording.toa_stamps ? "stamps" : "ranges";
    const std::string files = recording.tdoa ? "anchors,tdoa" : recording.toa_stamps ? "mics,toa" : "anchors,ranges";
    std::cout << fmt::format("mirage simulate: {} trajectory '{}' run {} (seed {}): {} steps, {} {} -> {}/"
                             "{{{},truth}}.csv and scenario.yaml\n",
                             config.name, config.trajectories[static_cast<std::size_t>(trajectory)].name, args.run,
                             config.seed, recording.steps.size(), rows, kind, args.out, files);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mirage: multipath-assisted, NLOS-robust indoor localization"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("mirage ") + MIRAGE_VERSION);
  RunArgs args;
  auto* run = app.add_subcommand("run", "simulate (or read) the scenario, run its method, report the result");
  run->add_option("scenario", args.scenario, "scenario file (YAML)")->required();
  run->add_option("--runs", args.runs, "Monte-Carlo runs per trajectory (overrides the scenario)");
  run->add_option("--seed", args.seed, "master seed, an integer in [0, 2^64 - 1] (overrides the scenario)");
  run->add_option("--threads", args.threads, "worker threads, 0 = all cores (results do not depend on it)");
  run->add_option("--json", args.json, "write the JSON report to this file");
  run->add_option("--csv", args.csv,
                  "write tracks.csv and runs.csv into this directory, and paths.csv (simulated anchor paths), map.csv "
                  "(methods with a map) and variants.csv, error_by_step.csv (scenarios with a grid)");
  run->add_option("--plot", args.plot, "write a picture (PNG, PDF or SVG) of the run");
  run->add_flag("--quiet", args.quiet, "print nothing but errors");

  SimulateArgs sim;
  auto* simulate = app.add_subcommand("simulate", "simulate one run and write it as recorded data (CSV) with a scenario that runs it");
  simulate->add_option("scenario", sim.scenario, "scenario file (YAML)")->required();
  simulate->add_option("--out", sim.out, "output directory")->required();
  simulate->add_option("--seed", sim.seed, "master seed, an integer in [0, 2^64 - 1] (overrides the scenario)");
  simulate->add_option("--trajectory", sim.trajectory, "trajectory name (default: the first)");
  simulate->add_option("--run", sim.run, "Monte-Carlo run index (start offset and random streams), default 0");
  simulate->add_flag("--quiet", sim.quiet, "print nothing but errors");

  std::string describe_method;
  bool describe_markdown = false;
  auto* describe = app.add_subcommand(
      "describe", "list the methods and scenario sections, or every option of one (unit, default, range)");
  describe->add_option("name", describe_method, "a method or scenario section name");
  describe->add_flag("--markdown", describe_markdown, "print a Markdown table (the form of docs/scenario.md)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and the usage hint
    return 2;     // every usage error is a bad input (CLI11's own codes are 100+)
  }
  try {
    if (run->parsed()) return Run(args);
    if (simulate->parsed()) return Simulate(sim);
    if (describe->parsed()) return Describe(describe_method, describe_markdown);
  } catch (const mirage::io::InputError& e) {
    std::cerr << "mirage: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mirage: internal error: " << e.what() << "\n";
    return 3;
  }
  return 0;
}
