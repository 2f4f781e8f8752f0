// SPDX-License-Identifier: MIT
// libFuzzer target for the recorded-data readers (anchors.csv, ranges.csv, truth.csv, mics.csv,
// toa.csv, tdoa.csv): the input is the six files' texts separated by NUL bytes (missing ones are
// empty; tdoa.csv pairs with anchors.csv and truth.csv); each must parse or be rejected with
// io::InputError. A crash, a sanitizer report, a hang or any other exception is a bug. A parsed
// recording is also walked (every step, range, stamp, time difference and truth lookup), as the
// estimators would, and replayed as epochs when it has pairwise TDOAs.
// Build and run: make fuzz.
#include <cmath>
#include <cstdint>
#include <string_view>

#include "mirage/io/input_error.h"
#include "mirage/io/recorded_data.h"
#include "mirage/pipeline/recorded_source.h"

namespace {

// Ranges: anchors, ranges, optional truth.
double WalkRanges(std::string_view anchors, std::string_view ranges, std::string_view truth) {
  mirage::pipeline::Recording recording;
  try {
    mirage::io::ParseAnchorsCsv(anchors, "anchors.csv", recording);
    mirage::io::ParseRangesCsv(ranges, "ranges.csv", recording);
    if (!truth.empty()) mirage::io::ParseTruthCsv(truth, "truth.csv", recording);
  } catch (const mirage::io::InputError&) {
    return 0.0;
  }
  double sum = 0.0;
  for (const auto& step : recording.steps) {
    if (step.anchors.size() != recording.anchor_ids.size() || !step.toas.empty()) __builtin_trap();
    for (const auto& anchor : step.anchors) {
      for (const auto& r : anchor.ranges) {
        if (!(r.range_m >= 0.0)) __builtin_trap();  // the reader must have rejected it
        sum += r.range_m + r.amplitude.value_or(0.0);
      }
    }
    if (const auto p = recording.TruthAt(step.t_s)) sum += p->x();
  }
  return sum;
}

// Acoustic stamps: mics, toa, optional truth.
double WalkStamps(std::string_view mics, std::string_view toa, std::string_view truth) {
  mirage::pipeline::Recording recording;
  try {
    mirage::io::ParseMicsCsv(mics, "mics.csv", recording);
    mirage::io::ParseToaCsv(toa, "toa.csv", recording);
    if (!truth.empty()) mirage::io::ParseTruthCsv(truth, "truth.csv", recording);
  } catch (const mirage::io::InputError&) {
    return 0.0;
  }
  double sum = 0.0;
  double previous_s = -1e308;
  for (const auto& step : recording.steps) {
    if (step.toas.size() != recording.anchor_ids.size() || !step.anchors.empty() || !(step.t_s > previous_s)) {
      __builtin_trap();
    }
    previous_s = step.t_s;
    for (std::size_t m = 0; m < step.toas.size(); ++m) {
      const auto& record = step.toas[m];
      if (record.receiver_index != static_cast<int>(m) || record.t_s != step.t_s) __builtin_trap();
      for (const double toa_s : record.toa_s) sum += toa_s;  // finite: the reader rejects the rest
    }
    if (const auto p = recording.TruthAt(step.t_s)) sum += p->z();
  }
  return sum;
}

// Pairwise TDOA: anchors (3-D), tdoa, optional truth; then the epochs the recording replays as.
double WalkTdoa(std::string_view anchors, std::string_view tdoa, std::string_view truth) {
  mirage::pipeline::Recording recording;
  try {
    mirage::io::ParseAnchorsCsv(anchors, "anchors.csv", recording);
    mirage::io::ParseTdoaCsv(tdoa, "tdoa.csv", recording);
    if (!truth.empty()) mirage::io::ParseTruthCsv(truth, "truth.csv", recording);
  } catch (const mirage::io::InputError&) {
    return 0.0;
  }
  if (!recording.tdoa || !recording.anchors_have_z) __builtin_trap();
  const int anchors_n = static_cast<int>(recording.anchor_ids.size());
  double sum = 0.0;
  double previous_s = -1e308;
  for (const auto& step : recording.steps) {
    if (step.tdoas.empty() || !step.anchors.empty() || !step.toas.empty() || !(step.t_s > previous_s)) __builtin_trap();
    previous_s = step.t_s;
    for (const auto& m : step.tdoas) {
      if (m.t_s != step.t_s || m.index_i == m.index_j || m.index_i < 0 || m.index_j < 0 || m.index_i >= anchors_n ||
          m.index_j >= anchors_n || m.id_i != recording.anchor_ids[static_cast<std::size_t>(m.index_i)] ||
          m.id_j != recording.anchor_ids[static_cast<std::size_t>(m.index_j)] || !std::isfinite(m.tdoa_m)) {
        __builtin_trap();
      }
      sum += m.tdoa_m;
    }
    if (const auto p = recording.TruthAt(step.t_s)) sum += p->z();
  }
  mirage::pipeline::RecordedSource source(recording, 0.0);
  std::size_t epochs = 0;
  while (const auto step = source.Next()) {
    if (step->epoch.tdoas.size() != recording.steps[epochs].tdoas.size()) __builtin_trap();
    ++epochs;
  }
  if (epochs != recording.steps.size()) __builtin_trap();
  return sum;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string_view parts[6];
  for (auto& part : parts) {
    const std::size_t nul = input.find('\0');
    part = input.substr(0, nul);
    input = nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
  }
  double sum = WalkRanges(parts[0], parts[1], parts[2]);
  if (!parts[3].empty()) sum += WalkStamps(parts[3], parts[4], parts[2]);
  if (!parts[5].empty()) sum += WalkTdoa(parts[0], parts[5], parts[2]);
  return sum == -1.0 ? 1 : 0;
}
