// SPDX-License-Identifier: MIT
// Output files are replaced only when complete: the target changes at Commit(), and an output
// abandoned before it (an exception half-way) leaves the target and no temporary file behind.
#include "mirage/io/output_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int FilesIn(const fs::path& dir) {
  int count = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++count;
  return count;
}

class OutputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("mirage_output_file_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "report.json") << "previous";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(OutputFileTest, ReplacesTheTargetOnlyAtCommit) {
  OutputFile file((dir_ / "report.json").string());
  file.stream() << "new";
  file.stream().flush();
  EXPECT_EQ(Read(dir_ / "report.json"), "previous");

  file.Commit();

  EXPECT_EQ(Read(dir_ / "report.json"), "new");
  EXPECT_EQ(FilesIn(dir_), 1);
}

TEST_F(OutputFileTest, AbandonedOutputLeavesTheTargetAndNoTemporaryFile) {
  {
    OutputFile file((dir_ / "report.json").string());
    file.stream() << "half a rep";
  }
  EXPECT_EQ(Read(dir_ / "report.json"), "previous");
  EXPECT_EQ(FilesIn(dir_), 1);
}

TEST_F(OutputFileTest, CreatesMissingParentDirectories) {
  OutputFile file((dir_ / "a" / "b" / "tracks.csv").string());
  file.stream() << "x\n";
  file.Commit();
  EXPECT_EQ(Read(dir_ / "a" / "b" / "tracks.csv"), "x\n");
}

TEST_F(OutputFileTest, RefusesADirectoryAsTarget) {
  EXPECT_THROW(OutputFile{dir_.string()}, InputError);
  EXPECT_THROW(CheckWritableFile(dir_.string(), "--json"), InputError);
}

TEST_F(OutputFileTest, WritableChecksAcceptNewPathsAndRefuseFilesAsDirectories) {
  EXPECT_NO_THROW(CheckWritableFile((dir_ / "new" / "report.json").string(), "--json"));
  EXPECT_NO_THROW(CheckWritableDirectory((dir_ / "csv").string(), "--csv"));
  EXPECT_TRUE(fs::is_directory(dir_ / "csv"));
  try {
    CheckWritableDirectory((dir_ / "report.json").string(), "--csv");
    FAIL() << "a file accepted as output directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--csv"), std::string::npos) << e.what();
  }
  // The checks leave no probe files behind.
  EXPECT_EQ(FilesIn(dir_ / "csv"), 0);
}

}  // namespace
}  // namespace mirage::io
