// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/robust_position_fix.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace mirage::estimation {
namespace {

/// At most this many anchors are left out: every further one multiplies the trials by the
/// anchors' count, and a fix that needs more has too few anchors left to be checked.
constexpr int kMaxLeftOut = 2;

std::optional<PositionFix> FixOf(std::span<const AnchorCandidates> candidates, const std::vector<int>& choice,
                                 std::optional<double> known_height_m, double range_sigma_m) {
  std::vector<Vec3> anchors_m;
  std::vector<double> ranges_m;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (choice[i] < 0) continue;
    anchors_m.push_back(candidates[i].anchor_m);
    ranges_m.push_back(candidates[i].ranges_m[static_cast<std::size_t>(choice[i])]);
  }
  return FixPosition(anchors_m, ranges_m, known_height_m, range_sigma_m);
}

/// The residual of range `index` of anchor `candidate` at the fix (m).
double Residual(const PositionFix& fix, const AnchorCandidates& candidate, int index) {
  return candidate.ranges_m[static_cast<std::size_t>(index)] - (fix.position_m - candidate.anchor_m).norm();
}

bool AllInsideGate(const PositionFix& fix, std::span<const AnchorCandidates> candidates, const std::vector<int>& choice,
                   double gate_m2) {
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (choice[i] < 0) continue;
    const double e = Residual(fix, candidates[i], choice[i]);
    if (!(e * e <= gate_m2)) return false;
  }
  return true;
}

int Used(const std::vector<int>& choice) {
  return static_cast<int>(std::count_if(choice.begin(), choice.end(), [](int c) { return c >= 0; }));
}

}  // namespace

std::optional<RobustPositionFix> FixPositionRobust(std::span<const AnchorCandidates> candidates,
                                                   std::optional<double> known_height_m, double range_sigma_m,
                                                   double gate_chi2) {
  const double gate_m2 = gate_chi2 * range_sigma_m * range_sigma_m;
  const int unknowns = known_height_m ? 2 : 3;
  // The earliest range of each anchor: the line of sight when it is not blocked.
  std::vector<int> choice(candidates.size(), -1);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const auto& ranges = candidates[i].ranges_m;
    if (!ranges.empty()) choice[i] = static_cast<int>(std::min_element(ranges.begin(), ranges.end()) - ranges.begin());
  }
  std::optional<PositionFix> fix;
  for (int left_out = 0;; ++left_out) {
    fix = FixOf(candidates, choice, known_height_m, range_sigma_m);
    // The deletion residual of each anchor: its range against the fix of the others, over the
    // variance of that prediction, sigma^2 + d^T P_-i d. A wrong range that the others' fix
    // absorbs (near-coplanar anchors trade it for a height error) passes its own residual's gate
    // but not this one, which the absorbing direction cannot hide.
    int worst = -1;
    double worst_score = 0.0;
    if (Used(choice) - 1 >= unknowns) {
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        if (choice[i] < 0) continue;
        std::vector<int> others = choice;
        others[i] = -1;
        const auto others_fix = FixOf(candidates, others, known_height_m, range_sigma_m);
        if (!others_fix) continue;
        const Vec3 to_agent = others_fix->position_m - candidates[i].anchor_m;
        const double predicted_m = to_agent.norm();
        if (!(predicted_m > 0.0)) continue;
        const Vec3 direction = to_agent / predicted_m;
        const double e_m = candidates[i].ranges_m[static_cast<std::size_t>(choice[i])] - predicted_m;
        const double score = e_m * e_m / (range_sigma_m * range_sigma_m + direction.dot(others_fix->covariance_m2 * direction));
        if (score > worst_score) {
          worst_score = score;
          worst = static_cast<int>(i);
        }
      }
    }
    const bool consistent = fix && AllInsideGate(*fix, candidates, choice, gate_m2) && worst_score <= gate_chi2;
    if (consistent) break;
    // Leaving one more out must leave more anchors than unknowns, or nothing could be checked.
    if (worst < 0 || left_out == kMaxLeftOut || Used(choice) - 1 <= unknowns) return std::nullopt;
    choice[static_cast<std::size_t>(worst)] = -1;
  }
  // Re-admit every anchor with its range nearest the fix, if that one passes the gate: an anchor
  // left out, or whose earliest range was a false peak before its line of sight.
  std::vector<int> readmitted(candidates.size(), -1);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    double nearest_m2 = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < candidates[i].ranges_m.size(); ++k) {
      const double e = Residual(*fix, candidates[i], static_cast<int>(k));
      if (e * e < nearest_m2) {
        nearest_m2 = e * e;
        readmitted[i] = static_cast<int>(k);
      }
    }
    if (!(nearest_m2 <= gate_m2)) readmitted[i] = -1;
  }
  if (readmitted != choice) {
    const auto refit = FixOf(candidates, readmitted, known_height_m, range_sigma_m);
    if (refit && AllInsideGate(*refit, candidates, readmitted, gate_m2)) {
      fix = refit;
      choice = std::move(readmitted);
    }
  }
  RobustPositionFix out;
  out.fix = *fix;
  out.range_index = std::move(choice);
  out.anchors_used = Used(out.range_index);
  out.redundant = out.anchors_used > unknowns;
  return out;
}

}  // namespace mirage::estimation
