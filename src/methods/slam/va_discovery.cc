// SPDX-License-Identifier: MIT
#include "mirage/methods/slam/va_discovery.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "mirage/core/derived_defaults.h"
#include "mirage/estimation/init/range_bancroft.h"
#include "mirage/estimation/init/range_point_fit.h"
#include "mirage/estimation/range_association.h"
#include "mirage/methods/elapsed_time.h"

namespace mirage::methods::slam {

const core::OptionsDescriptor<DiscoveryOptions>& DiscoveryOptionsDescriptor() {
  using core::ValueRange;
  using O = DiscoveryOptions;
  static const auto descriptor = [] {
    const ValueRange fraction_range = ValueRange::Closed(core::kTinyOption, 1.0);
    core::OptionsDescriptor<O> d("methods::slam::DiscoveryOptions");
    d.Boolean(&O::enabled, {.key = "enabled", .doc = "Discover new VAs at all."});
    d.Number(&O::max_agent_sigma_m,
             {.key = "max_agent_sigma_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "A step's ranges are used only while the agent's position std along its worst direction is at "
                     "most this (mirage; e.g. 100 switches it off). 0.1 m: at a 26 cm std a mirror VA was promoted "
                     "and held the track 1-3 m off (seminar room, seed 4); 0.05 m drops good steps. Derived: 5 range "
                     "sigmas; a tracked agent's std is the range noise times the geometry's dilution (1-2 with two "
                     "anchors), so 5 sigma marks a track that has lost its hold (0.1 m at 2 cm of noise).",
              .derived = core::RangeSigmas(5.0)});
    d.Number(&O::group_gate_m, {.key = "group_gate_m",
                                .unit = "m",
                                .range = ValueRange::Positive(),
                                .doc = "A range continues a group within this distance of the group's last range. "
                                       "0.07 m = v_max dT + 2 cm (a gap in the thesis; digest Sec. 3.3). Derived: the "
                                       "range changes by at most one step of motion, and the difference of two ranges "
                                       "has sqrt(2) sigma of noise, 2 sigma of it kept (95 %). The seminar room's "
                                       "consecutive CIR ranges are correlated, so their differences are smaller than "
                                       "white noise's.",
                                .derived = core::DerivedDefault{
                                    .formula = "speed_mps * dt_s + 2 * sqrt(2) * range_sigma_m",
                                    .needs = {core::PhysicalKey::kSpeed, core::PhysicalKey::kStepTime,
                                              core::PhysicalKey::kRangeSigma},
                                    .compute = [](const core::PhysicalKeys& k) {
                                      return *k.speed_mps * *k.dt_s + 2.0 * std::sqrt(2.0) * *k.range_sigma_m;
                                    }}});
    d.Integer(
        &O::group_max_gap_steps,
        {.key = "group_max_gap_steps",
         .unit = "steps",
         .range = ValueRange::Closed(0.0, 1e5),
         .doc = "A group that misses more than this many consecutive steps is dropped (a gap in the thesis). 3."});
    d.Integer(&O::group_size,
              {.key = "group_size",
               .range = ValueRange::Closed(3.0, 1e5),
               .doc = "Ranges in a group before the range-Bancroft initialisation. The thesis's 3 (Lafer Tab. 4.1) "
                      "span 10 cm at 5 cm steps and land metres off; 10 (about 0.5 m of walking), as the digest "
                      "suggests."});
    d.Number(&O::min_group_baseline_m, {.key = "min_group_baseline_m",
                                        .unit = "m",
                                        .range = ValueRange::NonNegative(),
                                        .doc = "The group's agent positions must span at least this distance. 0.3 m."});
    d.Number(&O::max_fit_rms_m,
             {.key = "max_fit_rms_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Largest RMS range residual of a Bancroft solution over its group: ranges that no single point "
                     "explains (diffuse peaks chained by chance) are no VA. 3 cm. Derived: 1.5 range sigmas, the 99th "
                     "percentile of a true group's RMS (sigma sqrt(chi^2_8 / 10) for 10 ranges and 2 unknowns).",
              .derived = core::RangeSigmas(1.5)});
    d.Number(&O::rls_initial_sigma_m,
             {.key = "rls_initial_sigma_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Initial RLS standard deviation of each hypothesis: P_0 = sigma^2 I, 10 m^2 in Lafer Tab. 4.1, "
                     "i.e. about 3.16 m."});
    d.Number(&O::rls_range_sigma_m,
             {.key = "rls_range_sigma_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Range standard deviation in the RLS: R_z = 0.04 m^2 in Lafer Tab. 4.1, i.e. "
                     "0.2 m."});
    d.Integer(&O::min_measurements,
              {.key = "min_measurements",
               .range = ValueRange::Closed(1.0, 1e5),
               .doc = "Measurements (group plus candidate updates) a hypothesis needs before promotion: N_rls = 10 "
                      "(Lafer Tab. 4.1)."});
    d.Number(
        &O::min_turn_m,
        {.key = "min_turn_m",
         .unit = "m",
         .range = ValueRange::NonNegative(),
         .doc = "A candidate is promoted only when its agent positions extend this far across their principal "
                "direction: a straight walk cannot tell a VA from its mirror image (Leitinger footnote 4). 0.2 m."});
    d.Boolean(&O::verify, {.key = "verify",
                           .doc = "Promotion by the batch check (mirage); false: the thesis's rule, promotion once the "
                                  "RLS association has dismissed one hypothesis."});
    d.Number(&O::verify_fit_rms_m,
             {.key = "verify_fit_rms_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Promotion check: largest RMS residual of the batch fit over the candidate's ranges (outliers "
                     "excluded). Range noise (1-2 cm) and the agent's error (about 3 cm) add to 3.6 cm; 4.5 cm leaves "
                     "25 % margin. Derived: 2 range sigmas; the noise and an agent error as large (the agent is "
                     "located by ranges of that noise) add to sqrt(2) sigma, plus 40 %.",
              .derived = core::RangeSigmas(2.0)});
    d.Number(&O::verify_min_inlier_fraction,
             {.key = "verify_min_inlier_fraction",
              .range = fraction_range,
              .doc = "Promotion check: smallest fraction of the candidate's ranges within the fit's outlier gate; a "
                     "few ranges of another path may be chained in, many mean no single point. 0.85."});
    d.Number(&O::verify_mirror_ratio,
             {.key = "verify_mirror_ratio",
              .range = ValueRange::Closed(1.0, core::kHugeOption),
              .doc = "Promotion check: the mirror solution's truncated RMS residual must be at least this many times "
                     "the winner's, else the pair is still ambiguous. 1.5: true VAs reach it after about 0.5 m of "
                     "walking across (seminar room)."});
    d.Number(&O::verify_residual_cap_m,
             {.key = "verify_residual_cap_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Promotion check: cap of each residual in the truncated RMS that compares a fit with its "
                     "mirror; a range of another path or clutter counts this much however far off. 0.1 m. Derived: 5 "
                     "range sigmas, above any residual of the VA's own ranges (3 sigma of the noise with an agent "
                     "error as large: 4.2 sigma).",
              .derived = core::RangeSigmas(5.0)});
    d.Number(&O::verify_max_sigma_m,
             {.key = "verify_max_sigma_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Promotion check: largest standard deviation of the fitted point along its worst direction. 5 "
                     "cm, the accuracy the agent is tracked to: a VA known worse would pull it. Derived: 2 range "
                     "sigmas, so that the VA's error moves its ranges by no more than the noise's 95 % band.",
              .derived = core::RangeSigmas(2.0)});
    d.Number(&O::verify_far_sigma_per_m,
             {.key = "verify_far_sigma_per_m",
              .range = ValueRange::NonNegative(),
              .doc = "Promotion of far VAs (mirage; 0 = off): a fit whose std exceeds verify_max_sigma_m still passes "
                     "if the std is at most this fraction of its distance from the agent and its RMS at most "
                     "verify_far_fit_rms_m. 1.5 %, just under 1 deg across the VA's direction (1 % gave nearly the "
                     "same)."});
    d.Number(&O::verify_far_fit_rms_m,
             {.key = "verify_far_fit_rms_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "RMS limit of the far-VA rule. 2.5 cm: right far VAs fit to about 2 cm; without the limit a false "
                     "far VA was promoted and a run diverged, and 3 cm was worse on trajectory 1. Derived: 1.25 range "
                     "sigmas, a fit about as clean as the range noise alone.",
              .derived = core::RangeSigmas(1.25)});
    d.Integer(
        &O::resolve_misses,
        {.key = "resolve_misses",
         .range = ValueRange::Closed(1.0, 1e5),
         .doc = "Consecutive steps in which a hypothesis failed the cut-off while its sibling passed, after which "
                "it is dismissed (a gap in the thesis). 3."});
    d.Number(&O::merge_hypotheses_m,
             {.key = "merge_hypotheses_m",
              .unit = "m",
              .range = ValueRange::Positive(),
              .doc = "Two hypotheses closer than this are the same point (the group already contained a turn) and the "
                     "better-fitting one is kept. 0.3 m."});
    d.Number(&O::candidate_timeout_s,
             {.key = "candidate_timeout_s",
              .unit = "s",
              .range = ValueRange::Positive(),
              .doc = "A candidate without a supporting range for this long is dropped (the digest's time-out, Sec. "
                     "2.10). 2 s. Derived: the time to walk 1 m (20 steps at 0.5 m/s and 0.1 s): a path goes out of "
                     "view with the distance walked, and missed detections alone do not last that long.",
              .derived = core::WalkingTime(1.0)});
    d.Number(&O::candidate_max_age_s,
             {.key = "candidate_max_age_s",
              .unit = "s",
              .range = ValueRange::Positive(),
              .doc = "A candidate still ambiguous after this long is dropped: a straight walk never resolves it, and "
                     "an old pair's evidence comes from positions far behind. 15 s. Derived: the time to walk 7.5 m, "
                     "about a room's length (150 steps at 0.5 m/s and 0.1 s).",
              .derived = core::WalkingTime(7.5)});
    d.Retired("candidate_timeout_steps", "candidate_timeout_s", "seconds, not steps: the old value times dt_s (20 steps of 0.1 s = 2 s), or leave it out for the default derived from speed_mps");
    d.Retired("candidate_max_age_steps", "candidate_max_age_s", "seconds, not steps: the old value times dt_s (150 steps of 0.1 s = 15 s), or leave it out for the default derived from speed_mps");
    d.Number(&O::duplicate_radius_m,
             {.key = "duplicate_radius_m",
              .unit = "m",
              .range = ValueRange::NonNegative(),
              .doc = "No new candidate within this distance of a candidate hypothesis or an active VA of the same "
                     "anchor: the same feature found twice (the digest's merge radius, Sec. 2.10). 0.2 m."});
    d.Section(&O::sweep, {.key = "sweep", .doc = "Stage D' (mirage): the sweep for far VAs."},
              SweepOptionsDescriptor());
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const DiscoveryOptions& options) {
  return DiscoveryOptionsDescriptor().Validate(options);
}

VaDiscovery::VaDiscovery(const DiscoveryOptions& options)
    : options_(options), sweep_(options.sweep, options.min_measurements, options.duplicate_radius_m) {}

void VaDiscovery::Reset() {
  groups_.clear();
  candidates_.clear();
  sweep_.Reset();
  sweep_candidates_ = 0;
}

void VaDiscovery::RlsUpdate(Hypothesis& h, const Vec2& agent_m, double range_m) const {
  // Lafer Eq. 4.11-4.14: row Jacobian h = (q - p)^T / |q - p| at the previous estimate, scalar
  // gain, Joseph-form covariance.
  const Vec2 d = h.position_m - agent_m;
  const double predicted_m = d.norm();
  if (predicted_m < 1e-6) return;
  const Eigen::RowVector2d H = d.transpose() / predicted_m;
  const double R = options_.rls_range_sigma_m * options_.rls_range_sigma_m;
  const double S = (H * h.covariance_m2 * H.transpose())(0, 0) + R;
  const Eigen::Vector2d K = h.covariance_m2 * H.transpose() / S;
  h.position_m += K * (range_m - predicted_m);
  const Eigen::Matrix2d A = Eigen::Matrix2d::Identity() - K * H;
  h.covariance_m2 = A * h.covariance_m2 * A.transpose() + K * R * K.transpose();
}

std::vector<bool> VaDiscovery::UpdateCandidates(int step, double t_s, int anchor_index, const Vec2& agent_m,
                                                std::span<const core::RangeMeasurement> ranges, double cutoff_m) {
  std::vector<bool> used(ranges.size(), false);
  std::vector<std::size_t> mine;
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    if (candidates_[c].anchor_index == anchor_index) mine.push_back(c);
  }
  if (mine.empty() || ranges.empty()) return used;
  // Stage A: one range per candidate, by the cut-off assignment on the distance to the closer of
  // its live hypotheses (the thesis uses the DA of Sec. 3.4 against both members of the pair).
  Eigen::MatrixXd distance(static_cast<Eigen::Index>(mine.size()), static_cast<Eigen::Index>(ranges.size()));
  for (std::size_t i = 0; i < mine.size(); ++i) {
    for (std::size_t j = 0; j < ranges.size(); ++j) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& h : candidates_[mine[i]].hypotheses) {
        if (h.alive) best = std::min(best, std::abs(ranges[j].range_m - (h.position_m - agent_m).norm()));
      }
      distance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = best;
    }
  }
  const std::vector<int> assignment = estimation::AssociateWithCutoff(distance, cutoff_m);
  for (std::size_t i = 0; i < mine.size(); ++i) {
    if (assignment[i] < 0) continue;  // no range near either hypothesis: not visible now
    Candidate& candidate = candidates_[mine[i]];
    const auto& z = ranges[static_cast<std::size_t>(assignment[i])];
    used[static_cast<std::size_t>(assignment[i])] = true;
    candidate.last_support_step = step;
    candidate.last_support_t_s = t_s;
    candidate.samples.push_back({agent_m, z.range_m, z.amplitude});
    // Stage B: each live hypothesis the range supports is RLS-updated; one that fails the cut-off
    // while its sibling passes counts a miss (the mirror image drifts apart after a turn).
    std::array<bool, 2> supports{false, false};
    for (std::size_t k = 0; k < 2; ++k) {
      Hypothesis& h = candidate.hypotheses[k];
      if (!h.alive) continue;
      const double residual_m = z.range_m - (h.position_m - agent_m).norm();
      supports[k] = std::abs(residual_m) < cutoff_m;
      if (supports[k]) {
        h.squared_residual_m2 += residual_m * residual_m;
        RlsUpdate(h, agent_m, z.range_m);
      }
    }
    for (std::size_t k = 0; k < 2; ++k) {
      Hypothesis& h = candidate.hypotheses[k];
      if (!h.alive) continue;
      if (supports[k]) {
        h.misses = 0;
      } else if (supports[1 - k]) {
        ++h.misses;
      }
    }
  }
  return used;
}

namespace {

// Extent of the agent positions across their principal direction (m): 0 for a straight walk.
double CrossExtent(const std::vector<DiscoverySample>& samples) {
  if (samples.size() < 3) return 0.0;
  Vec2 mean = Vec2::Zero();
  for (const auto& s : samples) mean += s.agent_m;
  mean /= static_cast<double>(samples.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& s : samples) scatter += (s.agent_m - mean) * (s.agent_m - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  const Vec2 normal = eig.eigenvectors().col(0);  // smallest eigenvalue: across the path
  double lo = 0.0, hi = 0.0;
  for (const auto& s : samples) {
    const double u = (s.agent_m - mean).dot(normal);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  return hi - lo;
}

// RMS of the residuals of q over all samples, each capped at cap_m: a robust score that an
// outlier cannot dominate and a wrong point cannot hide by rejecting ranges.
double TruncatedRms(const Vec2& q, const std::vector<DiscoverySample>& samples, double cap_m) {
  double sum_m2 = 0.0;
  for (const auto& s : samples) {
    const double r = std::min(std::abs((q - s.agent_m).norm() - s.range_m), cap_m);
    sum_m2 += r * r;
  }
  return std::sqrt(sum_m2 / static_cast<double>(std::max<std::size_t>(samples.size(), 1)));
}

}  // namespace

VaDiscovery::Verdict VaDiscovery::Verify(const Candidate& candidate) const {
  std::vector<Vec2> positions;
  std::vector<double> ranges;
  for (const auto& s : candidate.samples) {
    positions.push_back(s.agent_m);
    ranges.push_back(s.range_m);
  }
  // Starts: both RLS hypotheses (alive or not: the dismissed one is the mirror to refute) and
  // the range-Bancroft pair of all ranges (unique once the positions span 2-D).
  std::vector<Vec2> starts = {candidate.hypotheses[0].position_m, candidate.hypotheses[1].position_m};
  if (const auto pair = estimation::RangeBancroft(positions, ranges)) {
    starts.push_back(pair->positions_m[0]);
    if (pair->solutions == 2) starts.push_back(pair->positions_m[1]);
  }
  std::vector<estimation::RangePointFit> fits;
  std::vector<double> scores;
  for (const Vec2& start : starts) {
    if (const auto fit = estimation::FitPointToRanges(positions, ranges, start)) {
      fits.push_back(*fit);
      scores.push_back(TruncatedRms(fit->position_m, candidate.samples, options_.verify_residual_cap_m));
    }
  }
  Verdict verdict;
  if (fits.empty()) return verdict;  // kWait
  const auto best = static_cast<std::size_t>(std::min_element(scores.begin(), scores.end()) - scores.begin());
  const auto& fit = fits[best];
  const double inlier_fraction = static_cast<double>(fit.inliers) / static_cast<double>(candidate.samples.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(fit.covariance_m2);
  const double sigma_m = std::sqrt(std::max(eig.eigenvalues()(1), 0.0));
  // The best other solution: the lowest score among fits that ended elsewhere.
  double mirror_score = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fits.size(); ++i) {
    if ((fits[i].position_m - fit.position_m).norm() > options_.merge_hypotheses_m) {
      mirror_score = std::min(mirror_score, scores[i]);
    }
  }
  if (inlier_fraction < 0.5) {
    verdict.kind = Verdict::kReject;  // no single point explains most of these ranges
    return verdict;
  }
  // Placed well enough: within verify_max_sigma_m, or a far VA with a clean fit whose std is small
  // for its distance (verify_far_sigma_per_m).
  const double distance_m = (fit.position_m - candidate.samples.back().agent_m).norm();
  const bool placed = sigma_m <= options_.verify_max_sigma_m ||
                      (sigma_m <= options_.verify_far_sigma_per_m * distance_m &&
                       fit.rms_m <= options_.verify_far_fit_rms_m);
  if (fit.rms_m > options_.verify_fit_rms_m || inlier_fraction < options_.verify_min_inlier_fraction || !placed ||
      mirror_score < options_.verify_mirror_ratio * scores[best]) {
    return verdict;  // kWait: more ranges, a longer turn
  }
  verdict.kind = Verdict::kPromote;
  verdict.position_m = fit.position_m;
  verdict.covariance_m2 = fit.covariance_m2;
  return verdict;
}

std::vector<DiscoveredVa> VaDiscovery::Promote(int step, double t_s, int anchor_index) {
  std::vector<DiscoveredVa> promoted;
  std::vector<Candidate> kept;
  for (auto& candidate : candidates_) {
    if (candidate.anchor_index != anchor_index) {
      kept.push_back(std::move(candidate));
      continue;
    }
    auto& h = candidate.hypotheses;
    // Two live hypotheses that coincide are one point: keep the better-fitting one.
    if (h[0].alive && h[1].alive && (h[0].position_m - h[1].position_m).norm() < options_.merge_hypotheses_m) {
      h[h[0].squared_residual_m2 <= h[1].squared_residual_m2 ? 1 : 0].alive = false;
    }
    for (auto& hyp : h) {
      if (hyp.alive && hyp.misses >= options_.resolve_misses) hyp.alive = false;
    }
    const int alive = (h[0].alive ? 1 : 0) + (h[1].alive ? 1 : 0);
    const bool timed_out = Exceeds(t_s - candidate.last_support_t_s, options_.candidate_timeout_s);
    const bool too_old = Exceeds(t_s - candidate.created_t_s, options_.candidate_max_age_s);
    if (alive == 0 || timed_out || too_old) continue;  // dropped
    const bool ready = static_cast<int>(candidate.samples.size()) >= options_.min_measurements &&
                       CrossExtent(candidate.samples) >= options_.min_turn_m;
    if (!options_.verify) {
      if (alive == 1 && ready) {  // the thesis: the RLS survivor as it stands
        const Hypothesis& survivor = h[0].alive ? h[0] : h[1];
        promoted.push_back({anchor_index, survivor.position_m, survivor.covariance_m2, std::move(candidate.samples)});
        continue;
      }
      kept.push_back(std::move(candidate));
      continue;
    }
    // Verify only at steps with new support: the verdict cannot change otherwise.
    if (candidate.last_support_step == step && ready) {
      const Verdict verdict = Verify(candidate);
      if (verdict.kind == Verdict::kPromote) {
        promoted.push_back({anchor_index, verdict.position_m, verdict.covariance_m2, std::move(candidate.samples)});
        continue;
      }
      if (verdict.kind == Verdict::kReject) continue;
    }
    kept.push_back(std::move(candidate));
  }
  candidates_ = std::move(kept);
  return promoted;
}

bool VaDiscovery::AddCandidate(int step, double t_s, int anchor_index, const std::array<Vec2, 2>& starts,
                               std::vector<DiscoverySample> samples, std::span<const Vec2> known_vas_m) {
  Candidate candidate;
  candidate.anchor_index = anchor_index;
  candidate.last_support_step = step;
  candidate.created_t_s = t_s;
  candidate.last_support_t_s = t_s;
  int fitting = 0;
  bool duplicate = false;
  for (std::size_t k = 0; k < 2; ++k) {
    Hypothesis& h = candidate.hypotheses[k];
    h.position_m = starts[k];
    h.covariance_m2 = Eigen::Matrix2d::Identity() * options_.rls_initial_sigma_m * options_.rls_initial_sigma_m;
    double sum_m2 = 0.0;
    for (const auto& s : samples) {
      const double r = s.range_m - (h.position_m - s.agent_m).norm();
      sum_m2 += r * r;
    }
    h.squared_residual_m2 = sum_m2;
    const double rms_m = std::sqrt(sum_m2 / static_cast<double>(samples.size()));
    h.alive = std::isfinite(rms_m) && rms_m <= options_.max_fit_rms_m;
    // The ranges refine the hypothesis from its start (Lafer Sec. 4.2.1).
    if (h.alive) {
      for (const auto& s : samples) RlsUpdate(h, s.agent_m, s.range_m);
    }
    // A hypothesis on top of a known VA or of another candidate means the ranges are that
    // feature's (e.g. while the VA filter excludes it): its mirror is no new VA either.
    for (const auto& other : candidates_) {
      if (other.anchor_index != anchor_index) continue;
      for (const auto& oh : other.hypotheses) {
        if (oh.alive && (oh.position_m - h.position_m).norm() < options_.duplicate_radius_m) duplicate = true;
      }
    }
    for (const auto& va_m : known_vas_m) {
      if ((va_m - h.position_m).norm() < options_.duplicate_radius_m) duplicate = true;
    }
    if (h.alive) ++fitting;
  }
  if (fitting == 0 || duplicate) return false;
  candidate.samples = std::move(samples);
  candidates_.push_back(std::move(candidate));
  return true;
}

void VaDiscovery::UpdateGroups(int step, double t_s, int anchor_index, const Vec2& agent_m,
                               std::span<const core::RangeMeasurement> ranges, const std::vector<bool>& used,
                               std::span<const Vec2> known_vas_m) {
  // Age out groups that missed too many steps.
  std::erase_if(groups_, [&](const Group& g) {
    return g.anchor_index == anchor_index && step - g.last_step > options_.group_max_gap_steps + 1;
  });
  std::vector<std::size_t> mine;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (groups_[g].anchor_index == anchor_index) mine.push_back(g);
  }
  std::vector<std::size_t> free;
  for (std::size_t j = 0; j < ranges.size(); ++j) {
    if (!used[j]) free.push_back(j);
  }
  // Each group takes at most one range per step and each range joins at most one group: the
  // cut-off assignment on |z - last z of the group| with the group gate.
  std::vector<int> assignment(mine.size(), -1);
  if (!mine.empty() && !free.empty()) {
    Eigen::MatrixXd distance(static_cast<Eigen::Index>(mine.size()), static_cast<Eigen::Index>(free.size()));
    for (std::size_t i = 0; i < mine.size(); ++i) {
      const Group& g = groups_[mine[i]];
      for (std::size_t j = 0; j < free.size(); ++j) {
        distance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            g.last_step == step ? std::numeric_limits<double>::infinity()
                                : std::abs(ranges[free[j]].range_m - g.samples.back().range_m);
      }
    }
    assignment = estimation::AssociateWithCutoff(distance, options_.group_gate_m);
  }
  std::vector<bool> joined(free.size(), false);
  std::vector<std::size_t> full;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    if (assignment[i] < 0) continue;
    const auto j = static_cast<std::size_t>(assignment[i]);
    joined[j] = true;
    Group& g = groups_[mine[i]];
    g.samples.push_back({agent_m, ranges[free[j]].range_m, ranges[free[j]].amplitude});
    g.last_step = step;
    // A standing agent would grow the group without a baseline: keep the newest ranges only.
    const auto cap = static_cast<std::size_t>(4 * options_.group_size);
    if (g.samples.size() > cap) g.samples.erase(g.samples.begin());
    if (static_cast<int>(g.samples.size()) >= options_.group_size) full.push_back(mine[i]);
  }
  for (std::size_t j = 0; j < free.size(); ++j) {
    if (!joined[j]) {
      groups_.push_back({anchor_index, step, {{agent_m, ranges[free[j]].range_m, ranges[free[j]].amplitude}}});
    }
  }

  // Full groups with enough baseline become candidate pairs (Leitinger Sec. III-D stage D).
  std::vector<bool> remove(groups_.size(), false);
  for (const std::size_t g : full) {
    const Group& group = groups_[g];
    double baseline_m = 0.0;
    for (const auto& s : group.samples) baseline_m = std::max(baseline_m, (s.agent_m - group.samples.front().agent_m).norm());
    if (baseline_m < options_.min_group_baseline_m) continue;
    std::vector<Vec2> positions;
    std::vector<double> ranges_m;
    for (const auto& s : group.samples) {
      positions.push_back(s.agent_m);
      ranges_m.push_back(s.range_m);
    }
    remove[g] = true;  // used up, whether or not it gives a candidate
    const auto pair = estimation::RangeBancroft(positions, ranges_m);
    if (!pair) continue;
    const std::array<Vec2, 2> starts = {pair->positions_m[0], pair->positions_m[1]};
    AddCandidate(step, t_s, anchor_index, starts, group.samples, known_vas_m);
  }
  for (std::size_t g = groups_.size(); g-- > 0;) {
    if (g < remove.size() && remove[g]) groups_.erase(groups_.begin() + static_cast<std::ptrdiff_t>(g));
  }
}

std::vector<DiscoveredVa> VaDiscovery::Process(int step, double t_s, int anchor_index, const Vec2& agent_m,
                                               const Eigen::Matrix2d& agent_covariance_m2,
                                               std::span<const core::RangeMeasurement> unassociated,
                                               std::span<const Vec2> known_vas_m, double cutoff_m) {
  if (!options_.enabled) return {};
  // The agent's std along its worst direction: the largest eigenvalue of its position covariance.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> agent_eig(agent_covariance_m2, Eigen::EigenvaluesOnly);
  if (!(agent_eig.eigenvalues()(1) <= options_.max_agent_sigma_m * options_.max_agent_sigma_m)) return {};
  const std::vector<bool> used = UpdateCandidates(step, t_s, anchor_index, agent_m, unassociated, cutoff_m);
  auto promoted = Promote(step, t_s, anchor_index);
  UpdateGroups(step, t_s, anchor_index, agent_m, unassociated, used, known_vas_m);
  // Stage D'. Points already explained (an active VA of this anchor or a live candidate
  // hypothesis) are not searched for.
  sweep_.Buffer(t_s, anchor_index, agent_m, unassociated, used);
  if (sweep_.Due(step, anchor_index)) {
    std::vector<Vec2> taken_m(known_vas_m.begin(), known_vas_m.end());
    for (const auto& c : candidates_) {
      if (c.anchor_index != anchor_index) continue;
      for (const auto& h : c.hypotheses) {
        if (h.alive) taken_m.push_back(h.position_m);
      }
    }
    if (auto find = sweep_.Search(step, anchor_index, taken_m)) {
      if (AddCandidate(step, t_s, anchor_index, find->starts, std::move(find->samples), known_vas_m)) {
        ++sweep_candidates_;
      }
    }
  }
  return promoted;
}

}  // namespace mirage::methods::slam
