// SPDX-License-Identifier: MIT
#include "mirage/methods/acoustic/acoustic_options.h"

#include <algorithm>

#include "mirage/core/derived_defaults.h"

namespace mirage::methods::acoustic {

const core::OptionsDescriptor<AcousticOptions>& AcousticOptionsDescriptor() {
  using core::ValueRange;
  using O = AcousticOptions;
  static const auto descriptor = [] {
    core::OptionsDescriptor<O> d("methods::acoustic::AcousticOptions");
    d.Choice(&O::estimator,
             {.key = "estimator",
              .doc = "rekf: the robust EKF, Hampel-weighted reweighting of the prior and the stamps (Bordoy 2020 Eq. "
                     "5.24-5.30); ekf: the same filter with every weight 1; nlls: a Levenberg-Marquardt fix per "
                     "emission from random starts with every microphone's stamp; combinatorial: the 8-step LOS identification "
                     "per emission (Sec. 5.1), planar mode only; ground_echo: a 3-D fix per emission from the line of sight and "
                     "the floor echo at each microphone (ch. 8), mode 3d."},
             {"rekf", "ekf", "nlls", "combinatorial", "ground_echo"});
    d.Choice(&O::mode,
             {.key = "mode",
              .doc = "planar: x, y at the world's known sender height (ch. 5, errors in 2-D); 3d: the height too."},
             {"planar", "3d"});
    d.Number(&O::range_sigma_m, {.key = "range_sigma_m",
                                 .unit = "m",
                                 .range = ValueRange::Above(0.0),
                                 .doc = "Standard deviation of one stamp as a distance. 0.103 m = 0.3 ms at 343 m/s (the "
                                        "ch. 5 synthetic regime); derived from the scenario's stamp noise.",
                                 .derived = core::RangeSigmas(1.0)});
    d.Number(&O::emission_interval_s,
             {.key = "emission_interval_s",
              .unit = "s",
              .range = ValueRange::Above(0.0),
              .doc = "The sender's nominal emission interval I. 0.1 s (the ch. 5 data: 128 337 fixes in 213 min); "
                     "derived: the scenario's step time.",
              .derived = core::DerivedDefault{.formula = "dt_s",
                                              .needs = {core::PhysicalKey::kStepTime},
                                              .compute = [](const core::PhysicalKeys& k) { return *k.dt_s; }}});
    d.Number(&O::emission_jitter_s, {.key = "emission_jitter_s",
                                     .unit = "s",
                                     .range = ValueRange::AtLeast(0.0),
                                     .doc = "Standard deviation of the emission time's jitter per interval. 20 us: a "
                                            "phone's audio clock ticks at 48 kHz."});
    d.Number(&O::clock_drift_ppm, {.key = "clock_drift_ppm",
                                   .unit = "ppm",
                                   .range = ValueRange::AtLeast(0.0),
                                   .doc = "Largest rate error of the sender's clock: the prior of the interval's error, "
                                          "which the filter estimates (Eq. 3.39 over minutes). 50 ppm."});
    d.Boolean(&O::tdoa_bound_gate, {.key = "tdoa_bound_gate",
                                    .doc = "Leave out stamps that violate the TDOA bound |T_i - T_j| <= |M_i - M_j| / c "
                                           "(Eq. 5.5) against most other microphones."});
    d.Boolean(&O::restart_lost_track,
              {.key = "restart_lost_track",
               .doc = "Filters with the echo model: declare the track lost when its position leaves the floor plan "
                      "(or goes below the floor, above the heights the start searches) by more than 3 sigma, and start "
                      "again from all the stamps over the whole plan."});
    d.Number(&O::tdoa_bound_sigmas, {.key = "tdoa_bound_sigmas",
                                     .range = ValueRange::AtLeast(0.0),
                                     .doc = "Noise margin of the TDOA bound in stamp sigmas (times sqrt 2 for the "
                                            "difference). 3."});
    d.Integer(&O::echo_order,
              {.key = "echo_order",
               .range = ValueRange::Closed(0.0, 2.0),
               .doc = "Highest order of the floor plan's reflections (walls, floor, ceiling) whose paths the filters "
                      "predict per microphone: a stamp may be the direct path or an echo, a virtual receiver. 2: the "
                      "double echoes (floor-ceiling, wall-floor) arrive among the first-order ones and would be paired "
                      "with them; 1: first-order echoes only; 0: direct paths only (the thesis). Ignored without a "
                      "floor plan with a ceiling. 2."});
    d.Number(&O::detection_probability,
             {.key = "detection_probability",
              .range = ValueRange::LeftOpen(0.0, 1.0),
              .doc = "Probability that a predicted path's stamp is detected; with clutter_density_per_m it sets the "
                     "association's likelihood-ratio gate. 0.9; derived: the scenario's detection probability.",
              .derived = core::DerivedDefault{
                  .formula = "detection_probability",
                  .needs = {core::PhysicalKey::kDetectionProbability},
                  .compute = [](const core::PhysicalKeys& k) { return std::max(*k.detection_probability, 1e-3); }}});
    d.Number(&O::clutter_density_per_m,
             {.key = "clutter_density_per_m",
              .unit = "1/m",
              .range = ValueRange::AtLeast(0.0),
              .doc = "Stamps no predicted path explains (false alarms, higher-order echoes) per metre of c T and "
                     "microphone; 0: every path takes its nearest stamp, no gate (the thesis). Derived: the "
                     "scenario's false-alarm rate over a 40 m listening window.",
              .derived = core::DerivedDefault{
                  .formula = "clutter_rate / 40 m",
                  .needs = {core::PhysicalKey::kClutterRate},
                  .compute = [](const core::PhysicalKeys& k) { return *k.clutter_rate / 40.0; }}});
    d.Number(&O::virtual_sender_false_alarm,
             {.key = "virtual_sender_false_alarm",
              .range = ValueRange::RightOpen(0.0, 1.0),
              .doc = "The REKF with direct paths only and dead reckoning: the level of its virtual-sender test (Sec. "
                     "5.2), the chance that an update breaks the dead reckoning this far without one. A confirmed track "
                     "(its prediction explained most stamps) whose update breaks the dead reckoning beyond its "
                     "chi-square quantile at 1 - this level coasts on it until an update explains most stamps and agrees "
                     "with it again. 0: off. 1e-3."});
    d.Number(&O::virtual_sender_onset_s,
             {.key = "virtual_sender_onset_s",
              .unit = "s",
              .range = ValueRange::Above(0.0),
              .doc = "The longest a virtual sender's onset takes (the phone turning to face the wall): emissions within "
                     "it fit neither the track nor the mirror, so a track stays confirmed until its stamps have gone "
                     "unexplained for longer than this plus one emission interval. 0.25 s."});
    d.Number(&O::gate_chi2, {.key = "gate_chi2",
                             .range = ValueRange::AtLeast(0.0),
                             .doc = "Chi-square gate on one stamp's innovation (1 degree of freedom); 0 = off, as in "
                                    "the thesis (the REKF's weights do the rejecting)."});
    d.Section(&O::irls, {.key = "irls", .doc = "The REKF's reweighting; ekf runs it with every weight 1."},
              estimation::IrlsOptionsDescriptor());
    d.Number(&O::initial_position_sigma_m, {.key = "initial_position_sigma_m",
                                            .unit = "m",
                                            .range = ValueRange::Above(0.0),
                                            .doc = "Position standard deviation of a given start. 0.5 m."});
    d.Number(&O::initial_velocity_sigma_mps, {.key = "initial_velocity_sigma_mps",
                                              .unit = "m/s",
                                              .range = ValueRange::Above(0.0),
                                              .doc = "Velocity standard deviation at the start. 1 m/s; derived: the "
                                                     "walker's speed in an unknown direction.",
                                              .derived = core::SpeedTimes(1.0)});
    d.Section(&O::los,
              {.key = "los",
               .doc = "The combinatorial estimator's switches; its stamp sigma and TDOA bound are the method's "
                      "range_sigma_m, tdoa_bound_gate and tdoa_bound_sigmas."},
              LosIdentificationSectionDescriptor());
    d.Section(&O::ground_echo,
              {.key = "ground_echo",
               .doc = "The ground_echo estimator's options; its stamp sigma, emission interval and clock drift are "
                      "the method's."},
              GroundEchoOptionsDescriptor());
    d.Integer(&O::nlls_starts, {.key = "nlls_starts",
                                .range = ValueRange::Closed(1.0, 1000.0),
                                .doc = "Random starts of the snapshot NLLS per emission. 10."});
    d.Boolean(&O::inertial, {.key = "inertial",
                             .doc = "Fuse the phone's dead reckoning (Eq. 5.35-5.39): position increments between "
                                    "emissions (PositionIncrement records, or IMU samples through pedestrian dead "
                                    "reckoning) as rows on a clone of the previous position."});
    d.Section(&O::pdr, {.key = "pdr", .doc = "Pedestrian dead reckoning of raw IMU samples."},
              estimation::PdrOptionsDescriptor());
    d.Section(&O::motion, {.key = "motion", .doc = "White-acceleration model of the sender (Eq. 5.31-5.34)."},
              estimation::ConstantVelocityOptionsDescriptor());
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const AcousticOptions& options) {
  auto problems = AcousticOptionsDescriptor().Validate(options);
  if (options.estimator == "combinatorial" && options.mode != "planar") {
    problems.push_back("estimator: combinatorial needs mode planar (the closed form of Sec. 5.1 step 2 takes the "
                       "sender's height as known), got mode " + options.mode);
  }
  if (options.estimator == "ground_echo" && options.mode != "3d") {
    problems.push_back("estimator: ground_echo needs mode 3d (its point is the height), got mode " + options.mode);
  }
  return problems;
}

}  // namespace mirage::methods::acoustic
