// SPDX-License-Identifier: MIT
#include "mirage/io/output_file.h"

#include <filesystem>

#include "mirage/io/input_error.h"

namespace mirage::io {

std::ofstream OpenForWriting(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open for writing");
  return out;
}

void FinishWriting(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw InputError(path + ": write failed");
}

}  // namespace mirage::io
