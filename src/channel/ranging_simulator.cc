// SPDX-License-Identifier: MIT
#include "mirage/channel/ranging_simulator.h"

#include <cmath>

namespace mirage::channel {

std::vector<std::string> Validate(const RangingOptions& o) {
  std::vector<std::string> problems;
  if (!(o.range_sigma_m > 0.0) || !std::isfinite(o.range_sigma_m)) problems.push_back("range_sigma_m must be > 0 m");
  if (!(o.detection_probability >= 0.0 && o.detection_probability <= 1.0)) {
    problems.push_back("detection_probability must be in [0, 1]");
  }
  if (!(o.clutter_rate >= 0.0) || !std::isfinite(o.clutter_rate)) problems.push_back("clutter_rate must be >= 0");
  if (!(o.max_range_m > 0.0) || !std::isfinite(o.max_range_m)) problems.push_back("max_range_m must be > 0 m");
  return problems;
}

std::vector<core::RangeMeasurement> SimulateRanging(const RangingOptions& options, double true_range_m, core::Rng& rng) {
  std::vector<core::RangeMeasurement> out;
  // Draw noise and detection every time, so that the stream does not depend on the outcome.
  const bool detected = rng.Bernoulli(options.detection_probability);
  const double noise_m = rng.Normal(0.0, options.range_sigma_m);
  if (detected) out.push_back({true_range_m + noise_m, std::nullopt});
  const int clutter = rng.Poisson(options.clutter_rate);
  for (int i = 0; i < clutter; ++i) out.push_back({rng.Uniform(0.0, options.max_range_m), std::nullopt});
  return out;
}

}  // namespace mirage::channel
