// SPDX-License-Identifier: MIT
#include "mirage/methods/mint/relocalization.h"

#include <cmath>

#include "mirage/geometry/visibility.h"

namespace mirage::methods::mint {
namespace {
// Half-width of the coarse grid in cells at most (the grid has (2 n + 1)^2 points).
constexpr double kMaxSearchCells = 200.0;
// The fine grid around the best coarse point is this many times finer.
constexpr double kFineGridRatio = 4.0;
}  // namespace

std::vector<std::string> Validate(const RelocalizationOptions& options) {
  std::vector<std::string> problems;
  if (!(options.match_tolerance_m > 0.0) || !std::isfinite(options.match_tolerance_m)) problems.push_back("match_tolerance_m must be > 0 m");
  if (options.max_order < 0 || options.max_order > geometry::kMaxVirtualAnchorOrder) {
    problems.push_back("max_order must be in [0, " + std::to_string(geometry::kMaxVirtualAnchorOrder) + "]");
  }
  if (options.min_visible < 1) problems.push_back("min_visible must be >= 1");
  if (!(options.lost_score >= 0.0 && options.lost_score <= 1.0)) problems.push_back("lost_score must be in [0, 1]");
  if (options.lost_steps < 1) problems.push_back("lost_steps must be >= 1");
  if (!(options.search_radius_m > 0.0) || !std::isfinite(options.search_radius_m)) {
    problems.push_back("search_radius_m must be > 0 m");
  }
  if (!(options.search_step_m > 0.0) || !(options.search_step_m <= options.search_radius_m)) {
    problems.push_back("search_step_m must be > 0 m and <= search_radius_m");
  } else if (options.search_radius_m / options.search_step_m > kMaxSearchCells) {
    problems.push_back("search_step_m must be at least search_radius_m / " + std::to_string(static_cast<int>(kMaxSearchCells)));
  }
  if (!(options.found_score >= 0.0 && options.found_score <= 1.0)) problems.push_back("found_score must be in [0, 1]");
  return problems;
}

MatchScore ScorePosition(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan, const Vec2& p_m,
                         std::span<const core::AnchorRanges> measurements, const RelocalizationOptions& options) {
  MatchScore score;
  for (const auto& anchor : measurements) {
    for (const int id : geometry::VisibleVirtualAnchors(vas, anchor.anchor_index, plan, p_m, options.max_order)) {
      ++score.visible;
      if (core::HasRangeNear(anchor.ranges, (vas[id].position_m - p_m).norm(), options.match_tolerance_m)) {
        ++score.matched;
      }
    }
  }
  return score;
}

namespace {

// Better: more matches, then a higher fraction.
bool Better(const MatchScore& a, const MatchScore& b) {
  if (a.matched != b.matched) return a.matched > b.matched;
  return a.fraction() > b.fraction();
}

struct Best {
  Vec2 p_m = Vec2::Zero();
  MatchScore score;
  bool found = false;
};

void ScanGrid(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan, const Vec2& center_m,
              double radius_m, double step_m, std::span<const core::AnchorRanges> measurements,
              const RelocalizationOptions& options, Best& best) {
  const int n = static_cast<int>(std::lround(radius_m / step_m));
  for (int ix = -n; ix <= n; ++ix) {
    for (int iy = -n; iy <= n; ++iy) {
      const Vec2 p = center_m + step_m * Vec2(ix, iy);
      if (plan.InsideObstacle(p)) continue;
      const MatchScore s = ScorePosition(vas, plan, p, measurements, options);
      if (s.visible < options.min_visible) continue;
      // Enclosure is the expensive test, so it is only made for a new best.
      if ((!best.found || Better(s, best.score)) && plan.Encloses(p)) best = {p, s, true};
    }
  }
}

}  // namespace

std::optional<Vec2> SearchPosition(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
                                   const Vec2& center_m, std::span<const core::AnchorRanges> measurements,
                                   const RelocalizationOptions& options) {
  Best best;
  ScanGrid(vas, plan, center_m, options.search_radius_m, options.search_step_m, measurements, options, best);
  if (!best.found) return std::nullopt;
  const Vec2 coarse = best.p_m;
  ScanGrid(vas, plan, coarse, options.search_step_m, options.search_step_m / kFineGridRatio, measurements, options, best);
  if (best.score.fraction() < options.found_score) return std::nullopt;
  return best.p_m;
}

}  // namespace mirage::methods::mint
