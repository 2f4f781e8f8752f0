// SPDX-License-Identifier: MIT
#include "mirage/estimation/robust/hampel.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace mirage::estimation {

const core::OptionsDescriptor<HampelOptions>& HampelOptionsDescriptor() {
  using core::ValueRange;
  using O = HampelOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("estimation::HampelOptions");
    d.Number(&O::theta, {.key = "theta",
                         .range = ValueRange::Positive(),
                         .doc = "Tuning parameter theta of the clipping point a = 1.4826 MAD / theta (Bordoy Eq. "
                                "5.24; no value in the thesis). 1 puts a at the robust sigma and b = 4a at 4 sigma for "
                                "Gaussian residuals; 0.5 (2 and 8 sigma) lets decimetre NLOS biases keep weight."});
    d.Number(&O::b_over_a, {.key = "b_over_a",
                            .range = ValueRange::Closed(1.0 + 1e-9, core::kHugeOption),
                            .doc = "Ratio of the rejection point b to the clipping point a. 4 as in the thesis."});
    d.Number(&O::min_a, {.key = "min_a",
                         .range = ValueRange::Positive(),
                         .doc = "Floor of the clipping point a, in the residuals' unit: the MAD is 0 when more than "
                                "half the residuals fit exactly. 1.0 (one standard deviation) for whitened "
                                "residuals."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const HampelOptions& options) { return HampelOptionsDescriptor().Validate(options); }

double Median(std::span<const double> values) {
  if (values.empty()) return 0.0;
  std::vector<double> v(values.begin(), values.end());
  const auto half = static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), v.begin() + half, v.end());
  const double upper = v[static_cast<std::size_t>(half)];
  if (v.size() % 2 == 1) return upper;
  // The lower middle value is the largest of the lower half (nth_element partitioned it).
  const double lower = *std::max_element(v.begin(), v.begin() + half);
  return 0.5 * (lower + upper);
}

double Mad(std::span<const double> values) {
  if (values.empty()) return 0.0;
  const double center = Median(values);
  std::vector<double> deviation(values.size());
  std::transform(values.begin(), values.end(), deviation.begin(), [center](double r) { return std::abs(r - center); });
  return Median(deviation);
}

HampelParameters HampelFromClippingPoint(double a, double b_over_a) {
  assert(a > 0.0 && b_over_a > 1.0);
  HampelParameters p;
  p.a = a;
  p.b = b_over_a * a;
  // Root of g(d) = d tanh(c d) - a, c = (b - a) / 2; g increases on d > 0 from -a to infinity.
  // Since tanh(x) <= 1 and tanh(x) <= x, the root lies above lo = max(a, sqrt(a / c)); since
  // tanh(c d) >= tanh(c lo) there, it lies below hi = a / tanh(c lo).
  const double c = 0.5 * (p.b - a);
  double lo = std::max(a, std::sqrt(a / c));
  double hi = a / std::tanh(c * lo);
  double d = hi;
  for (int it = 0; it < 100 && hi - lo > 1e-14 * hi; ++it) {
    const double t = std::tanh(c * d);
    const double g = d * t - a;
    if (g == 0.0) {
      lo = hi = d;
      break;
    }
    (g < 0.0 ? lo : hi) = d;
    const double slope = t + c * d * (1.0 - t * t);
    const double next = d - g / slope;
    // Newton when it stays inside the bracket, bisection otherwise. Newton may approach the root
    // from one side only, so its step size, not the bracket, usually ends the loop.
    if (next > lo && next < hi) {
      const bool converged = std::abs(next - d) <= 1e-14 * d;
      d = next;
      if (converged) break;
    } else {
      d = 0.5 * (lo + hi);
    }
  }
  p.d = d;
  return p;
}

HampelParameters HampelFromResiduals(std::span<const double> residuals, const HampelOptions& options) {
  constexpr double kMadToSigma = 1.4826;  // 1 / Phi^-1(3/4): MAD -> standard deviation, Gaussian
  const double a = std::max(kMadToSigma * Mad(residuals) / options.theta, options.min_a);
  return HampelFromClippingPoint(a, options.b_over_a);
}

double HampelWeight(double residual, const HampelParameters& params) {
  const double r = std::abs(residual);
  if (r <= params.a) return 1.0;
  if (r > params.b) return 0.0;
  return params.d * std::tanh(0.5 * params.d * (params.b - r)) / r;  // Eq. (5.24) with |r|
}

}  // namespace mirage::estimation
