// SPDX-License-Identifier: MIT
#include "mirage/eval/error_stats.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

namespace mirage::eval {

double Percentile(std::vector<double> values, double q) {
  assert(!values.empty() && q >= 0.0 && q <= 100.0);
  std::sort(values.begin(), values.end());
  const double position = q / 100.0 * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(position));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  const double frac = position - static_cast<double>(lo);
  return values[lo] + frac * (values[hi] - values[lo]);
}

ErrorStats ComputeErrorStats(std::span<const double> errors_m) {
  ErrorStats s;
  s.count = errors_m.size();
  if (errors_m.empty()) return s;
  const std::vector<double> v(errors_m.begin(), errors_m.end());
  const double n = static_cast<double>(v.size());
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / n;
  s.rmse = std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0) / n);
  s.p50 = Percentile(v, 50.0);
  s.p90 = Percentile(v, 90.0);
  s.p95 = Percentile(v, 95.0);
  s.max = *std::max_element(v.begin(), v.end());
  return s;
}

const core::OptionsDescriptor<DivergenceRule>& DivergenceRuleDescriptor() {
  using core::ValueRange;
  using O = DivergenceRule;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("eval::DivergenceRule");
    d.Number(&O::threshold_m, {.key = "threshold_m",
                               .unit = "m",
                               .range = ValueRange::Positive(),
                               .doc = "A run diverged when its mean position error over the last part exceeds this. "
                                      "0.5 m, mirage's default rule; every report states the rule it used."});
    d.Number(&O::last_fraction, {.key = "last_fraction",
                                 .range = ValueRange::Closed(core::kTinyOption, 1.0),
                                 .doc = "The last part: this fraction of the run's final steps is averaged. 0.2."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const DivergenceRule& rule) { return DivergenceRuleDescriptor().Validate(rule); }

bool IsDiverged(std::span<const double> errors_m, const DivergenceRule& rule) {
  if (errors_m.empty()) return false;
  const auto n = errors_m.size();
  // The relative slack keeps products like 0.07 * 100 = 7.000000000000001 from rounding up.
  const double exact = rule.last_fraction * static_cast<double>(n);
  const auto tail = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(exact - 1e-9 * std::max(1.0, exact))));
  const auto last = errors_m.subspan(n - tail);
  const double mean = std::accumulate(last.begin(), last.end(), 0.0) / static_cast<double>(tail);
  return mean > rule.threshold_m;
}

std::string Describe(const DivergenceRule& rule) {
  return fmt::format("a run diverged if its mean position error over the last {:g} % of its steps exceeds {:g} m",
                     100.0 * rule.last_fraction, rule.threshold_m);
}

}  // namespace mirage::eval
