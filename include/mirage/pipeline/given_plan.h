// SPDX-License-Identifier: MIT
// The floor plan an estimator is given, made from the true one: the walls the plan has
// (Experiment::in_plan), each shifted by a fresh draw from U(-r/2, r/2) per coordinate (Kulmer et
// al. Sec. IV-E: the plan's inaccuracy r), and a wall moved along its normal by a bias (Sec.
// IV-C2), together with each given wall's true offset from where the plan puts it, which the
// evaluation of an estimated floor plan needs.
#pragma once

#include <vector>

#include "mirage/core/rng.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/pipeline/experiment.h"

namespace mirage::pipeline {

/// A given plan and its truth.
struct GivenPlan {
  geometry::FloorPlan plan;          ///< what the estimator is told
  std::vector<int> true_index;       ///< given wall -> wall of the true plan
  std::vector<double> true_offset_m; ///< given wall -> true minus given position along its normal (m)
  int biased = -1;                   ///< given index of the biased wall, -1 for none
};

/// The given plan of one run. Two uniform draws are taken from `rng` for every true wall, given
/// or not, so that the draws of a wall do not depend on the other walls or on r (common random
/// numbers across the variants of a grid).
GivenPlan MakeGivenPlan(const Experiment& experiment, core::Rng rng);

/// The true plan restricted to the walls the given plan has, at their true places.
geometry::FloorPlan TrueGivenWalls(const Experiment& experiment);

}  // namespace mirage::pipeline
