// SPDX-License-Identifier: MIT
// Linear least squares for an acoustic sender by squaring the rows (Bordoy 2020 Eq. 5.7 applied
// to the squared form of Eq. 3.37): (rho_i - b)^2 = |S - M_i|^2 becomes
//   2 M_i . S - 2 rho_i b + lambda = |M_i|^2 - rho_i^2,   lambda = b^2 - |S|^2,
// linear in (S, b, lambda) when lambda is treated as a free unknown (pseudo-ranges, unknown
// emission offset b); with ranges (b known, = 0) it is 2 M_i . S + lambda = |M_i|^2 - r_i^2,
// lambda = -|S|^2. The free lambda is the same as differencing the squared rows against their
// weighted mean. A known height moves 2 M_i,z z to the right-hand side. Solved by the weighted
// normal equations in fixed-size matrices (no heap in the solve), in coordinates centred at the
// receivers' weighted centroid (and rho at its weighted mean) for conditioning.
// Needs: pseudo-ranges >= 5 receivers not coplanar (>= 4 not collinear in xy with a known
// height); ranges >= 4 not coplanar (>= 3 not collinear in xy with a known height). Coplanar
// receivers make the height (and its mirror) invisible to the linear system: use
// closed_form_toa_3d.h, which returns both mirror roots.
// Choice: the weights are 1 / sigma_i^2 of the rows as given, although the squared rows' noise
// grows with the range (about 2 r_i sigma_i); the linear fix is a start for toa_nlls.h, which
// weights correctly, so the simpler weighting is kept.
#pragma once

#include <optional>
#include <span>

#include "mirage/core/types.h"
#include "mirage/estimation/solvers/solver_fix.h"

namespace mirage::estimation {

/// Position and emission offset from pseudo-ranges rho_i = c T_i = |S - M_i| + b.
/// The fix's rms, covariance and dop are those of toa_nlls.h's AssessFix at the solution.
/// status: kOk, kInvalidInput, kTooFewRows, kDegenerateGeometry (coplanar receivers, or b and the
/// position not separable, e.g. a sender far outside the array), kSingularNormalMatrix.
/// @param receivers_m      receiver positions M_i (m)
/// @param pseudo_ranges_m  rho_i (m), one per receiver
/// @param sigmas_m         per-receiver sigma of rho_i (m), each > 0; empty: equal weights
/// @param known_height_m   the sender's z (m) when known
SolverFix SolveLinearToa(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                         std::span<const double> sigmas_m, std::optional<double> known_height_m);

/// Position from ranges r_i = |S - M_i| (emission time known). Statuses as SolveLinearToa.
/// @param ranges_m  r_i (m), one per receiver
SolverFix SolveLinearRanges(std::span<const Vec3> receivers_m, std::span<const double> ranges_m,
                            std::span<const double> sigmas_m, std::optional<double> known_height_m);

}  // namespace mirage::estimation
