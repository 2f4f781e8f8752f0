// SPDX-License-Identifier: MIT
// Data association between expected ranges (to the visible VAs) and measured ranges by optimal
// sub-pattern assignment with a cut-off distance d_c (Lafer 2014 Sec. 3.4, Eq. 3.6-3.9):
// minimise sum_i min(|d_i - z_pi(i)|, d_c) over assignments; pairs at >= d_c are rejected.
// There is no Mahalanobis gating in the thesis: the gate is purely Euclidean in range.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

namespace mirage::estimation {

/// For each expected range, the index of the associated measured range, or -1 (no measurement
/// within the cut-off). A measured range is associated to at most one expected range.
/// @param expected_m predicted ranges d_i (m).
/// @param measured_m measured ranges z_j (m).
/// @param cutoff_m   cut-off distance d_c (m), > 0.
std::vector<int> AssociateRanges(std::span<const double> expected_m, std::span<const double> measured_m,
                                 double cutoff_m);

/// The same assignment on a precomputed distance matrix (expected x measured, m); entries >=
/// cutoff_m (e.g. +infinity for pairs ruled out beforehand) are never associated.
std::vector<int> AssociateWithCutoff(const Eigen::MatrixXd& distance_m, double cutoff_m);

}  // namespace mirage::estimation
