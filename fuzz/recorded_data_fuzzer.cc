// SPDX-License-Identifier: MIT
// libFuzzer target for the recorded-data readers (anchors.csv, ranges.csv, truth.csv): the input
// is the three files' texts separated by NUL bytes; each must parse or be rejected with
// io::InputError. A crash, a sanitizer report, a hang or any other exception is a bug. A parsed
// recording is also walked (every step, range and truth lookup), as the trackers would.
// Build and run: make fuzz.
#include <cstdint>
#include <string_view>

#include "mirage/io/input_error.h"
#include "mirage/io/recorded_data.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string_view parts[3];
  for (auto& part : parts) {
    const std::size_t nul = input.find('\0');
    part = input.substr(0, nul);
    input = nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
  }
  mirage::pipeline::Recording recording;
  try {
    mirage::io::ParseAnchorsCsv(parts[0], "anchors.csv", recording);
    mirage::io::ParseRangesCsv(parts[1], "ranges.csv", recording);
    if (!parts[2].empty()) mirage::io::ParseTruthCsv(parts[2], "truth.csv", recording);
  } catch (const mirage::io::InputError&) {
    return 0;
  }
  double sum = 0.0;
  for (const auto& step : recording.steps) {
    if (step.anchors.size() != recording.anchor_ids.size()) __builtin_trap();
    for (const auto& anchor : step.anchors) {
      for (const auto& r : anchor.ranges) {
        if (!(r.range_m >= 0.0)) __builtin_trap();  // the reader must have rejected it
        sum += r.range_m + r.amplitude.value_or(0.0);
      }
    }
    if (const auto p = recording.TruthAt(step.t_s)) sum += p->x();
  }
  return sum == -1.0 ? 1 : 0;
}
