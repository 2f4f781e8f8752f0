// SPDX-License-Identifier: MIT
// Test helpers of the scenario-loader tests: a scenario text with some lines replaced, the
// InputError message of loading a file, and the check that a message names the file, the line
// and what is wrong on one line.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/io/input_error.h"
#include "mirage/io/scenario.h"

namespace mirage::io::testing {

/// `text` with the given lines (1-based) replaced by their text (several lines allowed, ""
/// removes the line).
inline std::string WithLines(const std::string& text, const std::map<int, std::string>& lines) {
  std::string out;
  std::size_t start = 0;
  for (int n = 1; start < text.size(); ++n) {
    const std::size_t end = text.find('\n', start);
    const auto it = lines.find(n);
    if (it == lines.end()) {
      out += text.substr(start, end - start + 1);
    } else if (!it->second.empty()) {
      out += it->second + "\n";
    }
    start = end + 1;
  }
  return out;
}

/// The InputError message of loading `path` (fails the test if it loads).
inline std::string ErrorOf(const std::string& path, const ScenarioOverrides& overrides = {}) {
  try {
    LoadScenario(path, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without an error";
  return {};
}

/// Expects the error to name the file, the line as ":<line>:" (unless 0) and every fragment, on
/// one line.
inline void ExpectError(const std::string& message, const std::string& file, int line,
                        const std::vector<std::string>& fragments) {
  EXPECT_NE(message.find(file), std::string::npos) << "no file name in: " << message;
  if (line > 0) {
    EXPECT_NE(message.find(file + ":" + std::to_string(line) + ":"), std::string::npos)
        << "no '" << file << ":" << line << ":' in: " << message;
  }
  for (const auto& f : fragments) EXPECT_NE(message.find(f), std::string::npos) << "no '" << f << "' in: " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

}  // namespace mirage::io::testing
