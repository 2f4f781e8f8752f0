// SPDX-License-Identifier: MIT
#include "mirage/estimation/range_variance_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mirage/core/derived_defaults.h"

namespace mirage::estimation {

namespace {

// "key: value m must be <relation> other (value m)" when both lengths are in their ranges and
// `holds` is false; empty otherwise (an out-of-range value is reported by its own field).
std::vector<std::string> CompareLengths(const std::string& key, double value_m, const char* relation,
                                        const std::string& other, double other_m, const core::ValueRange& range,
                                        bool holds) {
  if (holds || !range.Contains(value_m) || !range.Contains(other_m)) return {};
  return {key + ": " + core::FormatNumber(value_m) + " m must be " + relation + " " + other + " (" +
          core::FormatNumber(other_m) + " m)"};
}

}  // namespace

const core::OptionsDescriptor<RangeVarianceOptions>& RangeVarianceOptionsDescriptor() {
  using core::ValueRange;
  using O = RangeVarianceOptions;
  static const auto descriptor = [] {
    const ValueRange window_range = ValueRange::Closed(1e-6, core::kHugeOption);
    core::OptionsDescriptor<O> d("estimation::RangeVarianceOptions");
    d.Boolean(&O::enabled, {.key = "enabled",
                            .doc = "Estimate each source's range variance online (Lafer Sec. 3.6); off, every range "
                                   "gets the method's fixed standard deviation."});
    d.Number(&O::window_min_m, {.key = "window_min_m",
                                .unit = "m",
                                .range = window_range,
                                .doc = "Minimum spatial extent d_min of the amplitude window, against correlated "
                                       "samples. 0.9 m (Lafer Tab. 3.2)."});
    d.Number(&O::window_max_m, {.key = "window_max_m",
                                .unit = "m",
                                .range = window_range,
                                .doc = "Maximum spatial extent d_max of the amplitude window, which keeps the channel "
                                       "stationary. 1.0 m (Lafer Tab. 3.2)."});
    d.Integer(&O::min_samples, {.key = "min_samples",
                                .range = ValueRange::Closed(3.0, 1e6),
                                .doc = "Minimum number of amplitudes N_min in the window. 15 (Lafer Tab. 3.2)."});
    d.Number(&O::default_sigma_m,
             {.key = "default_sigma_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Range standard deviation sigma_VA before any estimate. 0.07 m (Lafer's text; "
                     "Tab. 3.2 misprints it as 0.07 m^2). Derived: the scenario's range noise, which is then every "
                     "range's standard deviation until the window allows an estimate, and for good when the ranges "
                     "carry no amplitudes (range-level input).",
              .derived = core::RangeSigmas(1.0)});
    d.Number(&O::max_variance_factor, {.key = "max_variance_factor",
                                       .range = ValueRange::Closed(1.0, core::kHugeOption),
                                       .doc = "sigma_VA,max^2 = factor * sigma_VA^2 for an SINR estimate of zero or a "
                                              "complex one. 10 (Lafer Tab. 3.2)."});
    d.Number(&O::min_sigma_m, {.key = "min_sigma_m",
                               .unit = "m",
                               .range = ValueRange::Positive(),
                               .doc = "Floor of the estimated standard deviation (a gap in the thesis): Var[Y] -> 0 "
                                      "would give zero variance. 1 cm, about the delay error model mismatch leaves at "
                                      "high SINR. Derived: 1 cm, or the scenario's range noise if that is smaller (the "
                                      "floor cannot lie above the noise the ranges are stated to have).",
                               .derived = core::DerivedDefault{
                                   .formula = "min(" + core::FormatNumber(O{}.min_sigma_m) + " m, range_sigma_m)",
                                   .needs = {core::PhysicalKey::kRangeSigma},
                                   .compute = [](const core::PhysicalKeys& k) {
                                     return std::min(O{}.min_sigma_m, *k.range_sigma_m);
                                   }}});
    d.Number(&O::overlap_distance_m,
             {.key = "overlap_distance_m",
              .unit = "m",
              .range = ValueRange::NonNegative(),
              .doc = "Two expected ranges closer than this overlap, and their samples are discarded: Lafer Eq. (3.25) "
                     "does not hold for them (the thesis gives no criterion). 0.15 m is c T_p at T_p = 0.5 ns."});
    d.Check("window_max_m >= window_min_m", [=](const O& o) {
      return CompareLengths("window_max_m", o.window_max_m, ">=", "window_min_m", o.window_min_m, window_range,
                            o.window_max_m >= o.window_min_m);
    });
    d.Check("min_sigma_m <= default_sigma_m", [](const O& o) {
      return CompareLengths("min_sigma_m", o.min_sigma_m, "<=", "default_sigma_m", o.default_sigma_m,
                            ValueRange::Positive(), o.min_sigma_m <= o.default_sigma_m);
    });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const RangeVarianceOptions& options) {
  return RangeVarianceOptionsDescriptor().Validate(options);
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
