// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/va_sweep.h"

#include <algorithm>
#include <cmath>

#include "mirage/estimation/init/range_point_fit.h"

namespace mirage::methods::slam {

std::vector<std::string> Validate(const SweepOptions& o) {
  std::vector<std::string> problems;
  if (o.window_steps < 3) problems.push_back("sweep.window_steps must be >= 3");
  if (o.every_steps < 1) problems.push_back("sweep.every_steps must be >= 1");
  if (!(o.min_baseline_m > 0.0) || !std::isfinite(o.min_baseline_m)) {
    problems.push_back("sweep.min_baseline_m must be > 0 m");
  }
  if (!(o.gate_m > 0.0) || !std::isfinite(o.gate_m)) problems.push_back("sweep.gate_m must be > 0 m");
  if (!(o.min_support_fraction > 0.0 && o.min_support_fraction <= 1.0)) {
    problems.push_back("sweep.min_support_fraction must be in (0, 1]");
  }
  return problems;
}

VaSweep::VaSweep(const SweepOptions& options, int min_measurements, double exclusion_radius_m)
    : options_(options), min_measurements_(min_measurements), exclusion_radius_m_(exclusion_radius_m) {}

void VaSweep::Reset() { buffers_.clear(); }

std::size_t VaSweep::buffered_steps(int anchor_index) const {
  const auto a = static_cast<std::size_t>(anchor_index);
  return a < buffers_.size() ? buffers_[a].size() : 0;
}

std::size_t VaSweep::buffered_ranges(int anchor_index) const {
  const auto a = static_cast<std::size_t>(anchor_index);
  std::size_t count = 0;
  if (a < buffers_.size()) {
    for (const auto& b : buffers_[a]) count += b.scan.ranges_m.size();
  }
  return count;
}

void VaSweep::Buffer(int step, int anchor_index, const Vec2& agent_m, std::span<const core::RangeMeasurement> ranges,
                     const std::vector<bool>& used) {
  if (!options_.enabled || !agent_m.allFinite()) return;
  const auto anchor = static_cast<std::size_t>(anchor_index);
  if (buffers_.size() <= anchor) buffers_.resize(anchor + 1);
  auto& buffer = buffers_[anchor];
  std::erase_if(buffer, [&](const BufferedStep& b) { return step - b.step >= options_.window_steps; });
  // The ranges no candidate took, sorted (the consensus search looks them up by value).
  std::vector<core::RangeMeasurement> free;
  for (std::size_t j = 0; j < ranges.size(); ++j) {
    if (!used[j] && std::isfinite(ranges[j].range_m)) free.push_back(ranges[j]);
  }
  std::sort(free.begin(), free.end(),
            [](const core::RangeMeasurement& a, const core::RangeMeasurement& b) { return a.range_m < b.range_m; });
  BufferedStep entry;
  entry.step = step;
  entry.scan.position_m = agent_m;
  for (const auto& z : free) {
    entry.scan.ranges_m.push_back(z.range_m);
    entry.amplitudes.push_back(z.amplitude);
  }
  buffer.push_back(std::move(entry));
}

std::optional<SweepFind> VaSweep::Search(int step, int anchor_index, std::span<const Vec2> excluded_m) {
  if (!options_.enabled || (step + anchor_index) % options_.every_steps != 0) return std::nullopt;
  if (static_cast<std::size_t>(anchor_index) >= buffers_.size()) return std::nullopt;
  auto& buffer = buffers_[static_cast<std::size_t>(anchor_index)];
  const std::size_t n = buffer.size();
  double span_m = 0.0;
  for (const auto& b : buffer) span_m = std::max(span_m, (b.scan.position_m - buffer.front().scan.position_m).norm());
  if (n < 3 || span_m < options_.min_baseline_m) return std::nullopt;
  estimation::RangeConsensusOptions search;
  search.gate_m = options_.gate_m;
  // The fraction of the buffered steps, and never fewer ranges than a candidate needs to be
  // promoted (N_rls).
  search.min_support = static_cast<std::size_t>(
      std::max<double>(std::ceil(options_.min_support_fraction * static_cast<double>(n)), min_measurements_));
  search.min_pair_distance_m = 0.5 * options_.min_baseline_m;
  search.exclusion_radius_m = exclusion_radius_m_;
  std::vector<estimation::RangeScan> scans;
  scans.reserve(n);
  for (const auto& b : buffer) scans.push_back(b.scan);
  const auto found = estimation::FindRangeConsensus(scans, excluded_m, search);
  if (!found) return std::nullopt;
  SweepFind find;
  std::vector<Vec2> positions_m;
  std::vector<double> ranges_m;
  for (const auto& [k, j] : found->support) {
    const BufferedStep& b = buffer[k];
    find.samples.push_back({b.scan.position_m, b.scan.ranges_m[j], b.amplitudes[j]});
    positions_m.push_back(b.scan.position_m);
    ranges_m.push_back(b.scan.ranges_m[j]);
  }
  // The point and its mirror image, each fitted to the ranges (for a straight walk both fit).
  find.starts = {found->position_m, found->mirror_m};
  for (auto& start : find.starts) {
    if (const auto fit = estimation::FitPointToRanges(positions_m, ranges_m, start)) start = fit->position_m;
  }
  // The supporting ranges leave the buffer. support holds at most one range per step, steps in
  // ascending order, so erasing from the back keeps the remaining indices valid.
  for (auto it = found->support.rbegin(); it != found->support.rend(); ++it) {
    BufferedStep& b = buffer[it->first];
    b.scan.ranges_m.erase(b.scan.ranges_m.begin() + static_cast<std::ptrdiff_t>(it->second));
    b.amplitudes.erase(b.amplitudes.begin() + static_cast<std::ptrdiff_t>(it->second));
  }
  return find;
}

}  // namespace mirage::methods::slam
