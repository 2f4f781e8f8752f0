// SPDX-License-Identifier: MIT
// Nonlinear least squares (Gauss-Newton, Levenberg-Marquardt) for an acoustic sender from
// (a) pseudo-ranges rho_i = |S - M_i| + b with unknown emission offset b (TOA, Bordoy 2020
// Eq. 3.37 / 5.1 times c), (b) ranges r_i = |S - M_i| (known emission time), (c) differences
// rho_i - rho_j (TDOA, Eq. 3.36) against one reference receiver or over all pairs i < j. The
// state is [x, y, z, b] without the entries that are not unknowns: z with a known height, b for
// ranges and TDOA. Rows use the model of meas/toa.h (Jacobian rows u_i^T = (S - M_i)^T / r_i,
// and 1 for b; TDOA rows u_i - u_j, Eq. 8.13, 8.51-8.53). LM refines the Ch. 5 combinatorial fix
// (Sec. 5.1 step 8); GN and LM are the NLLS of Sec. 5.3's comparison.
//
// Noise. The per-receiver sigmas are those of rho_i (or r_i). TDOA rows share receivers, so their
// covariance is Sigma = D R D^T (Eq. 8.54-8.55, D the difference operator). With
// tdoa_correlated_weighting the weight is W = Sigma^+ (generalised LS). Over all pairs Sigma has
// rank N - 1 only, and W = Sigma^+ gives exactly the reference-receiver GLS fix: taking every
// receiver as reference adds no information. With diagonal weights 1 / (s_i^2 + s_j^2) the
// all-pairs rows are treated as independent although N(N-1)/2 rows carry N - 1 values: the fix
// stays reasonable, but the naive (H^T W H)^-1 is too small (by about N / 2 for equal sigmas).
// The returned covariance is therefore always the sandwich (H^T W H)^-1 H^T W Sigma W H
// (H^T W H)^-1, right for either weighting.
//
// Choices where the thesis is silent (it gives no damping parameters, Sec. 5.1 [GAP]): LM uses
// Marquardt's scaled damping lambda diag(H^T W H) (plus 1e-9 of the mean diagonal so a zero
// column stays invertible), lambda / 10 after a step that lowers the cost, x 10 and retry after
// one that does not; GN takes every full step. Both stop when the step is below tolerance_m.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/types.h"
#include "mirage/estimation/solvers/solver_fix.h"

namespace mirage::estimation {

/// What the rows measure.
enum class RowModel {
  kToa,    ///< rho_i = |S - M_i| + b, b unknown (TOA with unknown emission time)
  kRange,  ///< r_i = |S - M_i| (emission time known)
  kTdoa,   ///< rho_i - rho_j = |S - M_i| - |S - M_j| for the chosen pairs
};

/// tdoa_reference value that forms every pair i < j instead of differences to one receiver.
inline constexpr int kAllPairs = -1;

/// The measurements of one emission. The spans must outlive the call.
struct NllsProblem {
  RowModel model = RowModel::kToa;
  std::span<const Vec3> receivers_m;  ///< receiver positions M_i (m)
  /// rho_i = c T_i (kToa, kTdoa) or r_i (kRange), one per receiver (m).
  std::span<const double> values_m;
  /// Per-receiver standard deviation of values_m (m), each > 0; empty: equal and unknown (the
  /// covariance is then scaled by the residual variance estimate).
  std::span<const double> sigmas_m;
  /// kTdoa: the reference receiver index (rows rho_i - rho_ref, i != ref), or kAllPairs (rows
  /// rho_i - rho_j, i < j). Ignored otherwise.
  int tdoa_reference = 0;
  /// kTdoa: weight by Sigma^+ (Sigma = D R D^T, GLS) rather than diagonally by 1 / (s_i^2 + s_j^2).
  bool tdoa_correlated_weighting = true;
};

/// The iteration.
enum class NllsMethod { kGaussNewton, kLevenbergMarquardt };

/// Options of SolveNlls.
struct NllsOptions {
  /// Iteration limit, >= 1. 50: GN converges in < 10 from a start within a few metres; LM needs
  /// more from far starts while lambda adapts.
  int max_iterations = 50;
  /// Convergence: the step's norm (m) fell below this, > 0. 1e-7 m is far below any acoustic noise.
  double tolerance_m = 1e-7;
  /// LM's initial damping lambda, > 0 (relative to diag(H^T W H)). 1e-3: near-GN steps from a good start.
  double lm_initial_lambda = 1e-3;
  NllsMethod method = NllsMethod::kLevenbergMarquardt;
  /// The sender's height z (m) when known: z leaves the state (2-D fix with 3-D geometry).
  std::optional<double> known_height_m;
};

/// The problems with the options (empty when valid).
std::vector<std::string> Validate(const NllsOptions& options);

/// The number of unknowns: 2 (x, y) or 3 (+ z), plus 1 for b with kToa.
int StateDimension(RowModel model, bool known_height);

/// The state vector [x, y, (z), (b)] of a position and offset.
Eigen::VectorXd PackState(RowModel model, const Vec3& position_m, double offset_m,
                          std::optional<double> known_height_m);

/// The receiver pairs (i, j) of the TDOA rows rho_i - rho_j for n receivers: (i, ref) for i != ref
/// in increasing i, or every i < j with kAllPairs. Empty for an invalid reference.
std::vector<std::pair<int, int>> TdoaPairs(int receiver_count, int reference);

/// The rows' predicted values h(state) and their Jacobian dh/dstate at a state.
struct Linearization {
  Eigen::VectorXd predicted_m;     ///< h(state), one per row (m)
  Eigen::MatrixXd J_pred_state;    ///< rows x StateDimension (unitless)
};

/// h and its Jacobian at `state` (layout of PackState). std::nullopt when the sender is within
/// kMinToaRange_m (meas/toa.h) of a receiver, where u_i is undefined.
std::optional<Linearization> Linearize(const NllsProblem& problem, const Eigen::VectorXd& state,
                                       std::optional<double> known_height_m);

/// The rms, covariance and DOP of a given fix (no iteration): what the closed-form and linear
/// solvers report. status kSingularNormalMatrix (dop = infinity, zero covariance) when H^T W H is
/// singular, kDegenerateGeometry when the fix is on a receiver, kInvalidInput for bad input.
SolverFix AssessFix(const NllsProblem& problem, const Vec3& position_m, double offset_m,
                    std::optional<double> known_height_m);

/// Iterates from start_m (and start_offset_m for kToa; z is replaced by the known height). The
/// fix has converged, iterations and status kOk, kNotConverged, kTooFewRows (independent rows
/// N or N - 1 for TDOA < unknowns), kSingularNormalMatrix (GN step or final covariance),
/// kDegenerateGeometry (an iterate on a receiver) or kInvalidInput.
SolverFix SolveNlls(const NllsProblem& problem, const Vec3& start_m, double start_offset_m,
                    const NllsOptions& options);

/// kToa: pseudo-ranges with unknown offset. See SolveNlls.
SolverFix SolveToaNlls(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                       std::span<const double> sigmas_m, const Vec3& start_m, double start_offset_m,
                       const NllsOptions& options);

/// kRange: ranges (known emission time). See SolveNlls.
SolverFix SolveRangeNlls(std::span<const Vec3> receivers_m, std::span<const double> ranges_m,
                         std::span<const double> sigmas_m, const Vec3& start_m, const NllsOptions& options);

/// kTdoa: differences of the pseudo-ranges against `reference` (or kAllPairs), GLS weighting.
/// See SolveNlls.
SolverFix SolveTdoaNlls(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                        std::span<const double> sigmas_m, int reference, const Vec3& start_m,
                        const NllsOptions& options);

}  // namespace mirage::estimation
