// SPDX-License-Identifier: MIT
// The chi-square distribution with an integer number of degrees of freedom: its CDF and
// quantile, so that a gate stated for one degree of freedom (gate_chi2 = 9, 3 sigma) carries the
// same tail probability to a test of d dimensions (a 3-D position: 14.2).
#pragma once

namespace mirage::estimation {

/// P(X <= x) for X ~ chi^2 with `dof` >= 1 degrees of freedom; 0 for x <= 0.
double Chi2Cdf(double x, int dof);

/// The x with Chi2Cdf(x, dof) = p, for p in [0, 1) and dof >= 1 (bisection to 1e-12 relative).
double Chi2Quantile(double p, int dof);

/// The threshold of a `dof`-dimensional test with the tail probability of the one-dimensional
/// gate gamma_1dof (> 0): Chi2Quantile(Chi2Cdf(gamma_1dof, 1), dof).
double Chi2ThresholdLike1Dof(double gamma_1dof, int dof);

}  // namespace mirage::estimation
