// SPDX-License-Identifier: MIT
// Combinatorial line-of-sight identification for one acoustic emission (Bordoy 2020 PhD thesis,
// Univ. Freiburg, Sec. 5.1, the 8-step algorithm; digest Sec. 2.6): every receiver triplet and
// every choice of one of its K earliest stamps per receiver gives 0-2 closed-form fixes at the
// known sender height (step 2); the TDOA bound (5.5) prunes stamp choices beforehand; the
// causality test (5.4) drops virtual senders (step 3); every other receiver votes for a fix when
// its stamp lies within a window of the fix's prediction (Eq. 5.3; by default) or when the 4-row
// least-squares problem (triplet + that receiver) has no influential row by Cook's distance (the
// thesis's steps 4-7, `cook_voting`); the fix with most votes is refined by Levenberg-Marquardt
// over its triplet and its voters (step 8), and a stamp off that fit is left out (`final_test`).
// Everything is in metres: stamps enter as pseudo-ranges rho_i = c (T_i - t_ref) = |S - M_i| + b
// for any common t_ref, b = c (t_s - t_ref) the unknown emission offset.
//
// Choices where the thesis is silent, and why:
//  - Cook step in the TOA form, not the thesis's TDOA form (5.16): rows [u_x, u_y, 1] in the
//    unknowns (x, y, b), u_i = (S - M_i) / |S - M_i| (3-D, z known), at the closed-form fix.
//    The TDOA form with a reference receiver correlates the rows through the reference, which
//    the diagnostics ignore; TOA rows are independent with one known sigma.
//  - Residuals (digest [SUG]): the fix is exact for the triplet, so the residuals are those of
//    one linearised Gauss-Newton step from it over the 4 rows, e = (I - L) r0 with r0 the
//    prediction residuals at the fix. With m = 4 rows and p = 3 unknowns the residual space is
//    one-dimensional, spanned by n with n_j = (-1)^j det(H without row j) (the cofactors, n^T H
//    = 0), so L = I - n n^T / |n|^2 and e = n (n . r0) / |n|^2: no matrix factorisation in the
//    inner loop. The tests check this against estimation::DiagnoseRegression.
//  - Cook's distance in the textbook form D_j = e_j^2 l_jj / (p' sigma^2 (1 - l_jj)^2) (digest
//    typo list item 6) with the KNOWN sigma (range_sigma_m): with m - p = 1 the estimate (5.13)
//    has one degree of freedom and would make every D_j a function of the leverages only.
//    p' = 3: the thesis's p + 1 with p = 2 estimated dimensions, the +1 being the emission time,
//    which here is a column of H, so p' is also the textbook column count. The threshold is the
//    F_{cook_probability}(p', m - p') = F_0.5(3, 1) quantile (about 1.71), the common rule of thumb
//    "D > F_0.5(p, n - p) is influential". A row of leverage 1 cannot be tested (NaN): the
//    receiver does not vote.
//  - Why the default vote is the window and not Cook's distance: with m - p = 1 and the known
//    sigma, every studentised residual of the 4-row problem equals t = (n . r0) / (|n| sigma), a
//    N(0, 1) variate for four LOS rows, so D_j = t^2 l_jj / (p' (1 - l_jj)): Cook's test is a
//    residual test whose threshold shrinks with the largest leverage, and an F quantile has no
//    calibrated meaning for it (D is not F-distributed with sigma known). F_0.5 rejects a LOS
//    voter whenever t^2 > 5.1 (1 - l_max) / l_max, about one in five (recall 0.83 in the tests'
//    Monte Carlo); a looser F lets wrong candidates collect votes; the null-calibrated test (t^2
//    against a chi2(1) quantile) widens the window by the prediction's variance sigma^2 / (1 -
//    l_44), so poorly conditioned triplets, most of them wrong, collect votes. The window on the
//    raw prediction residual keeps sigma fixed: a triplet whose fix cannot predict a fourth stamp
//    to 3 sigma gets no vote from it. The measured comparison (failure rates, no-fix shares, the
//    hold-outs) is in docs/results/acoustic.md; Cook's vote stays as the thesis's ablation.
//  - Among the K stamps of a voting receiver, the one nearest the fix's prediction is tested.
//  - Ties in votes: the lower sum over the voters of ((rho_i - prediction_i) / sigma)^2 wins,
//    then the first candidate found (receivers ranked by their earliest stamp, triplets in
//    co-lexicographic order of rank, so that max_triplets keeps the triplets among the earliest
//    receivers, which are the most likely LOS, digest Sec. 1.2).
//  - The TDOA bound (5.5) with a non-negative margin is implied by the existence of a root: a
//    genuine root has r_i - r_j = rho_i - rho_j and |r_i - r_j| <= |M_i - M_j| by the triangle
//    inequality. So it only saves closed-form solves (the thesis: "reduce the number of
//    combinations"), it never changes the fix.
//  - Causality (5.4) checks the EARLIEST stamp of every receiver (all its stamps, not only the
//    K earliest; the earliest is the binding one) with a margin of causality_sigmas * sigma.
//  - Limitation (thesis Sec. 5.2, Fig. 5.3): when every receiver hears only one wall's
//    reflection, the stamps are exactly those of the mirrored (virtual) sender, nothing arrives
//    before its direct path, and the method returns the virtual sender. Residual methods cannot
//    detect this.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/estimation/solvers/solver_fix.h"

namespace mirage::methods::acoustic {

/// Options of IdentifyLos.
struct LosIdentificationOptions {
  /// Standard deviation of one stamp as a distance (m), > 0. 0.103 m = 0.3 ms at 343 m/s, the
  /// ch. 5 synthetic regime.
  double range_sigma_m = 0.103;
  /// K, >= 1: the K earliest stamps of each receiver enter the combinations (C(N, 3) K^3 closed
  /// forms). 2: the direct path and one echo or false peak.
  int max_stamps_per_receiver = 2;
  /// Skip a stamp choice whose pair |rho_i - rho_j| exceeds |M_i - M_j| plus the margin (Eq. 5.5).
  /// It saves closed-form solves and never changes the fix (see the file comment).
  bool tdoa_bound = true;
  /// Margin of the TDOA bound in sigmas of a stamp difference (sqrt(2) sigma), >= 0. 3.
  double tdoa_bound_sigmas = 3.0;
  /// Reject a fix when any receiver's earliest stamp arrives before the fix's direct path by more
  /// than causality_sigmas * sigma (Eq. 5.4): the fix is a virtual sender.
  bool causality_test = true;
  /// Margin of the causality test in stamp sigmas, >= 0. 3.
  double causality_sigmas = 3.0;
  /// Voting by Cook's distance (the thesis's steps 4-7): receiver i votes when the largest Cook's
  /// distance of the 4-row problem (triplet + i) is below the F threshold. false (default):
  /// receiver i votes when one of its K stamps lies within window_sigmas * sigma of the fix's
  /// prediction (Eq. 5.3; why this is the default: the file comment).
  bool cook_voting = false;
  /// Probability of the F quantile used as Cook's threshold (cook_voting), in (0, 1). 0.5: the usual rule of
  /// thumb D > F_0.5(p', m - p') (the thesis gives no number). F(3, 1) is heavy-tailed, and with
  /// pure noise the largest of the 4 distances is at least a chi2(1) variate, so 0.5 (threshold
  /// 1.71) is strict: in the tests' hall (sigma 0.1 m, biases >= 1 m) it keeps every NLOS stamp
  /// out but misses 17 % of the LOS ones; 0.8 (threshold 13.1) misses 4 % and still admits ~0.
  double cook_probability = 0.5;
  /// Half-width of the window of the vote (cook_voting false) around the fix's predicted stamp, in
  /// stamp sigmas, > 0. 3: a LOS stamp misses it with probability 0.3 % given an exact fix.
  double window_sigmas = 3.0;
  /// After the Levenberg-Marquardt refinement (step 8), while the stamp with the largest
  /// studentised residual e_i / (sigma sqrt(1 - l_ii)) (Eq. 5.12, the known sigma) lies beyond
  /// window_sigmas, leave it out and refit: the consistency test (5.3) again, at the fix of all
  /// the chosen stamps, which predicts far better than a triplet's (data snooping). The vote
  /// decides coarsely which stamps belong together; this test catches a stamp a few sigmas off (an
  /// echo whose path is a little longer) that fell inside the window of an imprecise triplet fix.
  /// No fix when fewer than 3 + min_votes stamps would remain; no test when the refinement
  /// failed (the closed-form start is kept). Its threshold is the vote's window_sigmas (one
  /// consistency test, Eq. 5.3, at two fixes), not corrected for testing several stamps.
  bool final_test = true;
  /// Fewest votes (receivers beyond the triplet) for a fix, >= 0. 1: a triplet's fix alone is
  /// exact for any three stamps, so without one more receiver nothing is verified.
  int min_votes = 1;
  /// Most receiver triplets enumerated (in the order of the file comment), >= 0; 0: all C(N, 3).
  int max_triplets = 0;
  /// Iteration limit of the final Levenberg-Marquardt refinement, >= 1. 50.
  int max_refine_iterations = 50;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<LosIdentificationOptions>& LosIdentificationOptionsDescriptor();

/// The descriptor without range_sigma_m, tdoa_bound and tdoa_bound_sigmas: a section of a method
/// that has those keys itself and copies them in (methods::acoustic "los").
const core::OptionsDescriptor<LosIdentificationOptions>& LosIdentificationSectionDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const LosIdentificationOptions& options);

/// The identified line-of-sight stamps and the fix they give.
struct LosIdentification {
  /// Sender position S (m); z is the known height. Zero when !found.
  Vec3 position_m = Vec3::Zero();
  /// Emission offset b (m) in rho_i = |S - M_i| + b, in the caller's t_ref.
  double offset_m = 0.0;
  /// Covariance of the position (m^2) from the refinement with the known sigma: the x, y block is
  /// filled, z (known) is zero.
  Eigen::Matrix3d covariance_m2 = Eigen::Matrix3d::Zero();
  /// The receivers whose stamps the fix uses (the triplet and its voters), increasing.
  std::vector<int> los_receivers;
  /// Per input receiver: the index (into that receiver's input stamps) of its LOS stamp, or -1.
  std::vector<int> los_stamp_index;
  /// The winning triplet's receivers (-1 when !found); the final test may have left one out of
  /// los_receivers.
  std::array<int, 3> triplet{-1, -1, -1};
  /// Closed-form fixes that passed the causality test and were voted on.
  int candidates_evaluated = 0;
  /// Closed-form fixes rejected as virtual senders by the causality test (5.4).
  int virtual_senders_rejected = 0;
  /// Stamp choices skipped by the TDOA bound (5.5) before the closed form.
  int combinations_pruned = 0;
  /// Closed-form solves performed.
  int closed_form_solves = 0;
  /// The winner's votes (receivers beyond its triplet), before the final test.
  int votes = 0;
  /// The winner's stamps left out by the final test (final_test), also when that left no fix.
  int stamps_left_out = 0;
  /// A fix with at least min_votes votes exists.
  bool found = false;
  /// Status of the Levenberg-Marquardt refinement; when it is not kOk the closed-form fix is kept.
  estimation::SolverStatus refine_status = estimation::SolverStatus::kOk;
  /// RMS of the pseudo-range residuals of the LOS stamps at the fix (m).
  double rms_m = 0.0;
};

/// Identifies the LOS stamps of one emission and locates the sender (steps 1-8 of Sec. 5.1).
/// Receivers without (finite) stamps take no part. found is false with fewer than 3 receivers
/// with stamps, or when no candidate survives with min_votes votes.
/// @param receivers_m      receiver positions M_i (m), any heights
/// @param pseudo_ranges_m  per receiver, its stamps as pseudo-ranges c (T - t_ref) (m), any order;
///                         same size as receivers_m
/// @param sender_height_m  the known sender height z (m)
/// @param options          valid options (Validate)
LosIdentification IdentifyLos(std::span<const Vec3> receivers_m, const std::vector<std::vector<double>>& pseudo_ranges_m,
                              double sender_height_m, const LosIdentificationOptions& options);

/// The Jacobian row d rho / d(x, y, b) = [u_x, u_y, 1] of rho = |S - M| + b with the height known,
/// u = (S - M) / |S - M| in 3-D (meas/toa.h); std::nullopt when S is within kMinToaRange_m of M.
/// @param sender_m   the sender S (m)
/// @param receiver_m the receiver M (m)
std::optional<Eigen::RowVector3d> ToaJacobianXyb(const Vec3& sender_m, const Vec3& receiver_m);

/// The largest Cook's distance of the 4-row TOA problem [u_j^T, 1] (j = the triplet and one more
/// receiver) with residuals of one linearised Gauss-Newton step (see the file comment); NaN when a
/// row has leverage 1 or the rows are rank-deficient.
/// @param J_pred_state        the 4 x 3 Jacobian rows [u_x, u_y, 1] (unitless)
/// @param prediction_residual_m rho_j - (|S - M_j| + b) at the fix, per row (m)
/// @param sigma_m             the stamps' standard deviation (m), > 0
/// @param p_prime             Cook's divisor, >= 1 (3 here)
double MaxCookDistance4x3(const Eigen::Matrix<double, 4, 3>& J_pred_state, const Eigen::Vector4d& prediction_residual_m,
                          double sigma_m, int p_prime);

}  // namespace mirage::methods::acoustic
