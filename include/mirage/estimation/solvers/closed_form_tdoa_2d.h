// SPDX-License-Identifier: MIT
// Closed-form TDOA position with three receivers and a known sender height (Bordoy 2020,
// Sec. 5.1 step 2, adapted from Bucher & Misra: the exact hyperbolic solution reduced to three
// stations plus the height). With receiver 0 as reference, r_i = r_0 + d_i (d_i = rho_i - rho_0);
// squaring and subtracting r_0^2 = |S - M_0|^2 makes the two equations linear in (x, y, r_0), so
// (x, y) = u + v r_0, and r_0^2 = |(x, y) - M_0,xy|^2 + (z - z_0)^2 is a quadratic in r_0 with
// 0, 1 or 2 admissible roots (r_i >= 0 for all three), the thesis's "one or two solutions".
// Receivers may have any heights. Allocation-free: fixed-size types only.
// Choices where the thesis is silent: a negative discriminant (noise pushed the hyperbolas apart)
// gives no root, not the vertex of the parabola, so the caller's gates see an honest "no fit"; a
// discriminant within 1e-12 of the squared linear term is taken as a double root (one root).
#pragma once

#include <array>

#include "mirage/core/types.h"
#include "mirage/estimation/solvers/solver_fix.h"

namespace mirage::estimation {

/// The admissible roots, ordered by increasing r_0.
struct TdoaRoots2d {
  std::array<Vec3, 2> positions_m{Vec3::Zero(), Vec3::Zero()};  ///< sender positions (z = the known height)
  /// r_0 = |S - M_0| of each root (m); with pseudo-ranges the emission offset is b = rho_0 - r_0.
  std::array<double, 2> reference_range_m{0.0, 0.0};
  int count = 0;  ///< number of valid entries (0, 1 or 2)
  /// kOk (count >= 1), kCollinearReceivers (the receivers' xy on one line, or two of them on one
  /// vertical), kNoAdmissibleRoot, kInvalidInput (non-finite input).
  SolverStatus status = SolverStatus::kOk;
};

/// Roots from the range differences d_i = rho_i - rho_0 (i = 1, 2) to receiver 0.
/// @param receivers_m      the three receivers M_0, M_1, M_2 (m), any heights
/// @param differences_m    {rho_1 - rho_0, rho_2 - rho_0} (m), i.e. c (T_i - T_0)
/// @param sender_height_m  the known sender z (m)
TdoaRoots2d SolveTdoa2d(const std::array<Vec3, 3>& receivers_m, const std::array<double, 2>& differences_m,
                        double sender_height_m);

/// The same from the three pseudo-ranges rho_i = c T_i (m); only their differences matter.
TdoaRoots2d SolveTdoa2dFromPseudoRanges(const std::array<Vec3, 3>& receivers_m,
                                        const std::array<double, 3>& pseudo_ranges_m, double sender_height_m);

}  // namespace mirage::estimation
