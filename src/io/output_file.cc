// SPDX-License-Identifier: MIT
#include "mirage/io/output_file.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "mirage/io/input_error.h"

namespace mirage::io {
namespace {

namespace fs = std::filesystem;

// A name beside the target that no other writer of this process or another one uses.
std::string TemporaryName(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void CreateParent(const std::string& path, const std::string& what) {
  const auto parent = fs::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec || !fs::is_directory(parent, ec)) throw InputError(what + ": cannot create directory " + parent.string());
}

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  std::error_code ec;
  if (fs::is_directory(path_, ec)) throw InputError(path_ + ": is a directory, expected a file to write");
  CreateParent(path_, path_);
  temporary_ = TemporaryName(path_);
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(path_ + ": cannot open for writing");
}

OutputFile::~OutputFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  fs::remove(temporary_, ec);
}

void OutputFile::Commit() {
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  if (!written || out_.fail()) throw InputError(path_ + ": write failed");
  std::error_code ec;
  fs::rename(temporary_, path_, ec);
  if (ec) throw InputError(path_ + ": cannot replace the file (" + ec.message() + ")");
  committed_ = true;
}

void CheckWritableFile(const std::string& path, const std::string& option) {
  if (path.empty()) throw InputError(option + ": empty path");
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(option + " " + path + ": is a directory, expected a file");
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    throw InputError(option + " " + path + ": exists and is not a regular file");
  }
  CreateParent(path, option + " " + path);
  // Probe the directory with a temporary file of our own; the target itself is not touched.
  const std::string probe = TemporaryName(path);
  {
    std::ofstream out(probe, std::ios::binary);
    if (!out) throw InputError(option + " " + path + ": cannot write in its directory");
  }
  fs::remove(probe, ec);
}

void CheckWritableDirectory(const std::string& dir, const std::string& option) {
  if (dir.empty()) throw InputError(option + ": empty path");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw InputError(option + " " + dir + ": exists and is not a directory");
  }
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec)) throw InputError(option + " " + dir + ": cannot create the directory");
  const std::string probe = TemporaryName((fs::path(dir) / ".mirage-write-check").string());
  {
    std::ofstream out(probe, std::ios::binary);
    if (!out) throw InputError(option + " " + dir + ": cannot write in the directory");
  }
  fs::remove(probe, ec);
}

}  // namespace mirage::io
