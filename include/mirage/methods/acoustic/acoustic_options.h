// SPDX-License-Identifier: MIT
// Options of the acoustic method family (Bordoy 2020 ch. 5): which estimator runs on the
// microphones' stamps, its geometry mode, the stamp noise, the emission interval and the
// safeguards, each with its own switch for the ablations.
#pragma once

#include <string>
#include <vector>

#include "mirage/core/options_descriptor.h"
#include "mirage/estimation/imu/pdr.h"
#include "mirage/estimation/motion/constant_velocity.h"
#include "mirage/estimation/robust/irls_update.h"
#include "mirage/methods/acoustic/ground_echo_fix.h"
#include "mirage/methods/acoustic/los_identification.h"

namespace mirage::methods::acoustic {

/// Options of the acoustic estimators.
struct AcousticOptions {
  /// "rekf": the robust EKF, Hampel-weighted iteratively reweighted least squares over the prior
  /// and the stamps (Sec. 5.2, Eq. 5.24-5.30); "ekf": the same filter with every weight 1 (the
  /// thesis's standard EKF); "nlls": a snapshot Levenberg-Marquardt fix per emission from random
  /// starts using every microphone's stamp (the thesis's NLLS comparison); "combinatorial": the
  /// 8-step LOS identification per emission (Sec. 5.1); "ground_echo": a 3-D fix per emission
  /// from the LOS and floor-echo stamps (ch. 8, ground_echo_fix.h), mode 3d.
  std::string estimator = "rekf";
  /// "planar": x, y at the world's known sender height (ch. 5: the combinatorial method and the
  /// thesis's errors are 2-D); "3d": the height too.
  std::string mode = "planar";
  /// Standard deviation of one stamp as a distance (m), > 0. 0.103 m = 0.3 ms at 343 m/s, the
  /// ch. 5 synthetic regime; derived from the scenario's stamp noise.
  double range_sigma_m = 0.103;
  /// The sender's nominal emission interval I (s), > 0. 0.1 s (the ch. 5 data: 128 337 fixes in
  /// 213 min); derived: the scenario's step time.
  double emission_interval_s = 0.1;
  /// Standard deviation of the sender's emission-time jitter per interval (s), >= 0. 20 us:
  /// a phone's audio clock ticks at 48 kHz.
  double emission_jitter_s = 20e-6;
  /// Largest rate error of the sender's clock (ppm), >= 0: the prior of the interval's error
  /// (Sec. 6.2: up to +-50 ppm), estimated in the state so that (3.39) holds over minutes.
  double clock_drift_ppm = 50.0;
  /// The TDOA bound (Eq. 5.5): a stamp pair with |T_i - T_j| > |M_i - M_j| / c plus
  /// tdoa_bound_sigmas * sqrt(2) sigma cannot both be direct paths; the stamp in most such pairs
  /// is left out. Applied to every estimator (the thesis's Fig. 5.5 setting).
  bool tdoa_bound_gate = true;
  /// Noise margin of the TDOA bound in stamp sigmas, >= 0. 3.
  double tdoa_bound_sigmas = 3.0;
  /// Highest order of the reflections (walls, floor, ceiling of the world's floor plan) whose
  /// paths the filters predict per microphone, in [0, 2]. Every stamp may be the direct path or an
  /// echo, a virtual receiver mirrored in the surfaces, so that an emission whose direct paths the
  /// body blocks still informs the filter. 2: a room with a floor and a ceiling returns the
  /// double echoes (floor-ceiling, wall-floor, wall-wall) among the first-order ones, and a filter
  /// that does not predict them pairs them with first-order paths and confirms the wrong pairing
  /// (docs/results/acoustic.md: order 1 loses hold-out runs and biases a 3-D height by
  /// 0.23 m). 1: first-order echoes only (a third of the cost). 0: direct paths only (the thesis).
  /// Ignored without a floor plan with a ceiling.
  int echo_order = 2;
  /// Probability that a predicted path's stamp is detected, in (0, 1]. With clutter_density_per_m
  /// it sets the association's likelihood-ratio gate (see the estimator). 0.9; derived: the
  /// scenario's detection probability.
  double detection_probability = 0.9;
  /// Density of stamps that no predicted path explains (false alarms, higher-order echoes) per
  /// metre of c T and microphone, >= 0; 0: every path takes its nearest stamp (no gate, the
  /// thesis). Derived: the scenario's false-alarm rate over a 40 m listening window.
  double clutter_density_per_m = 0.0;
  /// Filters with the echo model: declare the track lost when its position leaves the floor plan
  /// (or goes below the floor, above the heights the start searches) by more than 3 sigma, and
  /// start again from all the stamps over the whole plan (multipath_fix.h).
  bool restart_lost_track = true;
  /// The REKF with direct paths only (echo_order 0, or no floor plan to predict echoes from) and
  /// dead reckoning: the level of its virtual-sender test (Sec. 5.2: facing a wall, only its echoes
  /// arrive, and they fit the sender mirrored behind it), the chance that an update breaks the
  /// dead reckoning this far without one, in [0, 1); 0: off. Such stamps agree with each other, so
  /// no per-row weight rejects them. A confirmed track (its prediction explained most stamps) whose
  /// update breaks the dead reckoning beyond its chi-square quantile at 1 - this level coasts on
  /// the dead reckoning, stamps left out, until an update explains most stamps and agrees with the
  /// dead reckoning again. 1e-3 (1e-2 to 1e-9 measured alike: docs/results/acoustic.md).
  double virtual_sender_false_alarm = 1e-3;
  /// The longest a virtual sender's onset takes (s), > 0: the phone turning to face the wall.
  /// Emissions within it mix direct paths and echoes and fit neither the track nor the mirror, so
  /// a track stays confirmed until its stamps have gone unexplained for longer than this plus
  /// one emission interval. 0.25 s (0.25-1 s measured alike: docs/results/acoustic.md).
  double virtual_sender_onset_s = 0.25;
  /// Chi-square gate on one stamp's innovation (1 degree of freedom), >= 0; 0 = off (the thesis's
  /// EKF and REKF have none: the REKF's weights do the rejecting).
  double gate_chi2 = 0.0;
  /// The REKF's reweighting (Hampel weights over the whitened prior and stamp rows). The plain
  /// EKF ("ekf") uses the same update with every weight 1.
  estimation::IrlsOptions irls;
  /// Position standard deviation of a given start (m), > 0. 0.5 m.
  double initial_position_sigma_m = 0.5;
  /// Velocity standard deviation at the start (m/s), > 0. 1 m/s; derived: the walker's speed.
  double initial_velocity_sigma_mps = 1.0;
  /// The combinatorial estimator's switches (its stamp sigma, TDOA bound and margin are the
  /// method's range_sigma_m, tdoa_bound_gate and tdoa_bound_sigmas).
  LosIdentificationOptions los;
  /// The ground_echo estimator's options (its sigma, interval and drift are the method's).
  GroundEchoOptions ground_echo;
  /// Random starts of the snapshot NLLS, >= 1. 10.
  int nlls_starts = 10;
  /// Fuse the phone's dead reckoning (loose coupling, Eq. 5.35-5.39): position increments between
  /// emissions, from the epochs' PositionIncrement records or from their IMU samples through
  /// pedestrian dead reckoning, as rows S - S_prev = delta on a clone of the last position.
  bool inertial = false;
  /// Pedestrian dead reckoning of raw IMU samples. Its heading starts from the track's velocity
  /// once the speed is above initial_velocity_sigma_mps and known to a third of itself.
  estimation::PdrOptions pdr;
  /// White-acceleration model of the sender (Eq. 5.31-5.34).
  estimation::ConstantVelocityOptions motion;
};

/// The options' descriptor (keys, units, ranges, docs).
const core::OptionsDescriptor<AcousticOptions>& AcousticOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid.
std::vector<std::string> Validate(const AcousticOptions& options);

}  // namespace mirage::methods::acoustic
