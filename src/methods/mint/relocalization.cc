// SPDX-License-Identifier: MIT
#include "mirage/methods/mint/relocalization.h"

#include <algorithm>
#include <cmath>

#include "mirage/core/derived_defaults.h"
#include "mirage/geometry/visibility.h"

namespace mirage::methods::mint {
namespace {
// Half-width of the coarse grid in cells at most (the grid has (2 n + 1)^2 points).
constexpr double kMaxSearchCells = 200.0;
// The fine grid around the best coarse point is this many times finer.
constexpr double kFineGridRatio = 4.0;
}  // namespace

const core::OptionsDescriptor<RelocalizationOptions>& RelocalizationOptionsDescriptor() {
  using core::ValueRange;
  using O = RelocalizationOptions;
  static const auto descriptor = [] {
    // Sanity bounds of the search square's half-width and grid step (the scenario reader's).
    const ValueRange grid_range = ValueRange::Closed(1e-3, 100.0);
    core::OptionsDescriptor<O> d("methods::mint::RelocalizationOptions");
    d.Boolean(&O::enabled, {.key = "enabled", .doc = "Detect track loss and relocalize."});
    d.Number(&O::match_tolerance_m,
             {.key = "match_tolerance_m",
              .unit = "m",
              .range = ValueRange::Closed(1e-6, 10.0),
              .doc = "A VA matches when a measured range lies within this distance of its expected range. 5 cm: "
                     "about 2 sigma of a first-order reflection's range at 5 dB SINR. Derived: 2 range sigmas.",
              .derived = core::RangeSigmas(2.0)});
    d.Integer(&O::max_order,
              {.key = "max_order",
               .range = ValueRange::Closed(0.0, geometry::kMaxVirtualAnchorOrder),
               .doc = "Highest VA order used for the score. 1: first-order reflections are strong enough to be "
                      "detected most of the time; second-order ones mostly are not."});
    d.Integer(&O::min_visible, {.key = "min_visible",
                                .range = ValueRange::Closed(1.0, 10000.0),
                                .doc = "Minimum number of visible VAs for the score to count."});
    d.Number(&O::lost_score, {.key = "lost_score",
                              .range = ValueRange::Closed(0.0, 1.0),
                              .doc = "Score below which a step counts as lost. 0.4: a tracked agent's 5th "
                                     "percentile is about 0.55 in the seminar room."});
    d.Integer(&O::lost_steps, {.key = "lost_steps",
                               .unit = "steps",
                               .range = ValueRange::Closed(1.0, 100000.0),
                               .doc = "Consecutive lost steps that trigger a search."});
    d.Number(&O::search_radius_m, {.key = "search_radius_m",
                                   .unit = "m",
                                   .range = grid_range,
                                   .doc = "Half-width of the square searched around the estimate."});
    d.Number(&O::search_step_m, {.key = "search_step_m",
                                 .unit = "m",
                                 .range = grid_range,
                                 .doc = "Coarse grid step; the best coarse cell is refined on a grid 4 times finer."});
    d.Number(&O::found_score, {.key = "found_score",
                               .range = ValueRange::Closed(0.0, 1.0),
                               .doc = "Score the best position must reach to be accepted."});
    d.Check("search_step_m <= search_radius_m <= 200 * search_step_m (a coarse grid of at most 401 x 401 points)",
            [=](const O& o) -> std::vector<std::string> {
              // Out-of-range values are reported by their own fields.
              if (!grid_range.Contains(o.search_step_m) || !grid_range.Contains(o.search_radius_m)) {
                return {};
              }
              const std::string step = core::FormatNumber(o.search_step_m) + " m";
              const std::string radius = core::FormatNumber(o.search_radius_m) + " m";
              if (o.search_step_m > o.search_radius_m) {
                return {"search_step_m: " + step + " must be <= search_radius_m (" + radius + ")"};
              }
              if (o.search_radius_m / o.search_step_m > kMaxSearchCells) {
                return {"search_step_m: " + step + " must be at least search_radius_m / " +
                        std::to_string(static_cast<int>(kMaxSearchCells)) + " (" +
                        core::FormatNumber(o.search_radius_m / kMaxSearchCells) + " m)"};
              }
              return {};
            });
    return d;
  }();
  return descriptor;
}

std::vector<std::string> Validate(const RelocalizationOptions& options) {
  return RelocalizationOptionsDescriptor().Validate(options);
}

MatchScore ScorePosition(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan, const Vec2& p_m,
                         std::span<const core::RangeSet> measurements, const RelocalizationOptions& options) {
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
              double radius_m, double step_m, std::span<const core::RangeSet> measurements,
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
                                   const Vec2& center_m, std::span<const core::RangeSet> measurements,
                                   const RelocalizationOptions& options) {
  Best best;
  ScanGrid(vas, plan, center_m, options.search_radius_m, options.search_step_m, measurements, options, best);
  if (!best.found) return std::nullopt;
  const Vec2 coarse = best.p_m;
  ScanGrid(vas, plan, coarse, options.search_step_m, options.search_step_m / kFineGridRatio, measurements, options, best);
  if (best.score.fraction() < options.found_score) return std::nullopt;
  return best.p_m;
}

std::optional<PlanFix> SearchFloorPlan(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
                                       std::span<const core::RangeSet> measurements,
                                       const RelocalizationOptions& options) {
  if (plan.walls().empty()) return std::nullopt;
  const auto [lo, hi] = plan.Bounds();
  const Vec2 center_m = 0.5 * (lo + hi);
  const double radius_m = 0.5 * (hi - lo).maxCoeff();
  // At most 401 x 401 coarse cells, whatever the building's size.
  const double step_m = std::max(options.search_step_m, radius_m / 200.0);
  const int n = static_cast<int>(std::ceil(radius_m / step_m));
  // A range changes by at most the distance moved, so a cell's centre scored with the tolerance
  // widened by half the cell's diagonal matches at least what any point of the cell matches: the
  // agent's cell is among the best, however coarse the grid. The peaks are then refined with the
  // true tolerance before they are compared.
  RelocalizationOptions coarse = options;
  coarse.match_tolerance_m += step_m / std::sqrt(2.0);
  std::vector<Best> cells;
  for (int ix = -n; ix <= n; ++ix) {
    for (int iy = -n; iy <= n; ++iy) {
      const Vec2 p = center_m + step_m * Vec2(ix, iy);
      if (plan.InsideObstacle(p)) continue;
      const MatchScore s = ScorePosition(vas, plan, p, measurements, coarse);
      if (s.visible >= options.min_visible && s.matched > 0) cells.push_back({p, s, true});
    }
  }
  std::stable_sort(cells.begin(), cells.end(), [](const Best& a, const Best& b) { return Better(a.score, b.score); });
  constexpr std::size_t kPeaks = 8;
  std::vector<Best> peaks;
  for (const Best& cell : cells) {
    if (peaks.size() == kPeaks) break;
    const bool separate = std::all_of(peaks.begin(), peaks.end(), [&](const Best& peak) {
      return (peak.p_m - cell.p_m).norm() > 2.0 * step_m;
    });
    if (!separate || !plan.Encloses(cell.p_m)) continue;
    Best refined{cell.p_m, ScorePosition(vas, plan, cell.p_m, measurements, options), true};
    ScanGrid(vas, plan, cell.p_m, step_m, step_m / kFineGridRatio, measurements, options, refined);
    peaks.push_back(refined);
  }
  if (peaks.empty()) return std::nullopt;
  std::stable_sort(peaks.begin(), peaks.end(), [](const Best& a, const Best& b) { return Better(a.score, b.score); });
  const Best& best = peaks.front();
  if (best.score.fraction() < options.found_score) return std::nullopt;
  // Unique: no other peak explains the ranges as well (a symmetric room, or two anchors whose
  // line-of-sight circles cross twice with no reflection to tell the crossings apart).
  for (std::size_t k = 1; k < peaks.size(); ++k) {
    if ((peaks[k].p_m - best.p_m).norm() > 2.0 * step_m && !Better(best.score, peaks[k].score)) return std::nullopt;
  }
  return PlanFix{best.p_m, step_m};
}

std::optional<Vec2> ConfirmedStart::Add(double t_s, const std::optional<PlanFix>& fix) {
  if (!fix) {
    pending_.reset();
    return std::nullopt;
  }
  if (pending_) {
    const auto& [t0_s, previous] = *pending_;
    const double reach_m = 2.0 * std::max(previous.grid_step_m, fix->grid_step_m) + speed_mps_.value_or(0.0) * (t_s - t0_s);
    if ((fix->position_m - previous.position_m).norm() <= reach_m) return fix->position_m;
  }
  pending_ = {t_s, *fix};
  return std::nullopt;
}

}  // namespace mirage::methods::mint
