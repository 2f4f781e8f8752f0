// SPDX-License-Identifier: MIT
// One emission's fix from ALL its stamps with the echo model: the sender position and emission
// offset that explain the most stamps as predicted paths (the direct path and the echoes off the
// floor plan's surfaces), searched over a region. Beyond the thesis: its snapshot methods use each
// microphone's earliest stamp (NLLS, the combinatorial LOS identification) or the LOS / floor-echo
// pairs of the first arrivals (ch. 8), and fail where the body and partitions block the direct
// paths, because the earliest stamp is then an echo. Here a blocked direct path costs one stamp of
// the count, not the fix. The acoustic filters start from it (a self-start, or a first update
// whose prior is wider than the echoes' spacing).
//
// 1. Search. The region is cut into cells of about cell_m (planar: x, y at the known height). At
//    a cell's centre p every microphone's paths up to first order give the values z_k - L_j(p)
//    (z_k a stamp as c (T - t_ref), L_j a path's length), which at the true position all equal
//    the emission offset b for the stamps the paths explain. Since |grad L_j| = 1, a sender
//    anywhere in the cell, up to its half-diagonal r from the centre, moves every value by at
//    most r: the cell's score is the largest number of distinct stamps whose values fall in one
//    window of width 2 (r + 3 sigma), and the window's centre its b. First order only: the
//    second-order paths multiply the cost by the surfaces' count, and the first order with the
//    direct path already explains most stamps of a room.
// 2. Refinement. From the best cells (at most refine_candidates, one per neighbourhood) an
//    iterated robust update of [p, b] whose prior is the cell (sigma r per axis, the window's
//    half-width for b) and whose rows are the stamps paired with the paths up to echo_order by the
//    filters' association (path_association.h), redone at each iterate; Hampel IRLS
//    (irls_update.h), as the REKF's update.
// 3. Choice. The refined candidate with the largest log-likelihood of the stamps: per stamp
//    paired with a path ln(P_d N(nu; 0, s) / lambda), per predicted path without a stamp
//    ln(1 - P_d); a count of the stamps within 3 sigma is flat where ~30 paths per microphone meet
//    ~20 stamps (docs/methods/acoustic.md). Without a clutter model (P_d = 1 or lambda = 0): the
//    most stamps within 3 sigma, ties to the smaller sum of their squares. No fix when the choice
//    explains fewer stamps than unknowns + 2 or reaches fewer than 3 microphones (4 with the
//    height).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/types.h"
#include "mirage/estimation/robust/irls_update.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/reflector_3d.h"

namespace mirage::methods::acoustic {

/// Where the sender may be.
struct MultipathSearchRegion {
  Vec3 lo_m = Vec3::Zero();  ///< the box's lower corner (m)
  Vec3 hi_m = Vec3::Zero();  ///< its upper corner (m); hi.z == lo.z: the height is known
  /// Cells whose centre lies outside its walls (FloorPlan::Encloses) are skipped; may be null.
  const geometry::FloorPlan* plan = nullptr;
};

/// Options of the fix.
struct MultipathFixOptions {
  double range_sigma_m = 0.05;  ///< one stamp's standard deviation as a distance (m), > 0
  int echo_order = 2;           ///< highest echo order of the refinement and the score, >= 0
  /// The association's likelihood-ratio gate (path_association.h): P_d in (0, 1], lambda >= 0.
  double detection_probability = 0.9;
  double clutter_density_per_m = 0.0;
  /// The search grid's spacing (m), > 0. 0.4 m: a room of 100 m^2 and 2.5 m of height in 4000
  /// cells; the window then spans 2 (0.35 + 3 sigma) m.
  double cell_m = 0.4;
  /// Best cells refined, >= 1.
  int refine_candidates = 12;
  estimation::IrlsOptions irls = {};
};

/// The fix.
struct MultipathFix {
  bool found = false;
  Vec3 position_m = Vec3::Zero();  ///< planar: the known height in z
  /// The emission offset b (m): the stamps were given as c (T - t_ref); c t_emit = c t_ref + b.
  double offset_m = 0.0;
  /// Covariance of [x, y, z, b] (m^2); planar: the z row and column are zero.
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
  int explained_stamps = 0;     ///< stamps within 3 sigma of a predicted path at the fix
  int explained_receivers = 0;  ///< microphones with at least one of them
};

/// The fix of one emission (see the file comment).
/// @param reflectors  the surfaces whose echoes are predicted (empty: direct paths only)
/// @param mics_m      the microphones (m)
/// @param stamps_m    per microphone its stamps as c (T - t_ref) (m), any number, unlabeled
MultipathFix FixFromAllStamps(std::span<const geometry::Reflector3> reflectors, std::span<const Vec3> mics_m,
                              const std::vector<std::vector<double>>& stamps_m, const MultipathSearchRegion& region,
                              const MultipathFixOptions& options);

}  // namespace mirage::methods::acoustic
