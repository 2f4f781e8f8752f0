// SPDX-License-Identifier: MIT
// Ranging-level measurements: what a ranging system (UWB two-way ranging, a time-of-flight tag)
// reports per anchor and epoch, drawn directly from the geometry instead of from a channel: the
// 3-D distance plus Gaussian noise of a fixed standard deviation, a detection probability, and
// clutter ranges uniform over the system's range (a wrong peak, a reflection taken for the
// first path). The channel-level simulators (cir_synthesizer, range_level_simulator) model the
// multipath behind such numbers; this one is the plain input of a range EKF.
#pragma once

#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/records.h"
#include "mirage/core/rng.h"

namespace mirage::channel {

/// Parameters of the ranging simulation.
struct RangingOptions {
  /// Standard deviation of a range (m), > 0. 0.1 m, typical of UWB two-way ranging.
  double range_sigma_m = 0.1;
  /// Probability that an anchor's range arrives at an epoch, in [0, 1].
  double detection_probability = 1.0;
  /// Mean number of clutter ranges per anchor and epoch (Poisson), >= 0.
  double clutter_rate = 0.0;
  /// Clutter ranges are uniform on [0, max_range_m] (m), > 0.
  double max_range_m = 30.0;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<RangingOptions>& RangingOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const RangingOptions& options);

/// The ranges of one anchor at one epoch: the true distance plus noise if detected, then the
/// clutter; every draw from `rng` (one stream per anchor).
std::vector<core::RangeMeasurement> SimulateRanging(const RangingOptions& options, double true_range_m, core::Rng& rng);

}  // namespace mirage::channel
