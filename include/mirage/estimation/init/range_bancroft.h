// SPDX-License-Identifier: MIT
// 2-D range-Bancroft (Sirola 2010; Lafer 2014 Sec. 4.2; digest slam_multipath_leitinger.md
// Sec. 2.9): the point q with |q - a_i| = r_i for agent positions a_i, in the least-squares
// sense, as the pair of solutions of the closed form. Ranges from nearly collinear positions
// (a straight walk) determine q only up to its mirror image about the path line; both are
// returned and the caller resolves the ambiguity later.
#pragma once

#include <array>
#include <optional>
#include <span>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// The two candidate solutions.
struct BancroftPair {
  std::array<Vec2, 2> positions_m;  ///< the two solutions (identical when solutions == 1)
  int solutions = 0;                ///< 2 real roots, or 1 (double or complex root: real part)
};

/// Solves |q - a_i| = r_i. Needs at least 3 positions that are not all the same point and finite
/// input; returns std::nullopt otherwise.
std::optional<BancroftPair> RangeBancroft(std::span<const Vec2> positions_m, std::span<const double> ranges_m);

}  // namespace mirage::estimation
