// SPDX-License-Identifier: MIT
// Closed-form 3-D sender position from pseudo-ranges with an unknown emission offset (TOA with
// unknown emission time, i.e. 3-D TDOA; Bordoy 2020 Eq. 3.37, 5.1; a 3-D fix needs >= 4
// receivers, Sec. 3.2) and from ranges (emission time known). All admissible roots are returned.
//   Pseudo-ranges, receivers not coplanar: with >= 5 receivers the linear LS of linear_toa.h
//   (unique); with 4 (or when b is not separable from S linearly), the squared rows differenced
//   against their mean give S = u + w b, and the mean squared row (rho_i - b)^2 = |S - M_i|^2
//   gives a quadratic in b: 0-2 roots, both exact with 4 receivers (the known two-solution
//   ambiguity of 4-station TDOA).
//   Coplanar receivers (always so for 3 with ranges): the differenced rows see only the in-plane
//   position (and b), solved in the plane's frame; the height h above the plane follows from
//   h^2 = mean_i (r_i^2 - |s - q_i|^2), so the fix and its mirror image about the plane are both
//   returned (status kCoplanarHeightMirror, "coplanar receivers: height mirror"), lower z first.
// Choices where the thesis is silent: coplanarity is a relative test (rms distance of the
// receivers from their best-fit plane vs. their rms spread in it, options); a negative h^2
// (noise) gives the single in-plane root h = 0; a root is admissible when every range
// rho_i - b >= -1e-9 (1 + max |rho|) (causality, Eq. 5.4; the LS fix of >= 5 receivers is allowed
// 3 rms more for noise);
// roots are ordered by residual rms, then by z.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/estimation/solvers/solver_fix.h"

namespace mirage::estimation {

/// Options of the 3-D closed forms.
struct ClosedFormToaOptions {
  /// Receivers whose rms distance from their best-fit plane is below this fraction of their rms
  /// spread within it are coplanar (and below it for the spread across their best-fit line:
  /// collinear). In [0, 1). 1e-6: only layouts coplanar to rounding (equal mounting heights);
  /// nearly coplanar ones get the unique but ill-conditioned root, visible in its dop.
  double coplanar_tolerance = 1e-6;
};

/// The problems with the options (empty when valid).
std::vector<std::string> Validate(const ClosedFormToaOptions& options);

/// The admissible roots. Each fix carries AssessFix's rms, dop and covariance (unit sigma scaled
/// by the residual variance: zero for an exact fit) and the status of its root.
struct ToaRoots3d {
  std::array<SolverFix, 2> fixes{};
  int count = 0;  ///< valid entries of fixes (0, 1 or 2)
  /// kOk, kCoplanarHeightMirror (roots returned), kInvalidInput, kTooFewRows,
  /// kCollinearReceivers, kDegenerateGeometry, kNoAdmissibleRoot.
  SolverStatus status = SolverStatus::kOk;
};

/// Roots from pseudo-ranges rho_i = c T_i = |S - M_i| + b (>= 4 receivers).
/// @param receivers_m      receiver positions M_i (m)
/// @param pseudo_ranges_m  rho_i (m), one per receiver
ToaRoots3d SolveToa3dClosedForm(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                                const ClosedFormToaOptions& options = {});

/// Roots from ranges r_i = |S - M_i| (emission time known; >= 4 receivers not coplanar, or >= 3
/// coplanar ones with the height mirror).
/// @param ranges_m  r_i (m), one per receiver
ToaRoots3d SolveRange3dClosedForm(std::span<const Vec3> receivers_m, std::span<const double> ranges_m,
                                  const ClosedFormToaOptions& options = {});

}  // namespace mirage::estimation
