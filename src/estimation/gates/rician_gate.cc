// SPDX-License-Identifier: MIT
#include "mirage/estimation/gates/rician_gate.h"

#include <algorithm>
#include <cmath>

namespace mirage::estimation {

std::optional<RicianLaw> RicianFromMoments(double m1, double var_y) {
  if (!(m1 > 0.0) || !std::isfinite(m1) || !std::isfinite(var_y)) return std::nullopt;
  const double discriminant = m1 * m1 - std::max(var_y, 0.0);
  const double a2 = discriminant > 0.0 ? std::sqrt(discriminant) : 0.0;
  RicianLaw law;
  law.scatter_power = std::max(m1 - a2, 1e-4 * m1);
  law.nu = std::sqrt(std::max(m1 - law.scatter_power, 0.0));
  return law;
}

double RicianCdf(double r, const RicianLaw& law) {
  if (!(r > 0.0)) return 0.0;
  const double s2 = law.scatter_power;
  const double k = law.nu * law.nu / s2;  // K-factor: the Poisson mean of the mixture
  const double eta = r * r / s2;          // x / 2 below
  // exp(-k) and exp(-eta) must stay representable; beyond, the Gaussian is accurate (large K)
  // or the CDF is 1 to double precision (r far above the scatter, small K).
  if (k > 600.0 || eta > 700.0) {
    // |a + n| = |nu + x + i y| ~ nu + x + y^2 / (2 nu): Gaussian with mean nu + sigma^2 / (2 nu)
    // and variance sigma^2 = s^2 / 2 for large K (Rice 1944).
    const double sigma2 = s2 / 2.0;
    const double mean = law.nu + sigma2 / (2.0 * law.nu);
    return 0.5 * std::erfc(-(r - mean) / std::sqrt(2.0 * sigma2));
  }
  // With sigma^2 = s^2 / 2: R^2 / sigma^2 is non-central chi-square with 2 degrees of freedom
  // and non-centrality 2K, i.e. a Poisson(K) mixture over j of central chi-square with 2 + 2j
  // degrees of freedom, and P(chi2_{2m} <= x) = P(Poisson(x / 2) >= m). Both sums run together.
  double p_j = std::exp(-k);      // Poisson(K) pmf at j
  double q_i = std::exp(-eta);    // Poisson(eta) pmf at i = j
  double q_cdf = q_i;             // P(Poisson(eta) <= j)
  double cdf = 0.0;
  double weight = 0.0;
  const int last = static_cast<int>(k + 12.0 * std::sqrt(k) + 40.0);
  for (int j = 0; j <= last; ++j) {
    cdf += p_j * std::max(1.0 - q_cdf, 0.0);
    weight += p_j;
    p_j *= k / (j + 1);
    q_i *= eta / (j + 1);
    q_cdf += q_i;
  }
  return std::clamp(cdf / weight, 0.0, 1.0);
}

}  // namespace mirage::estimation
