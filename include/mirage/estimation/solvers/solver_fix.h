// SPDX-License-Identifier: MIT
// The result shared by the acoustic position solvers (Bordoy 2020, Sec. 3.2, 5.1, 8.1-8.3): a
// sender position, the emission-time offset b = c t_s in metres, the residual RMS, the
// covariance and the geometry figure DOP (Eq. 8.8-8.12), plus a status that says why a solve gave
// no or an ambiguous answer. Everything is in metres: arrival times T_i enter as pseudo-ranges
// rho_i = c T_i = |S - M_i| + b (Eq. 3.37 times c), the caller multiplies by c.
#pragma once

#include <string_view>

#include <Eigen/Core>

#include "mirage/core/types.h"

namespace mirage::estimation {

/// Why a solve ended as it did. The reasons are string literals (Describe), so a status costs no
/// allocation.
enum class SolverStatus {
  kOk,                    ///< a fix (or the listed roots) without reservation
  kInvalidInput,          ///< sizes differ, a value is not finite, a sigma is not > 0
  kTooFewRows,            ///< fewer (independent) rows than unknowns
  kCollinearReceivers,    ///< the receivers lie on a line (in the plane, for the 2-D solvers)
  kCoplanarHeightMirror,  ///< coplanar receivers: the fix and its mirror about their plane fit alike
  kDegenerateGeometry,    ///< the linear system is singular for another reason (e.g. b and the height trade off)
  kSingularNormalMatrix,  ///< H^T W H is singular at the fix (NLLS)
  kNoAdmissibleRoot,      ///< every root needs a negative range (r_i = rho_i - b < 0) or is complex
  kNotConverged,          ///< NLLS: max_iterations reached (or the iterate left the finite numbers)
};

/// A short description of the status ("coplanar receivers: height mirror", ...).
constexpr std::string_view Describe(SolverStatus status) {
  switch (status) {
    case SolverStatus::kOk: return "ok";
    case SolverStatus::kInvalidInput: return "invalid input";
    case SolverStatus::kTooFewRows: return "fewer rows than unknowns";
    case SolverStatus::kCollinearReceivers: return "collinear receivers";
    case SolverStatus::kCoplanarHeightMirror: return "coplanar receivers: height mirror";
    case SolverStatus::kDegenerateGeometry: return "degenerate geometry";
    case SolverStatus::kSingularNormalMatrix: return "singular normal matrix";
    case SolverStatus::kNoAdmissibleRoot: return "no admissible root";
    case SolverStatus::kNotConverged: return "not converged";
  }
  return "unknown";
}

/// The geometry (or the rows) cannot determine the unknowns uniquely: too few rows, collinear or
/// coplanar receivers, a singular system. Not degenerate: ok, invalid input, no root, no convergence.
constexpr bool IsDegenerate(SolverStatus status) {
  return status == SolverStatus::kTooFewRows || status == SolverStatus::kCollinearReceivers ||
         status == SolverStatus::kCoplanarHeightMirror || status == SolverStatus::kDegenerateGeometry ||
         status == SolverStatus::kSingularNormalMatrix;
}

/// One position fix of a sender. Fixed-size (no heap), cheap to copy.
struct SolverFix {
  Vec3 position_m = Vec3::Zero();  ///< sender position S (m); z = the known height when it was given
  /// Emission offset b = c t_s (m) in rho_i = |S - M_i| + b; 0 where not estimated (ranges, TDOA).
  double offset_m = 0.0;
  bool offset_estimated = false;  ///< b was an unknown of the solve
  /// RMS of the unweighted row residuals at the fix (m): pseudo-range, range or difference rows.
  double rms_m = 0.0;
  /// sqrt(trace) of the position block of (H^T R1^+ H)^-1 with unit noise, R1 = I for TOA and
  /// ranges and D D^T for TDOA (Eq. 8.8-8.12, 8.56): 3-D DOP, or HDOP when the height was known.
  /// Independent of the sigmas given. +infinity when H^T R1^+ H is singular.
  double dop = 0.0;
  /// Covariance of [x, y, z, b] (m^2), linearised at the fix; rows and columns of unknowns that
  /// were not estimated (known z, b of ranges/TDOA) are zero. With per-row sigmas it is
  /// (H^T W H)^-1 H^T W Sigma W H (H^T W H)^-1, which is (H^T W H)^-1 when W = Sigma^+; without
  /// sigmas, unit sigmas scaled by the residual variance estimate (zero when no rows are redundant).
  Eigen::Matrix4d covariance_m2 = Eigen::Matrix4d::Zero();
  /// NLLS: the last step was shorter than tolerance_m. Closed-form and linear solvers: a fix exists
  /// (also when its status reports no covariance, e.g. a fix on a receiver).
  bool converged = false;
  int iterations = 0;  ///< NLLS iterations taken (0 for closed-form and linear solvers)
  SolverStatus status = SolverStatus::kOk;

  /// The geometry could not determine the fix uniquely (IsDegenerate(status)).
  [[nodiscard]] bool degenerate() const { return IsDegenerate(status); }
  /// Describe(status).
  [[nodiscard]] std::string_view reason() const { return Describe(status); }
};

}  // namespace mirage::estimation
