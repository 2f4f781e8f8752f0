// SPDX-License-Identifier: MIT
// Diffuse multipath (DM): a zero-mean complex Gaussian process, uncorrelated in delay, whose
// power delay profile (PDP) starts at the line-of-sight delay with a double-exponential shape
// (Lafer 2014 Eq. 2.5; shape from the IEEE 802.15.4a-style model in the digest, Sec. 6.2 item 4).
// The thesis's own synthetic data had no DM; the digest calls it essential for realism.
#pragma once

#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"

namespace mirage::channel {

/// Parameters of the DM power delay profile S_nu(tau).
struct DiffuseOptions {
  /// Whether DM is simulated at all.
  bool enabled = true;
  /// Total DM energy relative to the free-space LOS energy at the LOS distance (dB), i.e. the
  /// inverse of a K-factor, in [-200, 100]. 0 dB puts first-order reflections at about -5 ... +10
  /// dB SINR and the LOS at 20-30 dB at 3 m, the range measured UWB channels show.
  double power_ratio_db = 0.0;
  /// Decay time constant gamma_1 (s), in [1e-12, 1]. 20 ns, typical indoor office.
  double decay_s = 20e-9;
  /// Rise time constant gamma_rise (s), in [1e-12, 1]. 5 ns.
  double rise_s = 5e-9;
  /// Rise weight chi in [0, 1]: 0 means an instantaneous start, 1 a PDP that starts at zero.
  double rise_weight = 0.98;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<DiffuseOptions>& DiffuseOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const DiffuseOptions& options);

/// Unit-area PDP shape at excess delay tau - tau_LOS (1/s):
/// (1 - chi e^{-t/gamma_rise}) e^{-t/gamma_1} / A, with A = gamma_1 - chi gamma_1 gamma_rise /
/// (gamma_1 + gamma_rise), and 0 before the LOS. (The digest's normalisation constant does not
/// integrate to 1; this one does, so that power_ratio_db is exactly the DM-to-LOS energy ratio.)
double DiffusePdpShape(const DiffuseOptions& options, double excess_delay_s);

}  // namespace mirage::channel
