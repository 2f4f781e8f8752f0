// SPDX-License-Identifier: MIT
// Rigid alignment of recorded data (Bordoy 2020 Sec. 3.3, Eq. 3.49-3.52): the acoustic recording of
// examples/recorded_acoustic/ with its truth moved into another frame (a motion-capture system's:
// rotated 30 degrees about the vertical and shifted by (5, -2) m). With `evaluation.align: rigid`
// the run starts itself (the truth's frame is not the microphones'), its estimates are aligned
// to the truth, the alignment found is the frame change, and the errors are those of the
// recording in its own frame (p50 0.019 m); without the alignment they are metres.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "mirage/io/scenario.h"
#include "mirage/pipeline/runner.h"
#include "mirage/pipeline/summary.h"

namespace mirage::pipeline {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(RecordedAlignment, RigidAlignmentUndoesTheTruthsFrame) {
  const fs::path example = fs::path(MIRAGE_SOURCE_DIR) / "examples" / "recorded_acoustic";
  const fs::path dir = fs::temp_directory_path() / ("mirage_alignment_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  fs::copy_file(example / "mics.csv", dir / "mics.csv", fs::copy_options::overwrite_existing);
  fs::copy_file(example / "toa.csv", dir / "toa.csv", fs::copy_options::overwrite_existing);
  // The truth in the other frame: x' = R x + (5, -2, 0), R 30 degrees about z.
  const double angle = 30.0 * std::numbers::pi / 180.0;
  {
    std::ifstream in(example / "truth.csv");
    std::ofstream out(dir / "truth.csv");
    std::string line;
    std::getline(in, line);
    out << line << "\n";
    while (std::getline(in, line)) {
      double t, x, y, z;
      ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &x, &y, &z), 4);
      out.precision(17);
      out << t << "," << std::cos(angle) * x - std::sin(angle) * y + 5.0 << "," << std::sin(angle) * x + std::cos(angle) * y - 2.0
          << "," << z << "\n";
    }
  }
  std::string scenario = ReadText(example / "scenario.yaml");
  const auto at = scenario.find("evaluation:\n");
  ASSERT_NE(at, std::string::npos);
  std::ofstream(dir / "aligned.yaml") << std::string(scenario).insert(at + 12, "  align: rigid\n");
  std::ofstream(dir / "plain.yaml") << scenario;

  const io::Scenario aligned = io::LoadScenario((dir / "aligned.yaml").string());
  const auto result = RunExperiment(aligned.variants);
  const auto summary = Summarize(aligned.variants, result).front().overall;
  EXPECT_EQ(summary.diverged_runs, 0);
  EXPECT_LT(summary.error.p50, 0.05);  // the recording in its own frame: 0.019 m
  const auto& agent = result.runs.front().agents.front();
  ASSERT_TRUE(agent.alignment.has_value());
  EXPECT_NEAR(agent.alignment->AngleRad(), angle, 0.01);
  EXPECT_GT(result.runs.front().health.epochs_before_start, 0);  // started itself

  const io::Scenario plain = io::LoadScenario((dir / "plain.yaml").string());
  const auto plain_summary = Summarize(plain.variants, RunExperiment(plain.variants)).front().overall;
  EXPECT_GT(plain_summary.error.p50, 1.0);  // the frames differ by metres
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mirage::pipeline
