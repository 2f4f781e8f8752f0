// SPDX-License-Identifier: MIT
// The files mirage writes (reports, CSV, recordings) are written to a temporary file beside the
// target and renamed over it only once everything was written: a failed write (disk full, a
// crash, an exception half-way) leaves the previous file as it was and no truncated file behind.
// Failures are InputErrors naming the file. Also the up-front check that an output path can be
// written, so that a run does not find out after minutes of work.
#pragma once

#include <fstream>
#include <string>

namespace mirage::io {

/// One output file being written. Write to stream(), then Commit(); destroyed without Commit()
/// (an exception in between), the temporary file is removed and the target left untouched.
class OutputFile {
 public:
  /// Creates the parent directories and opens a temporary file beside `path`.
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  [[nodiscard]] std::ofstream& stream() { return out_; }
  [[nodiscard]] const std::string& path() const { return path_; }

  /// Flushes, checks that every write succeeded and renames the temporary file to the target.
  void Commit();

 private:
  std::string path_;
  std::string temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Checks before a run that `path` can be written as a file: its directory exists or can be
/// created and is writable, and the path is not a directory. Throws InputError naming `option`
/// (e.g. "--json") and the path otherwise. Creates the directories it needs.
void CheckWritableFile(const std::string& path, const std::string& option);

/// The same for an output directory (created if missing; must be writable).
void CheckWritableDirectory(const std::string& dir, const std::string& option);

}  // namespace mirage::io
