// SPDX-License-Identifier: MIT
// Ranging-level measurements: what a ranging system (UWB two-way ranging, a time-of-flight tag)
// or a range-only benchmark reports per anchor and epoch, drawn directly from the geometry
// instead of from a channel: each path's length plus Gaussian noise of a fixed standard
// deviation, a detection probability, and clutter ranges uniform over the system's range (a
// wrong peak). With multipath, every visible specular path of the floor plan is a range too (the
// range-level benchmark of multipath SLAM: no amplitudes, fixed noise); without, only the line
// of sight. The channel-level simulators (cir_synthesizer, range_level_simulator) model the
// SINR-dependent noise behind such numbers.
#pragma once

#include <span>
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
  /// Every visible specular path up to the channel's max_order is measured, not only the line of
  /// sight.
  bool multipath = false;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<RangingOptions>& RangingOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const RangingOptions& options);

/// The ranges of one anchor at one epoch: each true path length (the line of sight first) plus
/// noise if detected, then the clutter; every draw from `rng` (one stream per anchor).
std::vector<core::RangeMeasurement> SimulateRanging(const RangingOptions& options, std::span<const double> true_ranges_m,
                                                    core::Rng& rng);

}  // namespace mirage::channel
