// SPDX-License-Identifier: MIT
// Range from the agent to a (virtual) anchor: h = |p - a| (Lafer 2014 Eq. 3.18), with the
// Jacobians J_range_p = (p - a)^T / h (Eq. 3.19) and J_range_a = -J_range_p (Eq. 4.5).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "mirage/core/types.h"
#include "mirage/estimation/measurement_row.h"
#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Predicted range and its Jacobians.
struct VaRangePrediction {
  double range_m = 0.0;                                  ///< |p - a| (m)
  Eigen::RowVector2d J_range_p = Eigen::RowVector2d::Zero();   ///< d range / d agent position
  Eigen::RowVector2d J_range_va = Eigen::RowVector2d::Zero();  ///< d range / d VA position
};

/// Agent-VA distances below this are degenerate: the direction (and so the Jacobian) is undefined.
inline constexpr double kMinVaRange_m = 1e-3;

/// The prediction, or std::nullopt if the agent is within kMinVaRange_m of the VA.
std::optional<VaRangePrediction> PredictVaRange(const Vec2& p_agent_m, const Vec2& p_va_m);

/// The linearised row of a range to a VA at `state`: the agent's position block (2-D) and,
/// when the VA is in the state (va_block), the VA's block (Leitinger Eq. 16); a VA outside the
/// state is fixed at va_m. std::nullopt in the degenerate case of PredictVaRange.
/// @param variance_m2 the range variance R (m^2).
std::optional<MeasurementRow> VaRangeRow(const State& state, const Block& agent_position, const Vec2& va_m,
                                         const std::optional<Block>& va_block, double variance_m2);

}  // namespace mirage::estimation
