// SPDX-License-Identifier: MIT
#include "mirage/dsp/mpc_extractor.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "mirage/core/units.h"

namespace mirage::dsp {
namespace {

// Autocorrelation table resolution: entries per sample period (linear interpolation between).
constexpr int kTableOversampling = 32;
// Samples per block of the running argmax.
constexpr int kBlock = 32;
// Components are subtracted out to where |R| falls below this; the truncation leaves residues
// 60 dB below the component, below the -30 dB default stopping threshold.
constexpr double kSupportThreshold = 1e-3;

int SupportSamples(const channel::RaisedCosinePulse& pulse, double sample_period_s) {
  int support = 1;
  for (int n = 1; n * sample_period_s <= pulse.autocorrelation_support_s(); ++n) {
    if (std::abs(pulse.Autocorrelation(n * sample_period_s)) >= kSupportThreshold) support = n + 1;
  }
  return support;
}

}  // namespace

const core::OptionsDescriptor<MpcExtractorOptions>& MpcExtractorOptionsDescriptor() {
  using core::ValueRange;
  using O = MpcExtractorOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("dsp::MpcExtractorOptions");
    d.Integer(&O::max_components,
              {.key = "max_components",
               .range = ValueRange::Closed(1.0, 1000.0),
               .doc = "Maximum number of components K extracted per CIR. 20 as in Lafer Tab. 3.1."});
    d.Number(
        &O::relative_threshold_db,
        {.key = "relative_threshold_db",
         .unit = "dB",
         .range = ValueRange::Closed(-300.0, -1e-9),
         .doc = "Stop when a component's energy falls this far below the strongest one (the thesis only says "
                "the threshold is relative). -30 dB is below the noise floor of a 20-35 dB LOS, so the last "
                "components are diffuse-multipath and noise peaks: clutter, as in measured data (Lafer Sec. 3.3)."});
    d.Boolean(&O::readjust, {.key = "readjust",
                             .doc = "Re-estimate the overlapping earlier components after each new one, which undoes "
                                    "the bias a strong neighbour leaves."});
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const MpcExtractorOptions& options) {
  return MpcExtractorOptionsDescriptor().Validate(options);
}

MpcExtractor::MpcExtractor(const MpcExtractorOptions& options, const channel::RaisedCosinePulse& pulse,
                           int sample_count, double sample_period_s, const core::Medium& medium)
    : options_(options),
      pulse_(pulse),
      sample_count_(sample_count),
      sample_period_s_(sample_period_s),
      medium_(medium),
      threshold_ratio_(core::DbToPowerRatio(options.relative_threshold_db)),
      support_samples_(SupportSamples(pulse, sample_period_s)),
      // Zero padding by the pulse's tail length keeps the circular correlation from wrapping.
      fft_(core::NextFastFftSize(
          static_cast<std::size_t>(sample_count + channel::PulseTailSamples(pulse.options(), sample_period_s)))) {
  assert(sample_count > 0 && medium.speed_mps > 0.0);
  autocorrelation_.resize(static_cast<std::size_t>((support_samples_ + 2) * kTableOversampling));
  for (std::size_t i = 0; i < autocorrelation_.size(); ++i) {
    autocorrelation_[i] = pulse_.Autocorrelation(static_cast<double>(i) * sample_period_s_ / kTableOversampling);
  }
  template_spectrum_ = pulse_.SampledSpectrum(fft_.size(), sample_period_s_);
}

std::vector<Complex> MpcExtractor::MatchedFilter(const core::Cir& cir) const {
  assert(static_cast<int>(cir.samples.size()) == sample_count_);
  std::vector<Complex> padded(fft_.size(), Complex(0.0, 0.0));
  std::copy(cir.samples.begin(), cir.samples.end(), padded.begin());
  std::vector<Complex> spectrum(fft_.size());
  fft_.Forward(padded, spectrum);
  // y = r correlated with the real, even template: Y[k] = R[k] conj(S[k]) = R[k] S[k].
  for (std::size_t k = 0; k < spectrum.size(); ++k) spectrum[k] *= template_spectrum_[k];
  fft_.Inverse(spectrum, padded);
  padded.resize(static_cast<std::size_t>(sample_count_));
  return padded;
}

MpcExtractor::Component MpcExtractor::Refine(const std::vector<Complex>& y, int n) const {
  Component c;
  c.offset_samples = n;
  c.amplitude = y[static_cast<std::size_t>(n)];
  if (n <= 0 || n >= sample_count_ - 1) return c;
  const Complex ya = y[static_cast<std::size_t>(n - 1)];
  const Complex yb = y[static_cast<std::size_t>(n)];
  const Complex yc = y[static_cast<std::size_t>(n + 1)];
  const double a = std::norm(ya), b = std::norm(yb), cc = std::norm(yc);
  const double curvature = a - 2.0 * b + cc;
  if (curvature >= 0.0) return c;  // not a local maximum of |y|^2
  const double delta = std::clamp(0.5 * (a - cc) / curvature, -0.5, 0.5);
  c.offset_samples = n + delta;
  // Quadratic (Lagrange) interpolation of the complex MF output at the refined delay.
  c.amplitude = yb + 0.5 * delta * (yc - ya) + 0.5 * delta * delta * (ya - 2.0 * yb + yc);
  return c;
}

void MpcExtractor::AddScaled(Residual& residual, const Component& c, double sign) const {
  const int center = static_cast<int>(std::lround(c.offset_samples));
  const int lo = std::max(0, center - support_samples_);
  const int hi = std::min(sample_count_ - 1, center + support_samples_);
  const Complex scaled = sign * c.amplitude;
  const auto add = [&](int n, std::size_t i, double frac) {
    const double r = autocorrelation_[i] + frac * (autocorrelation_[i + 1] - autocorrelation_[i]);
    auto& v = residual.y[static_cast<std::size_t>(n)];
    v += scaled * r;
    residual.energy[static_cast<std::size_t>(n)] = std::norm(v);
  };
  // R((n - offset) T_s) on each side of the component: the table position advances by exactly
  // kTableOversampling per sample, so the interpolation weight is the same on a side.
  const int first_right = std::max(lo, static_cast<int>(std::ceil(c.offset_samples)));
  if (first_right <= hi) {
    const double x = (first_right - c.offset_samples) * kTableOversampling;
    auto i = static_cast<std::size_t>(x);
    const double frac = x - static_cast<double>(i);
    for (int n = first_right; n <= hi; ++n, i += kTableOversampling) add(n, i, frac);
  }
  const int last_left = std::min(hi, first_right - 1);
  if (last_left >= lo) {
    const double x = (c.offset_samples - last_left) * kTableOversampling;
    auto i = static_cast<std::size_t>(x);
    const double frac = x - static_cast<double>(i);
    for (int n = last_left; n >= lo; --n, i += kTableOversampling) add(n, i, frac);
  }
  UpdateBlocks(residual, lo, hi);
}

void MpcExtractor::UpdateBlocks(Residual& residual, int lo, int hi) const {
  for (int b = lo / kBlock; b <= hi / kBlock; ++b) {
    const int begin = b * kBlock;
    const int end = std::min(sample_count_, begin + kBlock);
    int best = begin;
    for (int n = begin + 1; n < end; ++n) {
      if (residual.energy[static_cast<std::size_t>(n)] > residual.energy[static_cast<std::size_t>(best)]) best = n;
    }
    residual.block_argmax[static_cast<std::size_t>(b)] = best;
  }
}

int MpcExtractor::ArgMax(const Residual& residual) const {
  int best = residual.block_argmax.front();
  for (const int candidate : residual.block_argmax) {
    if (residual.energy[static_cast<std::size_t>(candidate)] > residual.energy[static_cast<std::size_t>(best)]) best = candidate;
  }
  return best;
}

void MpcExtractor::Readjust(Residual& residual, Component& c) const {
  // Add the component back, search its peak again within +-2 samples, subtract the new estimate.
  AddScaled(residual, c, +1.0);
  const int center = std::clamp(static_cast<int>(std::lround(c.offset_samples)), 0, sample_count_ - 1);
  int best = center;
  for (int n = std::max(0, center - 2); n <= std::min(sample_count_ - 1, center + 2); ++n) {
    if (residual.energy[static_cast<std::size_t>(n)] > residual.energy[static_cast<std::size_t>(best)]) best = n;
  }
  c = Refine(residual.y, best);
  AddScaled(residual, c, -1.0);
}

std::vector<Mpc> MpcExtractor::Extract(const core::Cir& cir) const { return Extract(cir, options_.max_components); }

std::vector<Mpc> MpcExtractor::Extract(const core::Cir& cir, int max_components) const {
  return ExtractFromMatchedFilter(MatchedFilter(cir), cir.start_s, max_components);
}

Complex MpcExtractor::ProjectAt(const std::vector<Complex>& y, double start_s, double delay_s) const {
  assert(static_cast<int>(y.size()) == sample_count_);
  const double x = (delay_s - start_s) / sample_period_s_;
  if (!(x >= 0.0 && x <= sample_count_ - 1)) return Complex(0.0, 0.0);
  // Quadratic (Lagrange) interpolation through the three samples around x, as in Refine().
  if (sample_count_ < 3) return y[static_cast<std::size_t>(std::lround(x))];
  const int n = std::clamp(static_cast<int>(std::lround(x)), 1, sample_count_ - 2);
  const double delta = x - n;
  const Complex ya = y[static_cast<std::size_t>(n - 1)];
  const Complex yb = y[static_cast<std::size_t>(n)];
  const Complex yc = y[static_cast<std::size_t>(n + 1)];
  return yb + 0.5 * delta * (yc - ya) + 0.5 * delta * delta * (ya - 2.0 * yb + yc);
}

std::vector<Mpc> MpcExtractor::ExtractFromMatchedFilter(std::vector<Complex> matched_filter_output, double start_s,
                                                        int max_components) const {
  assert(static_cast<int>(matched_filter_output.size()) == sample_count_);
  Residual residual;
  residual.y = std::move(matched_filter_output);
  residual.energy.resize(residual.y.size());
  for (std::size_t n = 0; n < residual.y.size(); ++n) residual.energy[n] = std::norm(residual.y[n]);
  residual.block_argmax.resize(static_cast<std::size_t>((sample_count_ + kBlock - 1) / kBlock));
  UpdateBlocks(residual, 0, sample_count_ - 1);

  std::vector<Component> found;
  found.reserve(static_cast<std::size_t>(std::max(0, max_components)));
  double reference_energy = 0.0;
  for (int k = 0; k < max_components; ++k) {
    // Search (Eq. 3.1): the strongest remaining peak of the matched-filter output.
    const Component c = Refine(residual.y, ArgMax(residual));
    const double energy = std::norm(c.amplitude);
    if (k == 0) reference_energy = energy;
    if (energy <= 0.0 || energy < threshold_ratio_ * reference_energy) break;
    // Subtract (Eq. 3.2).
    AddScaled(residual, c, -1.0);
    found.push_back(c);
    if (!options_.readjust) continue;
    // Readjust the earlier components that overlap the new one, then the new one again with
    // the corrected neighbours removed.
    bool overlapped = false;
    for (std::size_t j = 0; j + 1 < found.size(); ++j) {
      if (std::abs(found[j].offset_samples - c.offset_samples) > support_samples_) continue;
      Readjust(residual, found[j]);
      overlapped = true;
    }
    if (overlapped) Readjust(residual, found.back());
  }
  std::vector<Mpc> mpcs;
  mpcs.reserve(found.size());
  for (const auto& c : found) {
    Mpc mpc;
    mpc.delay_s = start_s + c.offset_samples * sample_period_s_;
    mpc.range_m = mpc.delay_s * medium_.speed_mps;
    mpc.amplitude = c.amplitude;
    mpcs.push_back(mpc);
  }
  std::sort(mpcs.begin(), mpcs.end(), [](const Mpc& a, const Mpc& b) { return a.delay_s < b.delay_s; });
  return mpcs;
}

}  // namespace mirage::dsp
