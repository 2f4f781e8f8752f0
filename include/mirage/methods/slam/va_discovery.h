// SPDX-License-Identifier: MIT
// Discovery of new virtual anchors from the ranges no known VA explains (Leitinger et al.
// Sec. III-D; Lafer 2014 Sec. 4.2, Fig. 4.3). Per anchor and step, the unassociated ranges go
// through the paper's stages in this order:
//   A. association to the existing candidate pairs (cut-off assignment on the predicted ranges
//      of the pair's closer hypothesis) and  B. a linearised RLS update of each hypothesis the
//      range supports (Lafer Eq. 4.11-4.14);
//   C. promotion of a resolved candidate: once the agent positions of its ranges span two
//      dimensions (the agent turned) and it has enough measurements, a batch least-squares fit
//      over all its ranges from both mirror hypotheses must find one point that explains them
//      (small residual, few outliers, small covariance, or for a far VA a covariance small for
//      its distance with a cleaner fit) and leave the mirror clearly worse;
//      that point is returned to the tracker, which puts it into the state (mirage choice: the
//      thesis promotes when the RLS association drops the wrong hypothesis, which on diffuse
//      multipath promoted many wrong points);
//   D. the remaining ranges extend groups of similar ranges from consecutive steps; a group long
//      enough, and walked over a long enough baseline, gives a new candidate pair by the
//      range-Bancroft algorithm (two mirror solutions);
//   D'. (mirage) the sweep (methods/slam/va_sweep): the ranges no candidate took are buffered
//      for the last 3 m of walking, and a consensus search over them gives a candidate pair for a
//      far VA whose ranges the groups of D cannot chain.
// The digest (slam_multipath_leitinger.md Sec. 2.9, 3.3) lists what the paper leaves open; the
// choices made here are the options below, each with its reason. Limits that are about noise are
// derived from the scenario's range noise, limits that are about what is visible from the
// distance walked (the descriptor's derived defaults); counts of ranges and of consecutive misses
// stay counts of measurements.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/methods/slam/discovery_sample.h"
#include "mirage/methods/slam/va_sweep.h"

namespace mirage::methods::slam {

/// Parameters of the VA discovery.
struct DiscoveryOptions {
  /// Discover new VAs at all.
  bool enabled = true;
  /// A step's ranges are used only while the agent's position standard deviation along its worst
  /// direction is at most this (m), > 0 (mirage; a large value, e.g. 100, switches it off).
  /// Groups and candidates store the estimated agent positions as exact (as the paper's
  /// past-measurement rows do, digest Sec. 2.7.3). Seminar room, seed 4: a candidate took a third
  /// of its ranges while A2's LOS was behind the pillar and the agent's std across A1's LOS grew to
  /// 26 cm; the drift made the mirror image of the VA about the walk fit better, it was promoted at
  /// the next corner and held the track 1-3 m off (1 diverged run of 25; none at 0.1 m). 0.05 m
  /// also drops good steps (a diverged run on trajectory 2). A skipped step still counts towards
  /// the gap and time-out limits below: after a long stretch without a good position, groups and
  /// candidates built before it are dropped. Derived: 5 range sigmas (a tracked agent's std is
  /// the range noise times the geometry's dilution, 1-2 with two anchors).
  double max_agent_sigma_m = 0.1;
  /// A range continues a group if it is within this distance of the group's last range (m), > 0.
  /// v_max dT + 2 cm = 0.5 m/s * 0.1 s + 2 cm [GAP; digest Sec. 3.3]. Derived: one step of range
  /// change plus 2 sigma of the difference of two ranges, speed dt + 2 sqrt(2) sigma.
  double group_gate_m = 0.07;
  /// A group that misses more than this many consecutive steps is dropped (>= 0) [GAP].
  int group_max_gap_steps = 3;
  /// Ranges in a group before the range-Bancroft initialisation (>= 3). The thesis uses 3
  /// (Tab. 4.1); with 5 cm steps three points span 10 cm and the pair lands metres off, so 10
  /// (about 0.5 m of walking) as the digest suggests (5-10).
  int group_size = 10;
  /// The group's agent positions must span at least this distance (m), >= 0.
  double min_group_baseline_m = 0.3;
  /// Largest RMS range residual of a Bancroft solution over its group (m), > 0: a group of ranges
  /// that no single point explains (diffuse-multipath peaks chained by chance) is no VA. Derived:
  /// 1.5 range sigmas, the 99th percentile of a true group's RMS (sigma sqrt(chi^2_8 / 10)).
  double max_fit_rms_m = 0.03;
  /// Initial RLS standard deviation of each hypothesis (m), > 0: P_0 = sigma^2 I, 10 m^2 in the
  /// thesis (Tab. 4.1), i.e. about 3.16 m.
  double rls_initial_sigma_m = 3.16;
  /// Range standard deviation in the RLS (m), > 0: R_z = 0.04 m^2 in the thesis (Tab. 4.1).
  double rls_range_sigma_m = 0.2;
  /// Measurements (group plus candidate updates) a hypothesis needs before promotion (>= 1):
  /// N_rls = 10 in the thesis (Tab. 4.1).
  int min_measurements = 10;
  /// A candidate is promoted only when its agent positions extend at least this far across their
  /// principal direction (m), >= 0: ranges from a straight walk cannot tell a VA from its mirror
  /// image about the path (Leitinger footnote 4), however well one hypothesis happens to fit.
  double min_turn_m = 0.2;
  /// Promotion by the batch check below (mirage). false: the thesis's rule, promotion as soon
  /// as the RLS association has dismissed one hypothesis (resolve_misses) and the survivor has
  /// min_measurements ranges and min_turn_m of turn.
  bool verify = true;
  /// Promotion check (mirage): largest RMS residual of the batch fit over the candidate's ranges
  /// (outliers excluded) (m), > 0. Range noise (1-2 cm) and the agent's own error (about 3 cm
  /// with only the anchors) add to sqrt(2^2 + 3^2) = 3.6 cm; 4.5 cm leaves 25 % margin. Derived:
  /// 2 range sigmas (noise and an agent error as large add to sqrt(2) sigma, plus 40 %).
  double verify_fit_rms_m = 0.045;
  /// Promotion check: smallest fraction of the candidate's ranges within the fit's outlier gate,
  /// in (0, 1]. A few ranges of another path may be chained in; many mean no single point.
  double verify_min_inlier_fraction = 0.85;
  /// Promotion check: the mirror solution's truncated RMS residual (residuals capped at
  /// verify_residual_cap_m) must be at least this many times the winner's, >= 1; otherwise the
  /// pair is still ambiguous. On the seminar-room signals true VAs reach 1.5 after about 0.5 m of
  /// walking across.
  double verify_mirror_ratio = 1.5;
  /// Cap of each range residual in the truncated RMS that compares a fit with its mirror (m),
  /// > 0: a range of another path or clutter counts as this much, however far off. 0.1 m.
  /// Derived: 5 range sigmas, above any residual of the VA's own ranges (3 sigma of the range
  /// noise with an agent error as large: 4.2 sigma).
  double verify_residual_cap_m = 0.1;
  /// Promotion check: largest standard deviation of the fitted point along its worst direction
  /// (m), > 0. 5 cm, the accuracy the agent is tracked to: a VA known worse would pull it
  /// (except a far one, whose ranges it moves little: verify_far_sigma_per_m below). Derived: 2
  /// range sigmas, so that the VA's error moves its ranges by no more than the noise's 95 % band.
  double verify_max_sigma_m = 0.05;
  /// Promotion check for far VAs (mirage; 0 = off), >= 0: a fit whose std exceeds
  /// verify_max_sigma_m still passes if that std is at most this fraction of the fitted point's
  /// distance from the agent's last sample and its RMS residual at most verify_far_fit_rms_m.
  /// Why: a VA seen from a walk much shorter than its distance is placed poorly across its
  /// direction, which moves its ranges little near where it was seen; the EKF carries that
  /// covariance. In the seminar room A2's top-wall (blackboard) VA, 11 m from trajectory 2, fits
  /// to 2 cm RMS with a 6-8 cm std and is otherwise never promoted. 1.5 %: just under 1 deg
  /// across the VA's direction. No absolute cap: the RMS limit below is the guard. 1 % gave
  /// nearly the same (docs/methods/slam.md).
  double verify_far_sigma_per_m = 0.015;
  /// RMS limit of the far-VA rule above (m), > 0. 2.5 cm: right far VAs fit to about 2 cm;
  /// without this limit (the 4.5 cm of verify_fit_rms_m) a false far VA, a fit across two
  /// wall offsets, was promoted and a run diverged; 3 cm was worse on trajectory 1. Derived: 1.25
  /// range sigmas, a fit about as clean as the range noise alone.
  double verify_far_fit_rms_m = 0.025;
  /// Consecutive steps in which a hypothesis failed the cut-off while its sibling passed, after
  /// which it is dismissed (>= 1) [GAP: the thesis promotes when the wrong hypothesis "is no
  /// longer associated"].
  int resolve_misses = 3;
  /// Two hypotheses closer than this are the same point (m), > 0: the group already contained a
  /// turn, there is nothing to resolve and the better-fitting one is kept.
  double merge_hypotheses_m = 0.3;
  /// A candidate without a supporting range for this long is dropped (s), > 0 [SUG: time-out of
  /// the digest Sec. 2.10]. 2 s (20 steps of 0.1 s). Derived: the time to walk 1 m, since the path
  /// goes out of view with the distance walked; missed detections alone do not last 1 m.
  double candidate_timeout_s = 2.0;
  /// A candidate still ambiguous after this long is dropped (s), > 0: a straight walk never
  /// resolves it, and an old pair's evidence comes from positions far behind. 15 s (150 steps of
  /// 0.1 s). Derived: the time to walk 7.5 m, about a room's length.
  double candidate_max_age_s = 15.0;
  /// A new candidate is not created if one of its hypotheses is within this distance of an
  /// existing candidate hypothesis or of an active VA of the same anchor (m), >= 0 [SUG merge
  /// radius, digest Sec. 2.10]: it would be the same feature found twice.
  double duplicate_radius_m = 0.2;
  /// Stage D' (mirage): the sweep for far VAs (methods/slam/va_sweep).
  SweepOptions sweep;
};

/// The options' descriptor (keys, units, ranges, docs; core/options_descriptor.h).
const core::OptionsDescriptor<DiscoveryOptions>& DiscoveryOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const DiscoveryOptions& options);

/// One mirror hypothesis of a candidate, tracked by RLS.
struct Hypothesis {
  Vec2 position_m = Vec2::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Identity();
  bool alive = true;
  int misses = 0;                  ///< consecutive steps failing the cut-off while the sibling passed
  double squared_residual_m2 = 0;  ///< sum of squared pre-update residuals
};

/// A candidate pair (Leitinger Sec. III-D stage A/B).
struct Candidate {
  int anchor_index = 0;
  std::array<Hypothesis, 2> hypotheses;
  int last_support_step = 0;
  double created_t_s = 0.0;       ///< time the candidate was created (s)
  double last_support_t_s = 0.0;  ///< time of last_support_step (s)
  std::vector<DiscoverySample> samples;  ///< the group's (or sweep's) ranges and every range since
};

/// A resolved candidate, ready to enter the state.
struct DiscoveredVa {
  int anchor_index = 0;
  Vec2 position_m = Vec2::Zero();
  Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Identity();  ///< the batch fit's covariance
  std::vector<DiscoverySample> samples;
};

/// Discovery state of one tracker (all anchors). Not thread-safe.
class VaDiscovery {
 public:
  explicit VaDiscovery(const DiscoveryOptions& options);

  /// Processes the unassociated ranges of one anchor at step `step`, time t_s (s), measured from
  /// the agent's current estimate agent_m with position covariance agent_covariance_m2; a step
  /// whose position std along its worst direction exceeds max_agent_sigma_m is skipped (nothing is
  /// updated or promoted, the step still counts for the time-outs). known_vas_m are the anchor's
  /// active VAs (for duplicate suppression). Returns the candidates promoted at this step.
  std::vector<DiscoveredVa> Process(int step, double t_s, int anchor_index, const Vec2& agent_m,
                                    const Eigen::Matrix2d& agent_covariance_m2,
                                    std::span<const core::RangeMeasurement> unassociated,
                                    std::span<const Vec2> known_vas_m, double cutoff_m);

  [[nodiscard]] const std::vector<Candidate>& candidates() const { return candidates_; }
  [[nodiscard]] int group_count() const { return static_cast<int>(groups_.size()); }
  /// Candidates created by the sweep (stage D') since the last Reset.
  [[nodiscard]] int sweep_candidates() const { return sweep_candidates_; }
  /// The sweep's buffers (stage D').
  [[nodiscard]] const VaSweep& sweep() const { return sweep_; }

  /// Forgets all groups, candidates and the sweep's buffers.
  void Reset();

 private:
  struct Group {
    int anchor_index = 0;
    int last_step = 0;
    std::vector<DiscoverySample> samples;
  };
  // Stage A/B; returns the indices of the ranges it used.
  std::vector<bool> UpdateCandidates(int step, double t_s, int anchor_index, const Vec2& agent_m,
                                     std::span<const core::RangeMeasurement> ranges, double cutoff_m);
  // Stage C.
  std::vector<DiscoveredVa> Promote(int step, double t_s, int anchor_index);
  // The batch check of stage C.
  struct Verdict {
    enum Kind { kWait, kPromote, kReject } kind = kWait;
    Vec2 position_m = Vec2::Zero();
    Eigen::Matrix2d covariance_m2 = Eigen::Matrix2d::Identity();
  };
  [[nodiscard]] Verdict Verify(const Candidate& candidate) const;
  // Stage D.
  void UpdateGroups(int step, double t_s, int anchor_index, const Vec2& agent_m,
                    std::span<const core::RangeMeasurement> ranges, const std::vector<bool>& used,
                    std::span<const Vec2> known_vas_m);
  // A candidate pair from two hypotheses and its samples, unless it duplicates a known VA or a
  // candidate (stages D and D').
  bool AddCandidate(int step, double t_s, int anchor_index, const std::array<Vec2, 2>& starts,
                    std::vector<DiscoverySample> samples, std::span<const Vec2> known_vas_m);
  // One RLS step of a hypothesis (Lafer Eq. 4.11-4.14).
  void RlsUpdate(Hypothesis& h, const Vec2& agent_m, double range_m) const;

  DiscoveryOptions options_;
  std::vector<Group> groups_;
  std::vector<Candidate> candidates_;
  VaSweep sweep_;
  int sweep_candidates_ = 0;
};

}  // namespace mirage::methods::slam
