// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/range_consensus.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "mirage/estimation/init/range_point_fit.h"

namespace mirage::estimation {

namespace {

// The two intersections of the circles |q - a| = ra and |q - b| = rb; none if they do not meet.
std::optional<std::array<Vec2, 2>> CircleIntersections(const Vec2& a, double ra, const Vec2& b, double rb) {
  const Vec2 ab = b - a;
  const double d = ab.norm();
  if (d < 1e-9 || std::abs(ra - rb) > d || ra + rb < d) return std::nullopt;
  const double along = (ra * ra - rb * rb + d * d) / (2.0 * d);
  const double across = std::sqrt(std::max(ra * ra - along * along, 0.0));
  const Vec2 u = ab / d;
  const Vec2 foot = a + along * u;
  const Vec2 normal(-u.y(), u.x());
  return std::array<Vec2, 2>{foot + across * normal, foot - across * normal};
}

// Index of the range of a sorted scan nearest to predicted_m, if one is within gate_m.
std::optional<std::size_t> Supporting(const std::vector<double>& sorted_m, double predicted_m, double gate_m) {
  const auto it = std::lower_bound(sorted_m.begin(), sorted_m.end(), predicted_m);
  auto nearest = sorted_m.end();
  if (it != sorted_m.end()) nearest = it;
  if (it != sorted_m.begin() && (nearest == sorted_m.end() || predicted_m - *std::prev(it) < *it - predicted_m)) {
    nearest = std::prev(it);
  }
  if (nearest == sorted_m.end() || std::abs(*nearest - predicted_m) > gate_m) return std::nullopt;
  return static_cast<std::size_t>(nearest - sorted_m.begin());
}

// The supporting ranges of q: the nearest range of each scan, if within gate_m.
std::vector<std::pair<std::size_t, std::size_t>> SupportOf(std::span<const RangeScan> scans, const Vec2& q,
                                                           double gate_m) {
  std::vector<std::pair<std::size_t, std::size_t>> support;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    if (const auto j = Supporting(scans[k].ranges_m, (q - scans[k].position_m).norm(), gate_m)) {
      support.emplace_back(k, *j);
    }
  }
  return support;
}

}  // namespace

std::optional<RangeConsensus> FindRangeConsensus(std::span<const RangeScan> scans, std::span<const Vec2> excluded_m,
                                                 const RangeConsensusOptions& options) {
  const std::size_t n = scans.size();
  if (n < 2 || options.min_support > n) return std::nullopt;
  // Support of q if it reaches `bar` scans, else 0: given up as soon as it cannot (most wrong
  // points are dropped after about n - bar scans).
  const auto support = [&](const Vec2& q, std::size_t bar) {
    std::size_t count = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (count + (n - k) < bar) return std::size_t{0};
      if (Supporting(scans[k].ranges_m, (q - scans[k].position_m).norm(), options.gate_m)) ++count;
    }
    return count >= bar ? count : std::size_t{0};
  };
  // Proposals need half the support: one from two noisy circles lies off along them (1 cm of
  // range noise moves the intersection of circles 3 m apart, 10 m away, by 10-20 cm), which leaves
  // the far scans outside the gate until the local optimisation below.
  const std::size_t proposal_bar = std::max<std::size_t>(3, (options.min_support + 1) / 2);
  std::size_t best_support = 0;
  Vec2 best_m = Vec2::Zero();
  Vec2 line_a_m = Vec2::Zero(), line_b_m = Vec2::Zero();  // the proposing scans of the best point
  std::size_t previous_offset = n;
  for (const std::size_t offset : {std::size_t{0}, n / 8, n / 4}) {
    if (offset == previous_offset) continue;  // a short buffer: the same pair again
    previous_offset = offset;
    const RangeScan& first = scans[offset];
    const RangeScan& last = scans[n - 1 - offset];
    if ((last.position_m - first.position_m).norm() < options.min_pair_distance_m) continue;
    for (const double ri_m : first.ranges_m) {
      for (const double rj_m : last.ranges_m) {
        const auto points = CircleIntersections(first.position_m, ri_m, last.position_m, rj_m);
        if (!points) continue;
        for (const Vec2& q : *points) {
          if (std::any_of(excluded_m.begin(), excluded_m.end(),
                          [&](const Vec2& e) { return (e - q).norm() < options.exclusion_radius_m; })) {
            continue;
          }
          const std::size_t count = support(q, std::max(proposal_bar, best_support + 1));
          if (count > best_support) {
            best_support = count;
            best_m = q;
            line_a_m = first.position_m;
            line_b_m = last.position_m;
          }
        }
      }
    }
  }
  if (best_support == 0) return std::nullopt;
  // Local optimisation (LO-RANSAC, Chum, Matas and Kittler 2003): the least-squares point of the
  // supporting ranges, then its support, while the support grows.
  std::vector<std::pair<std::size_t, std::size_t>> supporting = SupportOf(scans, best_m, options.gate_m);
  for (int round = 0; round < 3; ++round) {
    std::vector<Vec2> positions_m;
    std::vector<double> ranges_m;
    for (const auto& [k, j] : supporting) {
      positions_m.push_back(scans[k].position_m);
      ranges_m.push_back(scans[k].ranges_m[j]);
    }
    const auto fit = FitPointToRanges(positions_m, ranges_m, best_m);
    if (!fit) break;
    auto refined = SupportOf(scans, fit->position_m, options.gate_m);
    if (refined.size() <= supporting.size()) break;
    best_m = fit->position_m;
    supporting = std::move(refined);
  }
  if (supporting.size() < options.min_support) return std::nullopt;
  // The mirror image about the line through the proposing scans.
  const Vec2 u = (line_b_m - line_a_m).normalized();
  const Vec2 d = best_m - line_a_m;
  return RangeConsensus{best_m, line_a_m + 2.0 * u * u.dot(d) - d, std::move(supporting)};
}

}  // namespace mirage::estimation
