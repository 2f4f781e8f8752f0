// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/range_consensus.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "mirage/estimation/init/range_point_fit.h"
#include "mirage/geometry/segment.h"

namespace mirage::estimation {

namespace {

// Index of the range of a sorted scan nearest to predicted_m, if one is within gate_m (a NaN
// prediction is within no gate).
std::optional<std::size_t> NearestRangeInGate(const std::vector<double>& sorted_m, double predicted_m, double gate_m) {
  const auto it = std::lower_bound(sorted_m.begin(), sorted_m.end(), predicted_m);
  auto nearest = sorted_m.end();
  if (it != sorted_m.end()) nearest = it;
  if (it != sorted_m.begin() && (nearest == sorted_m.end() || predicted_m - *std::prev(it) < *it - predicted_m)) {
    nearest = std::prev(it);
  }
  if (nearest == sorted_m.end() || !(std::abs(*nearest - predicted_m) <= gate_m)) return std::nullopt;
  return static_cast<std::size_t>(nearest - sorted_m.begin());
}

// The supporting ranges of q: the nearest range of each scan, if within gate_m.
std::vector<std::pair<std::size_t, std::size_t>> SupportingRanges(std::span<const RangeScan> scans, const Vec2& q,
                                                                  double gate_m) {
  std::vector<std::pair<std::size_t, std::size_t>> support;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    if (const auto j = NearestRangeInGate(scans[k].ranges_m, (q - scans[k].position_m).norm(), gate_m)) {
      support.emplace_back(k, *j);
    }
  }
  return support;
}

// A proposal and the scans that proposed it.
struct Proposal {
  std::size_t support = 0;
  Vec2 position_m = Vec2::Zero();
  Vec2 line_a_m = Vec2::Zero();
  Vec2 line_b_m = Vec2::Zero();
};

// Keeps the best kKept proposals at least `apart_m` from each other, best first.
constexpr std::size_t kKept = 3;
void Keep(std::vector<Proposal>& kept, const Proposal& p, double apart_m) {
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if ((kept[i].position_m - p.position_m).norm() < apart_m) {  // the same point again
      if (p.support > kept[i].support) {
        kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(i));
        break;
      }
      return;
    }
  }
  const auto at = std::find_if(kept.begin(), kept.end(), [&](const Proposal& k) { return p.support > k.support; });
  kept.insert(at, p);
  if (kept.size() > kKept) kept.pop_back();
}

bool Excluded(const Vec2& q, std::span<const Vec2> excluded_m, double radius_m) {
  return std::any_of(excluded_m.begin(), excluded_m.end(), [&](const Vec2& e) { return (e - q).norm() < radius_m; });
}

}  // namespace

std::optional<RangeConsensus> FindRangeConsensus(std::span<const RangeScan> scans, std::span<const Vec2> excluded_m,
                                                 const RangeConsensusOptions& options) {
  const std::size_t n = scans.size();
  if (n < 2 || options.min_support > n) return std::nullopt;
  for ([[maybe_unused]] const auto& scan : scans) assert(std::is_sorted(scan.ranges_m.begin(), scan.ranges_m.end()));
  // Support of q if it reaches `bar` scans, else 0: given up as soon as it cannot (most wrong
  // points are dropped after about n - bar scans).
  const auto count_support = [&](const Vec2& q, std::size_t bar) {
    std::size_t count = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (count + (n - k) < bar) return std::size_t{0};
      if (NearestRangeInGate(scans[k].ranges_m, (q - scans[k].position_m).norm(), options.gate_m)) ++count;
    }
    return count >= bar ? count : std::size_t{0};
  };
  // Proposals need half the support: one from two noisy circles lies off along them (1 cm of
  // range noise moves the intersection of circles 3 m apart, 10 m away, by 10-20 cm), which leaves
  // the far scans outside the gate until the refinement below.
  const std::size_t proposal_bar = std::max<std::size_t>(3, (options.min_support + 1) / 2);
  std::vector<Proposal> kept;
  std::size_t previous_offset = n;
  for (const std::size_t offset : {std::size_t{0}, n / 8, n / 4}) {
    if (offset == previous_offset) continue;  // a short buffer: the same pair again
    previous_offset = offset;
    const RangeScan& first = scans[offset];
    const RangeScan& last = scans[n - 1 - offset];
    if ((last.position_m - first.position_m).norm() < options.min_pair_distance_m) continue;
    for (const double ri_m : first.ranges_m) {
      for (const double rj_m : last.ranges_m) {
        const auto points = geometry::IntersectCircles(first.position_m, ri_m, last.position_m, rj_m);
        if (!points) continue;
        for (const Vec2& q : *points) {
          if (Excluded(q, excluded_m, options.exclusion_radius_m)) continue;
          // To enter the kept list a proposal must beat its worst member once the list is full.
          const std::size_t bar = kept.size() < kKept ? proposal_bar : std::max(proposal_bar, kept.back().support + 1);
          if (const std::size_t count = count_support(q, bar)) {
            Keep(kept, {count, q, first.position_m, last.position_m}, options.exclusion_radius_m);
          }
        }
      }
    }
  }
  // Refinement (LO-RANSAC, Chum, Matas and Kittler 2003) of each kept proposal: the
  // least-squares point of its supporting ranges, then its support, while the support grows
  // (it converges within two or three rounds; three is the cap). The refined point must still
  // keep clear of the excluded points; the one with the most support wins.
  std::optional<RangeConsensus> best;
  for (const Proposal& proposal : kept) {
    Vec2 q = proposal.position_m;
    auto supporting = SupportingRanges(scans, q, options.gate_m);
    for (int round = 0; round < 3; ++round) {
      std::vector<Vec2> positions_m;
      std::vector<double> ranges_m;
      for (const auto& [k, j] : supporting) {
        positions_m.push_back(scans[k].position_m);
        ranges_m.push_back(scans[k].ranges_m[j]);
      }
      const auto fit = FitPointToRanges(positions_m, ranges_m, q);
      if (!fit) break;
      auto refined = SupportingRanges(scans, fit->position_m, options.gate_m);
      if (refined.size() <= supporting.size()) break;
      q = fit->position_m;
      supporting = std::move(refined);
    }
    if (supporting.size() < options.min_support || Excluded(q, excluded_m, options.exclusion_radius_m)) continue;
    if (best && supporting.size() <= best->support.size()) continue;
    best = RangeConsensus{q, geometry::MirrorPoint(q, proposal.line_a_m, proposal.line_b_m), std::move(supporting)};
  }
  return best;
}

}  // namespace mirage::estimation
