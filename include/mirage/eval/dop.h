// SPDX-License-Identifier: MIT
// CRLB and dilution of precision (DOP, HDOP, VDOP) of a 3-D sender heard by receivers, with
// optional ground-echo rows (Bordoy 2020, PhD thesis Univ. Freiburg, Ch. 8, Eq. 8.3-8.67).
// A ground echo is a line of sight to the receiver mirrored at the floor, M' = (x, y, 2 f - z).
// Models: TOA with a known emission time (rows u_i, Eq. 8.13-8.17), TDOA against one reference row
// with the correlated noise R_TD = D R D^T (Eq. 8.51-8.56; Deffenbaugh et al.), and pseudo-range
// with an unknown offset d_0 (columns [u, 1], Shin & Sung, Eq. 8.59-8.62).
// Choices where the thesis is silent:
//  - sigma_n, the divisor of every DOP (Eq. 8.10-8.12), is the LOS sigma: with per-receiver sigmas
//    it is `sigma_n_m` if set, else the first receiver's LOS sigma (with one sigma for all it is that
//    sigma, as in the thesis). The echo rows keep their own sigma_r, so VDOP with echoes is
//    "position bound in units of the LOS noise" (Eq. 8.43-8.45 with sigma_n / sigma_r).
//  - The weights are sigma_k^-2 once per row, i.e. A = H^T R^-1 H (the digest's typo item 10:
//    Eq. 8.24 and 8.63 show sigma_k^2 in each factor).
//  - Degenerate geometry: A is eigen-decomposed; eigenvalues below `min_eigen_ratio` times the
//    largest span the unidentifiable directions. A position coordinate with a non-negligible
//    component in them gets an infinite bound (and its DOPs are infinite); the others come from the
//    pseudo-inverse, which is the CRLB of an identifiable coordinate. E.g. TDOA, LOS only, all
//    receivers and the sender at one height: VDOP = inf while HDOP stays finite (Eq. 8.57-8.58).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mirage/core/types.h"

namespace mirage::eval {

/// The measurement model of the rows.
enum class DopModel {
  kToa,          ///< ranges with a known emission time (Eq. 8.13-8.17)
  kTdoa,         ///< differences to one reference row, correlated noise (Eq. 8.51-8.56)
  kPseudoRange,  ///< ranges plus one unknown common offset d_0 (Eq. 8.59-8.62)
};

/// A sender among receivers, the rows that exist and their noise.
struct DopInput {
  /// The sender (target) position S (m).
  Vec3 sender_m = Vec3::Zero();
  /// The receiver positions M_i (m).
  std::vector<Vec3> receivers_m;
  /// The LOS ranges' standard deviation (m), > 0: one value for all receivers, or one per receiver.
  std::vector<double> sigma_m{1.0};
  /// Per receiver: its LOS row exists. Empty: every receiver has one. (False for a blocked LOS, as
  /// in the thesis's Fig. 8.1(a), where one of three measurements is a ground echo.)
  std::vector<bool> los;
  /// Per receiver: a ground-echo row exists (receiver mirrored at the floor). Empty: none.
  std::vector<bool> ground_echo;
  /// The echo ranges' standard deviation sigma_r (m), > 0: one value, or one per receiver.
  std::vector<double> ground_sigma_m{1.0};
  /// The floor height f (m); the mirrored receiver is (x, y, 2 f - z). 0: the thesis's ground z = 0.
  double floor_z_m = 0.0;
  DopModel model = DopModel::kToa;
  /// kTdoa: the reference row, an index into the stacked rows (LOS rows of the receivers in order,
  /// then echo rows in order; see BuildRangeRows). The result does not depend on it.
  int tdoa_reference_row = 0;
  /// sigma_n (m) dividing the bounds into DOPs; <= 0: the first receiver's LOS sigma.
  double sigma_n_m = 0.0;
  /// Eigenvalues of A below this fraction of the largest are null directions, in (0, 1). 1e-10:
  /// a DOP of 1e5 (condition number 1e10) is still computed; exact degeneracies give ~1e-16.
  double min_eigen_ratio = 1e-10;
};

/// The CRLB of the sender position and the DOPs (Eq. 8.10-8.12).
struct DopResult {
  /// sqrt(sigma_x^2 + sigma_y^2 + sigma_z^2) / sigma_n; infinity if any coordinate is unidentifiable.
  double dop_3d = 0.0;
  /// sqrt(sigma_x^2 + sigma_y^2) / sigma_n (the thesis's DOP_xy / DOP_2D).
  double hdop = 0.0;
  /// sigma_z / sigma_n.
  double vdop = 0.0;
  /// The position block of (H^T R^-1 H)^-1 (m^2). Rows and columns of an unidentifiable coordinate
  /// are +infinity.
  Eigen::Matrix3d position_crlb_m2 = Eigen::Matrix3d::Zero();
  /// A has null directions (too few rows, coplanar geometry, a sender on a receiver, no rows).
  bool degenerate = false;
  /// The sigma_n used (m).
  double sigma_n_m = 0.0;
  /// The number of range rows (LOS + echo) before differencing.
  int rows = 0;
};

/// The stacked range rows: their Jacobian d|S - M_k| / dS = (S - M_k) / |S - M_k| (unit vectors
/// u_k, Eq. 8.15) and their sigmas. LOS rows of the receivers with a LOS come first (receiver
/// order), then the echo rows (receiver order) with M'_k = (x, y, 2 f - z).
struct RangeRows {
  Eigen::MatrixXd J_range_sender;  ///< rows x 3 (unitless)
  Eigen::VectorXd sigma_m;         ///< one per row (m)
  Eigen::MatrixXd points_m;        ///< rows x 3: the (possibly mirrored) receiver of each row (m)
  /// Some row's receiver coincides with the sender (its row is zero).
  bool sender_on_receiver = false;
};

/// The range rows of `input` (no differencing, no offset column).
RangeRows BuildRangeRows(const DopInput& input);

/// The Fisher information A = H^T R^-1 H (m^-2) of the model's unknowns: 3 x 3 for kToa and kTdoa
/// (with H = D H_toa, R = D R_t D^T, Eq. 8.54-8.56), 4 x 4 for kPseudoRange ([x, y, z, d_0]).
/// Empty (0 x 0) for a kTdoa with no rows or an invalid reference.
Eigen::MatrixXd FisherInformation(const DopInput& input);

/// The CRLB and the DOPs of `input`. Degenerate (all infinite) for a sender on a receiver, mismatched
/// per-receiver vectors, or non-positive sigmas.
DopResult ComputeDop(const DopInput& input);

}  // namespace mirage::eval
