// SPDX-License-Identifier: MIT
// UWB TDOA measurements as Bitcraze's Loco Positioning system makes them (TDOA2 / TDOA3): the
// anchors transmit, the tag receives and reports, per packet, the difference of the arrival
// distances of two anchors' packets, tdoa_m = |p - a_j| - |p - a_i| (core/records.h). One pair per
// slot at rate_hz; Gaussian noise; a positive excess path on every leg anchor -> tag that crosses
// an obstacle; rare gross outliers; missed packets. The example (uwb_tdoa_3d.yaml): 8
// anchors in a 7 x 7 m room, 200 Hz, sigma 0.15 m, a box, 1 % outliers up to 50 m. Not from the
// Bordoy thesis; the NLOS model mirrors its synthetic U(min, max) bias (Sec. 5.3, Eq. 5.1).
//
// Choices (the hardware papers give no simulator):
//   - Slots sit on the absolute grid t_k = k / rate_hz (k an integer), so a caller that steps
//     through time in any epochs [t_s, t_s + dt_s) gets every slot exactly once. Rows of one step
//     share the tag position the caller passes for it: at 1.5 m/s and a 10 ms epoch the tag moves
//     1.5 cm, a tenth of sigma. SimulateUwbTdoa evaluates a trajectory at every slot instead.
//   - No anchor clock offsets or drifts: TDOA3 estimates and removes them from the anchors'
//     broadcast timestamps, and TDOA2 anchors are synchronised, so the residual is in sigma_m.
//   - NLOS: a leg is blocked when a blocking reflector (Reflector3::blocks) crosses the segment
//     tag -> anchor; a box is its six faces. A blocked leg gets an excess path U(min, max) drawn
//     per row; a leg through both faces of a box counts once. The excess is positive: no path
//     is shorter than the straight line, and a wave inside a material travels slower than in air
//     (relative permittivity > 1). Default 0.2 - 1.0 m: through cardboard or wood the delay in
//     the material is centimetres (2 cm of wood, eps_r ~ 2-3: < 2 cm), so a large bias comes
//     when the attenuated direct path is missed and the first path detected goes around the box:
//     a detour of h^2 / 2 (1 / d1 + 1 / d2) for an edge h off the line at d1, d2 from its ends,
//     0.3 m for h = 0.5 m, d1 = 0.5 m, d2 = 3 m and 1.25 m for h = 1 m, d1 = 0.5 m, d2 = 2 m.
//   - Outliers replace tdoa_m by U(-outlier_max_m, outlier_max_m): gross errors (a wrong first
//     path, a corrupted timestamp, a clock-correction glitch) bear no relation to the geometry,
//     so the least-informative model is uniform. 50 m is far beyond the room's largest true TDOA
//     (the anchor baseline, <= 10.2 m in 7 x 7 x 2.3 m): most outliers fail a baseline check,
//     a fraction baseline / 50 m (up to one in five) passes it and needs a statistical gate.
//   - Per-row RNG discipline: each slot takes one 64-bit draw of the caller's rng to seed its own
//     generator, and that generator draws the detection, the pair, the noise, both legs' biases
//     and the outlier whether they are used or not. So an obstacle, a detection probability or
//     an outlier rate shifts no other row's numbers. Give the simulator its own sub-stream.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/records.h"
#include "mirage/core/rng.h"
#include "mirage/core/types.h"
#include "mirage/geometry/reflector_3d.h"

namespace mirage::channel {

/// How the two anchors of a slot are chosen.
enum class UwbPairSelection {
  /// i uniform among the anchors, j uniform among the others (TDOA3: the tag pairs each packet
  /// with a randomly chosen anchor heard recently).
  kRandom,
  /// Slot k pairs anchor k mod N (i) with anchor (k + 1) mod N (j) (TDOA2: anchors transmit in
  /// slot order and the tag differences each packet with the previous one).
  kRoundRobin,
};

/// Parameters of the UWB TDOA simulation.
struct UwbTdoaOptions {
  /// Measurements per second (Hz), in (0, 1e4]: one slot, one pair, every 1 / rate_hz. 200 Hz,
  /// the rate (Loco TDOA3 delivers a few hundred per second).
  double rate_hz = 200.0;
  /// Standard deviation of tdoa_m (m), >= 0 (0: noiseless). 0.15 m, the value.
  double sigma_m = 0.15;
  /// Pair choice per slot. kRandom (TDOA3).
  UwbPairSelection pair_selection = UwbPairSelection::kRandom;
  /// Smallest excess path of a blocked leg (m), >= 0. 0.2 m (file header: a detour round a box).
  double nlos_bias_min_m = 0.2;
  /// Largest excess path of a blocked leg (m), >= nlos_bias_min_m. 1.0 m (file header).
  double nlos_bias_max_m = 1.0;
  /// Probability that a row is a gross outlier, in [0, 1]. 0.01, the 1 %.
  double outlier_probability = 0.01;
  /// An outlier's tdoa_m is uniform in [-outlier_max_m, outlier_max_m] (m), > 0. 50 m (file
  /// header: far beyond the room's baselines).
  double outlier_max_m = 50.0;
  /// Probability that a slot's packet is received, in [0, 1]; a missed one gives no row. 1.
  double detection_probability = 1.0;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<UwbTdoaOptions>& UwbTdoaOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const UwbTdoaOptions& options);

/// The ground truth of one row.
struct UwbTdoaLabel {
  double true_tdoa_m = 0.0;    ///< |p - a_j| - |p - a_i| without noise, bias or outlier (m)
  bool nlos_i = false;         ///< the leg anchor i -> tag crosses an obstacle
  bool nlos_j = false;         ///< the leg anchor j -> tag crosses an obstacle
  double nlos_bias_i_m = 0.0;  ///< excess path of leg i (m): 0 when clear, else in [min, max]
  double nlos_bias_j_m = 0.0;  ///< excess path of leg j (m): 0 when clear, else in [min, max]
  /// tdoa_m is an outlier, uniform in [-outlier_max_m, outlier_max_m]; otherwise
  /// tdoa_m = true_tdoa_m + nlos_bias_j_m - nlos_bias_i_m + N(0, sigma_m^2).
  bool outlier = false;
};

/// One simulated row with its ground truth.
struct UwbTdoaSample {
  core::TdoaMeasurement measurement;  ///< what the tag reports
  UwbTdoaLabel label;                 ///< how it was made
};

/// The rows of the slots t_k = k / rate_hz in [t_s, t_s + dt_s) (bounds with a tolerance of 1e-6
/// of a slot, so that consecutive steps t_s + dt_s = next t_s share no slot and miss none), in
/// time order, all for the tag at tag_m. Takes exactly one draw of rng per slot (received or
/// not). Empty (no draw) when fewer than two anchors or not one id per anchor are given, the
/// options are invalid, or the interval is empty or not finite.
/// @param anchors_m   the anchors' positions (m), world frame
/// @param anchor_ids  the anchors' ids, one per anchor (copied into id_i, id_j)
/// @param obstacles   reflectors whose crossing biases a leg (only those with blocks = true)
/// @param t_s         start of the step (s)
/// @param dt_s        length of the step (s)
/// @param tag_m       the tag's position during the step (m), world frame
std::vector<UwbTdoaSample> SimulateUwbTdoaStep(const UwbTdoaOptions& options, std::span<const Vec3> anchors_m,
                                               std::span<const std::string> anchor_ids,
                                               std::span<const geometry::Reflector3> obstacles, double t_s,
                                               double dt_s, const Vec3& tag_m, core::Rng& rng);

/// The rows of the slots in [t_start_s, t_end_s), each for the tag at tag_position_at(t_k). With a
/// tag that does not move, the same rows (and rng draws) as SimulateUwbTdoaStep over the interval
/// in any number of steps.
/// @param tag_position_at  the tag's position (m) at a time (s)
std::vector<UwbTdoaSample> SimulateUwbTdoa(const UwbTdoaOptions& options, std::span<const Vec3> anchors_m,
                                           std::span<const std::string> anchor_ids,
                                           std::span<const geometry::Reflector3> obstacles,
                                           const std::function<Vec3(double)>& tag_position_at, double t_start_s,
                                           double t_end_s, core::Rng& rng);

}  // namespace mirage::channel
