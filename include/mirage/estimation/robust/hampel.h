// SPDX-License-Identifier: MIT
// Hampel's redescending hyperbolic-tangent weight (Bordoy 2020 PhD thesis, Univ. Freiburg, Sec. 5.2,
// Eq. 5.24; Hampel et al. 1986): w = 1 up to the clipping point a, a tanh taper to 0 at b = 4a,
// and 0 beyond, so that gross errors (NLOS timestamps, a bad prediction) are rejected outright.
// a = 1.4826 MAD / theta is set from the residuals' median absolute deviation.
// Choices where the thesis is silent (digest Sec. 2.7, typo list item 7):
//  - the middle branch uses |r| (the thesis prints r_i), so w is even in r;
//  - d is the root of d tanh(d (b - a) / 2) = a, which makes w continuous at a (w(b) = 0 holds
//    for any d). That equation is not scale invariant (d tanh(.) has the unit 1/[r], a the unit
//    [r]), so the weight's shape depends on the residuals' unit: it is meant for whitened
//    (unit-variance) residuals, as in the REKF (irls_update.h);
//  - theta defaults to 0.5 (see HampelOptions::theta) and a is floored at min_a, because the MAD
//    of few or exactly fitting residuals can be 0.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"

namespace mirage::estimation {

/// Tuning of the Hampel tanh weight, Bordoy Eq. (5.24).
struct HampelOptions {
  /// The tuning parameter theta of a = 1.4826 MAD / theta, > 0. The thesis gives no value.
  /// 1.4826 MAD estimates the residuals' standard deviation sigma for Gaussian residuals, so
  /// a = sigma / theta: 1 puts a at the robust sigma itself and b = 4a at 4 sigma, beyond which a
  /// residual is rejected outright; in between the weight falls smoothly. A larger a (theta 0.5:
  /// 2 and 8 sigma) lets NLOS stamps of a few decimetres keep part of their weight, which in the
  /// ch. 5 synthetic regime doubles the REKF's mean error (docs/methods/acoustic.md, ablation).
  double theta = 1.0;
  /// b / a, the ratio of the rejection point to the clipping point, > 1. 4 as in the thesis.
  double b_over_a = 4.0;
  /// Floor of the clipping point a (the residuals' unit), > 0. The MAD is 0 when more than half
  /// the residuals fit exactly (few rows, prior rows of an update that the measurements barely
  /// move), which would make a = b = 0 and reject every row. 1.0 suits whitened residuals: a is
  /// never below one standard deviation of a consistent residual. Set it in the residuals' unit
  /// for unwhitened residuals.
  double min_a = 1.0;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<HampelOptions>& HampelOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const HampelOptions& options);

/// The clipping points and the continuity constant of Eq. (5.24), in the residuals' unit (d in
/// its inverse).
struct HampelParameters {
  /// End of the unit-weight branch, > 0.
  double a = 1.0;
  /// Rejection point (weight 0 beyond), > a.
  double b = 4.0;
  /// Continuity constant: d tanh(d (b - a) / 2) = a.
  double d = 1.0;
};

/// The median of the values (the mean of the two middle ones for an even count); 0 if empty.
double Median(std::span<const double> values);

/// The median absolute deviation about the median, median(|r - median(r)|), in the values' unit;
/// 0 if empty. Not scaled: 1.4826 MAD estimates a Gaussian's standard deviation.
double Mad(std::span<const double> values);

/// The parameters for a given clipping point a (> 0) and ratio b / a (> 1): b = ratio a, and d
/// solved by safeguarded Newton iteration to relative 1e-14.
HampelParameters HampelFromClippingPoint(double a, double b_over_a);

/// The parameters of the residuals: a = max(1.4826 MAD(r) / theta, min_a), b = b_over_a a, d
/// from continuity. See Eq. (5.24) and the text under it.
/// @param residuals the residuals (any unit; whitened for the default min_a); may be empty
///                  (then a = min_a).
HampelParameters HampelFromResiduals(std::span<const double> residuals, const HampelOptions& options);

/// The weight w(r) of Eq. (5.24), in [0, 1]: 1 for |r| <= a, d tanh(d (b - |r|) / 2) / |r| for
/// a < |r| <= b, 0 beyond. Continuous, even, and non-increasing in |r|.
/// @param residual r, in the unit of the parameters.
double HampelWeight(double residual, const HampelParameters& params);

}  // namespace mirage::estimation
