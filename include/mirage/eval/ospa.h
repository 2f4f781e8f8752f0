// SPDX-License-Identifier: MIT
// OSPA distance between two finite point sets (Schuhmacher, Vo, Vo 2008), the map error of
// multipath SLAM and the data-association metric of Leitinger Eq. (8):
//   d = ( (1/n) ( min_pi sum_i min(c, |x_i - y_pi(i)|)^p + c^p |m - n'| ) )^(1/p),
// with n = max(|X|, |Y|): every point without a partner costs the cut-off c.
#pragma once

#include <span>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::eval {

/// OSPA distance with its decomposition and the optimal assignment.
struct OspaResult {
  double distance_m = 0.0;      ///< the OSPA distance (m)
  double localization_m = 0.0;  ///< ((1/n) sum of the assigned min(c, d)^p)^(1/p) (m)
  double cardinality_m = 0.0;   ///< ((1/n) c^p |m - n|)^(1/p) (m)
  /// For each estimated point, the index of its truth partner, or -1 when it has none or the
  /// partner is at least the cut-off away.
  std::vector<int> assignment;
};

/// OSPA between `estimated` and `truth` with cut-off cutoff_m (> 0) and order p (>= 1). Both
/// empty gives 0; exactly one empty gives the cut-off.
OspaResult Ospa(std::span<const Vec2> estimated, std::span<const Vec2> truth, double cutoff_m, double order_p = 1.0);

}  // namespace mirage::eval
