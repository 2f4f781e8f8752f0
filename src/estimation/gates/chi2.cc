// SPDX-License-Identifier: MIT
#include "mirage/estimation/gates/chi2.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace mirage::estimation {

double Chi2Cdf(double x, int dof) {
  assert(dof >= 1);
  if (!(x > 0.0)) return 0.0;
  // Start from 1 or 2 degrees of freedom in closed form and step up by two:
  // P(k + 2, x) = P(k, x) - (x/2)^(k/2) e^(-x/2) / Gamma(k/2 + 1).
  const bool odd = dof % 2 == 1;
  double cdf = odd ? std::erf(std::sqrt(0.5 * x)) : 1.0 - std::exp(-0.5 * x);
  for (int k = odd ? 1 : 2; k + 2 <= dof; k += 2) {
    const double half_k = 0.5 * k;
    cdf -= std::exp(half_k * std::log(0.5 * x) - 0.5 * x - std::lgamma(half_k + 1.0));
  }
  return cdf < 0.0 ? 0.0 : cdf;
}

double Chi2Quantile(double p, int dof) {
  assert(dof >= 1 && p >= 0.0 && p < 1.0);
  if (p == 0.0) return 0.0;
  double lo = 0.0;
  double hi = static_cast<double>(dof) + 10.0;
  while (Chi2Cdf(hi, dof) < p) hi *= 2.0;
  while (hi - lo > 1e-12 * hi) {
    const double mid = 0.5 * (lo + hi);
    (Chi2Cdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double Chi2ThresholdLike1Dof(double gamma_1dof, int dof) {
  assert(gamma_1dof > 0.0);
  return Chi2Quantile(Chi2Cdf(gamma_1dof, 1), dof);
}

}  // namespace mirage::estimation
