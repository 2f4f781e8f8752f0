// SPDX-License-Identifier: MIT
#include "mirage/channel/diffuse_multipath.h"

#include <cmath>

namespace mirage::channel {

const core::OptionsDescriptor<DiffuseOptions>& DiffuseOptionsDescriptor() {
  using core::ValueRange;
  using O = DiffuseOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("channel::DiffuseOptions");
    d.Boolean(&O::enabled, {.key = "enabled", .doc = "Simulate diffuse multipath at all."});
    d.Number(&O::power_ratio_db,
             {.key = "power_ratio_db",
              .unit = "dB",
              .range = ValueRange::Closed(-200.0, 100.0),
              .doc = "Total diffuse energy relative to the free-space LOS energy at the LOS distance (an inverse "
                     "K-factor). 0 dB puts first-order reflections at about -5 to +10 dB SINR and the LOS at 20-30 dB "
                     "at 3 m, as measured UWB channels show."});
    d.Number(&O::decay_s, {.key = "decay_s",
                           .unit = "s",
                           .range = ValueRange::Closed(1e-12, 1.0),
                           .doc = "Decay time constant gamma_1 of the power delay profile. 20 ns, typical of an "
                                  "indoor office."});
    d.Number(&O::rise_s, {.key = "rise_s",
                          .unit = "s",
                          .range = ValueRange::Closed(1e-12, 1.0),
                          .doc = "Rise time constant gamma_rise of the power delay profile. 5 ns."});
    d.Number(&O::rise_weight, {.key = "rise_weight",
                               .range = ValueRange::Closed(0.0, 1.0),
                               .doc = "Rise weight chi: 0 is an instantaneous start, 1 a profile that starts at zero. "
                                      "0.98."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const DiffuseOptions& options) {
  return DiffuseOptionsDescriptor().Validate(options);
}

double DiffusePdpShape(const DiffuseOptions& options, double excess_delay_s) {
  if (excess_delay_s < 0.0) return 0.0;
  const double g1 = options.decay_s;
  const double gr = options.rise_s;
  const double chi = options.rise_weight;
  const double area = g1 - chi * g1 * gr / (g1 + gr);
  return (1.0 - chi * std::exp(-excess_delay_s / gr)) * std::exp(-excess_delay_s / g1) / area;
}

}  // namespace mirage::channel
