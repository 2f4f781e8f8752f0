// SPDX-License-Identifier: MIT
// Outputs of `mirage run`, one schema for every method: the JSON report's contract (the keys
// ROADMAP.md promises with their types, for mint, slam, coop and range_ekf, each run on a tiny
// scenario; `variants` for a grid, `recorded_data` for a recording), the values it carries, the
// CSV files (tracks.csv and runs.csv with and without a grid, z columns for 3-D estimates,
// paths.csv, map.csv, variants.csv, error_by_step.csv) and the result table.
#include "mirage/io/report.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"
#include "pipeline/short_seminar_room.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using pipeline::testing::ExamplePath;
using pipeline::testing::ShortExample;

// A scenario run once, with its summaries and report.
struct Tiny {
  Scenario scenario;
  pipeline::ExperimentResult result;
  std::vector<pipeline::VariantSummary> summaries;
  json report;
};

Tiny RunTiny(Scenario scenario) {
  Tiny t;
  t.scenario = std::move(scenario);
  t.result = pipeline::RunExperiment(t.scenario.variants);
  t.summaries = pipeline::Summarize(t.scenario.variants, t.result);
  t.report = MakeJsonReport(t.scenario, t.result, t.summaries);
  return t;
}

// The tiny scenario of each case, run once for all tests of this file (well under a second each):
// mint, slam: the seminar-room examples, the first metre of each trajectory; coop: the coop room's
// first two grid variants for 3 steps; range_ekf: the 3-D RTLS room, the first metre; recorded:
// the example recording (with truth), and the same ranges without truth.
const Tiny& Case(const std::string& name) {
  static std::map<std::string, Tiny> cache;
  if (const auto it = cache.find(name); it != cache.end()) return it->second;
  Scenario s;
  if (name == "mint") {
    s = ShortExample("seminar_room.yaml", 1, 1.0);
  } else if (name == "slam") {
    s = ShortExample("seminar_room_slam.yaml", 1, 1.0);
  } else if (name == "coop") {
    ScenarioOverrides overrides;
    overrides.runs = 1;
    s = LoadScenario(ExamplePath("coop_room.yaml"), overrides);
    s.variants.erase(s.variants.begin() + 2, s.variants.end());
    for (auto& v : s.variants) v.experiment.steps = 3;
  } else if (name == "range_ekf") {
    s = ShortExample("rtls_room_3d.yaml", 1, 1.0);
  } else if (name == "recorded") {
    s = LoadScenario(ExamplePath("recorded/scenario.yaml"));
  } else if (name == "recorded_without_truth") {
    const std::string dir = ExamplePath("recorded/");
    const fs::path path = fs::temp_directory_path() / ("mirage_report_test_" + std::to_string(::getpid()) + "_no_truth.yaml");
    std::ofstream(path) << "name: no_truth\n"
                        << "measurements: {model: recorded, anchors: " << dir << "anchors.csv, ranges: " << dir
                        << "ranges.csv, start_m: [0.98, 1.38]}\n"
                        << "method: {name: mint}\n";
    s = LoadScenario(path.string());
    fs::remove(path);
  } else {
    throw std::invalid_argument("no case " + name);
  }
  return cache.emplace(name, RunTiny(std::move(s))).first->second;
}

std::vector<std::string> ReadLines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> Split(const std::string& row) {
  std::vector<std::string> fields;
  std::stringstream in(row);
  for (std::string cell; std::getline(in, cell, ',');) fields.push_back(cell);
  if (!row.empty() && row.back() == ',') fields.emplace_back();
  return fields;
}

// A fresh directory under the system temp directory, removed at the end of the test.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(fs::temp_directory_path() / ("mirage_report_test_" + std::to_string(::getpid()) + "_" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The CSV files of a case, written once into a directory that lives as long as the test binary.
const fs::path& CsvOf(const std::string& name) {
  static std::map<std::string, fs::path> dirs;
  if (const auto it = dirs.find(name); it != dirs.end()) return it->second;
  static const TempDir root("csv");
  const fs::path dir = root.path() / name;
  const Tiny& t = Case(name);
  WriteCsv(dir.string(), t.scenario, t.result, t.summaries);
  return dirs.emplace(name, dir).first->second;
}

// ---------------------------------------------------------------------------------------------
// The report's contract: every key with its type, for every method
// ---------------------------------------------------------------------------------------------

enum class Type { kString, kInteger, kNumber, kBoolean, kObject, kArray };

const char* Name(Type type) {
  switch (type) {
    case Type::kString: return "a string";
    case Type::kInteger: return "an integer";
    case Type::kNumber: return "a number";
    case Type::kBoolean: return "a boolean";
    case Type::kObject: return "an object";
    case Type::kArray: return "an array";
  }
  return "?";
}

bool Is(const json& j, Type type) {
  switch (type) {
    case Type::kString: return j.is_string();
    case Type::kInteger: return j.is_number_integer();
    case Type::kNumber: return j.is_number();
    case Type::kBoolean: return j.is_boolean();
    case Type::kObject: return j.is_object();
    case Type::kArray: return j.is_array();
  }
  return false;
}

// Expects j[key] to exist and be of `type` (or null when `nullable`); false when it is missing.
bool ExpectKey(const json& j, const std::string& where, const std::string& key, Type type, bool nullable = false) {
  if (!j.is_object()) {
    ADD_FAILURE() << where << " is not an object: " << j.dump();
    return false;
  }
  if (!j.contains(key)) {
    ADD_FAILURE() << "missing key " << where << "." << key;
    return false;
  }
  const json& v = j.at(key);
  if (nullable && v.is_null()) return true;
  EXPECT_TRUE(Is(v, type)) << where << "." << key << " is not " << Name(type) << (nullable ? " or null" : "") << ": "
                           << v.dump();
  return Is(v, type);
}

// The keys every group, variant and the top level carry (ROADMAP.md "Interfaces").
void ExpectGroupKeys(const json& g, const std::string& where, bool truth) {
  ExpectKey(g, where, "runs", Type::kInteger);
  ExpectKey(g, where, "steps", Type::kInteger);
  ExpectKey(g, where, "position_error_m", Type::kObject, !truth);
  if (truth) {
    ASSERT_FALSE(g.at("position_error_m").is_null()) << where;
    for (const char* key : {"rmse", "mean", "p50", "p90", "p95", "max"}) {
      ExpectKey(g.at("position_error_m"), where + ".position_error_m", key, Type::kNumber);
    }
    ExpectKey(g, where, "diverged_runs", Type::kInteger);
  } else {
    ExpectKey(g, where, "diverged_runs", Type::kInteger, /*nullable=*/true);
    EXPECT_TRUE(g.at("position_error_m").is_null()) << where;
    EXPECT_TRUE(g.value("diverged_runs", json(0)).is_null()) << where;
  }
  ExpectKey(g, where, "peb_m", Type::kObject, true);
  if (g.at("peb_m").is_object()) {
    for (const char* key : {"mean", "p50", "rms"}) ExpectKey(g.at("peb_m"), where + ".peb_m", key, Type::kNumber);
    ExpectKey(g.at("peb_m"), where + ".peb_m", "kind", Type::kString);
  }
  ExpectKey(g, where, "health", Type::kObject);
  ExpectKey(g.at("health"), where + ".health", "drifted_runs", Type::kInteger);
}

// The whole contract of a report of method `method`; `block` lists the keys of the method's
// block beyond its options.
void ExpectReportContract(const Tiny& t, const std::string& method, const std::vector<std::string>& block, bool truth = true) {
  const json& j = t.report;
  ExpectKey(j, "report", "scenario", Type::kString);
  EXPECT_EQ(j.at("scenario"), t.scenario.variants.front().experiment.name);
  ExpectKey(j, "report", "method", Type::kString);
  EXPECT_EQ(j.at("method"), method);
  ExpectKey(j, "report", "runs_per_trajectory", Type::kInteger);
  ExpectKey(j, "report", "seed", Type::kInteger);
  ExpectGroupKeys(j, "report", truth);
  EXPECT_GT(j.at("steps").get<int>(), 0);
  ExpectKey(j, "report", "timing", Type::kObject);
  for (const char* key : {"wall_s", "steps_per_s", "us_per_step"}) ExpectKey(j.at("timing"), "timing", key, Type::kNumber);
  ExpectKey(j, "report", "health", Type::kObject);
  ExpectKey(j.at("health"), "health", "runs", Type::kArray);
  ASSERT_EQ(j.at("health").at("runs").size(), t.result.runs.size());
  for (const json& run : j.at("health").at("runs")) {
    ExpectKey(run, "health.runs[]", "trajectory", Type::kString);
    ExpectKey(run, "health.runs[]", "run", Type::kInteger);
    ExpectKey(run, "health.runs[]", "steps", Type::kInteger);
    ExpectKey(run, "health.runs[]", "drifted", Type::kBoolean);
    ExpectKey(run, "health.runs[]", "drift_reason", Type::kString);
    ExpectKey(run, "health.runs[]", "covariance_growth", Type::kNumber);
  }
  ExpectKey(j, "report", "groups", Type::kArray);
  ASSERT_FALSE(j.at("groups").empty());
  for (const json& g : j.at("groups")) {
    ExpectKey(g, "groups[]", "name", Type::kString);
    ExpectGroupKeys(g, "groups[]", truth);
  }
  if (ExpectKey(j, "report", method, Type::kObject)) {
    if (ExpectKey(j.at(method), method, "options", Type::kObject)) {
      EXPECT_FALSE(j.at(method).at("options").empty());
    }
    for (const auto& key : block) ExpectKey(j.at(method), method, key, Type::kObject);
  }
  if (t.scenario.has_grid()) {
    ExpectKey(j, "report", "variants", Type::kArray);
    ASSERT_EQ(j.at("variants").size(), t.scenario.variants.size());
    for (const json& v : j.at("variants")) {
      ExpectKey(v, "variants[]", "name", Type::kString);
      ExpectKey(v, "variants[]", "overrides", Type::kObject);
      ExpectGroupKeys(v, "variants[]", truth);
      if (ExpectKey(v, "variants[]", method, Type::kObject)) {
        ExpectKey(v.at(method), "variants[]." + method, "options", Type::kObject);
      }
    }
  } else {
    EXPECT_FALSE(j.contains("variants"));
  }
  if (t.scenario.recording_files) {
    ExpectKey(j, "report", "recorded_data", Type::kObject);
    ExpectKey(j.at("recorded_data"), "recorded_data", "anchors", Type::kString);
    ExpectKey(j.at("recorded_data"), "recorded_data", "ranges", Type::kString);
    ExpectKey(j.at("recorded_data"), "recorded_data", "truth", Type::kString, !truth);
    ExpectKey(j.at("recorded_data"), "recorded_data", "epochs", Type::kInteger);
  } else {
    EXPECT_FALSE(j.contains("recorded_data"));
  }
}

TEST(JsonReportContract, MintHasEveryKeyOfTheRoadmapAndItsSinrBlock) {
  ExpectReportContract(Case("mint"), "mint", {"sinr_db"});
  EXPECT_TRUE(Case("mint").report.at("peb_m").is_object());  // the channel's snapshot PEB
  EXPECT_EQ(Case("mint").report.at("peb_m").at("kind"), "snapshot");
}

TEST(JsonReportContract, SlamHasEveryKeyOfTheRoadmapAndItsMapBlock) {
  ExpectReportContract(Case("slam"), "slam", {"map"});
  ExpectKey(Case("slam").report.at("slam").at("map"), "slam.map", "ospa_m", Type::kObject);
}

TEST(JsonReportContract, CoopHasEveryKeyOfTheRoadmapItsFloorPlanBlockAndItsVariants) {
  const Tiny& t = Case("coop");
  ASSERT_TRUE(t.scenario.has_grid());
  ExpectReportContract(t, "coop", {"floor_plan"});
  EXPECT_EQ(t.report.at("peb_m").at("kind"), "posterior");
  EXPECT_EQ(t.report.at("variants").at(1).at("overrides").at("method.anchor_links"), "true");
}

TEST(JsonReportContract, RangeEkfHasEveryKeyOfTheRoadmap) {
  ExpectReportContract(Case("range_ekf"), "range_ekf", {});
  EXPECT_EQ(Case("range_ekf").report.at("range_ekf").at("options").at("mode"), "3d");
}

TEST(JsonReportContract, ARecordingHasItsFilesAndEpochs) {
  const Tiny& t = Case("recorded");
  ExpectReportContract(t, "mint", {});
  EXPECT_EQ(t.report.at("recorded_data").at("epochs").get<std::size_t>(), t.scenario.variants.front().experiment.recording->steps.size());
  EXPECT_EQ(t.report.at("recorded_data").at("ranges"), ExamplePath("recorded/ranges.csv"));
  EXPECT_TRUE(t.report.at("peb_m").is_null());  // no simulated channel, no bound
}

TEST(JsonReportContract, ARecordingWithoutTruthHasNullsWhereTheErrorWouldBe) {
  const Tiny& t = Case("recorded_without_truth");
  ExpectReportContract(t, "mint", {}, /*truth=*/false);
  EXPECT_TRUE(t.report.at("recorded_data").at("truth").is_null());
}

// ---------------------------------------------------------------------------------------------
// The values
// ---------------------------------------------------------------------------------------------

TEST(JsonReport, CarriesTheSummaryValues) {
  // Arrange
  const Tiny& t = Case("mint");
  const auto& overall = t.summaries.front().overall;
  const auto& e = overall.error;

  // Act
  const json& j = t.report;

  // Assert
  const json& err = j.at("position_error_m");
  EXPECT_DOUBLE_EQ(err.at("rmse").get<double>(), e.rmse);
  EXPECT_DOUBLE_EQ(err.at("p90").get<double>(), e.p90);
  EXPECT_DOUBLE_EQ(err.at("max").get<double>(), e.max);
  EXPECT_LE(err.at("p50").get<double>(), err.at("p90").get<double>());
  EXPECT_LE(err.at("p90").get<double>(), err.at("p95").get<double>());
  EXPECT_LE(err.at("p95").get<double>(), err.at("max").get<double>());
  EXPECT_LE(err.at("mean").get<double>(), err.at("rmse").get<double>() + 1e-15);
  EXPECT_EQ(j.at("diverged_runs"), overall.diverged_runs);
  EXPECT_EQ(j.at("runs"), 2);  // 1 run of each trajectory
  EXPECT_EQ(j.at("runs_per_trajectory"), 1);
  EXPECT_EQ(j.at("steps"), overall.steps);
  // The seminar room always has a PEB (two anchors and their reflections).
  ASSERT_TRUE(overall.bound_mean_m.has_value());
  EXPECT_DOUBLE_EQ(j.at("peb_m").at("mean").get<double>(), *overall.bound_mean_m);
  EXPECT_DOUBLE_EQ(j.at("peb_m").at("p50").get<double>(), *overall.bound_p50_m);
  EXPECT_DOUBLE_EQ(j.at("peb_m").at("rms").get<double>(), *overall.bound_rms_m);
  const double steps = overall.steps;
  EXPECT_DOUBLE_EQ(j.at("timing").at("wall_s").get<double>(), t.result.wall_s);
  EXPECT_NEAR(j.at("timing").at("steps_per_s").get<double>(), steps / t.result.wall_s, 1e-9 * steps / t.result.wall_s);
  EXPECT_NEAR(j.at("timing").at("us_per_step").get<double>(), 1e6 * t.result.wall_s / steps, 1e-9);
  EXPECT_EQ(j.at("seed"), t.scenario.variants.front().experiment.seed);
  EXPECT_EQ(j.at("scenario_file"), ExamplePath("seminar_room.yaml"));
}

TEST(JsonReport, HasSinrStatisticsInTheMethodsBlockAndOneGroupPerTrajectory) {
  // Arrange
  const Tiny& t = Case("mint");
  const auto& trajectories = t.scenario.variants.front().experiment.trajectories;

  // Act
  const json& j = t.report;

  // Assert
  const json& sinr = j.at("mint").at("sinr_db");
  ASSERT_TRUE(sinr.contains("true"));
  ASSERT_TRUE(sinr.contains("estimated"));
  ASSERT_TRUE(sinr.at("true").contains("los"));
  for (const char* key : {"count", "mean", "p10", "p50", "p90"}) ExpectKey(sinr.at("true").at("los"), "sinr_db.true.los", key, Type::kNumber);
  EXPECT_GT(sinr.at("true").at("los").at("count").get<int>(), 0);
  ASSERT_EQ(j.at("groups").size(), 2u);
  int steps = 0;
  for (std::size_t i = 0; i < 2; ++i) {
    const json& g = j.at("groups").at(i);
    EXPECT_EQ(g.at("name"), trajectories[i].name);
    EXPECT_EQ(g.at("runs"), 1);
    steps += g.at("steps").get<int>();
  }
  EXPECT_EQ(steps, j.at("steps").get<int>());
}

TEST(JsonReport, RecordsTheEffectiveMethodOptions) {
  const json& options = Case("mint").report.at("mint").at("options");

  EXPECT_DOUBLE_EQ(options.at("cutoff_m").get<double>(), 0.15);
  EXPECT_EQ(options.at("relocalization").at("lost_steps"), 3);
  EXPECT_TRUE(options.at("variance").at("enabled").get<bool>());
}

TEST(JsonReport, SummarisesAGridOverAllVariantsAtTheTopAndPerVariantBelow) {
  const Tiny& t = Case("coop");
  const json& j = t.report;

  ASSERT_EQ(j.at("variants").size(), 2u);
  int steps = 0;
  for (std::size_t v = 0; v < 2; ++v) {
    EXPECT_EQ(j.at("variants").at(v).at("name"), t.scenario.variants[v].name);
    EXPECT_EQ(j.at("variants").at(v).at("steps"), t.summaries[v].overall.steps);
    EXPECT_EQ(j.at("variants").at(v).at("coop").at("options").at("anchor_links"), v == 1);
    steps += j.at("variants").at(v).at("steps").get<int>();
  }
  EXPECT_EQ(j.at("steps"), steps);  // the top level pools every variant's runs
  EXPECT_EQ(steps, 2 * 2 * 3);   // variants x agents x steps
  for (const json& run : j.at("health").at("runs")) ExpectKey(run, "health.runs[]", "variant", Type::kString);
}

TEST(JsonReport, WritesAFileThatParsesBackToTheSameReport) {
  // Arrange
  const Tiny& t = Case("mint");
  const TempDir dir("json");
  const fs::path path = dir.path() / "sub" / "report.json";

  // Act: the parent directory is created.
  WriteJson(path.string(), t.report);

  // Assert
  std::ifstream in(path);
  ASSERT_TRUE(in.good());
  EXPECT_EQ(json::parse(in), t.report);
}

TEST(JsonReport, ThrowsAnInputErrorNamingThePathWhenItCannotWrite) {
  // Arrange: a regular file where a directory would have to be.
  const TempDir dir("json_bad");
  const fs::path blocker = dir.path() / "file";
  std::ofstream(blocker) << "x";
  const std::string path = (blocker / "report.json").string();

  // Act / Assert
  try {
    WriteJson(path, json::object());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// CSV files
// ---------------------------------------------------------------------------------------------

const char* const kTracksHeader =
    "trajectory,run,step,t_s,x_true_m,y_true_m,x_est_m,y_est_m,error_m,sigma_x_m,sigma_y_m,peb_m,associations,relocalized";
const char* const kRunsHeader = "trajectory,run,offset_x_m,offset_y_m,steps,rmse_m,p90_m,diverged";

TEST(CsvFiles, HaveTheDocumentedHeadersAndOneRowPerStepAndRun) {
  // Arrange
  const Tiny& t = Case("mint");

  // Act
  const auto tracks = ReadLines(CsvOf("mint") / "tracks.csv");
  const auto runs = ReadLines(CsvOf("mint") / "runs.csv");

  // Assert
  ASSERT_FALSE(tracks.empty());
  ASSERT_FALSE(runs.empty());
  EXPECT_EQ(tracks[0], kTracksHeader);
  EXPECT_EQ(runs[0], kRunsHeader);
  EXPECT_EQ(static_cast<int>(tracks.size()) - 1, t.summaries.front().overall.steps);
  EXPECT_EQ(runs.size() - 1, t.result.runs.size());
  // Rows are named by trajectory; the first track row is trajectory 1, run 0, step 0.
  const auto& trajectories = t.scenario.variants.front().experiment.trajectories;
  EXPECT_EQ(tracks[1].rfind(trajectories[0].name + ",0,0,", 0), 0u) << tracks[1];
  EXPECT_EQ(runs[2].rfind(trajectories[1].name + ",0,", 0), 0u) << runs[2];
  for (std::size_t i = 1; i < tracks.size(); ++i) ASSERT_EQ(Split(tracks[i]).size(), 14u) << tracks[i];
}

TEST(CsvFiles, LeadEveryRowWithTheVariantIndexForAGridAndAddTheVariantTables) {
  const Tiny& t = Case("coop");
  const fs::path& dir = CsvOf("coop");

  const auto tracks = ReadLines(dir / "tracks.csv");
  const auto runs = ReadLines(dir / "runs.csv");
  const auto variants = ReadLines(dir / "variants.csv");
  const auto by_step = ReadLines(dir / "error_by_step.csv");

  ASSERT_FALSE(tracks.empty());
  EXPECT_EQ(tracks[0], std::string("variant,") + kTracksHeader);
  EXPECT_EQ(runs[0], std::string("variant,") + kRunsHeader);
  EXPECT_EQ(tracks.size() - 1, 2u * 2u * 3u);  // variants x agents x steps
  EXPECT_EQ(runs.size() - 1, 2u * 2u);         // variants x agents (one run each)
  EXPECT_EQ(tracks[1].rfind("0,agent_1,0,0,", 0), 0u) << tracks[1];
  EXPECT_EQ(tracks.back().rfind("1,agent_2,0,2,", 0), 0u) << tracks.back();
  ASSERT_EQ(variants.size(), 3u);
  EXPECT_EQ(variants[0].rfind("variant,name,runs,", 0), 0u) << variants[0];
  EXPECT_EQ(variants[2].rfind("1,\"" + t.scenario.variants[1].name + "\",1,", 0), 0u) << variants[2];
  EXPECT_EQ(by_step[0], "variant,step,mean_error_m,peb_m");
  EXPECT_EQ(by_step.size() - 1, 2u * 3u);  // variants x steps
}

TEST(CsvFiles, HaveNoVariantTablesWithoutAGrid) {
  EXPECT_FALSE(fs::exists(CsvOf("mint") / "variants.csv"));
  EXPECT_FALSE(fs::exists(CsvOf("mint") / "error_by_step.csv"));
}

TEST(CsvFiles, AddTheHeightColumnsForThreeDimensionalEstimates) {
  const auto tracks = ReadLines(CsvOf("range_ekf") / "tracks.csv");
  const auto planar = ReadLines(CsvOf("mint") / "tracks.csv");

  ASSERT_GT(tracks.size(), 1u);
  EXPECT_EQ(tracks[0], std::string(kTracksHeader) + ",z_true_m,z_est_m,sigma_z_m");
  const auto row = Split(tracks[1]);
  ASSERT_EQ(row.size(), 17u);
  EXPECT_NEAR(std::stod(row[14]), 0.6, 1e-9);  // the tag's height
  EXPECT_GT(std::stod(row[16]), 0.0);          // the estimate's own z variance
  EXPECT_EQ(planar[0].find("z_est_m"), std::string::npos);  // planar methods have none
}

TEST(CsvFiles, LeaveTheTruthColumnsEmptyWithoutTruth) {
  const auto tracks = ReadLines(CsvOf("recorded_without_truth") / "tracks.csv");
  const auto runs = ReadLines(CsvOf("recorded_without_truth") / "runs.csv");

  ASSERT_GT(tracks.size(), 1u);
  const auto row = Split(tracks[1]);
  EXPECT_EQ(row[0], "recorded");
  EXPECT_EQ(row[4], "");  // x_true_m
  EXPECT_EQ(row[8], "");  // error_m
  EXPECT_NE(row[6], "");  // x_est_m
  const auto run = Split(runs[1]);
  EXPECT_EQ(run[5], "");  // rmse_m
  EXPECT_EQ(run[7], "");  // diverged
}

TEST(CsvFiles, WriteOnePathRowPerVisiblePathOfTheFirstRuns) {
  // Arrange
  const Tiny& t = Case("mint");

  // Act
  const auto paths = ReadLines(CsvOf("mint") / "paths.csv");

  // Assert: the header, and as many rows as run 0 of all trajectories recorded paths; a LOS row
  // has order 0, range = c * delay, and |amplitude| = 1 m / range (free space).
  ASSERT_GT(paths.size(), 1u);
  EXPECT_EQ(paths[0],
            "trajectory,run,step,anchor_id,va_id,order,delay_s,range_m,amplitude_re,amplitude_im,true_sinr_db,"
            "estimated_sinr_db");
  std::size_t expected_rows = 0;
  for (const auto& run : t.result.runs) {
    if (run.run == 0) expected_rows += run.paths.size();
  }
  EXPECT_EQ(paths.size() - 1, expected_rows);
  bool found_los = false;
  for (std::size_t i = 1; i < paths.size() && !found_los; ++i) {
    const auto f = Split(paths[i]);
    if (f.size() < 11 || f[5] != "0") continue;
    found_los = true;
    const double delay_s = std::stod(f[6]), range_m = std::stod(f[7]);
    const double magnitude = std::hypot(std::stod(f[8]), std::stod(f[9]));
    EXPECT_NEAR(range_m, delay_s * 299792458.0, 1e-4);
    EXPECT_NEAR(magnitude * range_m, 1.0, 1e-4);
  }
  EXPECT_TRUE(found_los);
}

TEST(CsvFiles, WriteTheMapOfAMethodThatBuildsOne) {
  const Tiny& t = Case("slam");

  const auto map = ReadLines(CsvOf("slam") / "map.csv");

  ASSERT_GT(map.size(), 1u);
  EXPECT_EQ(map[0].rfind("trajectory,run,va_id,anchor_id,origin,x_m,y_m,cov_xx_m2,cov_xy_m2,cov_yy_m2", 0), 0u) << map[0];
  std::size_t features = 0;
  for (const auto& run : t.result.runs) features += run.map.size();
  EXPECT_EQ(map.size() - 1, features);
  EXPECT_FALSE(fs::exists(CsvOf("range_ekf") / "map.csv"));
}

// ---------------------------------------------------------------------------------------------
// The result table
// ---------------------------------------------------------------------------------------------

TEST(ResultTable, ListsEveryTrajectoryAndTheOverallRow) {
  // Arrange
  const Tiny& t = Case("mint");

  // Act
  const std::string table = FormatResultTable(t.scenario, t.result, t.summaries);

  // Assert
  EXPECT_NE(table.find("seminar_room"), std::string::npos) << table;
  for (const auto& trajectory : t.scenario.variants.front().experiment.trajectories) {
    EXPECT_NE(table.find(trajectory.name), std::string::npos) << table;
  }
  EXPECT_NE(table.find("\nall "), std::string::npos) << table;
  EXPECT_NE(table.find("p90_m"), std::string::npos) << table;
  EXPECT_NE(table.find("timing:"), std::string::npos) << table;
}

TEST(ResultTable, ListsEveryVariantOfAGrid) {
  const Tiny& t = Case("coop");

  const std::string table = FormatResultTable(t.scenario, t.result, t.summaries);

  EXPECT_NE(table.find("method coop"), std::string::npos) << table;
  EXPECT_NE(table.find("runs per variant"), std::string::npos) << table;
  for (const auto& v : t.scenario.variants) {
    const std::string label = v.name.size() > 28 ? v.name.substr(0, 25) : v.name;
    EXPECT_NE(table.find(label), std::string::npos) << label << " not in\n" << table;
  }
}

TEST(ResultTable, SaysWhenARecordingHasNoTruth) {
  const Tiny& t = Case("recorded_without_truth");

  const std::string table = FormatResultTable(t.scenario, t.result, t.summaries);

  EXPECT_NE(table.find("no truth file, so no position error"), std::string::npos) << table;
}

}  // namespace
}  // namespace mirage::io
