// SPDX-License-Identifier: MIT
#include "mirage/channel/range_level_simulator.h"

#include <algorithm>
#include <cmath>

#include "mirage/core/units.h"

namespace mirage::channel {

const core::OptionsDescriptor<RangeLevelOptions>& RangeLevelOptionsDescriptor() {
  using core::ValueRange;
  using O = RangeLevelOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("channel::RangeLevelOptions");
    d.Number(&O::detection_probability,
             {.key = "detection_probability",
              .range = ValueRange::Closed(0.0, 1.0),
              .doc = "Probability that a path above min_sinr_db is detected. 0.95: a simulation "
                     "default (the MINT and SLAM papers give none), one missed path in twenty."});
    d.Number(&O::clutter_rate, {.key = "clutter_rate",
                                .range = ValueRange::Closed(0.0, 1000.0),
                                .doc = "Mean number of clutter ranges per anchor and step (Poisson), uniform over "
                                       "the CIR window. 1: a simulation default (the MINT and SLAM papers give none)."});
    d.Number(&O::min_sinr_db, {.key = "min_sinr_db",
                               .unit = "dB",
                               .range = ValueRange::Closed(-200.0, 200.0),
                               .doc = "Paths below this true SINR are never detected. -10 dB: below it a path's "
                                      "matched-filter peak is lost in the diffuse multipath."});
    d.Number(&O::resolution_m,
             {.key = "resolution_m",
              .unit = "m",
              .range = ValueRange::NonNegative(),
              .doc = "Detected paths closer than this merge into one range. 7.5 cm, half the pulse "
                     "length c T_p / 2 at T_p = 0.5 ns, where two pulses stop being separate peaks."});
    d.Number(&O::max_range_sigma_m, {.key = "max_range_sigma_m",
                                     .unit = "m",
                                     .range = ValueRange::Positive(),
                                     .doc = "Cap on the CRLB range standard deviation: sigma_VA,max = 0.22 m of Lafer "
                                            "2014."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const RangeLevelOptions& options) {
  return RangeLevelOptionsDescriptor().Validate(options);
}

RangeLevelSimulator::RangeLevelSimulator(const RangeLevelOptions& options, const CirSynthesizer& synthesizer)
    : options_(options), synthesizer_(&synthesizer) {}

core::RangeSet RangeLevelSimulator::Simulate(int anchor_index, std::span<const SpecularPath> paths,
                                                 double los_distance_m, core::Rng& rng,
                                                 std::vector<PathTruth>* truth) const {
  const auto& channel = synthesizer_->options();
  const double window_begin_s = channel.window_start_s;
  const double window_end_s = channel.window_start_s + channel.window_length_s;
  const double sigma1_m = synthesizer_->pulse().range_sigma_at_unit_sinr_m(channel.medium.speed_mps);
  const double min_sinr = core::DbToPowerRatio(options_.min_sinr_db);
  if (truth != nullptr) truth->clear();

  struct Detection {
    double true_range_m;
    double range_m;
    Complex amplitude;
    double sinr;
  };
  std::vector<Detection> detections;
  for (const auto& path : paths) {
    if (path.delay_s < window_begin_s || path.delay_s >= window_end_s) continue;
    const double sinr = synthesizer_->TrueSinr(path.amplitude, path.delay_s, los_distance_m);
    if (truth != nullptr) truth->push_back({path.va_id, path.order, path.delay_s, path.amplitude, sinr});
    // Every path draws the same numbers whether or not it is detected, so that one path's
    // detection does not shift the noise of the others.
    const bool detected = rng.Bernoulli(options_.detection_probability);
    const double range_noise = rng.Normal();
    const Complex amplitude_noise = rng.ComplexNormal(1.0);
    if (!detected || !(sinr >= min_sinr)) continue;
    // CRLB range std (Lafer Eq. 3.28), capped; amplitude Rician with K = SINR (Eq. 3.25).
    const double sigma_m = std::min(sigma1_m / std::sqrt(sinr), options_.max_range_sigma_m);
    const double range_m = path.delay_s * channel.medium.speed_mps;
    const Complex amplitude = path.amplitude + amplitude_noise * (std::abs(path.amplitude) / std::sqrt(sinr));
    detections.push_back({range_m, range_m + sigma_m * range_noise, amplitude, sinr});
  }
  // Paths closer than the resolution merge: one range, the stronger path's draw, the sum of the
  // amplitudes (the overlap the SINR model of Eq. 3.25 does not cover).
  std::sort(detections.begin(), detections.end(),
            [](const Detection& a, const Detection& b) { return a.true_range_m < b.true_range_m; });
  std::vector<Detection> merged;
  for (const auto& d : detections) {
    if (!merged.empty() && d.true_range_m - merged.back().true_range_m < options_.resolution_m) {
      Detection& m = merged.back();
      if (d.sinr > m.sinr) {
        m.range_m = d.range_m;
        m.sinr = d.sinr;
      }
      m.amplitude += d.amplitude;
      continue;
    }
    merged.push_back(d);
  }

  core::RangeSet out;
  out.anchor_index = anchor_index;
  for (const auto& d : merged) out.ranges.push_back({d.range_m, std::abs(d.amplitude)});
  // Clutter: Poisson count, uniform over the observed range window, Rayleigh amplitude at the
  // interference level N0 + T_eff S_nu(tau) of its delay.
  const int clutter = rng.Poisson(options_.clutter_rate);
  for (int i = 0; i < clutter; ++i) {
    const double delay_s = rng.Uniform(window_begin_s, window_end_s);
    const double interference = synthesizer_->noise_psd() +
                                synthesizer_->pulse().effective_duration_s() * synthesizer_->DiffusePdp(delay_s, los_distance_m);
    out.ranges.push_back({delay_s * channel.medium.speed_mps, std::abs(rng.ComplexNormal(interference))});
  }
  std::sort(out.ranges.begin(), out.ranges.end(),
            [](const core::RangeMeasurement& a, const core::RangeMeasurement& b) { return a.range_m < b.range_m; });
  return out;
}

}  // namespace mirage::channel
