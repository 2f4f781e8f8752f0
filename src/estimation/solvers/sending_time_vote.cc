// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/sending_time_vote.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace mirage::estimation {
namespace {

/// One (L, r) pair of peaks at a microphone.
struct PeakPair {
  int los_index = 0;
  int ground_index = 0;
  LosGroundStamps stamps;
  /// The latest other stamp of the microphone before T_L (-infinity if none): T_L is the first
  /// arrival after a hypothesis t_0 iff previous_s <= t_0.
  double previous_s = -std::numeric_limits<double>::infinity();
};

/// One t_0 candidate and the two pairs that gave it.
struct Candidate {
  double t0_s = 0.0;
  double gain = 0.0;
  int emission = 0;
  int mic_i = 0;
  int pair_i = 0;
  int mic_j = 0;
  int pair_j = 0;
};

/// The (L, r) pairs of one microphone with 0 < T_r - T_L <= max_delay_s.
std::vector<PeakPair> PairsOf(const std::vector<double>& stamps_s, double max_delay_s) {
  std::vector<PeakPair> pairs;
  for (std::size_t a = 0; a < stamps_s.size(); ++a) {
    double previous_s = -std::numeric_limits<double>::infinity();
    for (const double s : stamps_s) {
      if (s < stamps_s[a]) previous_s = std::max(previous_s, s);
    }
    for (std::size_t b = 0; b < stamps_s.size(); ++b) {
      const double delay_s = stamps_s[b] - stamps_s[a];
      if (delay_s > 0.0 && delay_s <= max_delay_s) {
        pairs.push_back({static_cast<int>(a), static_cast<int>(b), {stamps_s[a], stamps_s[b]}, previous_s});
      }
    }
  }
  return pairs;
}

/// Microphone m's height above the floor (m), from options.mic_heights_m (non-empty).
double MicHeight(const SendingTimeVoteOptions& options, std::size_t m) { return options.mic_heights_m.at(m); }

/// The longest delay of a pair's later stamp after its LOS (s): 2 h_s / c for a floor echo; with
/// the floor-ceiling echo modelled 2 (C - h_m + h_s) / c (see SendingTimeRow), h_m the lowest
/// microphone's height.
double MaxEchoDelay(const SendingTimeVoteOptions& options) {
  double extra_m = 0.0;
  if (options.ceiling_height_m > 0.0 && !options.mic_heights_m.empty()) {
    extra_m = options.ceiling_height_m - *std::min_element(options.mic_heights_m.begin(), options.mic_heights_m.end());
  }
  return 2.0 * (options.max_sender_height_m + extra_m) / options.speed_mps;
}

/// Both pairs are physically possible for this t_0 (see VoteSendingTime).
bool Plausible(const LosGroundStamps& p, double t0_s, const SendingTimeVoteOptions& options) {
  const double los_rel_s = p.los_s - t0_s;
  const double ground_rel_s = p.ground_s - t0_s;
  if (!(los_rel_s > 0.0) || los_rel_s * options.speed_mps > options.max_range_m) return false;
  const double c2 = options.speed_mps * options.speed_mps;
  // |S_v - M|^2 - |S - M|^2 = 4 h_s h_m.
  const double excess_m2 = (ground_rel_s * ground_rel_s - los_rel_s * los_rel_s) * c2;
  return excess_m2 <= 4.0 * options.max_sender_height_m * options.max_mic_height_m && excess_m2 >= options.min_excess_m2;
}

}  // namespace

std::optional<double> SendingTimeFromGroundEchoes(const LosGroundStamps& i, const LosGroundStamps& j,
                                                  double min_delay_difference_s) {
  // The denominator is 2 (d_i - d_j), d the echo delay.
  const double delay_difference_s = (i.ground_s - i.los_s) - (j.ground_s - j.los_s);
  if (!(std::abs(delay_difference_s) > min_delay_difference_s)) return std::nullopt;
  // Relative to the earliest stamp: squares of ~10 ms instead of absolute stamps (digest SUG).
  const double ref_s = std::min({i.los_s, i.ground_s, j.los_s, j.ground_s});
  const double li = i.los_s - ref_s, ri = i.ground_s - ref_s, lj = j.los_s - ref_s, rj = j.ground_s - ref_s;
  const double numerator_s2 = ri * ri - rj * rj - li * li + lj * lj;  // Eq. 8.77
  return ref_s + numerator_s2 / (2.0 * delay_difference_s);
}

double SendingTimeNoiseGain(const LosGroundStamps& i, const LosGroundStamps& j, double t0_s) {
  // dt_0/dT_k = +-(T_k - t_0) / (d_i - d_j), from differentiating Eq. 8.77.
  const double delay_difference_s = (i.ground_s - i.los_s) - (j.ground_s - j.los_s);
  if (delay_difference_s == 0.0) return std::numeric_limits<double>::infinity();
  const double sum_s2 = std::pow(i.los_s - t0_s, 2) + std::pow(i.ground_s - t0_s, 2) +
                        std::pow(j.los_s - t0_s, 2) + std::pow(j.ground_s - t0_s, 2);
  return std::sqrt(sum_s2) / std::abs(delay_difference_s);
}

std::vector<std::string> Validate(const SendingTimeVoteOptions& options) {
  std::vector<std::string> problems;
  const auto positive = [&](double v, const char* what) {
    if (!(v > 0.0 && std::isfinite(v))) problems.emplace_back(std::string(what) + " must be > 0 and finite");
  };
  positive(options.speed_mps, "speed_mps");
  positive(options.max_sender_height_m, "max_sender_height_m");
  positive(options.max_mic_height_m, "max_mic_height_m");
  positive(options.max_range_m, "max_range_m");
  positive(options.stamp_sigma_s, "stamp_sigma_s");
  positive(options.max_noise_gain, "max_noise_gain");
  positive(options.pile_sigmas, "pile_sigmas");
  for (const double h : options.mic_heights_m) {
    if (!(h > 0.0 && std::isfinite(h))) {
      problems.emplace_back("mic_heights_m must be > 0 and finite");
      break;
    }
  }
  if (!(options.mic_height_spread_m >= 0.0 && std::isfinite(options.mic_height_spread_m))) {
    problems.emplace_back("mic_height_spread_m must be >= 0 and finite");
  }
  if (!(options.min_excess_m2 >= 0.0 && std::isfinite(options.min_excess_m2))) {
    problems.emplace_back("min_excess_m2 must be >= 0 and finite");
  }
  if (!std::isfinite(options.pile_tolerance_s)) problems.emplace_back("pile_tolerance_s must be finite");
  if (!(options.ceiling_height_m >= 0.0 && std::isfinite(options.ceiling_height_m))) {
    problems.emplace_back("ceiling_height_m must be >= 0 and finite");
  } else if (options.ceiling_height_m > 0.0) {
    if (options.mic_heights_m.empty() || !options.los_is_first_arrival) {
      problems.emplace_back("ceiling_height_m needs mic_heights_m and los_is_first_arrival");
    }
    for (const double h : options.mic_heights_m) {
      if (!(h < options.ceiling_height_m)) {
        problems.emplace_back("ceiling_height_m must be above every microphone");
        break;
      }
    }
  }
  if (options.max_combinations < 1) problems.emplace_back("max_combinations must be >= 1");
  return problems;
}

std::size_t CountVoteCombinations(std::span<const EmissionStamps> emissions, const SendingTimeVoteOptions& options) {
  const double max_delay_s = MaxEchoDelay(options);
  std::size_t total = 0;
  for (const EmissionStamps& e : emissions) {
    std::size_t sum = 0;  // running sum of P over the microphones before this one
    for (const auto& stamps : e.mic_stamps_s) {
      const std::size_t p = PairsOf(stamps, max_delay_s).size();
      total += sum * p;
      sum += p;
    }
  }
  return total;
}

namespace {

using PairTable = std::vector<std::vector<std::vector<PeakPair>>>;  // [emission][mic][pair]

/// What a selected pair's later stamp is: the floor echo, or the echo off the floor and then the
/// ceiling (options.ceiling_height_m).
enum PairKind : int { kFloor = 0, kFloorCeiling = 1, kKinds = 2 };

/// A microphone's slot for a pair of one kind: each microphone has one per kind.
std::size_t Slot(std::size_t mic, int kind) { return kKinds * mic + static_cast<std::size_t>(kind); }

/// Chosen (slot -> pair index) per emission, -1 where none; Slot(m, kind) of microphone m.
using Selection = std::vector<std::vector<int>>;

/// The thesis's steps 4-6: each candidate stands for the interval t_0 +- w_k; the pile is the set
/// of intervals covering the most-covered instant (a sweep over the sorted interval ends). Fills
/// t0_s (median), pile_size and the per-microphone votes.
void ThesisPile(const std::vector<Candidate>& candidates, const PairTable& pairs,
                const SendingTimeVoteOptions& options, SendingTimeVote* vote, Selection* selection) {
  std::vector<double> half_width_s(candidates.size());
  std::vector<std::pair<double, int>> events;  // (time, -1 open / +1 close): opens sort first
  events.reserve(2 * candidates.size());
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    half_width_s[k] = options.pile_tolerance_s > 0.0 ? options.pile_tolerance_s
                                                     : options.pile_sigmas * options.stamp_sigma_s * candidates[k].gain;
    events.emplace_back(candidates[k].t0_s - half_width_s[k], -1);
    events.emplace_back(candidates[k].t0_s + half_width_s[k], +1);
  }
  std::sort(events.begin(), events.end());
  int depth = 0, best_depth = 0;
  double best_time_s = 0.0;
  for (const auto& [time_s, kind] : events) {
    depth -= kind;
    if (depth > best_depth) {
      best_depth = depth;
      best_time_s = time_s;
    }
  }
  std::vector<double> member_t0_s;
  std::vector<std::vector<std::vector<int>>> votes(pairs.size());
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    for (const auto& mic_pairs : pairs[e]) votes[e].emplace_back(mic_pairs.size(), 0);
  }
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Candidate& c = candidates[k];
    if (std::abs(c.t0_s - best_time_s) > half_width_s[k]) continue;
    member_t0_s.push_back(c.t0_s);
    const auto e = static_cast<std::size_t>(c.emission);
    ++votes[e][static_cast<std::size_t>(c.mic_i)][static_cast<std::size_t>(c.pair_i)];
    ++votes[e][static_cast<std::size_t>(c.mic_j)][static_cast<std::size_t>(c.pair_j)];
  }
  std::sort(member_t0_s.begin(), member_t0_s.end());
  const std::size_t size = member_t0_s.size();
  const std::size_t mid = size / 2;
  vote->t0_s = size % 2 == 1 ? member_t0_s[mid] : 0.5 * (member_t0_s[mid - 1] + member_t0_s[mid]);
  vote->pile_size = static_cast<int>(size);
  selection->assign(pairs.size(), {});
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    (*selection)[e].assign(kKinds * pairs[e].size(), -1);
    for (std::size_t m = 0; m < pairs[e].size(); ++m) {
      const auto& v = votes[e][m];
      const auto best = std::max_element(v.begin(), v.end());  // first of equals: deterministic
      if (best != v.end() && *best > 0) (*selection)[e][Slot(m, kFloor)] = static_cast<int>(best - v.begin());
    }
  }
}

/// K = (T_r - t)^2 - (T_L - t)^2 (s^2) of a pair under the hypothesis t, equal for every
/// microphone of one emission (4 h_s h_m / c^2), and its tolerance. With the heights known it is
/// kappa = 4 h_s / c^2 (s^2 / m), the same for both kinds of pair.
struct KEntry {
  double k_s2 = 0.0;
  double tol_s2 = 0.0;
  int mic = 0;
  int pair = 0;
  int kind = kFloor;
  double later_s = 0.0;  ///< the pair's later stamp (its echo)
};

/// The offset of a floor-ceiling pair's K at microphone height h_m: 4 C (C - h_m) / c^2 (s^2).
double FloorCeilingOffset(const SendingTimeVoteOptions& options, double mic_height_m) {
  const double c = options.ceiling_height_m;
  return 4.0 * c * (c - mic_height_m) / (options.speed_mps * options.speed_mps);
}

/// The plausible pairs of one emission under hypothesis t_s, sorted by K.
std::vector<KEntry> KEntries(const std::vector<std::vector<PeakPair>>& mic_pairs, double t_s,
                             const SendingTimeVoteOptions& options) {
  const double c2 = options.speed_mps * options.speed_mps;
  // Unequal microphone heights spread K by 4 h_s dh / c^2.
  // With the microphones' heights known, K / h_m = 4 h_s / c^2 is shared exactly instead.
  const bool heights = !options.mic_heights_m.empty();
  const double height_slack_s2 = heights ? 0.0 : 4.0 * options.max_sender_height_m * options.mic_height_spread_m / c2;
  // The pairs read as (LOS, floor-ceiling echo) too: K = offset + C kappa (Validate: only with
  // the heights and the first-arrival rule, so that every pair of a microphone shares its LOS
  // stamp), plausible as a sender's for 0 < kappa <= 4 max_sender_height_m / c^2.
  const bool floor_ceiling = options.ceiling_height_m > 0.0;
  const double max_kappa_s2_per_m = 4.0 * options.max_sender_height_m / c2;
  std::vector<KEntry> entries, floor_ceiling_entries;
  for (std::size_t m = 0; m < mic_pairs.size(); ++m) {
    const double offset_s2 = floor_ceiling ? FloorCeilingOffset(options, MicHeight(options, m)) : 0.0;
    floor_ceiling_entries.clear();
    for (std::size_t p = 0; p < mic_pairs[m].size(); ++p) {
      const LosGroundStamps& s = mic_pairs[m][p].stamps;
      if (options.los_is_first_arrival && mic_pairs[m][p].previous_s > t_s) continue;
      const double los_s = s.los_s - t_s, ground_s = s.ground_s - t_s;
      const double k_s2 = ground_s * ground_s - los_s * los_s;
      // dK/dT_r = 2 (T_r - t), dK/dT_L = -2 (T_L - t).
      const double sigma_k_s2 = 2.0 * options.stamp_sigma_s * std::hypot(los_s, ground_s);
      if (Plausible(s, t_s, options)) {
        const double scale = heights ? 1.0 / MicHeight(options, m) : 1.0;
        entries.push_back({scale * k_s2, scale * options.pile_sigmas * sigma_k_s2 + height_slack_s2,
                           static_cast<int>(m), static_cast<int>(p), kFloor, s.ground_s});
      }
      if (!floor_ceiling || !(los_s > 0.0) || los_s * options.speed_mps > options.max_range_m) continue;
      const double kappa = (k_s2 - offset_s2) / options.ceiling_height_m;
      if (!(kappa > 0.0) || kappa > max_kappa_s2_per_m) continue;
      floor_ceiling_entries.push_back({kappa, options.pile_sigmas * sigma_k_s2 / options.ceiling_height_m,
                                       static_cast<int>(m), static_cast<int>(p), kFloorCeiling, s.ground_s});
    }
    entries.insert(entries.end(), floor_ceiling_entries.begin(), floor_ceiling_entries.end());
  }
  std::sort(entries.begin(), entries.end(), [](const KEntry& a, const KEntry& b) { return a.k_s2 < b.k_s2; });
  return entries;
}

/// A K cluster's size: its pairs (rows of the least squares), its microphones, its floor pairs.
struct ClusterSize {
  int rows = 0;
  int mics = 0;
  int floor_rows = 0;
  /// Most pairs; among equals most floor pairs; then the smaller cost.
  [[nodiscard]] bool Beats(const ClusterSize& o, double cost, double other_cost) const {
    if (rows != o.rows) return rows > o.rows;
    if (floor_rows != o.floor_rows) return floor_rows > o.floor_rows;
    return cost < other_cost;
  }
};

/// The largest tolerance of the entries (s^2): the pairs covering a point lie within it.
double MaxTolerance(const std::vector<KEntry>& entries) {
  double out = 0.0;
  for (const KEntry& e : entries) out = std::max(out, e.tol_s2);
  return out;
}

/// The pairs sharing K at `point_s2`: those whose own interval K +- tol covers it (each pair is
/// tested with its own tolerance: a far microphone's K is noisier than a near one's). Per slot
/// (microphone and kind) the pair nearest the point in units of its tolerance (-1 if none) in
/// *members, their count, and in *cost their squared misses from the members' weighted mean K
/// in units of their tolerances (MSAC-like: typically each below 4).
ClusterSize ClusterAt(const std::vector<KEntry>& entries, double point_s2, double max_tol_s2,
                      bool floor_ceiling_alone, std::vector<int>* members, std::vector<double>* distance, double* cost) {
  std::fill(members->begin(), members->end(), -1);
  std::fill(distance->begin(), distance->end(), std::numeric_limits<double>::infinity());
  std::vector<const KEntry*> member_entry(members->size(), nullptr);
  ClusterSize size;
  // The scan reaches a little beyond the largest tolerance: at an interval's lower end k - tol
  // the rounded (k - tol) + tol can fall below k. Membership is decided by the test below.
  const double reach_s2 = max_tol_s2 + 1e-9 * (std::abs(point_s2) + max_tol_s2);
  const auto lo = std::lower_bound(entries.begin(), entries.end(), point_s2 - reach_s2,
                                   [](const KEntry& a, double v) { return a.k_s2 < v; });
  for (auto it = lo; it != entries.end() && it->k_s2 <= point_s2 + reach_s2; ++it) {
    if (!(it->k_s2 - it->tol_s2 <= point_s2 && point_s2 <= it->k_s2 + it->tol_s2)) continue;
    const std::size_t slot = Slot(static_cast<std::size_t>(it->mic), it->kind);
    const std::size_t other = Slot(static_cast<std::size_t>(it->mic), kKinds - 1 - it->kind);
    const double d = std::abs(it->k_s2 - point_s2) / it->tol_s2;
    if ((*members)[slot] < 0) {
      ++size.rows;
      if (it->kind == kFloor) ++size.floor_rows;
      // A microphone counts once, by whichever of its slots joins first.
      if ((*members)[other] < 0) ++size.mics;
    }
    if (d < (*distance)[slot]) {
      (*distance)[slot] = d;
      (*members)[slot] = it->pair;
      member_entry[slot] = &*it;
    }
  }
  // A microphone's floor-ceiling pair is left out of the cluster
  //  - without its floor pair, unless floor_ceiling_alone: where the floor-ceiling echo (two
  //    reflections, a longer path) is heard, the floor echo (one, shorter) mostly is too.
  //    Counted, such pairs let a reading of the floor pairs as floor-ceiling ones (a sender lower
  //    by (C - h) (C + z) / C) compete through chance stamps in its floor slots, in rooms that
  //    return no second order; kept as rows, the chance ones bias t_0 there (both measured:
  //    docs/results/acoustic.md). In a room that does return it, a body that shadows the floor
  //    echo leaves the floor-ceiling one alone (FillChosen);
  //  - when its stamp does not come after the floor echo's: the floor-ceiling image (h_m - 2 C) is
  //    farther than the floor image (-h_m) from any sender (this also keeps one stamp from
  //    being both echoes).
  for (std::size_t slot = kFloorCeiling; slot < members->size(); slot += kKinds) {
    if ((*members)[slot] < 0) continue;
    const std::size_t floor = slot - kFloorCeiling;
    const bool with_floor = (*members)[floor] >= 0;
    if (with_floor ? member_entry[slot]->later_s > member_entry[floor]->later_s : floor_ceiling_alone) continue;
    (*members)[slot] = -1;
    member_entry[slot] = nullptr;
    --size.rows;
    if ((*members)[floor] < 0) --size.mics;
  }
  double sum_w = 0.0, sum_wk = 0.0;
  for (const KEntry* e : member_entry) {
    if (e == nullptr) continue;
    const double w = 1.0 / (e->tol_s2 * e->tol_s2);
    sum_w += w;
    sum_wk += w * e->k_s2;
  }
  *cost = 0.0;
  if (sum_w > 0.0) {
    const double mean_s2 = sum_wk / sum_w;
    for (const KEntry* e : member_entry) {
      if (e != nullptr) *cost += std::pow((e->k_s2 - mean_s2) / e->tol_s2, 2);
    }
  }
  return size;
}

/// Calls visit(size, cost, members) for the pairs of one emission sharing K under hypothesis
/// t_s at every point tried: every pair's K (exact stamps share it exactly) and the lower end of
/// its interval (every maximal set of intervals sharing a point contains the largest lower end
/// among its members, so no such set is missed). A centre pair's own tolerance alone (the rule
/// before) left out true pairs of far microphones, whose K is noisier, around a near one, and a
/// wrong cluster of as many microphones won. Measured and not kept: re-centring each cluster once
/// on its members' mean (the office hold-out's emissions without a fix 1961 -> 2230).
template <typename Visit>
void ForEachCluster(const std::vector<std::vector<PeakPair>>& mic_pairs, double t_s,
                    const SendingTimeVoteOptions& options, bool floor_ceiling_alone, Visit&& visit) {
  const std::vector<KEntry> entries = KEntries(mic_pairs, t_s, options);
  const double max_tol_s2 = MaxTolerance(entries);
  std::vector<double> distance(kKinds * mic_pairs.size());
  std::vector<int> members(kKinds * mic_pairs.size());
  for (const KEntry& entry : entries) {
    for (const double point_s2 : {entry.k_s2, entry.k_s2 - entry.tol_s2}) {
      double cost = 0.0;
      const ClusterSize size = ClusterAt(entries, point_s2, max_tol_s2, floor_ceiling_alone, &members, &distance, &cost);
      visit(size, cost, members);
    }
  }
}

/// The largest set of pairs of one emission sharing K under hypothesis t_s (ForEachCluster): per
/// slot the pair index (or -1). Returns its size.
ClusterSize BestKCluster(const std::vector<std::vector<PeakPair>>& mic_pairs, double t_s,
                         const SendingTimeVoteOptions& options, std::vector<int>* chosen, double* cost) {
  chosen->assign(kKinds * mic_pairs.size(), -1);
  ClusterSize best;
  *cost = 0.0;
  ForEachCluster(mic_pairs, t_s, options, false, [&](const ClusterSize& size, double point_cost, const std::vector<int>& members) {
    if (size.Beats(best, point_cost, *cost)) {
      best = size;
      *cost = point_cost;
      *chosen = members;
    }
  });
  return best;
}

/// Every distinct K cluster of at least three microphones of one emission under t_s, ranked as
/// BestKCluster ranks them (most pairs first), among equals the tightest; floor_ceiling_alone:
/// see ClusterAt.
std::vector<std::vector<int>> KClusters(const std::vector<std::vector<PeakPair>>& mic_pairs, double t_s,
                                        const SendingTimeVoteOptions& options, bool floor_ceiling_alone) {
  struct Ranked {
    ClusterSize size;
    double cost;
    std::vector<int> members;
  };
  std::vector<Ranked> clusters;
  ForEachCluster(mic_pairs, t_s, options, floor_ceiling_alone, [&](const ClusterSize& size, double cost,
                                                                    const std::vector<int>& members) {
    if (size.mics < 3) return;
    const auto same = std::find_if(clusters.begin(), clusters.end(), [&](const Ranked& r) { return r.members == members; });
    if (same == clusters.end()) {
      clusters.push_back({size, cost, members});
    } else {
      same->cost = std::min(same->cost, cost);
    }
  });
  // A cluster contained in another (its pairs all the other's: the points between two lower
  // ends cover fewer intervals) is no alternative of its own.
  const auto within = [](const std::vector<int>& a, const std::vector<int>& b) {
    for (std::size_t slot = 0; slot < a.size(); ++slot) {
      if (a[slot] >= 0 && a[slot] != b[slot]) return false;
    }
    return true;
  };
  std::vector<Ranked> maximal;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    bool contained = false;
    for (std::size_t j = 0; j < clusters.size() && !contained; ++j) {
      contained = j != i && clusters[j].size.rows > clusters[i].size.rows && within(clusters[i].members, clusters[j].members);
    }
    if (!contained) maximal.push_back(clusters[i]);
  }
  std::stable_sort(maximal.begin(), maximal.end(),
                   [](const Ranked& a, const Ranked& b) { return a.size.Beats(b.size, a.cost, b.cost); });
  std::vector<std::vector<int>> out;
  for (auto& r : maximal) out.push_back(std::move(r.members));
  return out;
}

/// One selected pair's row of 2 d t_0 + h K_e = d (T_r + T_L) (Eq. 8.77 generalised to any
/// number of microphones; with two it is 8.77), relative to the hypothesis t_s so that the right
/// side is small (no cancellation): a = 2 d, b = h (the microphone's height, 1 without heights),
/// y = d (T_r - t_s + T_L - t_s), weight w = 1 / var(row) with var = 4 sigma^2 ((T_r - t_s)^2 +
/// (T_L - t_s)^2) (dy/dT_r = 2 (T_r - t_0), dy/dT_L = -2 (T_L - t_0)). A floor-ceiling pair's
/// row has b = C and its offset 4 C (C - h) / c^2 taken from y. max_delay_extra_s: what its delay
/// may exceed a floor echo's bound 2 z / c by (0 for a floor pair; 2 (C - h) / c for a floor-
/// ceiling pair, whose delay 4 C (C - h + z) / (c (R + R_L)) <= 2 (C - h + z) / c, R + R_L >= 2 C).
struct SendingTimeRow {
  double a = 0.0, b = 0.0, y = 0.0, w = 0.0;
  double max_delay_extra_s = 0.0;
  int mic = 0;
  /// Its LOS stamp relative to t_s (s): a microphone's floor and floor-ceiling rows share it, so
  /// their y are correlated, cov = 4 sigma^2 u_L^2 (dy/dT_L = -2 u_L in both).
  double u_l_s = 0.0;
};

/// The weighted sums of one emission's rows for the least squares of (t_0, K_e): sum over rows of
/// a W a, a W b, b W b, a W y, b W y, with W the inverse covariance of the rows, block-diagonal
/// per microphone (a floor and a floor-ceiling row share the LOS stamp; consecutive rows of one
/// microphone form its block).
struct RowSums {
  double saa = 0.0, sab = 0.0, sbb = 0.0, say = 0.0, sby = 0.0;
};
/// `skip`: a row left out (the leave-one-out sums); a microphone has at most two rows.
RowSums SumRows(const std::vector<SendingTimeRow>& rows, double var_s2,
                std::size_t skip = std::numeric_limits<std::size_t>::max()) {
  RowSums s;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i == skip) continue;
    const SendingTimeRow& r = rows[i];
    if (i + 1 < rows.size() && i + 1 != skip && rows[i + 1].mic == r.mic) {
      const SendingTimeRow& q = rows[i + 1];
      const double v1 = 1.0 / r.w, v2 = 1.0 / q.w, c = 4.0 * var_s2 * r.u_l_s * q.u_l_s;
      const double det = v1 * v2 - c * c;
      const double w11 = v2 / det, w22 = v1 / det, w12 = -c / det;
      const auto form = [&](double x1, double x2, double z1, double z2) {
        return w11 * x1 * z1 + w12 * (x1 * z2 + x2 * z1) + w22 * x2 * z2;
      };
      s.saa += form(r.a, q.a, r.a, q.a), s.sab += form(r.a, q.a, r.b, q.b), s.sbb += form(r.b, q.b, r.b, q.b);
      s.say += form(r.a, q.a, r.y, q.y), s.sby += form(r.b, q.b, r.y, q.y);
      ++i;
      continue;
    }
    s.saa += r.w * r.a * r.a, s.sab += r.w * r.a * r.b, s.sbb += r.w * r.b * r.b;
    s.say += r.w * r.a * r.y, s.sby += r.w * r.b * r.y;
  }
  return s;
}

/// t_0 of the window from the selected pairs, robust to the picks the K clusters let through.
/// Per emission the rows are reduced to one estimate of t_0 (K_e eliminated: a Schur complement
/// of its weighted least squares, information I_e); the window's t_0 is their information-
/// weighted mean, the same as the joint least squares of t_0 and every K_e. Then, while the
/// worst of them exceeds 3 sigma, one is left out and the mean recomputed (the selection itself
/// is unchanged):
///  - a row whose miss at the window's t_0 (with its emission's K_e at that t_0) exceeds 3 of its
///    sigmas (a false alarm or a heavy-tail stamp inside the cluster's K tolerance, which is 3
///    sigma about the cluster's mean), or whose delay T_r - T_L exceeds the largest a floor echo can
///    have at the height K_e gives, 2 z / c, by 3 sigmas (with the microphones' heights: a later
///    echo or a false alarm as r, whose large regressor 2 d makes it a high-leverage row that its
///    emission's other rows cannot check, claiming most of the window's information), while its
///    emission keeps at least two rows. The miss is not
///    corrected for the row's leverage (a threshold nearer 3.7 sigma with three rows), and an
///    emission's disagreement with the others' t_0 enters it (the emission test, which needs
///    three emissions, fires first when that dominates);
///  - an emission whose own t_0 differs from the others' by more than 3 sigma of the difference
///    (a wrong cluster consistent in itself: K_e absorbs it, only t_0 shows it), when at least
///    three emissions have one.
/// The sigma is scaled by the Birge ratio sqrt(chi^2 / (E - 1)) of the emissions' estimates when
/// above one (the scatter the stamps' sigma does not explain). Left in: a bias of second order
/// in the noise (the regressor 2 d carries the stamps' noise, correlated with the row's,
/// E[da dy] = 4 sigma^2 (u_r + u_L)), which makes t_0 late. Each step's effect, and the bias's
/// size, measured: docs/results/acoustic.md (ch. 8, "The vote's t_0 and its sigma").
/// Returns t_0 and its standard deviation (s).
std::optional<std::pair<double, double>> RefineSendingTime(const PairTable& pairs, const Selection& selection, double t_s,
                                                           const SendingTimeVoteOptions& options) {
  const double var_s2 = options.stamp_sigma_s * options.stamp_sigma_s;
  std::vector<std::vector<SendingTimeRow>> rows(pairs.size());
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    for (std::size_t m = 0; m < pairs[e].size(); ++m) {
      for (int kind = kFloor; kind < kKinds; ++kind) {
        const int p = selection[e][Slot(m, kind)];
        if (p < 0) continue;
        const LosGroundStamps& s = pairs[e][m][static_cast<std::size_t>(p)].stamps;
        const double u_r = s.ground_s - t_s, u_l = s.los_s - t_s;
        const double delay_s = u_r - u_l;
        SendingTimeRow row{2.0 * delay_s, options.mic_heights_m.empty() ? 1.0 : MicHeight(options, m),
                           delay_s * (u_r + u_l), 1.0 / (4.0 * var_s2 * (u_r * u_r + u_l * u_l))};
        row.mic = static_cast<int>(m);
        row.u_l_s = u_l;
        if (kind == kFloorCeiling) {
          row.b = options.ceiling_height_m;
          row.y -= FloorCeilingOffset(options, MicHeight(options, m));
          row.max_delay_extra_s = 2.0 * (options.ceiling_height_m - MicHeight(options, m)) / options.speed_mps;
        }
        rows[e].push_back(row);
      }
    }
  }
  const bool heights = !options.mic_heights_m.empty();  // the delay bound needs them
  const double c2 = options.speed_mps * options.speed_mps;
  struct Estimate {
    double info = 0.0;  // I_e (s^-2)
    double t0 = 0.0;    // relative to t_s
    double sbb = 0.0, sab = 0.0, sby = 0.0;  // for K_e at a given t_0
  };
  for (;;) {
    std::vector<Estimate> estimates(pairs.size());
    double sum_info = 0.0, sum_weighted = 0.0;
    int used = 0;
    for (std::size_t e = 0; e < rows.size(); ++e) {
      if (rows[e].size() < 2) continue;  // K_e undetermined
      const auto [saa, sab, sbb, say, sby] = SumRows(rows[e], var_s2);
      const double info = saa - sab * sab / sbb;
      // The delays do not vary with the heights (or only by rounding): no t_0.
      if (!(info > 1e-12 * saa)) continue;
      estimates[e] = {info, (say - sab * sby / sbb) / info, sbb, sab, sby};
      sum_info += info, sum_weighted += info * estimates[e].t0;
      ++used;
    }
    if (used == 0) return std::nullopt;
    const double t0 = sum_weighted / sum_info;
    double chi2 = 0.0;
    double worst_z2 = 9.0;
    std::size_t worst_e = 0;
    int worst_row = -2;  // -2: none, -1: the whole emission
    for (std::size_t e = 0; e < rows.size(); ++e) {
      const Estimate& est = estimates[e];
      if (!(est.info > 0.0)) continue;
      chi2 += est.info * (est.t0 - t0) * (est.t0 - t0);
      // Two emissions that disagree cannot tell which is wrong: the test needs three.
      const double rest_info = sum_info - est.info;
      if (used >= 3 && rest_info > 0.0) {
        const double rest = (sum_weighted - est.info * est.t0) / rest_info;
        const double z2 = (est.t0 - rest) * (est.t0 - rest) / (1.0 / est.info + 1.0 / rest_info);
        if (z2 > worst_z2) worst_z2 = z2, worst_e = e, worst_row = -1;
      }
      if (rows[e].size() <= 2) continue;
      const double k = (est.sby - t0 * est.sab) / est.sbb;  // K_e at the window's t_0
      for (std::size_t i = 0; i < rows[e].size(); ++i) {
        const auto& r = rows[e][i];
        const double miss = r.y - r.a * t0 - r.b * k;
        double z2 = r.w * miss * miss;
        // With the microphones' heights (b = h) K = 4 z / c^2 gives the sender's height z, and a
        // floor echo lags its LOS by at most 2 z / c = K c / 2 (R_r - R_L = 4 h z / (R_r + R_L)
        // and R_r + R_L >= 2 h, equal with the sender below the microphone). K from the
        // emission's other rows (a late high-leverage row would raise its own bound); the
        // delay's sigma: its two stamps' and the bound's (that K's variance at this t_0). A
        // K that is not positive is no sender's: the emission test handles that emission.
        const RowSums rest_sums = SumRows(rows[e], var_s2, i);
        const double sbb_rest = rest_sums.sbb;
        if (heights && sbb_rest > 0.0) {
          const double k_rest = (rest_sums.sby - t0 * rest_sums.sab) / sbb_rest;
          const double delay_sigma_s = std::sqrt(2.0 * var_s2 + 0.25 * c2 / sbb_rest);
          const double late = (0.5 * r.a - r.max_delay_extra_s - 0.5 * k_rest * options.speed_mps) / delay_sigma_s;
          if (k_rest > 0.0 && late > 0.0) z2 = std::max(z2, late * late);
        }
        if (z2 > worst_z2) worst_z2 = z2, worst_e = e, worst_row = static_cast<int>(i);
      }
    }
    if (worst_row == -2) {
      const double birge2 = used > 1 ? std::max(1.0, chi2 / (used - 1)) : 1.0;
      return std::make_pair(t_s + t0, std::sqrt(birge2 / sum_info));
    }
    if (worst_row == -1) {
      rows[worst_e].clear();
    } else {
      rows[worst_e].erase(rows[worst_e].begin() + worst_row);
    }
  }
}

/// A consensus hypothesis's support.
struct Score {
  int redundant = -1;  // inlier pairs beyond two, summed over emissions
  double cost = 0.0;   // their truncated squared residuals
  int inliers = 0;
  [[nodiscard]] bool Beats(const Score& o) const {
    return redundant > o.redundant || (redundant == o.redundant && cost < o.cost);
  }
};

/// The support of hypothesis t_s: per emission the best K cluster of at least three microphones.
Score ScoreHypothesis(const PairTable& pairs, double t_s, const SendingTimeVoteOptions& options, Selection* chosen) {
  Score score{0, 0.0, 0};
  chosen->assign(pairs.size(), {});
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    double cost = 0.0;
    const ClusterSize size = BestKCluster(pairs[e], t_s, options, &(*chosen)[e], &cost);
    if (size.mics < 3) {
      std::fill((*chosen)[e].begin(), (*chosen)[e].end(), -1);
      continue;
    }
    score.redundant += size.rows - 2;
    score.cost += cost;
    score.inliers += size.rows;
  }
  return score;
}

/// From hypothesis t_s: cluster, refine t_0 by RefineSendingTime, re-cluster, until t_0 settles.
/// Returns the final support.
Score RefineHypothesis(double t_s, const PairTable& pairs, const SendingTimeVoteOptions& options, SendingTimeVote* vote,
                       Selection* selection);

/// Consensus: every candidate t_0 (deduplicated to one per stamp_sigma_s) is a hypothesis; its
/// score is, summed over emissions, the pairs beyond two that share K (two
/// always do, for the hypotheses they generate). The best hypothesis's clusters are the chosen
/// stamps; t_0 is then refined (RefineHypothesis).
void Consensus(std::vector<Candidate> candidates, const PairTable& pairs, const SendingTimeVoteOptions& options,
               SendingTimeVote* vote, Selection* selection) {
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.t0_s < b.t0_s; });
  Score best;
  double best_t_s = candidates.front().t0_s;
  double last_t_s = -std::numeric_limits<double>::infinity();
  Selection chosen;
  for (const Candidate& c : candidates) {
    if (c.t0_s - last_t_s < options.stamp_sigma_s) continue;
    last_t_s = c.t0_s;
    const Score score = ScoreHypothesis(pairs, c.t0_s, options, &chosen);
    if (score.Beats(best)) {
      best = score;
      best_t_s = c.t0_s;
    }
  }
  RefineHypothesis(best_t_s, pairs, options, vote, selection);
}

Score RefineHypothesis(double t_s, const PairTable& pairs, const SendingTimeVoteOptions& options, SendingTimeVote* vote,
                       Selection* selection) {
  Score best = ScoreHypothesis(pairs, t_s, options, selection);
  // Re-cluster at the refined t_0 until it settles (K hardly depends on t_0, so the search's
  // hypothesis can be off by ~1 ms; each least-squares step moves it to its clusters' t_0).
  for (int iteration = 0; iteration < 8; ++iteration) {
    const auto refined = RefineSendingTime(pairs, *selection, t_s, options);
    if (!refined) break;
    const bool settled = std::abs(refined->first - t_s) < 0.1 * options.stamp_sigma_s;
    Selection again;
    const Score score = ScoreHypothesis(pairs, refined->first, options, &again);
    if (score.redundant < best.redundant) break;  // keep the better-supported hypothesis
    t_s = refined->first;
    *selection = std::move(again);
    best = score;
    if (settled) break;
  }
  if (const auto final_t = RefineSendingTime(pairs, *selection, t_s, options)) {
    t_s = final_t->first;
    vote->t0_sigma_s = final_t->second;
  }
  vote->t0_s = t_s;
  vote->pile_size = best.inliers;
  return best;
}

/// Known microphone heights must cover every emission's microphones.
bool HeightsMatch(std::span<const EmissionStamps> emissions, const SendingTimeVoteOptions& options) {
  if (options.mic_heights_m.empty()) return true;
  return std::all_of(emissions.begin(), emissions.end(), [&](const EmissionStamps& e) {
    return e.mic_stamps_s.size() == options.mic_heights_m.size();
  });
}

/// The (L, r) pairs of every microphone of every emission.
PairTable PairsOfEmissions(std::span<const EmissionStamps> emissions, const SendingTimeVoteOptions& options) {
  PairTable pairs(emissions.size());
  for (std::size_t e = 0; e < emissions.size(); ++e) {
    for (const auto& stamps : emissions[e].mic_stamps_s) pairs[e].push_back(PairsOf(stamps, MaxEchoDelay(options)));
  }
  return pairs;
}

/// One emission's chosen stamps' indices from its selected pairs (both kinds of a microphone
/// share its LOS stamp: the first arrival, see ceiling_height_m).
std::vector<MicStampChoice> ChosenStamps(const std::vector<std::vector<PeakPair>>& mic_pairs,
                                         const std::vector<int>& selected) {
  std::vector<MicStampChoice> chosen(mic_pairs.size());
  for (std::size_t m = 0; m < mic_pairs.size(); ++m) {
    if (const int p = selected[Slot(m, kFloor)]; p >= 0) {
      const PeakPair& pair = mic_pairs[m][static_cast<std::size_t>(p)];
      chosen[m].los_index = pair.los_index;
      chosen[m].ground_index = pair.ground_index;
    }
    if (const int p = selected[Slot(m, kFloorCeiling)]; p >= 0) {
      const PeakPair& pair = mic_pairs[m][static_cast<std::size_t>(p)];
      chosen[m].los_index = pair.los_index;
      chosen[m].floor_ceiling_index = pair.ground_index;
    }
  }
  return chosen;
}

/// Over every emission, the selected floor pairs and those whose microphone has a selected
/// floor-ceiling pair too.
struct FloorCeilingCounts {
  std::size_t with_floor = 0;
  std::size_t with_both = 0;
};
FloorCeilingCounts CountFloorCeilingHeard(const Selection& selection) {
  FloorCeilingCounts counts;
  for (const auto& members : selection) {
    for (std::size_t slot = 0; slot < members.size(); slot += kKinds) {
      if (members[slot + kFloor] < 0) continue;
      ++counts.with_floor;
      if (members[slot + kFloorCeiling] >= 0) ++counts.with_both;
    }
  }
  return counts;
}

/// Every emission's chosen stamps; and the last emission's other K clusters at the vote's t_0.
/// Among those, a microphone may be read from its floor-ceiling pair alone (its floor echo
/// missed: a body shadowing the downward path, measured in the second-order examples) when the
/// window shows the room returns that echo at most microphones where the floor echo is heard:
/// the echo more often heard than missed, significantly (the count above half the floor pairs by
/// two binomial standard deviations, sqrt(n) / 2 each at p = 1/2: a short window's few pairs
/// decide nothing). Measured: a fraction of 0.74-1.00 per window in a world with second-order
/// echoes, 0-0.30 (median 0.04, chance pairs) without. Only for the alternatives: the vote's own
/// search for t_0 keeps the rule (chance pairs of that reading bias t_0 in every world:
/// docs/results/acoustic.md).
void FillChosen(const PairTable& pairs, const Selection& selection, const SendingTimeVoteOptions& options,
                SendingTimeVote* vote) {
  vote->chosen.clear();
  for (std::size_t e = 0; e < pairs.size(); ++e) vote->chosen.push_back(ChosenStamps(pairs[e], selection[e]));
  vote->alternatives.clear();
  const auto [with_floor, with_both] = CountFloorCeilingHeard(selection);
  const double n = static_cast<double>(with_floor);
  vote->floor_ceiling_heard_fraction = with_floor == 0 ? 0.0 : static_cast<double>(with_both) / n;
  if (pairs.empty() || options.method != SendingTimeVoteMethod::kConsensus) return;
  const bool floor_ceiling_alone = static_cast<double>(with_both) > 0.5 * n + std::sqrt(n);
  for (const auto& members : KClusters(pairs.back(), vote->t0_s, options, floor_ceiling_alone)) {
    if (members == selection.back()) continue;
    vote->alternatives.push_back(ChosenStamps(pairs.back(), members));
  }
}

}  // namespace

std::optional<SendingTimeVote> VoteSendingTime(std::span<const EmissionStamps> emissions,
                                               const SendingTimeVoteOptions& options) {
  if (!Validate(options).empty() || !HeightsMatch(emissions, options)) return std::nullopt;
  const std::size_t combinations = CountVoteCombinations(emissions, options);
  if (combinations > options.max_combinations) return std::nullopt;

  // Steps 1-3 of Sec. 8.4 for every 4-tuple.
  const PairTable pairs = PairsOfEmissions(emissions, options);
  std::vector<Candidate> candidates;
  for (std::size_t e = 0; e < emissions.size(); ++e) {
    const auto& mics = emissions[e].mic_stamps_s;
    for (std::size_t i = 0; i < mics.size(); ++i) {
      for (std::size_t j = i + 1; j < mics.size(); ++j) {
        for (std::size_t pi = 0; pi < pairs[e][i].size(); ++pi) {
          for (std::size_t pj = 0; pj < pairs[e][j].size(); ++pj) {
            const LosGroundStamps& a = pairs[e][i][pi].stamps;
            const LosGroundStamps& b = pairs[e][j][pj].stamps;
            const auto t0_s = SendingTimeFromGroundEchoes(a, b);
            if (!t0_s) continue;
            const double gain = SendingTimeNoiseGain(a, b, *t0_s);
            if (gain > options.max_noise_gain) continue;
            if (!Plausible(a, *t0_s, options) || !Plausible(b, *t0_s, options)) continue;
            candidates.push_back({*t0_s, gain, static_cast<int>(e), static_cast<int>(i), static_cast<int>(pi),
                                  static_cast<int>(j), static_cast<int>(pj)});
          }
        }
      }
    }
  }
  if (candidates.empty()) return std::nullopt;

  SendingTimeVote vote;
  vote.combinations = combinations;
  vote.candidates = candidates.size();
  Selection selection;
  if (options.method == SendingTimeVoteMethod::kThesisPile) {
    ThesisPile(candidates, pairs, options, &vote, &selection);
  } else {
    Consensus(std::move(candidates), pairs, options, &vote, &selection);
  }
  FillChosen(pairs, selection, options, &vote);
  return vote;
}

std::optional<SendingTimeVote> VoteSendingTimeAt(std::span<const EmissionStamps> emissions, double t0_hypothesis_s,
                                                 const SendingTimeVoteOptions& options) {
  if (!Validate(options).empty() || !HeightsMatch(emissions, options) || !std::isfinite(t0_hypothesis_s)) {
    return std::nullopt;
  }
  const PairTable pairs = PairsOfEmissions(emissions, options);
  SendingTimeVote vote;
  Selection selection;
  const Score score = RefineHypothesis(t0_hypothesis_s, pairs, options, &vote, &selection);
  if (score.inliers == 0) return std::nullopt;
  FillChosen(pairs, selection, options, &vote);
  return vote;
}

}  // namespace mirage::estimation
