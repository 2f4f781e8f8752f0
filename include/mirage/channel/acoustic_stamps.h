// SPDX-License-Identifier: MIT
// The acoustic event-level simulator (Bordoy 2020, digest Sec. 6.2): a sender (a smartphone
// speaker) emits chirps; microphones that share one time base stamp the arrivals. Per emission
// and microphone it draws the timestamps a correlation-peak detector would report: the direct
// path if it is visible, echoes off the floor, ceiling, walls and partitions up to max_order,
// each detected with a probability that falls with the path length, plus false alarms; every
// stamp with Gaussian noise of a heavy tail and its ground-truth label.
//
// Choices where the thesis is silent (see SimulateEmission for the details):
//   - The synthetic NLOS bias (Eq. 5.1, b_i ~ U) applies only to a direct stamp that exists: a
//     direct path that is blocked has no stamp to delay, so the measured biased fraction is
//     nlos_fraction times the fraction of detected direct paths.
//   - The clock drift is not applied here: the caller computes t_emit_s (emission k at
//     t_0 + k I (1 + ppm 1e-6)) and passes it in, since only it knows k and I.
//   - Each microphone gets its own generator seeded by one draw of the caller's rng, and inside
//     it every candidate surface sequence consumes its draws whether its path exists, is blocked
//     or detected: toggling the body, a facing episode or a partition shifts no other noise.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/rng.h"
#include "mirage/core/types.h"
#include "mirage/geometry/reflector_3d.h"

namespace mirage::channel {

/// An interval during which the speaker faces a reflector: only paths whose first reflection is on
/// it arrive (the virtual-sender case of Bordoy Sec. 5.2, Fig. 5.3).
struct FacingEpisode {
  double t_start_s = 0.0;  ///< start of the episode (s), inclusive
  double t_end_s = 0.0;    ///< end of the episode (s), exclusive, > t_start_s
  std::string reflector;  ///< a reflector's name
};

/// Parameters of the acoustic stamp simulation.
struct AcousticStampOptions {
  /// Air temperature of the simulation (C): the true sound speed 331.3 sqrt(1 + theta/273.15)
  /// (Eq. 3.31). The estimator assumes the scenario medium's speed; a difference is the optional
  /// sound-speed mismatch.
  double temperature_c = 20.0;
  /// Highest reflection order simulated, in [0, 3]; 2 (Sec. 3.2: first and second order are the
  /// ones that can be mistaken for the line of sight).
  int max_order = 2;
  /// Standard deviation of a stamp (s), > 0; 0.3 ms, the ch. 5 synthetic regime.
  double stamp_sigma_s = 0.3e-3;
  /// Fraction of stamps drawn with heavy_tail_scale times the sigma, in [0, 1] (App.: heavy-tailed
  /// histograms from synchronisation and detection errors).
  double heavy_tail_fraction = 0.0;
  double heavy_tail_scale = 10.0;  ///< > 0
  /// Detection probability of a path at zero length, in [0, 1].
  double detection_probability = 1.0;
  /// Path length at which the detection probability has halved (m), > 0: P_d(d) =
  /// detection_probability * gain / (1 + (d / half_detection_range_m)^4) (ref. [1] of the thesis:
  /// 48 % of chirps detected at 30 m).
  double half_detection_range_m = 30.0;
  /// Paths longer than this are never detected (m), > 0.
  double max_range_m = 40.0;
  /// Mean number of false alarms per microphone and emission (Poisson), uniform over the
  /// listening window [0, max_range_m / c] after the emission, >= 0.
  double false_alarm_rate = 0.0;
  /// The synthetic NLOS regime of Sec. 5.3: each microphone's direct stamp is, with this
  /// probability, delayed by a draw from U(nlos_bias_min_s, nlos_bias_max_s), in [0, 1].
  double nlos_fraction = 0.0;
  double nlos_bias_min_s = 3e-3;   ///< >= 0
  double nlos_bias_max_s = 13e-3;  ///< >= nlos_bias_min_s
  /// The person holding the phone: a vertical cylinder of this radius (m, >= 0; 0 = no body) whose
  /// axis stands body_offset_m behind the sender, opposite to its heading, from the floor to
  /// body_height_m. Paths leaving the sender through it are blocked.
  double body_radius_m = 0.0;
  double body_offset_m = 0.25;
  double body_height_m = 1.8;
  /// The sender's clock rate error (ppm): emission k leaves at t_0 + k I (1 + ppm 1e-6), so the
  /// interval must be estimated (Eq. 3.39), not assumed.
  double clock_drift_ppm = 0.0;
  /// The system also knows each emission's true time (a sender synchronised with the
  /// microphones, or a reference system: the thesis's motion-capture-derived sending time of
  /// Sec. 8.5): the stamps' records carry it (core::ToaStamps::emission_s). false.
  bool emission_time_known = false;
  /// Virtual-sender episodes. Not in the descriptor (io/ parses the list); Validate checks the
  /// times, the caller checks that each reflector name exists. When episodes overlap, the first
  /// active one in the list applies.
  std::vector<FacingEpisode> facing;
};

/// The options' descriptor (core/options_descriptor.h).
const core::OptionsDescriptor<AcousticStampOptions>& AcousticStampOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid: the descriptor's, then
/// "facing[i].t_end_s: ..." for an episode that does not end after it starts.
std::vector<std::string> Validate(const AcousticStampOptions& options);

/// Speed of sound in dry air at theta_c degrees Celsius (m/s), Eq. (3.31).
double SoundSpeedMps(double theta_c);

/// The ground truth of one stamp.
enum class StampLabel {
  kDirect,       ///< the direct path, unbiased
  kDirectBiased, ///< the direct path with the synthetic NLOS bias
  kEcho,         ///< a specular echo
  kFalseAlarm,   ///< noise
};

/// One timestamp a microphone reports.
struct AcousticStamp {
  double toa_s = 0.0;        ///< arrival time in the receivers' time base (s)
  StampLabel label = StampLabel::kDirect;
  std::vector<int> surfaces;  ///< the echo's reflectors (indices), empty otherwise
};

/// One emission's stamps at every microphone.
struct AcousticEmission {
  double t_emit_s = 0.0;                          ///< true emission time (s)
  std::vector<std::vector<AcousticStamp>> stamps;  ///< per microphone, sorted by time
  /// Per microphone: the direct path exists (not blocked by a reflector, the body, or a facing
  /// episode).
  std::vector<bool> direct_visible;
};

/// Simulates the stamps of one emission. Per microphone: every path of SpecularPaths3 up to
/// max_order; the direct path if it exists, the body does not block its first leg and no facing
/// episode is active; an echo if the body does not block its first leg and, during a facing
/// episode (t_start_s <= t_emit_s < t_end_s), its first surface is the faced reflector. A path of
/// length d is detected with probability detection_probability * reflection_gain /
/// (1 + (d / half_detection_range_m)^4) if d <= max_range_m; its stamp is t_emit_s + d / c +
/// N(0, sigma^2), sigma = stamp_sigma_s, or heavy_tail_scale * stamp_sigma_s with probability
/// heavy_tail_fraction, c = SoundSpeedMps(temperature_c). With probability nlos_fraction a
/// detected direct stamp is delayed by U(nlos_bias_min_s, nlos_bias_max_s) (kDirectBiased).
/// Then Poisson(false_alarm_rate) stamps uniform in [t_emit_s, t_emit_s + max_range_m / c].
/// clock_drift_ppm is not applied: t_emit_s already includes it. The body blocks a first leg
/// whose horizontal projection enters the body's circle at a height below body_height_m.
/// Every draw comes from rng: one 64-bit draw per microphone seeds that microphone's generator.
/// @param reflectors  the hall's reflectors (geometry/reflector_3d.h)
/// @param mics_m      the microphones' positions (m)
/// @param sender_m    the speaker's position (m)
/// @param heading     the sender's horizontal heading (unit; zero: no body blocking)
/// @param t_emit_s    the emission time (s)
AcousticEmission SimulateEmission(const AcousticStampOptions& options, std::span<const geometry::Reflector3> reflectors,
                                  std::span<const Vec3> mics_m, const Vec3& sender_m, const Vec2& heading,
                                  double t_emit_s, core::Rng& rng);

}  // namespace mirage::channel
