// SPDX-License-Identifier: MIT
// Summary statistics of position errors: RMSE, mean, percentiles, max; and the divergence rule
// of the JSON report (ROADMAP.md).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"

namespace mirage::eval {

/// Error statistics (m).
struct ErrorStats {
  double rmse = 0.0;
  double mean = 0.0;
  double p50 = 0.0;
  double p90 = 0.0;
  double p95 = 0.0;
  double max = 0.0;
  std::size_t count = 0;
};

/// Percentile q in [0, 100] by linear interpolation between order statistics (the "linear"
/// method of numpy.percentile). values must not be empty.
double Percentile(std::vector<double> values, double q);

/// Statistics of the errors; all zero for an empty input.
ErrorStats ComputeErrorStats(std::span<const double> errors_m);

/// A run diverged when its mean error over the last `last_fraction` of the steps exceeds
/// `threshold_m`.
struct DivergenceRule {
  /// Error threshold (m), in [1e-9, 1e9]. 0.5 m, mirage's default rule; every report states the
  /// rule it used.
  double threshold_m = 0.5;
  /// Fraction of the final steps that is averaged, in [1e-9, 1]. 0.2.
  double last_fraction = 0.2;
};

/// The rule's descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<DivergenceRule>& DivergenceRuleDescriptor();

/// Problems with the rule ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const DivergenceRule& rule);

/// True if the run with these per-step errors diverged.
bool IsDiverged(std::span<const double> errors_m, const DivergenceRule& rule);

/// Human-readable statement of the rule, for the report.
std::string Describe(const DivergenceRule& rule);

}  // namespace mirage::eval
