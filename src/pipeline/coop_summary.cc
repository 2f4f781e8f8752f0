// SPDX-License-Identifier: MIT
#include "mirage/pipeline/coop_summary.h"

#include <algorithm>
#include <cmath>

#include "mirage/eval/error_stats.h"

namespace mirage::pipeline {

std::vector<CoopVariantSummary> SummarizeCoop(const CoopExperimentResult& result) {
  std::vector<CoopVariantSummary> out;
  for (const auto& v : result.variants) {
    CoopVariantSummary s;
    s.variant = v.variant;
    s.name = v.variant.Name();
    s.runs = static_cast<int>(v.runs.size());
    std::vector<double> errors, relative, finals, bias_finals;
    double sum_sq = 0.0, tracked_sq = 0.0, associated = 0.0, expected = 0.0, wall = 0.0;
    int tracked_count = 0, step_count = 0;
    const std::size_t steps = v.runs.empty() ? 0 : v.runs.front().error_m.size();
    s.error_by_step_m.assign(steps, 0.0);
    for (const auto& run : v.runs) {
      for (std::size_t n = 1; n < run.error_m.size(); ++n) {
        for (std::size_t m = 0; m < run.error_m[n].size(); ++m) {
          const double e = run.error_m[n][m];
          errors.push_back(e);
          relative.push_back(run.relative_error_m[n][m]);
          sum_sq += e * e;
          if (!run.diverged) {
            tracked_sq += e * e;
            ++tracked_count;
          }
        }
        associated += run.associated[n];
        expected += run.expected[n];
        ++step_count;
      }
      for (std::size_t n = 0; n < run.error_m.size(); ++n) {
        double mean = 0.0;
        for (const double e : run.error_m[n]) mean += e;
        s.error_by_step_m[n] += mean / static_cast<double>(run.error_m[n].size()) / static_cast<double>(v.runs.size());
      }
      for (const double e : run.error_m.back()) finals.push_back(e);
      s.diverged += run.diverged ? 1 : 0;
      if (!run.bias_wall_error_m.empty()) bias_finals.push_back(std::abs(run.bias_wall_error_m.back()));
      wall += run.wall_rms_error_m;
    }
    if (!errors.empty()) {
      s.error_p50_m = eval::Percentile(errors, 50.0);
      s.error_p90_m = eval::Percentile(errors, 90.0);
      s.error_rmse_m = std::sqrt(sum_sq / static_cast<double>(errors.size()));
      s.relative_p90_m = eval::Percentile(relative, 90.0);
    }
    if (!finals.empty()) {
      double sum = 0.0;
      for (const double e : finals) sum += e;
      s.final_mean_m = sum / static_cast<double>(finals.size());
      s.final_p90_m = eval::Percentile(finals, 90.0);
    }
    double peb_sq = 0.0;
    int peb_count = 0;
    s.peb_by_step_m.assign(v.peb_m.size(), 0.0);
    for (std::size_t n = 0; n < v.peb_m.size(); ++n) {
      double step_sq = 0.0;
      for (const double b : v.peb_m[n]) step_sq += b * b;
      s.peb_by_step_m[n] = std::sqrt(step_sq / static_cast<double>(std::max<std::size_t>(1, v.peb_m[n].size())));
      if (n == 0) continue;
      peb_sq += step_sq;
      peb_count += static_cast<int>(v.peb_m[n].size());
    }
    if (peb_count > 0) s.peb_rms_m = std::sqrt(peb_sq / peb_count);
    if (s.peb_rms_m > 0.0) {
      s.rmse_over_peb = s.error_rmse_m / s.peb_rms_m;
      if (tracked_count > 0) s.tracked_rmse_over_peb = std::sqrt(tracked_sq / tracked_count) / s.peb_rms_m;
    }
    s.has_bias = !bias_finals.empty();
    if (s.has_bias) {
      double sum = 0.0;
      for (const double e : bias_finals) sum += e;
      s.bias_final_mean_abs_m = sum / static_cast<double>(bias_finals.size());
      s.bias_final_p90_abs_m = eval::Percentile(bias_finals, 90.0);
    }
    if (s.runs > 0) s.wall_rms_mean_m = wall / s.runs;
    if (step_count > 0) {
      s.associated_per_step = associated / step_count;
      s.expected_per_step = expected / step_count;
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace mirage::pipeline
