// SPDX-License-Identifier: MIT
// Opening and finishing the files mirage writes (reports, CSV, recordings): a failed open or a
// failed write (disk full, ...) is an InputError naming the file, so that a truncated file never
// passes silently.
#pragma once

#include <fstream>
#include <string>

namespace mirage::io {

/// Opens path for writing, creating its parent directories.
std::ofstream OpenForWriting(const std::string& path);

/// Flushes out and throws if anything written to it failed.
void FinishWriting(std::ofstream& out, const std::string& path);

}  // namespace mirage::io
