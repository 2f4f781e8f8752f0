// SPDX-License-Identifier: MIT
// The physical bound of a time difference of arrival: by the triangle inequality no true
// difference of distances to two points exceeds the distance between them,
// | |p - a_j| - |p - a_i| | <= |a_i - a_j| (Bordoy 2020 Eq. 5.5, there for stamps times c). A
// measured difference may exceed it by its noise; by more it cannot be a line-of-sight or NLOS
// measurement of this pair (an NLOS excess only lengthens legs, by less than the baseline for a
// real detour), so it is a gross error and is dropped before any statistics.
#pragma once

#include <cmath>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// Whether |tdoa_m| <= |a_i - a_j| + margin_m (finite tdoa_m only).
inline bool InsideTdoaBound(double tdoa_m, const Vec3& anchor_i_m, const Vec3& anchor_j_m, double margin_m) {
  return std::isfinite(tdoa_m) && std::abs(tdoa_m) <= (anchor_i_m - anchor_j_m).norm() + margin_m;
}

}  // namespace mirage::estimation
