// SPDX-License-Identifier: MIT
#include "mirage/estimation/range_variance_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mirage::estimation {

std::vector<std::string> Validate(const RangeVarianceOptions& options) {
  std::vector<std::string> problems;
  if (!(options.window_min_m > 0.0) || !std::isfinite(options.window_min_m)) problems.push_back("window_min_m must be > 0 m");
  if (!(options.window_max_m >= options.window_min_m) || !std::isfinite(options.window_max_m)) {
    problems.push_back("window_max_m must be >= window_min_m");
  }
  if (options.min_samples < 3) problems.push_back("min_samples must be >= 3");
  if (!(options.default_sigma_m > 0.0) || !std::isfinite(options.default_sigma_m)) problems.push_back("default_sigma_m must be > 0 m");
  if (!(options.max_variance_factor >= 1.0) || !std::isfinite(options.max_variance_factor)) {
    problems.push_back("max_variance_factor must be >= 1");
  }
  if (!(options.min_sigma_m > 0.0) || !(options.min_sigma_m <= options.default_sigma_m)) {
    problems.push_back("min_sigma_m must be > 0 m and <= default_sigma_m");
  }
  if (!(options.overlap_distance_m >= 0.0) || !std::isfinite(options.overlap_distance_m)) {
    problems.push_back("overlap_distance_m must be >= 0 m");
  }
  return problems;
}

RangeVarianceEstimator::RangeVarianceEstimator(const RangeVarianceOptions& options, double range_sigma_at_unit_sinr_m)
    : options_(options), sigma1_squared_m2_(range_sigma_at_unit_sinr_m * range_sigma_at_unit_sinr_m) {}

void RangeVarianceEstimator::AddSample(int va_id, const Vec2& agent_m, double amplitude) {
  VaHistory& history = vas_[va_id];
  history.samples.push_back({agent_m, amplitude * amplitude});
  // Design choice: the history is the contiguous run of samples within d_max of the newest one;
  // older samples are dropped even though the agent might come back to them.
  const Vec2& newest = history.samples.back().agent_m;
  std::size_t keep_from = 0;
  for (std::size_t i = history.samples.size(); i-- > 0;) {
    if ((history.samples[i].agent_m - newest).norm() > options_.window_max_m) {
      keep_from = i + 1;
      break;
    }
  }
  // A slow or standing agent collects many samples within d_max; the newest few times N_min
  // describe the window as well and keep the cost per step bounded.
  const std::size_t cap = static_cast<std::size_t>(std::max(4 * options_.min_samples, 64));
  keep_from = std::max(keep_from, history.samples.size() > cap ? history.samples.size() - cap : std::size_t{0});
  history.samples.erase(history.samples.begin(), history.samples.begin() + static_cast<std::ptrdiff_t>(keep_from));
}

double RangeVarianceEstimator::FallbackVariance(const VaHistory& history) const {
  if (history.variance_count == 0) return options_.default_sigma_m * options_.default_sigma_m;
  return history.variance_sum / history.variance_count;
}

double RangeVarianceEstimator::CurrentVariance(int va_id) const {
  const auto it = vas_.find(va_id);
  if (it == vas_.end()) return options_.default_sigma_m * options_.default_sigma_m;
  return FallbackVariance(it->second);
}

std::optional<double> RangeVarianceEstimator::LastEstimatedVariance(int va_id) const {
  const auto it = vas_.find(va_id);
  if (it == vas_.end() || it->second.variance_count == 0) return std::nullopt;
  return it->second.last_variance;
}

std::optional<AmplitudeMoments> RangeVarianceEstimator::Moments(int va_id, const Vec2& at_m) const {
  const auto it = vas_.find(va_id);
  if (it == vas_.end()) return std::nullopt;
  // Eq. (3.27): moments of Y = |alpha_hat|^2 over the window; m2 is the (unbiased) variance.
  AmplitudeMoments m;
  double extent_m = 0.0;
  for (const auto& s : it->second.samples) {
    const double distance_m = (s.agent_m - at_m).norm();
    if (distance_m > options_.window_max_m) continue;
    extent_m = std::max(extent_m, distance_m);
    m.mean += s.energy;
    ++m.count;
  }
  if (m.count < options_.min_samples || extent_m < options_.window_min_m) return std::nullopt;
  m.mean /= static_cast<double>(m.count);
  for (const auto& s : it->second.samples) {
    if ((s.agent_m - at_m).norm() <= options_.window_max_m) m.variance += (s.energy - m.mean) * (s.energy - m.mean);
  }
  m.variance /= static_cast<double>(m.count - 1);
  return m;
}

RangeVariance RangeVarianceEstimator::Variance(int va_id, bool associated_now) {
  VaHistory& history = vas_[va_id];
  const double max_variance = options_.max_variance_factor * options_.default_sigma_m * options_.default_sigma_m;
  // Associated now means the newest sample was taken at the current position.
  const auto moments = associated_now && !history.samples.empty()
                           ? Moments(va_id, history.samples.back().agent_m)
                           : std::nullopt;
  if (!moments) return {FallbackVariance(history), std::nullopt, std::nullopt};
  const double m1 = moments->mean;
  const double m2 = moments->variance;

  RangeVariance out{max_variance, 0.0, moments};
  const double discriminant = m1 * m1 - m2;
  if (discriminant > 0.0) {
    // Eq. (3.26); m2 >= 0 makes the denominator >= 0, and 0 only for constant amplitudes.
    const double denominator = m1 / std::sqrt(discriminant) - 1.0;
    const double sinr = denominator > 0.0 ? 1.0 / denominator : std::numeric_limits<double>::infinity();
    out.sinr = sinr;
    // Eq. (3.28), kept within [sigma_min^2, sigma_VA,max^2].
    out.variance_m2 = std::clamp(sigma1_squared_m2_ / sinr, options_.min_sigma_m * options_.min_sigma_m, max_variance);
  }
  // Otherwise Rayleigh-like amplitudes: SINR 0 or complex, sigma_VA,max^2 (out's initial value).
  history.variance_sum += out.variance_m2;
  ++history.variance_count;
  history.last_variance = out.variance_m2;
  return out;
}

}  // namespace mirage::estimation
