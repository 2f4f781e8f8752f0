// SPDX-License-Identifier: MIT
// The only code that writes a State's covariance (STYLE.md Sec. 3; open_vins's StateHelper):
// linear propagation of Euclidean blocks, the Kalman correction (Joseph or standard form, the
// mean corrected through each block's boxplus), symmetrisation, augmentation with a new block,
// re-initialisation and marginalisation of a block.
#pragma once

#include <Eigen/Core>

#include "mirage/estimation/state.h"

namespace mirage::estimation {

/// Covariance (and mean) operations on a State.
class CovarianceOps {
 public:
  /// x_b <- F x_b and P <- F_full P F_full^T + Q_b, where F_full is the identity except for the
  /// square block F acting on the F.rows() tangent rows starting at block `first` (consecutive,
  /// Euclidean blocks), and Q is added on that range. Cost O(n k) for k rows in a state of size
  /// n. The state's time is not changed (Stamp does that once all models have moved it).
  static void PropagateBlock(State& state, BlockKey first, const Eigen::MatrixXd& F, const Eigen::MatrixXd& Q);
  /// Sets the state's time (s).
  static void Stamp(State& state, double t_s);
  /// Applies a tangent correction dx (state.dimension() values) to the mean: x <- x [+] dx block
  /// by block (plain addition for Euclidean blocks).
  static void Correct(State& state, const Eigen::VectorXd& dx);
  /// Kalman update with gain K for a measurement with Jacobian H, innovation covariance S and
  /// noise R: x <- x [+] K nu and the Joseph form P <- (I - K H) P (I - K H)^T + K R K^T,
  /// evaluated as P - K U^T - U K^T + K S K^T with U = P H^T (identical for any K, O(n^2 m)).
  static void JosephUpdate(State& state, const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                           const Eigen::MatrixXd& S, const Eigen::VectorXd& innovation);
  /// Kalman update in the standard form P <- P - K U^T (then symmetrised), exact for the
  /// optimal gain K = U S^-1 and half the O(n^2 m) cost of the Joseph form, at the price of its
  /// guard against rounding in K.
  static void StandardUpdate(State& state, const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                             const Eigen::VectorXd& innovation);
  /// P <- (P + P^T) / 2.
  static void Symmetrize(State& state);
  /// Appends a block of `type` owned by `id` with mean x_new (type.dim values), cross-covariance
  /// P_new_x (tangent_dim x n, against the old state) and covariance P_new (Lafer 2014 Eq.
  /// 4.7-4.9).
  static void Augment(State& state, const BlockType& type, int id, const Eigen::VectorXd& x_new,
                      const Eigen::MatrixXd& P_new_x, const Eigen::MatrixXd& P_new);
  /// Sets a block's mean to x_new and its covariance to P_new, uncorrelated with the rest of the
  /// state: the block starts afresh (a tracker restarting a lost agent), the rest keeps its
  /// marginal.
  static void Reinitialize(State& state, BlockKey key, const Eigen::VectorXd& x_new, const Eigen::MatrixXd& P_new);
  /// Removes a block, marginalising it out of the Gaussian.
  static void Marginalize(State& state, BlockKey key);
};

}  // namespace mirage::estimation
