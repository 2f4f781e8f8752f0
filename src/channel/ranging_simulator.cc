// SPDX-License-Identifier: MIT
#include "mirage/channel/ranging_simulator.h"

namespace mirage::channel {

const core::OptionsDescriptor<RangingOptions>& RangingOptionsDescriptor() {
  using core::ValueRange;
  using O = RangingOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("channel::RangingOptions");
    d.Number(&O::range_sigma_m, {.key = "range_sigma_m",
                                 .unit = "m",
                                 .range = ValueRange::Above(0.0),
                                 .doc = "Standard deviation of a range. 0.1 m, typical of UWB two-way ranging."});
    d.Number(&O::detection_probability,
             {.key = "detection_probability",
              .range = ValueRange::Closed(0.0, 1.0),
              .doc = "Probability that an anchor's range arrives at an epoch. 1: every one does."});
    d.Number(&O::clutter_rate, {.key = "clutter_rate",
                                .range = ValueRange::AtLeast(0.0),
                                .doc = "Mean number of clutter ranges per anchor and epoch (Poisson). 0: no clutter."});
    d.Number(&O::max_range_m, {.key = "max_range_m",
                               .unit = "m",
                               .range = ValueRange::Above(0.0),
                               .doc = "Clutter ranges are uniform on [0, max_range_m]."});
    d.Boolean(&O::multipath, {.key = "multipath",
                              .doc = "Every visible specular path up to channel.max_order gives a range, not only the "
                                     "line of sight (a range-level multipath benchmark)."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const RangingOptions& options) {
  return RangingOptionsDescriptor().Validate(options);
}

std::vector<core::RangeMeasurement> SimulateRanging(const RangingOptions& options, std::span<const double> true_ranges_m,
                                                    core::Rng& rng) {
  std::vector<core::RangeMeasurement> out;
  for (const double range_m : true_ranges_m) {
    // Draw noise and detection every time, so that the stream does not depend on the outcome.
    const bool detected = rng.Bernoulli(options.detection_probability);
    const double noise_m = rng.Normal(0.0, options.range_sigma_m);
    if (detected) out.push_back({range_m + noise_m, std::nullopt});
  }
  const int clutter = rng.Poisson(options.clutter_rate);
  for (int i = 0; i < clutter; ++i) out.push_back({rng.Uniform(0.0, options.max_range_m), std::nullopt});
  return out;
}

}  // namespace mirage::channel
