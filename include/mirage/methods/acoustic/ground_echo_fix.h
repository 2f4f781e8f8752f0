// SPDX-License-Identifier: MIT
// The sender's 3-D position, its height above all, from the line of sight and the floor echo at
// each ceiling microphone (Bordoy 2020, PhD thesis Univ. Freiburg, ch. 8, Sec. 8.4-8.5). The floor
// echo is the line of sight of the microphone mirrored in the floor, M' = (x, y, 2 f - z); with
// microphones on the ceiling the two rows of a microphone point nearly opposite ways in z, which
// pins the height (VDOP ~1 instead of up to ~24 for TDOA on the line of sight alone, Sec. 8.3).
//
// Per emission (estimator "ground_echo" of the acoustic family, one fix per emission, no motion
// model, as the thesis's Sec. 8.5 evaluation):
//  1. Stamp selection: the consensus vote of Sec. 8.4 (estimation/solvers/sending_time_vote.h)
//     over the emissions of the last vote_window_s, each emission's stamps minus its elapsed
//     intervals k I (Eq. 8.79), picks t_0 and each microphone's LOS and floor-echo stamp. The
//     thesis votes over all emissions of a static test; a moving sender with a drifting clock
//     needs a window, shortened so that clock_drift_ppm moves t_0 by at most half a stamp sigma
//     across it. The full search runs once; afterwards the last t_0 plus the elapsed intervals is
//     the hypothesis (VoteSendingTimeAt), the search again only when no emission of the window had
//     a t_0; a known sending time is itself the hypothesis.
//  2. Geometry the vote is given (all from the world): the microphones' heights, which make
//     K = 4 h_s h_m / c^2 exact (Eq. 8.77 assumes one height: the ASSIST spread of 5.5 cm
//     biases t_0 by 0.1-0.4 ms); the ceiling, whose echo pairs with the LOS like a floor echo
//     and is excluded by the excess bound 4 (C - h_m) h_m (valid while the sender is higher above
//     the floor than the microphones are below the ceiling); and the rule that the LOS is each
//     microphone's first arrival after t_0 (every pair of horizontal-plane or wall images, e.g.
//     (ceiling echo, floor echo), satisfies Eq. 8.74-8.77 with the same t_0 and K). With the
//     ceiling known (`floor_ceiling_echoes`, beyond the thesis) the echo off the floor and then
//     the ceiling is modelled too: paired with the LOS it looks like the floor echo of a sender
//     higher by (C - h) (C + z) / h, so its pairs formed clusters of their own that competed
//     with the floor pairs; now it is a second row of the same (t_0, sender height)
//     (SendingTimeVoteOptions::ceiling_height_m).
//  3. The sending time: "estimated", the vote's t_0 (Eq. 8.77-8.79), by default a prior on an
//     offset solved with the fix (`vote_prior`, step 5), else plugged in; "known", the records'
//     emission time (core::ToaStamps::emission_s: a synchronised sender or a reference system,
//     the thesis's MoCap-derived t_s); "unknown", an offset b = c t_s solved with the position
//     (pseudo-ranges, whose position fix equals the TDOA fix with the correlated covariance
//     R_TD = D R D^T: Shin & Sung, Sec. 8.3; the thesis's "TDOA" rows).
//  4. The fix: Levenberg-Marquardt (Eq. 8.80-8.82; the thesis uses gradient descent and Gauss-
//     Newton) on the LOS rows |S - M_i| = c (T_L,i - t_0) and, with echoes, the floor-echo rows
//     |S - M'_i| = c (T_r,i - t_0) and the floor-ceiling rows (the microphone mirrored in the
//     ceiling, then the floor: (x, y, 2 f - (2 C - z))), from the last fix, else below the
//     microphones' centroid. A floor-ceiling row beyond 3 sigma is left out alone; the
//     microphones are tested on their LOS and floor rows (one read from its floor-ceiling
//     echo alone, its floor echo missed, on its LOS row).
//     When a row lies beyond 3 sigma, the largest consensus of microphones (every smallest set
//     with rows for the unknowns solved, at least three with a solved offset; the microphones
//     within 3 sigma of its fix counted, ties to the fix explaining more of all the emission's
//     stamps; Fischler & Bolles) is refitted, then the worst microphone beyond 3 sigma left out
//     while rows remain; a fix of no more microphones than the smallest set fits them whatever
//     their stamps and is no fix. The vote's other K clusters are fitted too, and the fix that
//     explains the emission's stamps best wins: every modelled arrival at every microphone
//     (LOS, floor echo, and with the ceiling known the ceiling and floor-ceiling echoes), its
//     nearest stamp within 3 sigma scored 9 - (miss / sigma)^2 (MSAC, Torr & Zisserman 2000;
//     exact ties, as of one selection reached twice, to the fix keeping more microphones). The
//     consensus's tie-break above counts the same arrivals (SupportAt). With the vote's t_0 as a
//     prior it is one more arrival of that score (the solved offset's miss over the prior's
//     and the fix's variance, within the prior's own 3 sigma gate of step 5): pseudo-ranges
//     alone fit the floor-ceiling echoes read as floor echoes (a sender higher by
//     (C - h) (C + z) / h, 0.4-0.5 m in the hall, and a later offset) nearly as well as the true
//     reading. With the thesis's plug-in t_0 only the clusters of as many microphones as the
//     vote's are fitted (its fits take the vote's t_0 as exact, and the score over all stamps
//     then prefers wrong smaller clusters).
//     With LOS rows only, coplanar microphones fit the sender's mirror image in their
//     plane as well: a fix above the ceiling restarts from that mirror; a fix more than 3 of its
//     vertical sigmas below the floor is no fix.
//  5. Its CRLB and DOPs at the fix: (H^T R^-1 H)^-1 of the rows used, the range model (t_0 given)
//     or the pseudo-range model (t_0 unknown); eval/dop.h computes the same from the geometry.
//     The reported covariance adds, for a plugged-in voted t_0, its own error (the vote's sigma
//     through the fix's response to a common range offset): the CRLB does not contain it.
//     With `vote_prior` the fix of the solved offset is updated by the vote's t_0 (a linear
//     update with the vote's robust sigma); its DOPs are those of the information used, the
//     rows plus the vote's t_0 (between the range and the pseudo-range model's). They depend on
//     the data: on the vote's sigma, and where the prior is left out (beyond 3 sigma of the
//     solved offset) they are the pseudo-range model's.
// An emission without three microphones in the vote's cluster, or with fewer rows than unknowns,
// or an unverified fix, or a degenerate or unconverged solve, has no fix. Left open: the other
// second-order echoes (wall-floor, floor-wall) and higher orders are not modelled
// (docs/results/acoustic.md: order 2 in the example's grid).
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "mirage/core/epoch.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/estimation/solvers/sending_time_vote.h"
#include "mirage/estimation/solvers/solver_fix.h"

namespace mirage::methods::acoustic {

/// Options of the floor-echo fix (the "ground_echo" section of the acoustic options).
struct GroundEchoOptions {
  /// Use the floor-echo rows (microphones mirrored in the floor). false: the LOS rows only, the
  /// thesis's "without echoes" variants.
  bool echoes = true;
  /// "estimated": t_0 from the vote (Eq. 8.77-8.79); "known": the records' emission time;
  /// "unknown": an offset solved with the position (the TDOA variants).
  std::string sending_time = "estimated";
  /// With sending_time "estimated": true, the vote's t_0 is a prior (its robust sigma) on an
  /// offset solved with the fix, the DOPs those of the rows plus the prior (step 5); false, the
  /// thesis's plug-in (Eq. 8.80, t_0 fixed) with the range model's DOPs.
  /// true fits as "unknown" does: a fix with echoes then needs four microphones.
  bool vote_prior = true;
  /// Longest span of emissions voted together (s), > 0. 1 s: ten emissions at the thesis's
  /// 0.1 s interval (its vote pools all emissions of a static test); shortened to
  /// stamp sigma / (2 clock_drift_ppm 1e-6) so that the clock's drift stays below half a sigma.
  double vote_window_s = 1.0;
  /// Largest height of the sender above the floor (m), > 0; bounds the echo delay (2 h_s / c).
  /// 2.5 m: a hand-held or worn sender.
  double max_sender_height_m = 2.5;
  /// The vote drops 4-tuples whose t_0 noise gain exceeds this (Eq. 8.77's conditioning), > 0. 20.
  double max_noise_gain = 20.0;
  /// With the ceiling known: the echo off the floor and then the ceiling is modelled in the vote
  /// (a second row of the floor echo's (t_0, kappa); SendingTimeVoteOptions::ceiling_height_m)
  /// and, with `echoes`, is a row of the fix (the microphone mirrored in the ceiling, then the
  /// floor). false: only the floor echo, as the thesis (its (LOS, floor-ceiling) pairs then
  /// compete with the floor pairs in the vote).
  bool floor_ceiling_echoes = true;
};

/// The section's descriptor (keys, units, ranges, docs).
const core::OptionsDescriptor<GroundEchoOptions>& GroundEchoOptionsDescriptor();

/// One emission's fix.
struct GroundEchoFix {
  bool found = false;
  Vec3 position_m = Vec3::Zero();
  /// The CRLB of the rows used, plus a voted t_0's error (m^2; see step 5).
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
  double hdop = 0.0;  ///< at the fix, the rows used (Eq. 8.10-8.12)
  double vdop = 0.0;
  int los_rows = 0;
  int echo_rows = 0;
  /// The sending time used, in the stamps' time base (s; "unknown": the epoch time plus the
  /// solved offset over c); empty without a fix.
  std::optional<double> sending_time_s;
  /// With sending_time estimated: the vote's t_0 (s, the stamps' time base) and its standard
  /// deviation (s; 0 when the vote's refinement gave none) as the vote reports them, before the
  /// fix uses them; set when the vote found t_0 with at least three microphones' pairs in this
  /// emission, also when the emission then gets no fix.
  std::optional<double> voted_sending_time_s;
  double voted_sending_time_sigma_s = 0.0;
};

/// A fix of [x, y, z, b] (b the offset, m) updated by a prior on b (step 5).
struct OffsetPriorUpdate {
  bool used = false;                                 ///< false: no prior, or one beyond 3 sigma
  Vec3 shift_m = Vec3::Zero();                       ///< added to the fix's position
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();   ///< the position's, after the update
  double offset_m = 0.0;                             ///< b after the update
};

/// The linear (Kalman) update of a fix [x, b] with covariance `covariance_m2` by the
/// pseudo-measurement b = prior_m of standard deviation prior_sigma_m. The prior is left out when
/// its sigma is not positive or it lies beyond 3 sigma of the innovation.
OffsetPriorUpdate UpdateWithOffsetPrior(const Eigen::Matrix4d& covariance_m2, double offset_m, double prior_m,
                                        double prior_sigma_m);

/// The per-emission floor-echo fixer of one run: keeps the window of recent emissions for the vote.
class GroundEchoFixer {
 public:
  /// @param mics_m            the microphones (m)
  /// @param floor_z_m         the floor's height (m)
  /// @param speed_mps         the assumed speed of sound (m/s), > 0
  /// @param range_sigma_m     one stamp's standard deviation as a distance (m), > 0
  /// @param interval_s        the nominal emission interval I (s), > 0
  /// @param clock_drift_ppm   the sender clock's largest rate error (ppm), >= 0
  /// @param ceiling_z_m       the ceiling's height (m) when the room has one: the vote then
  ///                          excludes the LOS / ceiling-echo pairs (SendingTimeVoteOptions::min_excess_m2)
  ///                          and, with options.floor_ceiling_echoes, models the floor-ceiling echo
  GroundEchoFixer(std::vector<Vec3> mics_m, double floor_z_m, double speed_mps, double range_sigma_m,
                  double interval_s, double clock_drift_ppm, const GroundEchoOptions& options,
                  std::optional<double> ceiling_z_m = std::nullopt);

  /// The fix of one emission (its stamps in epoch.toas, receiver_index into mics_m).
  GroundEchoFix Process(const core::Epoch& epoch);

  /// The effective vote window (s).
  [[nodiscard]] double vote_window_s() const { return window_s_; }

 private:
  struct Emission {
    double t_s = 0.0;                              // the epoch's time
    std::vector<std::vector<double>> stamps_s;     // per microphone, absolute times
  };

  std::vector<Vec3> mics_m_;
  double floor_z_m_;
  double c_mps_;
  double sigma_m_;
  double interval_s_;
  double window_s_;
  double mic_plane_z_m_ = 0.0;          // the microphones' mean height (m)
  std::optional<double> ceiling_z_m_;   // the room's ceiling (m), if known
  std::vector<Vec3> floor_images_m_;    // each microphone mirrored in the floor
  /// Each microphone mirrored in the ceiling (the ceiling echo's receiver); empty without a
  /// known ceiling above the microphones. Only the stamp support counts it (SupportAt).
  std::vector<Vec3> ceiling_images_m_;
  /// Each microphone mirrored in the ceiling, then in the floor (the floor-ceiling echo's
  /// receiver); empty unless the vote models that echo (vote_.ceiling_height_m > 0).
  std::vector<Vec3> floor_ceiling_images_m_;
  GroundEchoOptions options_;
  estimation::SendingTimeVoteOptions vote_;
  struct Track {
    double epoch_s = 0.0;  // the epoch time of the last emission with a t_0
    double t0_s = 0.0;     // its t_0 (s)
  };
  /// Levenberg-Marquardt from start_m (if any), else from fallback_start_m.
  [[nodiscard]] std::optional<estimation::SolverFix> Solve(const std::vector<Vec3>& receivers_m,
                                                           const std::vector<double>& values_m, bool offset_unknown,
                                                           const std::optional<Vec3>& start_m,
                                                           const Vec3& fallback_start_m) const;

  /// A selection's fix: the microphones kept within 3 sigma, their sum of squared residuals.
  struct SelectionFit {
    estimation::SolverFix fix;
    int mics = 0;
    double sum_sq_m2 = 0.0;
    /// The arrivals of the whole emission the fix explains (SupportAt).
    int support_rows = 0;
    /// Their MSAC score (StampSupport::score): how the fixes of the vote's clusters rank.
    double support_score = 0.0;
    int los_rows = 0;
    int echo_rows = 0;
    /// The fix's change per metre of a range offset common to every row (a sending time off by
    /// dt moves each range by c dt): (H^T H)^-1 H^T 1, unitless.
    Vec3 common_shift_gain = Vec3::Zero();
  };
  /// The fix of one emission's selection (per microphone its LOS and floor-echo stamp, indices
  /// into stamps_s): the largest consensus of microphones within 3 sigma; std::nullopt when no
  /// rows for the unknowns remain, no solve converges, or the fix keeps no more microphones than
  /// the smallest set (unverified), with or without the consensus search.
  [[nodiscard]] std::optional<SelectionFit> FitSelection(const std::vector<estimation::MicStampChoice>& chosen,
                                                         const std::vector<std::vector<double>>& stamps_s,
                                                         const std::optional<double>& t0_s) const;

  /// The stamps a hypothesis explains, over all of an emission's stamps (not only a selection's):
  /// per microphone and modelled arrival (LOS, floor echo, and with the ceiling known the ceiling
  /// echo and, when the vote models it, the floor-ceiling echo) its nearest stamp within 3 sigma,
  /// each stamp explaining one arrival. A blocked LOS does not keep the echoes from counting.
  struct StampSupport {
    int rows = 0;             // arrivals explained
    double sum_sq_m2 = 0.0;   // of the nearest stamps' misses
    /// Sum of 9 - (miss / sigma)^2 over the explained arrivals: the MSAC score (a stamp at the
    /// gate adds nothing, a chance stamp little, a true one ~8).
    double score = 0.0;
  };
  /// @param origin_m  c t_0 (t_0 given) or the solved offset: a stamp t lies at range c t - origin_m
  [[nodiscard]] StampSupport SupportAt(const Vec3& position_m, double origin_m,
                                       const std::vector<std::vector<double>>& stamps_s) const;

  std::deque<Emission> window_;
  std::optional<Track> track_;
  std::optional<Vec3> last_m_;
};

}  // namespace mirage::methods::acoustic
