// SPDX-License-Identifier: MIT
#include "mirage/channel/diffuse_multipath.h"

#include <cmath>

namespace mirage::channel {

std::vector<std::string> Validate(const DiffuseOptions& options) {
  std::vector<std::string> problems;
  if (!std::isfinite(options.power_ratio_db)) problems.push_back("power_ratio_db must be a finite number of dB");
  if (!(options.decay_s > 0.0) || !std::isfinite(options.decay_s)) problems.push_back("decay_s must be > 0 s");
  if (!(options.rise_s > 0.0) || !std::isfinite(options.rise_s)) problems.push_back("rise_s must be > 0 s");
  if (!(options.rise_weight >= 0.0 && options.rise_weight <= 1.0)) problems.push_back("rise_weight must be in [0, 1]");
  return problems;
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
