// SPDX-License-Identifier: MIT
// Outputs of `mirage run`: the JSON report (every key ROADMAP.md promises, plus sinr_db and the
// per-trajectory blocks), the CSV files and the result table, computed on a tiny seminar-room
// experiment (1 run per trajectory, first 1.5 m of each).
#include "mirage/io/report.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
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

// One tiny experiment shared by all tests of this file (a few tens of milliseconds).
struct Tiny {
  Scenario scenario;
  pipeline::MintExperimentResult result;
  pipeline::MintSummary summary;
};

const Tiny& TinyExperiment() {
  static const Tiny tiny = [] {
    Tiny t;
    t.scenario = pipeline::testing::ShortSeminarRoom(1, 1.5);
    t.result = pipeline::RunMintExperiment(t.scenario.mint);
    t.summary = pipeline::Summarize(t.scenario.mint, t.result);
    return t;
  }();
  return tiny;
}

void ExpectNumber(const json& j, const std::string& key) {
  ASSERT_TRUE(j.contains(key)) << "missing key " << key << " in " << j.dump();
  EXPECT_TRUE(j[key].is_number()) << key << " is " << j[key].dump();
}

std::vector<std::string> ReadLines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
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

TEST(JsonReport, HasEveryKeyOfTheRoadmap) {
  // Arrange
  const Tiny& t = TinyExperiment();

  // Act
  const json j = MakeJsonReport(t.scenario, t.result, t.summary);

  // Assert: { scenario, method, runs, steps, position_error_m{...}, diverged_runs, peb_m, timing{...} }
  ASSERT_TRUE(j.contains("scenario"));
  EXPECT_EQ(j["scenario"], "seminar_room");
  ASSERT_TRUE(j.contains("method"));
  EXPECT_EQ(j["method"], "mint");
  ASSERT_TRUE(j.contains("runs"));
  EXPECT_TRUE(j["runs"].is_number_integer());
  EXPECT_EQ(j["runs"], 2);
  ASSERT_TRUE(j.contains("steps"));
  EXPECT_TRUE(j["steps"].is_number_integer());
  EXPECT_EQ(j["steps"], t.summary.overall.steps);
  ASSERT_TRUE(j.contains("position_error_m"));
  for (const char* key : {"rmse", "mean", "p50", "p90", "p95", "max"}) ExpectNumber(j["position_error_m"], key);
  ASSERT_TRUE(j.contains("diverged_runs"));
  EXPECT_TRUE(j["diverged_runs"].is_number_integer());
  ASSERT_TRUE(j.contains("peb_m"));
  if (!j["peb_m"].is_null()) {
    ExpectNumber(j["peb_m"], "mean");
    ExpectNumber(j["peb_m"], "p50");
  }
  ASSERT_TRUE(j.contains("timing"));
  for (const char* key : {"wall_s", "steps_per_s", "us_per_step"}) ExpectNumber(j["timing"], key);
}

TEST(JsonReport, CarriesTheSummaryValues) {
  // Arrange
  const Tiny& t = TinyExperiment();
  const auto& e = t.summary.overall.error;

  // Act
  const json j = MakeJsonReport(t.scenario, t.result, t.summary);

  // Assert
  const json& err = j["position_error_m"];
  EXPECT_DOUBLE_EQ(err["rmse"].get<double>(), e.rmse);
  EXPECT_DOUBLE_EQ(err["p90"].get<double>(), e.p90);
  EXPECT_DOUBLE_EQ(err["max"].get<double>(), e.max);
  EXPECT_LE(err["p50"].get<double>(), err["p90"].get<double>());
  EXPECT_LE(err["p90"].get<double>(), err["p95"].get<double>());
  EXPECT_LE(err["p95"].get<double>(), err["max"].get<double>());
  EXPECT_LE(err["mean"].get<double>(), err["rmse"].get<double>() + 1e-15);
  EXPECT_EQ(j["diverged_runs"], t.summary.overall.diverged_runs);
  // The seminar room always has a PEB (two anchors and their reflections).
  ASSERT_TRUE(t.summary.overall.peb_mean_m.has_value());
  EXPECT_DOUBLE_EQ(j["peb_m"]["mean"].get<double>(), *t.summary.overall.peb_mean_m);
  EXPECT_DOUBLE_EQ(j["peb_m"]["p50"].get<double>(), *t.summary.overall.peb_p50_m);
  const double steps = t.summary.overall.steps;
  EXPECT_DOUBLE_EQ(j["timing"]["wall_s"].get<double>(), t.summary.wall_s);
  EXPECT_NEAR(j["timing"]["steps_per_s"].get<double>(), steps / t.summary.wall_s, 1e-9 * steps / t.summary.wall_s);
  EXPECT_NEAR(j["timing"]["us_per_step"].get<double>(), 1e6 * t.summary.wall_s / steps, 1e-9);
  EXPECT_EQ(j["seed"], t.scenario.mint.seed);
}

TEST(JsonReport, HasSinrStatisticsAndOneBlockPerTrajectory) {
  // Arrange
  const Tiny& t = TinyExperiment();

  // Act
  const json j = MakeJsonReport(t.scenario, t.result, t.summary);

  // Assert
  ASSERT_TRUE(j.contains("sinr_db"));
  ASSERT_TRUE(j["sinr_db"].contains("true"));
  ASSERT_TRUE(j["sinr_db"].contains("estimated"));
  ASSERT_TRUE(j["sinr_db"]["true"].contains("los"));
  for (const char* key : {"count", "mean", "p10", "p50", "p90"}) ExpectNumber(j["sinr_db"]["true"]["los"], key);
  EXPECT_GT(j["sinr_db"]["true"]["los"]["count"].get<int>(), 0);
  ASSERT_TRUE(j.contains("trajectories"));
  ASSERT_TRUE(j["trajectories"].is_array());
  ASSERT_EQ(j["trajectories"].size(), 2u);
  int steps = 0;
  for (std::size_t i = 0; i < 2; ++i) {
    const json& g = j["trajectories"][i];
    EXPECT_EQ(g["name"], t.scenario.mint.trajectories[i].name);
    EXPECT_EQ(g["runs"], 1);
    for (const char* key : {"rmse", "mean", "p50", "p90", "p95", "max"}) ExpectNumber(g["position_error_m"], key);
    ASSERT_TRUE(g.contains("diverged_runs"));
    ASSERT_TRUE(g.contains("peb_m"));
    steps += g["steps"].get<int>();
  }
  EXPECT_EQ(steps, j["steps"].get<int>());
}

TEST(JsonReport, WritesAFileThatParsesBackToTheSameReport) {
  // Arrange
  const Tiny& t = TinyExperiment();
  const TempDir dir("json");
  const json j = MakeJsonReport(t.scenario, t.result, t.summary);
  const fs::path path = dir.path() / "sub" / "report.json";

  // Act: the parent directory is created.
  WriteJson(path.string(), j);

  // Assert
  std::ifstream in(path);
  ASSERT_TRUE(in.good());
  EXPECT_EQ(json::parse(in), j);
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

TEST(CsvFiles, HaveTheDocumentedHeadersAndOneRowPerStepRunAndVa) {
  // Arrange
  const Tiny& t = TinyExperiment();
  const TempDir dir("csv");
  const fs::path out = dir.path() / "csv";

  // Act
  WriteCsv(out.string(), t.scenario, t.result);

  // Assert
  const auto tracks = ReadLines(out / "tracks.csv");
  const auto runs = ReadLines(out / "runs.csv");
  const auto vas = ReadLines(out / "virtual_anchors.csv");
  ASSERT_FALSE(tracks.empty());
  ASSERT_FALSE(runs.empty());
  ASSERT_FALSE(vas.empty());
  EXPECT_EQ(tracks[0],
            "trajectory,run,step,t_s,x_true_m,y_true_m,x_est_m,y_est_m,error_m,sigma_x_m,sigma_y_m,peb_m,associations,"
            "relocalized");
  EXPECT_EQ(runs[0], "trajectory,run,offset_x_m,offset_y_m,steps,rmse_m,p90_m,diverged");
  EXPECT_EQ(vas[0], "va_id,anchor_id,order,x_m,y_m,walls,reflection_gain");
  EXPECT_EQ(static_cast<int>(tracks.size()) - 1, t.summary.overall.steps);
  EXPECT_EQ(runs.size() - 1, t.result.runs.size());
  EXPECT_EQ(static_cast<int>(vas.size()) - 1, t.result.known_vas.size());
  // Rows are named by trajectory and anchor id; the first track row is trajectory 1, step 0.
  EXPECT_EQ(tracks[1].rfind(t.scenario.mint.trajectories[0].name + ",0,0,", 0), 0u) << tracks[1];
  EXPECT_EQ(vas[1].rfind("0,A1,0,", 0), 0u) << vas[1];
  EXPECT_EQ(runs[2].rfind(t.scenario.mint.trajectories[1].name + ",0,", 0), 0u) << runs[2];
}

TEST(CsvFiles, WriteOnePathRowPerVisiblePathOfTheFirstRuns) {
  // Arrange
  const Tiny& t = TinyExperiment();
  const TempDir dir("paths");
  const fs::path out = dir.path() / "csv";

  // Act
  WriteCsv(out.string(), t.scenario, t.result);

  // Assert: the header, and as many rows as run 0 of all trajectories recorded paths; a LOS row
  // has order 0, range = c * delay, and |amplitude| = 1 m / range (free space).
  const auto paths = ReadLines(out / "paths.csv");
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
    std::vector<std::string> f;
    std::stringstream row(paths[i]);
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(cell);
    if (f.size() < 11 || f[5] != "0") continue;
    found_los = true;
    const double delay_s = std::stod(f[6]), range_m = std::stod(f[7]);
    const double magnitude = std::hypot(std::stod(f[8]), std::stod(f[9]));
    EXPECT_NEAR(range_m, delay_s * 299792458.0, 1e-4);
    EXPECT_NEAR(magnitude * range_m, 1.0, 1e-4);
  }
  EXPECT_TRUE(found_los);
}

TEST(ResultTable, ListsEveryTrajectoryAndTheOverallRow) {
  // Arrange
  const Tiny& t = TinyExperiment();

  // Act
  const std::string table = FormatResultTable(t.scenario, t.summary);

  // Assert
  EXPECT_NE(table.find("seminar_room"), std::string::npos) << table;
  for (const auto& trajectory : t.scenario.mint.trajectories) {
    EXPECT_NE(table.find(trajectory.name), std::string::npos) << table;
  }
  EXPECT_NE(table.find("\nall "), std::string::npos) << table;
  EXPECT_NE(table.find("p90_m"), std::string::npos) << table;
  EXPECT_NE(table.find("timing:"), std::string::npos) << table;
}

}  // namespace
}  // namespace mirage::io
