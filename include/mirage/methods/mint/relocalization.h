// SPDX-License-Identifier: MIT
// Track-loss detection and relocalization for MINT (a mirage addition; the thesis's tracker
// cannot recover once it has run into a wall, Lafer 2014 Sec. 3.7.1). The match score of a
// position is the fraction of the LOS and first-order VAs visible from it whose expected range
// has a measured range within a small tolerance; a tracked agent scores about 0.8, a lost one
// below 0.4. After a few low-score steps the tracker searches the neighbourhood of its
// estimate for the best-scoring position (coarse grid, then fine) and restarts there.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/records.h"
#include "mirage/core/options_descriptor.h"
#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/virtual_anchor.h"

namespace mirage::methods::mint {

/// Parameters of loss detection and relocalization.
struct RelocalizationOptions {
  /// Detect track loss and relocalize.
  bool enabled = true;
  /// A VA matches when a measured range lies within this distance of its expected range (m), in
  /// [1e-6, 10]. 5 cm: about 2 sigma of a first-order reflection's range at 5 dB SINR. Derived:
  /// 2 range sigmas.
  double match_tolerance_m = 0.05;
  /// Highest VA order used for the score, in [0, 6]. 1: first-order reflections are strong
  /// enough to be detected most of the time; second-order ones mostly are not.
  int max_order = 1;
  /// Minimum number of visible VAs for the score to count, in [1, 10000].
  int min_visible = 4;
  /// Score below which a step counts as lost, in [0, 1]. 0.4 (a tracked agent's 5th
  /// percentile is about 0.55 in the seminar room).
  double lost_score = 0.4;
  /// Consecutive lost steps that trigger a search, in [1, 100000].
  int lost_steps = 3;
  /// Half-width of the square searched around the estimate (m), in [1e-3, 100].
  double search_radius_m = 1.5;
  /// Coarse grid step (m), in [1e-3, 100], at most search_radius_m and at least search_radius_m /
  /// 200; the best coarse cell is refined on a grid 4 times finer.
  double search_step_m = 0.1;
  /// Score the best position must reach to be accepted, in [0, 1].
  double found_score = 0.6;
};

/// The options' descriptor (keys, units, ranges, docs, the search-grid check;
/// core/options_descriptor.h).
const core::OptionsDescriptor<RelocalizationOptions>& RelocalizationOptionsDescriptor();

/// Problems with the options ("key: message"), empty if valid; see the descriptor.
std::vector<std::string> Validate(const RelocalizationOptions& options);

/// Matched and visible counts of a position.
struct MatchScore {
  int matched = 0;
  int visible = 0;
  /// matched / visible, 0 when nothing is visible.
  [[nodiscard]] double fraction() const { return visible > 0 ? static_cast<double>(matched) / visible : 0.0; }
};

/// The match score of agent position p_m for the measurements of all anchors.
MatchScore ScorePosition(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan, const Vec2& p_m,
                         std::span<const core::RangeSet> measurements, const RelocalizationOptions& options);

/// The best-scoring position within the search square around center_m, if its score reaches
/// found_score with at least min_visible visible VAs. Points inside obstacles are skipped.
std::optional<Vec2> SearchPosition(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
                                   const Vec2& center_m, std::span<const core::RangeSet> measurements,
                                   const RelocalizationOptions& options);

/// A position found in the whole floor plan, and the coarse grid step it was found on (m).
struct PlanFix {
  Vec2 position_m = Vec2::Zero();
  double grid_step_m = 0.0;
};

/// The best-scoring position anywhere in the floor plan's bounds (a coarse grid of
/// search_step_m, or finer steps for a plan wider than 400 of them, then refined), if it
/// reaches found_score with at least min_visible visible VAs and no cell more than two coarse
/// steps away scores as well: a start without a start point. Empty for an empty plan.
std::optional<PlanFix> SearchFloorPlan(const geometry::VirtualAnchorSet& vas, const geometry::FloorPlan& plan,
                                       std::span<const core::RangeSet> measurements,
                                       const RelocalizationOptions& options);

/// A start from SearchFloorPlan is taken only when the next epoch's search confirms it: within
/// two coarse grid steps plus the distance the walker can cover in between (speed_mps times the
/// time, when the scenario states the speed). One epoch's ranges can match a wrong position by
/// chance (diffuse multipath puts a peak near many expected ranges); two in a row rarely do.
class ConfirmedStart {
 public:
  explicit ConfirmedStart(std::optional<double> speed_mps) : speed_mps_(speed_mps) {}

  /// The confirmed start, if `fix` (this epoch's search, at t_s) confirms the previous epoch's.
  std::optional<Vec2> Add(double t_s, const std::optional<PlanFix>& fix);

 private:
  std::optional<double> speed_mps_;
  std::optional<std::pair<double, PlanFix>> pending_;
};

}  // namespace mirage::methods::mint
