// SPDX-License-Identifier: MIT
// The sending time t_0 of an acoustic sender from its line-of-sight (LOS) and ground-echo arrival
// stamps at two microphones, and a vote over all such 4-tuples of several emissions that picks
// t_0 and the LOS / ground-echo stamps out of unlabeled peaks (Bordoy 2020, PhD thesis Univ.
// Freiburg, Sec. 8.4, Eq. 8.70-8.79; the thesis calls the vote "RANSAC").
// Assumptions (the thesis's): the floor is a plane and the microphones lie in one plane parallel
// to it (Eq. 8.74-8.76); then (8.77) is exact and needs neither positions nor the speed of sound.
// Microphones at unequal heights h_i bias it: T_r,i^2 - T_r,j^2 - T_L,i^2 + T_L,j^2 =
// 4 h_s (h_i - h_j) / c^2 (h_s the sender's height), so t_0 is off by that over 2 (d_i - d_j).
// Choices where the thesis is silent:
//  - (8.77) is evaluated in times relative to the earliest of the four stamps (digest SUG), which
//    avoids the cancellation of squaring absolute stamps; the result is shifted back.
//  - Its denominator is 2 (d_i - d_j), d = T_r - T_L the echo delay; its noise gain (d t_0 / d T,
//    root-sum-square over the four stamps) is sqrt(sum (T_k - t_0)^2) / |d_i - d_j|, often 10-50
//    for ceiling microphones. 4-tuples above `max_noise_gain` are dropped (the vote's version of
//    "denominator near zero").
//  - kThesisPile (the thesis's steps 4-6): a candidate joins a pile within pile_sigmas of its own
//    sigma (stamp_sigma_s * gain); the pile is the largest set of candidates whose intervals share
//    an instant (a sweep, independent of the order); t_0 is its median; each microphone keeps its
//    most-voted (L, r) pair. It works while each microphone has few peaks, but the wrong 4-tuples
//    grow as P^2 per microphone pair and are spread over tens of ms: with 4 wall echoes and a
//    ceiling echo per microphone (9 mics, 6 emissions) they outnumber the true ones ~100:1 and a
//    wrong pile wins (measured; see the tests).
//  - kConsensus (default, added here): a true emission's pairs share t_0 AND
//    K = (T_r - t_0)^2 - (T_L - t_0)^2 = 4 h_s h_m / c^2 at every microphone (Eq. 8.72-8.76).
//    Every candidate t_0 (one per stamp_sigma_s) is a hypothesis; per emission the microphones
//    whose pairs share K, each within pile_sigmas of its own K's sigma (plus the height-spread
//    slack 4 max_sender_height_m mic_height_spread_m / c^2) of a common value (intervals sharing
//    a point), are its inliers; the hypothesis with the most inliers
//    beyond two per emission wins (ties: the smaller sum of squared K residuals over their
//    tolerances, as in MSAC). t_0 is then the weighted least-squares solution of
//    2 d_m t_0 + K_e = d_m (T_r,m + T_L,m) over the inliers (linear in t_0 and one K_e per
//    emission; with two microphones it is Eq. 8.77), re-clustered and re-solved until t_0 settles.
//    The least squares is robust (where the thesis is silent): one t_0 per emission (K_e
//    eliminated), an emission more than 3 sigma from the others' t_0 and a row more than 3 sigma
//    off its emission's fit left out, and with the microphones' heights a row whose delay
//    exceeds the 2 z / c a floor echo can lag its LOS (z from its emission's K), the sigma
//    scaled by the Birge ratio of the emissions' scatter when above one (a wrong but
//    self-consistent cluster in one emission otherwise pulls the window's t_0; measured in
//    docs/results/acoustic.md).
//    Hypothesis scoring costs O(H E P_e (log P_e + W)) for H <= candidates hypotheses, E
//    emissions, P_e pairs per emission, W the pairs within the largest tolerance of a point
//    (two points per pair: its K and its interval's lower end). The refinement re-clusters until
//    t_0 moves by less than a tenth of a stamp sigma (K hardly depends on t_0, so the search's
//    hypothesis may be ~1 ms off).
//  - Options beyond the thesis, for a known geometry (methods/acoustic/ground_echo_fix.h sets
//    them): the microphones' heights (exact K per microphone), a lower bound on the echo excess
//    (excludes the ceiling echo), and the LOS as each microphone's first arrival.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mirage::estimation {

/// The LOS and ground-echo arrival stamps of one emission at one microphone (s), any common origin.
struct LosGroundStamps {
  double los_s = 0.0;     ///< T_L, the line of sight
  double ground_s = 0.0;  ///< T_r, the floor echo (later than T_L)
};

/// Eq. 8.77: the sending time (s, same origin as the stamps) from two microphones i, j:
/// t_0 = (T_r,i^2 - T_r,j^2 - T_L,i^2 + T_L,j^2) / (2 (T_r,i - T_L,i - T_r,j + T_L,j)).
/// std::nullopt when the echo delays differ by less than min_delay_difference_s (the denominator
/// vanishes: e.g. microphones symmetric about the sender).
/// @param min_delay_difference_s >= 0 (s); 1e-7 s is far below acoustic stamp noise (~1e-5 s).
std::optional<double> SendingTimeFromGroundEchoes(const LosGroundStamps& i, const LosGroundStamps& j,
                                                  double min_delay_difference_s = 1e-7);

/// The noise gain of Eq. 8.77 at its solution t0_s: the standard deviation of t_0 per unit
/// standard deviation of each (independent) stamp, sqrt(sum_k (T_k - t_0)^2) / |d_i - d_j|
/// (unitless). Infinity when the delays are equal.
double SendingTimeNoiseGain(const LosGroundStamps& i, const LosGroundStamps& j, double t0_s);

/// The stamps of one emission: for each microphone, its unlabeled arrival peaks (s), already minus
/// the emission's elapsed intervals k I (Eq. 8.79), so every emission shares t_0.
struct EmissionStamps {
  std::vector<std::vector<double>> mic_stamps_s;  ///< [mic][peak], any order
};

/// How the vote picks the winner (see the file header).
enum class SendingTimeVoteMethod {
  kThesisPile,  ///< Bordoy's steps 4-6: the largest pile of t_0 candidates, its median
  kConsensus,   ///< hypotheses scored by microphones sharing t_0 and K, least-squares t_0
};

/// Options of VoteSendingTime.
struct SendingTimeVoteOptions {
  SendingTimeVoteMethod method = SendingTimeVoteMethod::kConsensus;
  /// Speed of sound (m/s), > 0. 343: dry air at 20 degC. Used only by the physical bounds below.
  double speed_mps = 343.0;
  /// Largest height of the sender above the floor (m), > 0. The echo path exceeds the LOS by at
  /// most 2 h_s (triangle inequality), so T_r - T_L <= 2 h_s / c. 2.5 m: a hand-held or worn
  /// sender (the thesis's senders are below 3 m); raise it for senders near the ceiling.
  double max_sender_height_m = 2.5;
  /// Largest height of a microphone above the floor (m), > 0: |S_v - M|^2 - |S - M|^2 = 4 h_s h_m
  /// is bounded by 4 max_sender_height_m max_mic_height_m. 5 m: above the ASSIST ceiling (4.84 m).
  double max_mic_height_m = 5.0;
  /// Largest LOS range (m), > 0: a candidate needs 0 < T_L - t_0 <= max_range_m / c at both
  /// microphones. 50 m: larger than any room here.
  double max_range_m = 50.0;
  /// The stamps' standard deviation (s), > 0. 44e-6: the thesis's sigma (0.044 ms, Sec. 8.5).
  double stamp_sigma_s = 44e-6;
  /// 4-tuples whose noise gain (SendingTimeNoiseGain) exceeds this are dropped, > 0. 20: keeps the
  /// pairs whose echo delays differ by >~ 2 ms at 5-10 m ranges; near-symmetric pairs carry ~no
  /// information about t_0 and would only widen the piles.
  double max_noise_gain = 20.0;
  /// A candidate joins a pile within pile_sigmas of its own standard deviation,
  /// stamp_sigma_s * gain, > 0. 3: a true candidate is left out with probability ~0.3 %.
  double pile_sigmas = 3.0;
  /// kThesisPile: a fixed pile half-width (s) for every candidate instead; <= 0: use pile_sigmas.
  double pile_tolerance_s = 0.0;
  /// kConsensus: the spread of the microphones' heights (m), >= 0; it spreads K by up to
  /// 4 h_s dh / c^2. 0.06: the ASSIST ceiling microphones span 4.824-4.879 m.
  double mic_height_spread_m = 0.06;
  /// kConsensus: each microphone's height above the floor (m, > 0), in the emissions' microphone
  /// order; empty: unknown, taken as equal. Known heights make the model exact: K_m =
  /// 4 h_s h_m / c^2, so the clusters compare K / h_m (no height-spread slack) and the least
  /// squares solve 2 d_m t_0 + h_m kappa_e = d_m (T_r,m + T_L,m) with kappa_e = 4 h_s / c^2 per
  /// emission. Eq. 8.77 assumes equal heights: the ASSIST spread of 5.5 cm biases its t_0 by
  /// ~0.1-0.4 ms (4 h_s dh / (2 c dd)), i.e. 3-13 cm of range.
  std::vector<double> mic_heights_m;
  /// Smallest (c (T_r - t_0))^2 - (c (T_L - t_0))^2 of a floor-echo pair (m^2), >= 0; 0: none.
  /// A ceiling echo pairs with the LOS exactly like a floor echo (Eq. 8.74-8.76 hold for any
  /// plane parallel to the microphones'): its excess 4 (C - h_m) (C - h_s) is that of a floor
  /// echo of a sender at (C - h_m) (C - h_s) / h_m, and its 4-tuples share t_0 and K as well.
  /// With 4 (C - h_m) h_m here (C the ceiling's height above the floor, h_m the lowest
  /// microphone's), ceiling pairs are excluded whenever the sender is higher above the floor than
  /// the microphones are below the ceiling (h_s > C - h_m), the only case in which the floor
  /// pairs have the larger excess; below that height the two cannot be told apart by the stamps.
  double min_excess_m2 = 0.0;
  /// kConsensus: a pair's LOS stamp must be its microphone's first arrival after the hypothesis
  /// t_0. Every pair of the sender's images in horizontal planes (LOS, floor, ceiling,
  /// floor-ceiling, ...) satisfies Eq. 8.74-8.77 with the same t_0 and shares K across
  /// microphones of one height, and so do the images in vertical walls with their own floor
  /// echoes: a (ceiling echo, floor echo) or (wall echo, wall-floor echo) set is as consistent as
  /// the (LOS, floor echo) one, and the direct path is the shortest of all paths. true: the
  /// thesis's ch. 8 condition (line of sight), for sparse false alarms: a blocked or missed
  /// direct path, or a false alarm before it, drops that microphone. false (default): every
  /// (L, r) pair, as the thesis enumerates them; right with dense false alarms, but then the
  /// K clusters of other image pairs compete with the true one.
  bool los_is_first_arrival = false;
  /// kConsensus with known microphone heights and los_is_first_arrival: the ceiling's height
  /// above the floor C (m, above every microphone); 0 (default): not modelled. The echo off the
  /// floor and then the ceiling (the microphone's image at h_m - 2 C) pairs with the LOS as
  /// well: its K is 4 C (C - h_m) / c^2 + C kappa with the floor echo's kappa = 4 h_s / c^2, so
  /// such a pair is a second row of the same emission's (t_0, kappa) (b = C, an offset 4 C (C -
  /// h_m) / c^2) instead of a floor-echo pair of a sender at C (C - h_m + h_s) / h_m, whose
  /// cluster would compete with the true one and, through the microphones' unequal heights,
  /// shift t_0 (measured: docs/results/acoustic.md, ch. 8). A cluster is then ranked by its rows
  /// (each microphone's floor pair and floor-ceiling pair), among equals by its floor rows, then
  /// by cost. In the vote a floor-ceiling pair counts only beside its microphone's floor pair
  /// (the weaker, longer echo is rarely heard without the stronger one): otherwise, in a room
  /// without second-order echoes, the floor pairs read as floor-ceiling ones (a lower sender)
  /// gather chance stamps as their floor pairs and compete. The last emission's alternatives may
  /// read a microphone from its floor-ceiling pair alone where the window shows the room returns
  /// that echo (SendingTimeVote::floor_ceiling_heard_fraction).
  double ceiling_height_m = 0.0;
  /// The vote refuses inputs with more 4-tuples than this (>= 1), see CountVoteCombinations.
  /// 5e6: ~0.1 s of work and ~100 MB of candidates at most.
  std::size_t max_combinations = 5'000'000;
};

/// The problems with the options (empty when valid).
std::vector<std::string> Validate(const SendingTimeVoteOptions& options);

/// The vote's cost: the number of 4-tuples (L_i, r_i, L_j, r_j) it evaluates by Eq. 8.77,
/// sum over emissions of sum_{i<j} P_i P_j, with P_i the (L, r) pairs of microphone i that pass
/// 0 < T_r - T_L <= 2 max_sender_height_m / c (at most n_i (n_i - 1) / 2 for n_i peaks). E.g. 9
/// microphones with 6 peaks each: <= 36 * 15^2 = 8100 per emission. Sorting the candidates adds
/// O(C log C).
std::size_t CountVoteCombinations(std::span<const EmissionStamps> emissions, const SendingTimeVoteOptions& options);

/// The stamps chosen at one microphone for one emission: indices into its peaks, -1 if none.
struct MicStampChoice {
  int los_index = -1;
  int ground_index = -1;
  /// The echo off the floor and then the ceiling (only with ceiling_height_m), -1 if none. In
  /// SendingTimeVote::alternatives it may be set while ground_index is -1 (the floor echo missed).
  int floor_ceiling_index = -1;
};

/// The winner.
struct SendingTimeVote {
  /// t_0 (s, the stamps' origin): the pile's median (kThesisPile) or the least-squares solution
  /// over the inliers (kConsensus).
  double t0_s = 0.0;
  /// kThesisPile: the pile's candidates; kConsensus: the inlier pairs over all emissions (one
  /// per microphone, two where a floor-ceiling pair joins its floor pair).
  int pile_size = 0;
  /// kConsensus: the standard deviation of t0_s from the robust least squares, scaled by the
  /// emissions' scatter when it exceeds the stamps' sigma (s); 0 for kThesisPile. An emission or
  /// a pair the robust least squares leaves out stays in `chosen` and `pile_size`.
  double t0_sigma_s = 0.0;
  /// The 4-tuples evaluated and the candidates that passed every check.
  std::size_t combinations = 0;
  std::size_t candidates = 0;
  /// [emission][mic]: the chosen (L, r) pair: the most-voted in the pile (kThesisPile) or the
  /// inlier pair (kConsensus); -1 where none.
  std::vector<std::vector<MicStampChoice>> chosen;
  /// The fraction of the chosen floor pairs (over every emission) whose microphone has a chosen
  /// floor-ceiling pair too: how often the room returns the floor-ceiling echo where the floor
  /// echo is heard (0 without floor pairs, without ceiling_height_m and for kThesisPile).
  double floor_ceiling_heard_fraction = 0.0;
  /// kConsensus: the last emission's other K clusters of at least three microphones at t0_s,
  /// ranked as the winner (most pairs first), among equals the tightest; a cluster contained in
  /// a larger one is not listed. When floor_ceiling_heard_fraction exceeds one half by two
  /// binomial standard deviations, a microphone may be read from its floor-ceiling pair alone
  /// (its floor echo missed). Each is as consistent
  /// in t_0 and K as `chosen` (a wall echo and its floor echo share K like the LOS and the floor
  /// echo, see los_is_first_arrival): the stamps alone cannot rank them, a position fit can.
  std::vector<std::vector<MicStampChoice>> alternatives;
};

/// Eq. 8.77-8.79 and the thesis's steps 1-3: every pair of microphones i < j of an emission, every
/// (L, r) pair of each passing the echo-delay bound, gives a candidate t_0 by Eq. 8.77 when its
/// noise gain is at most max_noise_gain, t_0 precedes both LOS stamps by at most max_range_m / c,
/// and (c T_r)^2 - (c T_L)^2 <= 4 max_sender_height_m max_mic_height_m (relative to t_0) at both. Candidates of all
/// emissions are combined (t_0 does not depend on the position); then options.method decides.
/// std::nullopt for invalid options, more than max_combinations 4-tuples, or no candidate.
std::optional<SendingTimeVote> VoteSendingTime(std::span<const EmissionStamps> emissions,
                                               const SendingTimeVoteOptions& options);

/// The consensus from one hypothesis instead of the vote's search: the K clusters of every
/// emission under t0_hypothesis_s, t_0 refined by weighted least squares over their pairs,
/// re-clustered and refined until t_0 moves by less than 0.1 stamp sigma, at most 8 times (the
/// steps after the search of kConsensus). For a tracked
/// sending time, predicted from the last emission's t_0 and the interval: K hardly depends on
/// t_0 (dK/dt_0 = -2 (T_r - T_L)), so a hypothesis within ~0.1 ms finds the same clusters.
/// std::nullopt for invalid options or when no emission has three microphones sharing K.
std::optional<SendingTimeVote> VoteSendingTimeAt(std::span<const EmissionStamps> emissions, double t0_hypothesis_s,
                                                 const SendingTimeVoteOptions& options);

}  // namespace mirage::estimation
