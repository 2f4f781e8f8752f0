// SPDX-License-Identifier: MIT
// Recorded range data (anchors.csv, ranges.csv, truth.csv): good files parse into steps with
// several unlabeled ranges per anchor, writing and reading back gives the same doubles, and every
// kind of bad input named by issue 4 (missing field, unknown anchor, time going backwards,
// negative or NaN range) and by docs/recorded_data.md throws an InputError naming file and line.
// Recorded acoustic stamps (mics.csv, toa.csv, issue 26 item 9): the same for one step per
// emission with one ToaStamps record per microphone, as the acoustic simulator makes them.
// Recorded pairwise TDOA (anchors.csv with z_m, tdoa.csv, issue 26 item 9): rows of one time form
// one step and one epoch, outliers are kept, and each bad row is named by file, line and column.
#include "mirage/io/recorded_data.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"
#include "mirage/pipeline/recorded_source.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;

const char* const kAnchors = "anchor_id,x_m,y_m\nA1,0.5,7\nA2,5.2,2.3\n";

pipeline::Recording WithAnchors() {
  pipeline::Recording r;
  ParseAnchorsCsv(kAnchors, "anchors.csv", r);
  return r;
}

// The message of the InputError `f` throws (fails the test when it throws nothing).
template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

TEST(RecordedData, ParsesAnchorsWithOptionalHeight) {
  pipeline::Recording r;
  ParseAnchorsCsv("anchor_id,x_m,y_m,z_m\r\nA1, 0.5 ,7,2.1\r\n\r\nB,1e-1,-2,0\r\n", "a.csv", r);
  ASSERT_EQ(r.anchor_ids.size(), 2u);
  EXPECT_EQ(r.anchor_ids[1], "B");
  EXPECT_DOUBLE_EQ(r.anchors_m[0].x(), 0.5);
  EXPECT_DOUBLE_EQ(r.anchors_m[1].x(), 0.1);
  EXPECT_DOUBLE_EQ(r.anchors_m[1].y(), -2.0);
  EXPECT_TRUE(r.anchors_have_z);
  EXPECT_DOUBLE_EQ(r.anchors_m[0].z(), 2.1);
}

TEST(RecordedData, PutsAnchorsWithoutHeightOnTheFloor) {
  const auto r = WithAnchors();
  EXPECT_FALSE(r.anchors_have_z);
  EXPECT_EQ(r.anchors_m[1], Vec3(5.2, 2.3, 0.0));
}

TEST(RecordedData, GroupsRowsByTimeIntoStepsWithSeveralRangesPerAnchor) {
  auto r = WithAnchors();
  // Columns in another order, an amplitude missing in one row, A2 silent at t = 0.1.
  ParseRangesCsv("anchor_id,t_s,range_m,amplitude\n"
                 "A1,0,5.6,0.2\n"
                 "A2,0,3.1,\n"
                 "A1,0,6.2,0.05\n"
                 "A1,0.1,5.65,0.19\n",
                 "ranges.csv", r);
  ASSERT_EQ(r.steps.size(), 2u);
  EXPECT_DOUBLE_EQ(r.steps[0].t_s, 0.0);
  ASSERT_EQ(r.steps[0].anchors.size(), 2u);
  ASSERT_EQ(r.steps[0].anchors[0].ranges.size(), 2u);
  EXPECT_DOUBLE_EQ(r.steps[0].anchors[0].ranges[1].range_m, 6.2);
  ASSERT_TRUE(r.steps[0].anchors[0].ranges[1].amplitude.has_value());
  EXPECT_DOUBLE_EQ(*r.steps[0].anchors[0].ranges[1].amplitude, 0.05);
  EXPECT_EQ(r.steps[0].anchors[1].anchor_index, 1);
  ASSERT_EQ(r.steps[0].anchors[1].ranges.size(), 1u);
  EXPECT_FALSE(r.steps[0].anchors[1].ranges[0].amplitude.has_value());
  EXPECT_TRUE(r.steps[1].anchors[1].ranges.empty());  // a missed detection, not an error
}

TEST(RecordedData, TruthIsInterpolatedBetweenSamples) {
  auto r = WithAnchors();
  ParseTruthCsv("t_s,x_m,y_m\n0,1,1\n1,3,1\n", "truth.csv", r);
  EXPECT_FALSE(r.truth_has_z);
  ASSERT_TRUE(r.TruthAt(0.25).has_value());
  EXPECT_DOUBLE_EQ(r.TruthAt(0.25)->x(), 1.5);
  EXPECT_DOUBLE_EQ(r.TruthAt(0.25)->z(), 0.0);
  EXPECT_DOUBLE_EQ(r.TruthAt(1.0)->x(), 3.0);
  EXPECT_FALSE(r.TruthAt(1.5).has_value());
  EXPECT_FALSE(r.TruthAt(-0.1).has_value());
}

TEST(RecordedData, InterpolatesTheTruthsHeightToo) {
  auto r = WithAnchors();
  ParseTruthCsv("t_s,x_m,y_m,z_m\n0,1,1,0.5\n1,3,1,1.5\n", "truth.csv", r);
  EXPECT_TRUE(r.truth_has_z);
  ASSERT_TRUE(r.TruthAt(0.25).has_value());
  EXPECT_DOUBLE_EQ(r.TruthAt(0.25)->z(), 0.75);
}

struct BadCase {
  const char* name;
  const char* text;
  const char* expect;  // the message must contain this, after "ranges.csv:<line>:"
  int line;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadRanges : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadRanges, NamesFileAndLine) {
  const BadCase& c = GetParam();
  auto r = WithAnchors();
  const std::string message = ErrorOf([&] { ParseRangesCsv(c.text, "ranges.csv", r); });
  EXPECT_NE(message.find("ranges.csv:" + std::to_string(c.line) + ":"), std::string::npos) << message;
  EXPECT_NE(message.find(c.expect), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    RecordedData, BadRanges,
    ::testing::Values(
        BadCase{"missing_field", "t_s,anchor_id,range_m\n0,A1,5.6\n0,A2\n", "expected 3 fields", 3},
        BadCase{"extra_field", "t_s,anchor_id,range_m\n0,A1,5.6,7\n", "expected 3 fields", 2},
        BadCase{"empty_range", "t_s,anchor_id,range_m\n0,A1,\n", "range_m '': missing value", 2},
        BadCase{"unknown_anchor", "t_s,anchor_id,range_m\n0,A1,5.6\n0,A7,5.6\n", "anchor_id 'A7': unknown anchor", 3},
        BadCase{"time_backwards", "t_s,anchor_id,range_m\n0.1,A1,5.6\n0.2,A1,5.6\n0.15,A2,3\n",
                "t_s '0.15': time goes backwards", 4},
        BadCase{"negative_range", "t_s,anchor_id,range_m\n\n0,A1,-0.5\n", "range_m '-0.5': a range must be >= 0", 3},
        BadCase{"nan_range", "t_s,anchor_id,range_m\n0,A1,nan\n", "range_m 'nan': must be finite", 2},
        BadCase{"inf_time", "t_s,anchor_id,range_m\ninf,A1,1\n", "t_s 'inf': must be finite", 2},
        BadCase{"text_range", "t_s,anchor_id,range_m\n0,A1,5.6m\n", "range_m '5.6m': not a number", 2},
        BadCase{"huge_range", "t_s,anchor_id,range_m\n0,A1,1e999\n", "number out of range", 2},
        BadCase{"negative_amplitude", "t_s,anchor_id,range_m,amplitude\n0,A1,5,-1\n", "amplitude '-1'", 2},
        BadCase{"quoted", "t_s,anchor_id,range_m\n0,\"A1\",5\n", "quoted fields are not supported", 2},
        BadCase{"unknown_column", "t_s,anchor_id,range_m,snr_db\n", "unknown column 'snr_db'", 1},
        BadCase{"duplicate_column", "t_s,anchor_id,range_m,t_s\n", "duplicate column 't_s'", 1},
        BadCase{"missing_column", "t_s,range_m\n", "lacks the required column 'anchor_id'", 1}),
    [](const ::testing::TestParamInfo<BadCase>& param_info) { return std::string(param_info.param.name); });

TEST(RecordedData, RejectsBadAnchorsAndTruth) {
  pipeline::Recording r;
  EXPECT_NE(ErrorOf([&] { ParseAnchorsCsv("anchor_id,x_m,y_m\nA1,0,0\nA1,1,1\n", "anchors.csv", r); })
                .find("anchors.csv:3: anchor_id 'A1': duplicate anchor id"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseAnchorsCsv("anchor_id,x_m,y_m\n", "anchors.csv", r); }).find("anchors.csv: no anchors"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseAnchorsCsv("", "anchors.csv", r); }).find("anchors.csv: empty file"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseTruthCsv("t_s,x_m,y_m\n0,1,1\n0,1,2\n", "truth.csv", r); })
                .find("truth.csv:3: t_s '0': time must increase"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseTruthCsv("t_s,x_m,y_m\n0,1,NaN\n", "truth.csv", r); }).find("truth.csv:2: y_m 'NaN'"),
            std::string::npos);
}

class RecordedFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("mirage_recorded_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  fs::path dir_;
};

TEST_F(RecordedFiles, WriteThenLoadGivesTheSameDoubles) {
  pipeline::Recording r = WithAnchors();
  for (int k = 0; k < 5; ++k) {
    pipeline::RecordedStep step;
    step.t_s = 0.1 * k;  // 0.30000000000000004 must come back exactly
    step.anchors.resize(2);
    step.anchors[0].anchor_index = 0;
    step.anchors[0].ranges = {{1.0 / 3.0 + k, 0.123456789012345678}, {M_PI, std::nullopt}};
    step.anchors[1].anchor_index = 1;
    step.anchors[1].ranges = {{std::sqrt(2.0), 1e-300}};
    r.steps.push_back(step);
    r.truth.push_back({step.t_s, Vec3(std::exp(1.0), -1.0 / 7.0 * k, 0.0)});
  }
  WriteRecording(dir_.string(), r);
  const auto back = LoadRecording({(dir_ / "anchors.csv").string(), (dir_ / "ranges.csv").string(),
                                   (dir_ / "truth.csv").string(), {}, {}});
  ASSERT_EQ(back.steps.size(), r.steps.size());
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    EXPECT_EQ(back.steps[k].t_s, r.steps[k].t_s);
    for (std::size_t a = 0; a < 2; ++a) {
      ASSERT_EQ(back.steps[k].anchors[a].ranges.size(), r.steps[k].anchors[a].ranges.size());
      for (std::size_t i = 0; i < r.steps[k].anchors[a].ranges.size(); ++i) {
        EXPECT_EQ(back.steps[k].anchors[a].ranges[i].range_m, r.steps[k].anchors[a].ranges[i].range_m);
        EXPECT_EQ(back.steps[k].anchors[a].ranges[i].amplitude, r.steps[k].anchors[a].ranges[i].amplitude);
      }
    }
    EXPECT_EQ(back.truth[k].position_m, r.truth[k].position_m);
  }
}

TEST_F(RecordedFiles, WriteThenLoadKeepsTheHeightsOfAThreeDimensionalRecording) {
  pipeline::Recording r = WithAnchors();
  r.anchors_m[0].z() = 2.9;
  r.anchors_have_z = true;
  r.truth_has_z = true;
  for (int k = 0; k < 2; ++k) {
    pipeline::RecordedStep step;
    step.t_s = 0.1 * k;
    step.anchors.resize(2);
    step.anchors[0].anchor_index = 0;
    step.anchors[0].ranges = {{3.0, std::nullopt}};
    step.anchors[1].anchor_index = 1;
    r.steps.push_back(step);
    r.truth.push_back({step.t_s, Vec3(1.0, 2.0, 0.6 + 0.1 * k)});
  }
  WriteRecording(dir_.string(), r);
  const auto back = LoadRecording({(dir_ / "anchors.csv").string(), (dir_ / "ranges.csv").string(),
                                   (dir_ / "truth.csv").string(), {}, {}});
  EXPECT_TRUE(back.anchors_have_z);
  EXPECT_TRUE(back.truth_has_z);
  EXPECT_EQ(back.anchors_m[0], Vec3(0.5, 7.0, 2.9));
  EXPECT_EQ(back.anchors_m[1], Vec3(5.2, 2.3, 0.0));
  ASSERT_EQ(back.truth.size(), 2u);
  EXPECT_EQ(back.truth[1].position_m, r.truth[1].position_m);
}

TEST_F(RecordedFiles, TruthMustCoverEveryStep) {
  const auto anchors = Write("anchors.csv", kAnchors);
  const auto ranges = Write("ranges.csv", "t_s,anchor_id,range_m\n0,A1,1\n2,A1,1\n");
  const auto truth = Write("truth.csv", "t_s,x_m,y_m\n0,1,1\n1,1,1\n");
  const std::string message = ErrorOf([&] { (void)LoadRecording({anchors, ranges, truth, {}, {}}); });
  EXPECT_NE(message.find("truth.csv: covers t_s in [0, 1] s"), std::string::npos) << message;
  EXPECT_NE(message.find("step at t_s = 2 s"), std::string::npos) << message;
}

TEST_F(RecordedFiles, MissingFileIsNamed) {
  const auto anchors = Write("anchors.csv", kAnchors);
  const std::string message = ErrorOf([&] { (void)LoadRecording({anchors, (dir_ / "nope.csv").string(), {}, {}, {}}); });
  EXPECT_NE(message.find("nope.csv: cannot open"), std::string::npos) << message;
}

// ---- Acoustic stamps: mics.csv, toa.csv ----

const char* const kMics = "receiver_id,x_m,y_m,z_m\nM1,0.6,0.6,3.3\nM2,6,0.5,3.3\nM3,11.4,0.6,3.2\n";

pipeline::Recording WithMics() {
  pipeline::Recording r;
  ParseMicsCsv(kMics, "mics.csv", r);
  return r;
}

TEST(RecordedStamps, ParsesMicrophonesInThreeDimensions) {
  const auto r = WithMics();
  EXPECT_TRUE(r.toa_stamps);
  EXPECT_TRUE(r.anchors_have_z);
  ASSERT_EQ(r.anchor_ids.size(), 3u);
  EXPECT_EQ(r.anchor_ids[2], "M3");
  EXPECT_EQ(r.anchors_m[2], Vec3(11.4, 0.6, 3.2));
}

TEST(RecordedStamps, GroupsRowsByEmissionWithOneRecordPerMicrophone) {
  auto r = WithMics();
  // Emission 1: two stamps at M3 (direct path and an echo, unlabeled, in file order), one at M1,
  // none at M2. Emission 2: one stamp at M2. A column order other than the header's usual.
  ParseToaCsv("toa_s,t_s,receiver_id\n0.53,0.5,M3\n0.5,0.5,M1\n0.51,0.5,M3\n\n0.66,0.65,M2\n", "toa.csv", r);
  ASSERT_EQ(r.steps.size(), 2u);
  const auto& first = r.steps[0];
  EXPECT_EQ(first.t_s, 0.5);
  EXPECT_TRUE(first.anchors.empty());
  ASSERT_EQ(first.toas.size(), 3u);
  for (int m = 0; m < 3; ++m) {
    const auto& record = first.toas[static_cast<std::size_t>(m)];
    EXPECT_EQ(record.receiver_index, m);
    EXPECT_EQ(record.receiver_id, r.anchor_ids[static_cast<std::size_t>(m)]);
    EXPECT_EQ(record.t_s, 0.5);  // the emission's time, as the simulator stamps its records
  }
  EXPECT_EQ(first.toas[0].toa_s, std::vector<double>{0.5});
  EXPECT_TRUE(first.toas[1].toa_s.empty());
  EXPECT_EQ(first.toas[2].toa_s, (std::vector<double>{0.53, 0.51}));
  EXPECT_EQ(r.steps[1].t_s, 0.65);
  EXPECT_EQ(r.steps[1].toas[1].toa_s, std::vector<double>{0.66});
  EXPECT_EQ(r.steps[1].toas[1].t_s, 0.65);
}

TEST(RecordedStamps, ReplaysOneEpochPerEmissionWhateverTheEpochWindow) {
  auto r = WithMics();
  ParseToaCsv("t_s,receiver_id,toa_s\n0.5,M1,0.5\n0.5,M2,0.52\n0.51,M3,0.51\n", "toa.csv", r);
  pipeline::RecordedSource source(r, 1.0);  // a window that would merge both range steps
  const auto first = source.Next();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->epoch.t_s, 0.5);
  ASSERT_EQ(first->epoch.toas.size(), 3u);
  EXPECT_TRUE(first->epoch.range_sets.empty());
  EXPECT_EQ(first->epoch.toas[1].toa_s, std::vector<double>{0.52});
  EXPECT_EQ(first->epoch.toas[1].receiver_id, "M2");
  const auto second = source.Next();
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->epoch.t_s, 0.51);
  EXPECT_EQ(second->epoch.toas[2].toa_s, std::vector<double>{0.51});
  EXPECT_FALSE(source.Next().has_value());
}

class BadToa : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadToa, NamesFileAndLine) {
  const BadCase& c = GetParam();
  auto r = WithMics();
  const std::string message = ErrorOf([&] { ParseToaCsv(c.text, "toa.csv", r); });
  EXPECT_NE(message.find("toa.csv:" + std::to_string(c.line) + ":"), std::string::npos) << message;
  EXPECT_NE(message.find(c.expect), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    RecordedStamps, BadToa,
    ::testing::Values(
        BadCase{"missing_field", "t_s,receiver_id,toa_s\n0,M1,0.01\n0,M2\n", "expected 3 fields", 3},
        BadCase{"empty_toa", "t_s,receiver_id,toa_s\n0,M1,\n", "toa_s '': missing value", 2},
        BadCase{"unknown_receiver", "t_s,receiver_id,toa_s\n0,M1,0.01\n0,M9,0.02\n",
                "receiver_id 'M9': unknown microphone", 3},
        BadCase{"time_backwards", "t_s,receiver_id,toa_s\n0.1,M1,0.1\n0.25,M1,0.25\n0.2,M2,0.2\n",
                "t_s '0.2': time goes backwards", 4},
        BadCase{"text_toa", "t_s,receiver_id,toa_s\n0,M1,12ms\n", "toa_s '12ms': not a number", 2},
        BadCase{"nan_toa", "t_s,receiver_id,toa_s\n0,M1,nan\n", "toa_s 'nan': must be finite", 2},
        BadCase{"inf_time", "t_s,receiver_id,toa_s\n-inf,M1,0\n", "t_s '-inf': must be finite", 2},
        BadCase{"missing_column", "t_s,receiver_id\n", "lacks the required column 'toa_s'", 1},
        BadCase{"range_column", "t_s,receiver_id,toa_s,range_m\n", "unknown column 'range_m'", 1}),
    [](const ::testing::TestParamInfo<BadCase>& param_info) { return std::string(param_info.param.name); });

TEST(RecordedStamps, RejectsBadMicrophones) {
  pipeline::Recording r;
  const auto error = [&](const char* text) { return ErrorOf([&] { ParseMicsCsv(text, "mics.csv", r); }); };
  EXPECT_NE(error("receiver_id,x_m,y_m\nM1,0,0\n").find("mics.csv:1:"), std::string::npos);
  EXPECT_NE(error("receiver_id,x_m,y_m\nM1,0,0\n").find("lacks the required column 'z_m'"), std::string::npos);
  EXPECT_NE(error("receiver_id,x_m,y_m,z_m\nM1,0,0,3\nM1,1,1,3\n").find("mics.csv:3: receiver_id 'M1': duplicate microphone id"),
            std::string::npos);
  EXPECT_NE(error("receiver_id,x_m,y_m,z_m\nM1,0,0,3\nM2,1,1\n").find("mics.csv:3: expected 4 fields"), std::string::npos);
  EXPECT_NE(error("receiver_id,x_m,y_m,z_m\nM1,0,x,3\n").find("mics.csv:2: y_m 'x': not a number"), std::string::npos);
  EXPECT_NE(error("receiver_id,x_m,y_m,z_m\n,0,0,3\n").find("mics.csv:2: receiver_id '': missing value"), std::string::npos);
  EXPECT_NE(error("receiver_id,x_m,y_m,z_m\n").find("mics.csv: no microphones"), std::string::npos);
  auto mics = WithMics();
  EXPECT_NE(ErrorOf([&] { ParseToaCsv("t_s,receiver_id,toa_s\n", "toa.csv", mics); }).find("toa.csv: no stamps"),
            std::string::npos);
}

TEST_F(RecordedFiles, WriteThenLoadStampsGivesTheSameDoubles) {
  pipeline::Recording r = WithMics();
  for (int k = 0; k < 4; ++k) {
    pipeline::RecordedStep step;
    step.t_s = 0.1 * k + 1.0 / 3.0;
    step.toas.resize(3);
    for (int m = 0; m < 3; ++m) {
      step.toas[static_cast<std::size_t>(m)].t_s = step.t_s;
      step.toas[static_cast<std::size_t>(m)].receiver_id = r.anchor_ids[static_cast<std::size_t>(m)];
      step.toas[static_cast<std::size_t>(m)].receiver_index = m;
    }
    step.toas[0].toa_s = {step.t_s, step.t_s + M_PI * 1e-3};
    if (k % 2 == 0) step.toas[2].toa_s = {step.t_s + std::sqrt(2.0) * 1e-2};  // M2 hears nothing
    r.steps.push_back(step);
    r.truth.push_back({step.t_s, Vec3(std::exp(1.0), -1.0 / 7.0 * k, 1.3 + 1e-3 / 3.0 * k)});
  }
  r.truth_has_z = true;
  WriteRecording(dir_.string(), r);
  EXPECT_FALSE(fs::exists(dir_ / "anchors.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "ranges.csv"));
  RecordingFiles files;
  files.mics = (dir_ / "mics.csv").string();
  files.toa = (dir_ / "toa.csv").string();
  files.truth = (dir_ / "truth.csv").string();
  const auto back = LoadRecording(files);
  EXPECT_TRUE(back.toa_stamps);
  EXPECT_EQ(back.anchor_ids, r.anchor_ids);
  EXPECT_EQ(back.anchors_m, r.anchors_m);
  ASSERT_EQ(back.steps.size(), r.steps.size());
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    EXPECT_EQ(back.steps[k].t_s, r.steps[k].t_s);
    ASSERT_EQ(back.steps[k].toas.size(), 3u);
    for (std::size_t m = 0; m < 3; ++m) {
      EXPECT_EQ(back.steps[k].toas[m].toa_s, r.steps[k].toas[m].toa_s) << k << " " << m;
      EXPECT_EQ(back.steps[k].toas[m].t_s, r.steps[k].toas[m].t_s);
      EXPECT_EQ(back.steps[k].toas[m].receiver_id, r.steps[k].toas[m].receiver_id);
    }
    EXPECT_EQ(back.truth[k].position_m, r.truth[k].position_m);
  }
}

TEST_F(RecordedFiles, TruthMustCoverEveryEmission) {
  RecordingFiles files;
  files.mics = Write("mics.csv", kMics);
  files.toa = Write("toa.csv", "t_s,receiver_id,toa_s\n0,M1,0\n2,M1,2\n");
  files.truth = Write("truth.csv", "t_s,x_m,y_m,z_m\n0,1,1,1.3\n1,1,1,1.3\n");
  const std::string message = ErrorOf([&] { (void)LoadRecording(files); });
  EXPECT_NE(message.find("truth.csv: covers t_s in [0, 1] s, but " + files.toa + " has a step at t_s = 2 s"),
            std::string::npos)
      << message;
}

// ---- Pairwise TDOA: anchors.csv (3-D), tdoa.csv ----

const char* const kAnchors3d = "anchor_id,x_m,y_m,z_m\nA1,0,0,0.15\nA2,4,0,2.4\nA3,4,4,0.15\n";

pipeline::Recording WithAnchors3d() {
  pipeline::Recording r;
  ParseAnchorsCsv(kAnchors3d, "anchors.csv", r);
  return r;
}

TEST(RecordedTdoa, GroupsRowsWithOneTimeIntoOneStepInFileOrder) {
  auto r = WithAnchors3d();
  // Columns in another order; two pairs at t = 0, one at t = 0.0125 whose 30.5 m is far beyond
  // any baseline (an outlier, kept: rejecting it is the estimator's job).
  ParseTdoaCsv("id_j,tdoa_m,t_s,id_i\nA2,0.25,0,A1\nA1,-1.5,0,A3\n\nA3,30.5,0.0125,A2\n", "tdoa.csv", r);
  EXPECT_TRUE(r.tdoa);
  EXPECT_FALSE(r.toa_stamps);
  ASSERT_EQ(r.steps.size(), 2u);
  const auto& first = r.steps[0];
  EXPECT_EQ(first.t_s, 0.0);
  EXPECT_TRUE(first.anchors.empty());
  EXPECT_TRUE(first.toas.empty());
  ASSERT_EQ(first.tdoas.size(), 2u);
  EXPECT_EQ(first.tdoas[0].id_i, "A1");
  EXPECT_EQ(first.tdoas[0].id_j, "A2");
  EXPECT_EQ(first.tdoas[0].index_i, 0);
  EXPECT_EQ(first.tdoas[0].index_j, 1);
  EXPECT_EQ(first.tdoas[0].tdoa_m, 0.25);
  EXPECT_EQ(first.tdoas[1].index_i, 2);
  EXPECT_EQ(first.tdoas[1].index_j, 0);
  EXPECT_EQ(first.tdoas[1].tdoa_m, -1.5);
  ASSERT_EQ(r.steps[1].tdoas.size(), 1u);
  EXPECT_EQ(r.steps[1].t_s, 0.0125);
  EXPECT_EQ(r.steps[1].tdoas[0].t_s, 0.0125);
  EXPECT_EQ(r.steps[1].tdoas[0].index_i, 1);
  EXPECT_EQ(r.steps[1].tdoas[0].index_j, 2);
  EXPECT_EQ(r.steps[1].tdoas[0].tdoa_m, 30.5);
}

TEST(RecordedTdoa, ReplaysOneEpochPerTimeWithItsDifferencesWhateverTheEpochWindow) {
  auto r = WithAnchors3d();
  ParseTdoaCsv("t_s,id_i,id_j,tdoa_m\n0.5,A1,A2,0.1\n0.5,A2,A3,0.2\n0.51,A3,A1,0.3\n", "tdoa.csv", r);
  pipeline::RecordedSource source(r, 1.0);  // a window that would merge both range steps
  const auto first = source.Next();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->epoch.t_s, 0.5);
  EXPECT_TRUE(first->epoch.range_sets.empty());
  EXPECT_TRUE(first->epoch.toas.empty());
  ASSERT_EQ(first->epoch.tdoas.size(), 2u);
  EXPECT_EQ(first->epoch.tdoas[1].t_s, 0.5);
  EXPECT_EQ(first->epoch.tdoas[1].id_i, "A2");
  EXPECT_EQ(first->epoch.tdoas[1].id_j, "A3");
  EXPECT_EQ(first->epoch.tdoas[1].index_i, 1);
  EXPECT_EQ(first->epoch.tdoas[1].index_j, 2);
  EXPECT_EQ(first->epoch.tdoas[1].tdoa_m, 0.2);
  const auto second = source.Next();
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->epoch.t_s, 0.51);
  ASSERT_EQ(second->epoch.tdoas.size(), 1u);
  EXPECT_EQ(second->epoch.tdoas[0].t_s, 0.51);
  EXPECT_EQ(second->epoch.tdoas[0].id_i, "A3");
  EXPECT_EQ(second->epoch.tdoas[0].index_j, 0);
  EXPECT_EQ(second->epoch.tdoas[0].tdoa_m, 0.3);
  EXPECT_FALSE(source.Next().has_value());
  EXPECT_EQ(source.out_of_order(), 0);
}

class BadTdoa : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadTdoa, NamesFileLineAndColumn) {
  const BadCase& c = GetParam();
  auto r = WithAnchors3d();
  const std::string message = ErrorOf([&] { ParseTdoaCsv(c.text, "tdoa.csv", r); });
  EXPECT_NE(message.find("tdoa.csv:" + std::to_string(c.line) + ":"), std::string::npos) << message;
  EXPECT_NE(message.find(c.expect), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    RecordedTdoa, BadTdoa,
    ::testing::Values(
        BadCase{"unknown_id_i", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n0,A9,A2,0.1\n", "id_i 'A9': unknown anchor", 3},
        BadCase{"unknown_id_j", "t_s,id_i,id_j,tdoa_m\n0,A1,a2,0.1\n", "id_j 'a2': unknown anchor", 2},
        BadCase{"empty_id", "t_s,id_i,id_j,tdoa_m\n0,,A2,0.1\n", "id_i '': unknown anchor", 2},
        BadCase{"same_ids", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n\n0.01,A3,A3,0\n", "id_j 'A3': the same anchor as id_i",
                4},
        BadCase{"text_tdoa", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1m\n", "tdoa_m '0.1m': not a number", 2},
        BadCase{"nan_tdoa", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,NaN\n", "tdoa_m 'NaN': must be finite", 2},
        BadCase{"inf_tdoa", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,-inf\n", "tdoa_m '-inf': must be finite", 2},
        BadCase{"empty_tdoa", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,\n", "tdoa_m '': missing value", 2},
        BadCase{"time_backwards", "t_s,id_i,id_j,tdoa_m\n0.1,A1,A2,0\n0.2,A1,A2,0\n0.2,A2,A3,0\n0.15,A1,A3,0\n",
                "t_s '0.15': time goes backwards", 5},
        BadCase{"missing_field", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n0,A1,A2\n", "expected 4 fields", 3},
        BadCase{"missing_column", "t_s,id_i,id_j\n0,A1,A2\n", "lacks the required column 'tdoa_m'", 1},
        BadCase{"range_column", "t_s,id_i,id_j,tdoa_m,anchor_id\n", "unknown column 'anchor_id'", 1}),
    [](const ::testing::TestParamInfo<BadCase>& param_info) { return std::string(param_info.param.name); });

TEST(RecordedTdoa, RejectsAnchorsWithoutHeightAndAnEmptyFile) {
  auto flat = WithAnchors();  // anchor_id,x_m,y_m
  const std::string message = ErrorOf([&] { ParseTdoaCsv("t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n", "tdoa.csv", flat); });
  EXPECT_NE(message.find("tdoa.csv: the anchors have no z_m column"), std::string::npos) << message;
  auto mics = WithMics();
  EXPECT_NE(ErrorOf([&] { ParseTdoaCsv("t_s,id_i,id_j,tdoa_m\n0,M1,M2,0.1\n", "tdoa.csv", mics); }).find("tdoa.csv: "),
            std::string::npos);
  auto r = WithAnchors3d();
  EXPECT_NE(ErrorOf([&] { ParseTdoaCsv("t_s,id_i,id_j,tdoa_m\n\n", "tdoa.csv", r); })
                .find("tdoa.csv: no time differences"),
            std::string::npos);
}

TEST_F(RecordedFiles, WriteThenLoadTdoaGivesTheSameDoubles) {
  pipeline::Recording r = WithAnchors3d();
  r.anchors_m[1].z() = 1.0 / 3.0;
  r.tdoa = true;
  for (int k = 0; k < 4; ++k) {
    pipeline::RecordedStep step;
    step.t_s = 0.1 * k + 1.0 / 7.0;
    for (int n = 0; n <= k % 2; ++n) {  // one pair, then two
      core::TdoaMeasurement m;
      m.t_s = step.t_s;
      m.index_i = (k + n) % 3;
      m.index_j = (k + n + 1) % 3;
      m.id_i = r.anchor_ids[static_cast<std::size_t>(m.index_i)];
      m.id_j = r.anchor_ids[static_cast<std::size_t>(m.index_j)];
      m.tdoa_m = (n == 0 ? -1.0 : 1.0) * std::sqrt(2.0 + k) + (k == 3 ? 27.0 : 0.0);  // k = 3: an outlier
      step.tdoas.push_back(m);
    }
    r.steps.push_back(step);
    r.truth.push_back({step.t_s, Vec3(std::exp(1.0), -1.0 / 7.0 * k, 1.3 + 1e-3 / 3.0 * k)});
  }
  r.truth_has_z = true;
  WriteRecording(dir_.string(), r);
  EXPECT_FALSE(fs::exists(dir_ / "ranges.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "mics.csv"));
  RecordingFiles files;
  files.anchors = (dir_ / "anchors.csv").string();
  files.tdoa = (dir_ / "tdoa.csv").string();
  files.truth = (dir_ / "truth.csv").string();
  const auto back = LoadRecording(files);
  EXPECT_TRUE(back.tdoa);
  EXPECT_FALSE(back.toa_stamps);
  EXPECT_TRUE(back.anchors_have_z);
  EXPECT_EQ(back.anchor_ids, r.anchor_ids);
  EXPECT_EQ(back.anchors_m, r.anchors_m);
  ASSERT_EQ(back.steps.size(), r.steps.size());
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    EXPECT_EQ(back.steps[k].t_s, r.steps[k].t_s);
    ASSERT_EQ(back.steps[k].tdoas.size(), r.steps[k].tdoas.size()) << k;
    for (std::size_t n = 0; n < r.steps[k].tdoas.size(); ++n) {
      const auto& got = back.steps[k].tdoas[n];
      const auto& want = r.steps[k].tdoas[n];
      EXPECT_EQ(got.t_s, want.t_s);
      EXPECT_EQ(got.id_i, want.id_i);
      EXPECT_EQ(got.id_j, want.id_j);
      EXPECT_EQ(got.index_i, want.index_i);
      EXPECT_EQ(got.index_j, want.index_j);
      EXPECT_EQ(got.tdoa_m, want.tdoa_m) << k << " " << n;
    }
    EXPECT_EQ(back.truth[k].position_m, r.truth[k].position_m);
  }
}

TEST_F(RecordedFiles, TdoaNeedsAnchorsWithHeight) {
  RecordingFiles files;
  files.anchors = Write("anchors.csv", kAnchors);
  files.tdoa = Write("tdoa.csv", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n");
  const std::string message = ErrorOf([&] { (void)LoadRecording(files); });
  EXPECT_NE(message.find(files.anchors + ":1: the header lacks the column 'z_m'"), std::string::npos) << message;
  EXPECT_NE(message.find("TDOA"), std::string::npos) << message;
}

TEST_F(RecordedFiles, TdoaTogetherWithRangesOrStampsIsAnError) {
  RecordingFiles files;
  files.anchors = Write("anchors.csv", kAnchors3d);
  files.tdoa = Write("tdoa.csv", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n");
  files.ranges = Write("ranges.csv", "t_s,anchor_id,range_m\n0,A1,1\n");
  std::string message = ErrorOf([&] { (void)LoadRecording(files); });
  EXPECT_NE(message.find(files.tdoa + ": a recording has either tdoa"), std::string::npos) << message;
  EXPECT_NE(message.find("also given: ranges " + files.ranges), std::string::npos) << message;
  files.ranges.clear();
  files.toa = Write("toa.csv", "t_s,receiver_id,toa_s\n0,A1,0\n");
  message = ErrorOf([&] { (void)LoadRecording(files); });
  EXPECT_NE(message.find("also given: toa " + files.toa), std::string::npos) << message;
}

TEST_F(RecordedFiles, TruthMustCoverEveryTdoaStep) {
  RecordingFiles files;
  files.anchors = Write("anchors.csv", kAnchors3d);
  files.tdoa = Write("tdoa.csv", "t_s,id_i,id_j,tdoa_m\n0,A1,A2,0.1\n2,A1,A2,0.1\n");
  files.truth = Write("truth.csv", "t_s,x_m,y_m,z_m\n0,1,1,1\n1,1,1,1\n");
  const std::string message = ErrorOf([&] { (void)LoadRecording(files); });
  EXPECT_NE(message.find("truth.csv: covers t_s in [0, 1] s, but " + files.tdoa + " has a step at t_s = 2 s"),
            std::string::npos)
      << message;
}

// The fixture the fuzz seeds come from: 8 anchors in 3-D, a tag on a circle, 30 rows with two
// outliers (+25 m at t = 0.09 s, -18 m at t = 0.19 s). Its differences follow the sign convention
// tdoa_m = |p - a_j| - |p - a_i| within the 5 cm noise the generator added.
TEST(RecordedTdoa, LoadsTheExampleRecordingWithTheDocumentedSign) {
  const std::string dir = std::string(MIRAGE_SOURCE_DIR) + "/tests/io/data/recorded_tdoa/";
  RecordingFiles files;
  files.anchors = dir + "anchors.csv";
  files.tdoa = dir + "tdoa.csv";
  files.truth = dir + "truth.csv";
  const auto r = LoadRecording(files);
  ASSERT_EQ(r.anchor_ids.size(), 8u);
  std::size_t rows = 0;
  int outliers = 0;
  for (const auto& step : r.steps) {
    const Vec3 p = *r.TruthAt(step.t_s);
    for (const auto& m : step.tdoas) {
      ++rows;
      const double expected_m = (p - r.anchors_m[static_cast<std::size_t>(m.index_j)]).norm() -
                                (p - r.anchors_m[static_cast<std::size_t>(m.index_i)]).norm();
      if (std::abs(m.tdoa_m - expected_m) > 10.0) {
        ++outliers;
      } else {
        EXPECT_NEAR(m.tdoa_m, expected_m, 0.25) << m.t_s << " " << m.id_i << " " << m.id_j;
      }
    }
  }
  EXPECT_EQ(rows, 30u);
  EXPECT_EQ(outliers, 2);
  EXPECT_LT(r.steps.size(), rows);  // some times carry two pairs
}

}  // namespace
}  // namespace mirage::io
