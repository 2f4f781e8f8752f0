// SPDX-License-Identifier: MIT
// Amplitude gate of an association: is a measured MPC amplitude plausible for a path whose
// amplitudes so far follow a Rician law? Y = |a + n|^2 with n ~ CN(0, s^2) is the model of
// Lafer 2014 Eq. (3.25)-(3.26) (the SINR estimator fits K = |a|^2 / s^2 to the same window);
// a blocked path's "range" is a diffuse-multipath peak far weaker than the path's history, which
// the range alone cannot tell (mirage; the papers gate on ranges only).
#pragma once

#include <optional>

namespace mirage::estimation {

/// A Rician amplitude law: |a| = nu, complex scatter power s^2.
struct RicianLaw {
  double nu = 0.0;             ///< line-of-sight amplitude |a| (>= 0)
  double scatter_power = 0.0;  ///< s^2 = E|n|^2 (> 0)
};

/// The law whose Y = |a + n|^2 has mean m1 and variance var_y (method of moments, Lafer Eq.
/// 3.26 as the digest reads it): |a|^2 = sqrt(m1^2 - var_y), s^2 = m1 - |a|^2; a window with
/// var_y >= m1^2 is Rayleigh (nu = 0). s^2 is kept >= 1e-4 m1 (K <= 40 dB) so that a window
/// of nearly constant amplitudes does not make every other amplitude impossible. Empty for
/// m1 <= 0 or non-finite input.
std::optional<RicianLaw> RicianFromMoments(double m1, double var_y);

/// P(|a + n| <= r): the Rician CDF 1 - Q_1(nu / sigma, r / sigma) with sigma^2 = s^2 / 2, as a
/// Poisson mixture of central chi-square CDFs for K <= 600, and the Gaussian approximation
/// N(nu + sigma^2 / (2 nu), sigma^2) of the amplitude above, where it is accurate to < 1e-3.
double RicianCdf(double r, const RicianLaw& law);

}  // namespace mirage::estimation
