// SPDX-License-Identifier: MIT
#include "mirage/channel/uwb_tdoa_simulator.h"

#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace mirage::channel {
namespace {

// Slot bounds are rounded with this tolerance (in slots), so that a step end computed as t + dt
// and the next step's start computed otherwise, a few ulps apart, fall on the same slot.
constexpr double kSlotTolerance = 1e-6;

// The first slot k with k / rate_hz >= t_s (up to the tolerance).
std::int64_t FirstSlotAtOrAfter(double t_s, double rate_hz) {
  return static_cast<std::int64_t>(std::ceil(t_s * rate_hz - kSlotTolerance));
}

// The interval [t_begin_s, t_end_s) can be simulated: valid options, ids for the anchors, at
// least two anchors, finite times whose slot numbers fit an int64 with room to spare.
bool Simulatable(const UwbTdoaOptions& options, std::size_t anchors, std::size_t ids, double t_begin_s, double t_end_s) {
  if (anchors < 2 || ids != anchors || !Validate(options).empty()) return false;
  constexpr double kLargestSlot = 4.0e18;
  return std::isfinite(t_begin_s) && std::isfinite(t_end_s) && t_end_s > t_begin_s &&
         std::abs(t_begin_s * options.rate_hz) < kLargestSlot && std::abs(t_end_s * options.rate_hz) < kLargestSlot;
}

// k mod n in [0, n) for negative k too.
std::size_t Modulo(std::int64_t k, std::size_t n) {
  const auto n_signed = static_cast<std::int64_t>(n);
  return static_cast<std::size_t>(((k % n_signed) + n_signed) % n_signed);
}

// The row of slot k, or nothing when its packet is missed. Every variate is drawn from the slot's
// own generator in a fixed order whether it is used or not (header: per-row RNG discipline).
std::optional<UwbTdoaSample> SimulateSlot(const UwbTdoaOptions& options, std::span<const Vec3> anchors_m,
                                          std::span<const std::string> anchor_ids,
                                          std::span<const geometry::Reflector3> obstacles, std::int64_t k,
                                          const Vec3& tag_m, core::Rng& rng) {
  const std::size_t n = anchors_m.size();
  core::Rng slot_rng(rng.NextU64());
  const double detect_u = slot_rng.Uniform();
  const auto draw_i = static_cast<std::size_t>(slot_rng.UniformInt(n));
  const auto draw_j = static_cast<std::size_t>(slot_rng.UniformInt(n - 1));
  const double z = slot_rng.Normal();
  const double bias_i_m = slot_rng.Uniform(options.nlos_bias_min_m, options.nlos_bias_max_m);
  const double bias_j_m = slot_rng.Uniform(options.nlos_bias_min_m, options.nlos_bias_max_m);
  const bool outlier = slot_rng.Bernoulli(options.outlier_probability);
  const double outlier_tdoa_m = slot_rng.Uniform(-options.outlier_max_m, options.outlier_max_m);
  if (!(detect_u < options.detection_probability)) return std::nullopt;

  std::size_t i = 0, j = 0;
  switch (options.pair_selection) {
    case UwbPairSelection::kRandom:
      i = draw_i;
      j = draw_j >= i ? draw_j + 1 : draw_j;  // uniform over the n - 1 anchors other than i
      break;
    case UwbPairSelection::kRoundRobin:
      i = Modulo(k, n);
      j = (i + 1) % n;
      break;
  }
  assert(i != j && i < n && j < n);

  UwbTdoaSample sample;
  UwbTdoaLabel& label = sample.label;
  label.true_tdoa_m = (tag_m - anchors_m[j]).norm() - (tag_m - anchors_m[i]).norm();
  label.nlos_i = !geometry::IsSegmentClear(obstacles, tag_m, anchors_m[i]);
  label.nlos_j = !geometry::IsSegmentClear(obstacles, tag_m, anchors_m[j]);
  label.nlos_bias_i_m = label.nlos_i ? bias_i_m : 0.0;
  label.nlos_bias_j_m = label.nlos_j ? bias_j_m : 0.0;
  label.outlier = outlier;

  core::TdoaMeasurement& m = sample.measurement;
  m.t_s = static_cast<double>(k) / options.rate_hz;
  m.id_i = anchor_ids[i];
  m.id_j = anchor_ids[j];
  m.index_i = static_cast<int>(i);
  m.index_j = static_cast<int>(j);
  // A bias lengthens its own leg: +b_j on |p - a_j|, -b_i through |p - a_i|.
  m.tdoa_m = outlier ? outlier_tdoa_m
                     : label.true_tdoa_m + label.nlos_bias_j_m - label.nlos_bias_i_m + options.sigma_m * z;
  return sample;
}

}  // namespace

const core::OptionsDescriptor<UwbTdoaOptions>& UwbTdoaOptionsDescriptor() {
  using core::ValueRange;
  using O = UwbTdoaOptions;
  static const auto descriptor = [] {
    const ValueRange bias_range = ValueRange::AtLeast(0.0);
    core::OptionsDescriptor<O> d("channel::UwbTdoaOptions");
    d.Number(&O::rate_hz, {.key = "rate_hz",
                           .unit = "Hz",
                           .range = ValueRange::LeftOpen(0.0, 1e4),
                           .doc = "Measurements per second: one pair per slot t_k = k / rate_hz. 200 Hz, the "
                                  "issue's rate (Loco TDOA3 gives a few hundred per second)."});
    d.Number(&O::sigma_m, {.key = "sigma_m",
                           .unit = "m",
                           .range = ValueRange::AtLeast(0.0),
                           .doc = "Standard deviation of tdoa_m; 0 gives noiseless rows. 0.15 m, the issue's value."});
    d.Choice(&O::pair_selection,
             {.key = "pair_selection",
              .doc = "random: i uniform, j uniform among the others (TDOA3); round_robin: slot k pairs anchor k mod "
                     "N with (k + 1) mod N (TDOA2's slot order). random."},
             {{"random", UwbPairSelection::kRandom}, {"round_robin", UwbPairSelection::kRoundRobin}});
    d.Number(&O::nlos_bias_min_m,
             {.key = "nlos_bias_min_m",
              .unit = "m",
              .range = bias_range,
              .doc = "Smallest excess path U(min, max) of a leg tag -> anchor that crosses an obstacle (NLOS excess "
                     "is positive). 0.2 m: the detour round a box when its attenuated direct path is missed."});
    d.Number(&O::nlos_bias_max_m, {.key = "nlos_bias_max_m",
                                   .unit = "m",
                                   .range = bias_range,
                                   .doc = "Largest excess path of a blocked leg, >= nlos_bias_min_m. 1.0 m: the "
                                          "detour round a 1 m box edge seen from 0.5 m."});
    d.Number(&O::outlier_probability,
             {.key = "outlier_probability",
              .range = ValueRange::Closed(0.0, 1.0),
              .doc = "Probability that a row is a gross outlier (a wrong first path, a corrupted timestamp). 0.01, "
                     "the issue's 1 %."});
    d.Number(&O::outlier_max_m,
             {.key = "outlier_max_m",
              .unit = "m",
              .range = ValueRange::Above(0.0),
              .doc = "An outlier's tdoa_m is uniform in [-outlier_max_m, outlier_max_m]. 50 m, far beyond a room's "
                     "baselines, so that most outliers fail a baseline check and some pass it."});
    d.Number(&O::detection_probability, {.key = "detection_probability",
                                         .range = ValueRange::Closed(0.0, 1.0),
                                         .doc = "Probability that a slot's packet is received; a missed one gives no "
                                                "row. 1."});
    d.Check("nlos_bias_max_m >= nlos_bias_min_m", [=](const O& o) -> std::vector<std::string> {
      if (!bias_range.Contains(o.nlos_bias_min_m) || !bias_range.Contains(o.nlos_bias_max_m) ||
          o.nlos_bias_max_m >= o.nlos_bias_min_m) {
        return {};
      }
      return {"nlos_bias_max_m: " + core::FormatNumber(o.nlos_bias_max_m) + " m must be at least nlos_bias_min_m (" +
              core::FormatNumber(o.nlos_bias_min_m) + " m)"};
    });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const UwbTdoaOptions& options) {
  return UwbTdoaOptionsDescriptor().Validate(options);
}

std::vector<UwbTdoaSample> SimulateUwbTdoaStep(const UwbTdoaOptions& options, std::span<const Vec3> anchors_m,
                                               std::span<const std::string> anchor_ids,
                                               std::span<const geometry::Reflector3> obstacles, double t_s,
                                               double dt_s, const Vec3& tag_m, core::Rng& rng) {
  std::vector<UwbTdoaSample> rows;
  if (!Simulatable(options, anchors_m.size(), anchor_ids.size(), t_s, t_s + dt_s)) return rows;
  const std::int64_t k_begin = FirstSlotAtOrAfter(t_s, options.rate_hz);
  const std::int64_t k_end = FirstSlotAtOrAfter(t_s + dt_s, options.rate_hz);
  for (std::int64_t k = k_begin; k < k_end; ++k) {
    if (auto row = SimulateSlot(options, anchors_m, anchor_ids, obstacles, k, tag_m, rng)) {
      rows.push_back(std::move(*row));
    }
  }
  return rows;
}

std::vector<UwbTdoaSample> SimulateUwbTdoa(const UwbTdoaOptions& options, std::span<const Vec3> anchors_m,
                                           std::span<const std::string> anchor_ids,
                                           std::span<const geometry::Reflector3> obstacles,
                                           const std::function<Vec3(double)>& tag_position_at, double t_start_s,
                                           double t_end_s, core::Rng& rng) {
  std::vector<UwbTdoaSample> rows;
  if (!Simulatable(options, anchors_m.size(), anchor_ids.size(), t_start_s, t_end_s)) return rows;
  const std::int64_t k_begin = FirstSlotAtOrAfter(t_start_s, options.rate_hz);
  const std::int64_t k_end = FirstSlotAtOrAfter(t_end_s, options.rate_hz);
  for (std::int64_t k = k_begin; k < k_end; ++k) {
    const Vec3 tag_m = tag_position_at(static_cast<double>(k) / options.rate_hz);
    if (auto row = SimulateSlot(options, anchors_m, anchor_ids, obstacles, k, tag_m, rng)) {
      rows.push_back(std::move(*row));
    }
  }
  return rows;
}

}  // namespace mirage::channel
