// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/va_sweep.h"

#include <algorithm>
#include <cmath>

#include "mirage/core/derived_defaults.h"
#include "mirage/estimation/init/range_point_fit.h"
#include "mirage/methods/elapsed_time.h"

namespace mirage::methods::slam {

const core::OptionsDescriptor<SweepOptions>& SweepOptionsDescriptor() {
  using core::ValueRange;
  using O = SweepOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("methods::slam::SweepOptions");
    d.Boolean(&O::enabled, {.key = "enabled",
                            .doc = "Run the sweep (stage D', mirage): a consensus search for far VAs over the last "
                                   "steps' unexplained ranges."});
    d.Number(&O::window_s, {.key = "window_s",
                            .unit = "s",
                            .range = ValueRange::Positive(),
                            .doc = "How far back ranges are searched. 6 s (60 steps of 0.1 s). Derived: the time to "
                                   "walk 3 m, within which the buffered positions must span min_baseline_m.",
                            .derived = core::WalkingTime(3.0)});
    d.Retired("window_steps", "window_s", "seconds, not steps: the old value times dt_s (60 steps of 0.1 s = 6 s), or leave it out for the default derived from speed_mps");
    d.Integer(&O::every_steps,
              {.key = "every_steps",
               .unit = "steps",
               .range = ValueRange::Closed(1.0, 1e5),
               .doc = "The sweep runs for an anchor every this many steps, the anchors on different steps. A search "
                      "costs about 130 us at 15 unexplained ranges per step; 10 instead of 5 halves the cost for a "
                      "p90 0-0.3 cm worse in the seminar room."});
    d.Number(&O::min_baseline_m, {.key = "min_baseline_m",
                                  .unit = "m",
                                  .range = ValueRange::Positive(),
                                  .doc = "The buffered agent positions must span at least this distance: two circles "
                                         "intersect well only over a long baseline. 1 m."});
    d.Number(&O::gate_m, {.key = "gate_m",
                          .unit = "m",
                          .range = ValueRange::Positive(),
                          .doc = "A range supports a point within this distance of its predicted range: range noise "
                                 "(1-2 cm) plus the agent's error (2-3 cm). 4 cm. Derived: 2 range sigmas, 95 % of the "
                                 "VA's ranges (the agent's error over the buffer is mostly absorbed by the point).",
                          .derived = core::RangeSigmas(2.0)});
    d.Number(&O::min_support_fraction,
             {.key = "min_support_fraction",
              .range = ValueRange::Closed(core::kTinyOption, 1.0),
              .doc = "Smallest fraction of the buffered steps that must support a point. A wrong point collects about "
                     "10 % of the steps within a 4 cm gate, a VA extracted at 80 % of the steps 80 %; 0.5 and 0.7 "
                     "gave p90 within 0.5 cm of 0.6 (seminar room)."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const SweepOptions& options) { return SweepOptionsDescriptor().Validate(options); }

VaSweep::VaSweep(const SweepOptions& options, int min_measurements, double exclusion_radius_m)
    : options_(options), min_measurements_(min_measurements), exclusion_radius_m_(exclusion_radius_m) {}

void VaSweep::Reset() { buffers_.clear(); }

std::size_t VaSweep::buffered_steps(int anchor_index) const {
  const auto a = static_cast<std::size_t>(anchor_index);
  return a < buffers_.size() ? buffers_[a].times_s.size() : 0;
}

std::size_t VaSweep::buffered_ranges(int anchor_index) const {
  const auto a = static_cast<std::size_t>(anchor_index);
  std::size_t count = 0;
  if (a < buffers_.size()) {
    for (const auto& scan : buffers_[a].scans) count += scan.ranges_m.size();
  }
  return count;
}

void VaSweep::Buffer(double t_s, int anchor_index, const Vec2& agent_m,
                     std::span<const core::RangeMeasurement> ranges, const std::vector<bool>& used) {
  if (!options_.enabled || !agent_m.allFinite()) return;
  const auto anchor = static_cast<std::size_t>(anchor_index);
  if (buffers_.size() <= anchor) buffers_.resize(anchor + 1);
  AnchorBuffer& buffer = buffers_[anchor];
  // Steps older than the window leave from the front.
  const auto old = static_cast<std::ptrdiff_t>(
      std::find_if(buffer.times_s.begin(), buffer.times_s.end(),
                   [&](double s) { return !Reaches(t_s - s, options_.window_s); }) -
      buffer.times_s.begin());
  buffer.times_s.erase(buffer.times_s.begin(), buffer.times_s.begin() + old);
  buffer.scans.erase(buffer.scans.begin(), buffer.scans.begin() + old);
  buffer.amplitudes.erase(buffer.amplitudes.begin(), buffer.amplitudes.begin() + old);
  // The ranges no candidate took, sorted (the consensus search looks them up by value).
  std::vector<core::RangeMeasurement> free;
  for (std::size_t j = 0; j < ranges.size(); ++j) {
    if (!used[j] && std::isfinite(ranges[j].range_m)) free.push_back(ranges[j]);
  }
  std::sort(free.begin(), free.end(),
            [](const core::RangeMeasurement& a, const core::RangeMeasurement& b) { return a.range_m < b.range_m; });
  estimation::RangeScan scan;
  scan.position_m = agent_m;
  std::vector<std::optional<double>> amplitudes;
  for (const auto& z : free) {
    scan.ranges_m.push_back(z.range_m);
    amplitudes.push_back(z.amplitude);
  }
  buffer.times_s.push_back(t_s);
  buffer.scans.push_back(std::move(scan));
  buffer.amplitudes.push_back(std::move(amplitudes));
}

bool VaSweep::Due(int step, int anchor_index) const {
  return options_.enabled && (step + anchor_index) % options_.every_steps == 0;
}

std::optional<SweepFind> VaSweep::Search(int step, int anchor_index, std::span<const Vec2> excluded_m) {
  if (!Due(step, anchor_index) || static_cast<std::size_t>(anchor_index) >= buffers_.size()) return std::nullopt;
  AnchorBuffer& buffer = buffers_[static_cast<std::size_t>(anchor_index)];
  const std::size_t n = buffer.scans.size();
  const Vec2 first_m = n > 0 ? buffer.scans.front().position_m : Vec2::Zero();
  double span_m = 0.0;
  for (const auto& scan : buffer.scans) span_m = std::max(span_m, (scan.position_m - first_m).norm());
  if (n < 3 || span_m < options_.min_baseline_m) return std::nullopt;
  estimation::RangeConsensusOptions search;
  search.gate_m = options_.gate_m;
  // The fraction of the buffered steps, and never fewer ranges than a candidate needs to be
  // promoted (N_rls).
  search.min_support = static_cast<std::size_t>(
      std::max<double>(std::ceil(options_.min_support_fraction * static_cast<double>(n)), min_measurements_));
  search.min_pair_distance_m = 0.5 * options_.min_baseline_m;
  search.exclusion_radius_m = exclusion_radius_m_;
  const auto found = estimation::FindRangeConsensus(buffer.scans, excluded_m, search);
  if (!found) return std::nullopt;
  SweepFind find;
  std::vector<Vec2> positions_m;
  std::vector<double> ranges_m;
  for (const auto& [k, j] : found->support) {
    const estimation::RangeScan& scan = buffer.scans[k];
    find.samples.push_back({scan.position_m, scan.ranges_m[j], buffer.amplitudes[k][j]});
    positions_m.push_back(scan.position_m);
    ranges_m.push_back(scan.ranges_m[j]);
  }
  // The point and its mirror image, each fitted to the ranges (for a straight walk both fit).
  find.starts = {found->position_m, found->mirror_m};
  for (auto& start : find.starts) {
    if (const auto fit = estimation::FitPointToRanges(positions_m, ranges_m, start)) start = fit->position_m;
  }
  // The supporting ranges leave the buffer. support holds at most one range per step, steps in
  // ascending order, so erasing from the back keeps the remaining indices valid.
  for (auto it = found->support.rbegin(); it != found->support.rend(); ++it) {
    auto& ranges_at = buffer.scans[it->first].ranges_m;
    auto& amplitudes_at = buffer.amplitudes[it->first];
    ranges_at.erase(ranges_at.begin() + static_cast<std::ptrdiff_t>(it->second));
    amplitudes_at.erase(amplitudes_at.begin() + static_cast<std::ptrdiff_t>(it->second));
  }
  return find;
}

}  // namespace mirage::methods::slam
