// SPDX-License-Identifier: MIT
// Which stamp of a microphone belongs to which predicted path (Bordoy 2020 ch. 5 extended with
// the floor plan's echoes): every microphone hears the direct path and, when the floor plan is
// known, the echoes off its walls, floor and ceiling, each the direct path of a virtual receiver
// mirrored in the surfaces (the image-source model, Eq. 3.34). A filter that predicts only the
// direct path must treat the echo of a blocked direct path as an outlier; predicting the echoes
// turns it into a measurement (multipath-assisted, the idea of mirage's MINT and SLAM families).
//
// Association per microphone is global nearest neighbour with a likelihood-ratio gate: a path j
// with innovation variance s_j and a stamp k with innovation nu_jk pair when "path detected with
// this stamp" is likelier than "path missed and the stamp is clutter",
//   P_d N(nu; 0, s) > (1 - P_d) lambda  <=>  nu^2 / s < 2 ln(P_d / ((1 - P_d) lambda sqrt(2 pi s))),
// lambda the density of unexplained stamps per metre. Pairs are taken by increasing nu^2 / s,
// each path and each stamp once. With P_d = 1 or lambda = 0 the gate is open and every path takes
// its nearest stamp (the thesis's association of the direct path).
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "mirage/core/types.h"
#include "mirage/geometry/reflector_3d.h"

namespace mirage::methods::acoustic {

/// One predicted arrival at a microphone.
struct PredictedPath {
  /// Number of reflections; 0 the direct path.
  int order = 0;
  /// Predicted stamp as a distance, path length + b (m).
  double predicted_m = 0.0;
  /// d (path length) / d S: the unit vector from the first reflection point (the receiver for the
  /// direct path) to the sender. The reflection points are stationary (Fermat's principle), so
  /// only the first leg's direction enters to first order.
  Vec3 d_sender = Vec3::Zero();
};

/// The direct path (always, no visibility test: the plan may be approximate) and every existing
/// echo of order 1 .. echo_order off the reflectors, for a sender at sender_m (m) and a microphone
/// at mic_m (m), with the emission offset offset_m (m). Empty when the sender is on the microphone.
std::vector<PredictedPath> PredictPaths(std::span<const geometry::Reflector3> reflectors, const Vec3& sender_m,
                                        const Vec3& mic_m, double offset_m, int echo_order);

/// The largest normalised innovation squared nu^2 / s (unitless) of a pair, from the likelihood
/// ratio above; +infinity when detection_probability is 1 or clutter_density_per_m is 0, and
/// negative (nothing pairs) when s is so large that a stamp is likelier clutter wherever it lies.
/// @param innovation_var_m2      s, the innovation variance of the path (m^2), > 0
/// @param detection_probability  P_d in (0, 1]
/// @param clutter_density_per_m  lambda (1/m), >= 0
double AssociationGate(double innovation_var_m2, double detection_probability, double clutter_density_per_m);

/// One path paired with one stamp.
struct PathStampPair {
  int path = 0;   ///< index into the paths
  int stamp = 0;  ///< index into the stamps
};

/// Global nearest neighbour over one microphone's paths and stamps (see the file comment).
/// @param predicted_m            per path its prediction (m)
/// @param innovation_var_m2      per path its innovation variance (m^2), > 0
/// @param stamps_m               the stamps (m), in the predictions' frame
/// @param detection_probability  P_d in (0, 1]
/// @param clutter_density_per_m  lambda (1/m), >= 0
std::vector<PathStampPair> AssociatePaths(std::span<const double> predicted_m, std::span<const double> innovation_var_m2,
                                          std::span<const double> stamps_m, double detection_probability,
                                          double clutter_density_per_m);

/// Where a state vector holds the sender's position and the emission offset b (m).
struct PathStateLayout {
  /// The position's columns 0 .. position_columns - 1: 2 (x, y; planar) or 3.
  int position_columns = 3;
  /// The column of b.
  int offset_column = 3;
};

/// One path of a microphone paired with one of its stamps.
struct AssociatedPath {
  PredictedPath path;
  int path_index = 0;               ///< among the microphone's predicted paths
  int stamp = 0;                    ///< index into the microphone's stamps
  double innovation_var_m2 = 0.0;   ///< s = h P h^T + sigma^2 (m^2)
  Eigen::RowVectorXd h;             ///< d prediction / d state: d_sender on the position, 1 on b
};

/// One microphone's association at a state: its predicted paths (PredictPaths), each path's
/// innovation variance from the state covariance, and the pairs of AssociatePaths. Shared by the
/// filters' update and their start from all stamps (multipath_fix.h).
/// @param reflectors, sender_m, mic_m, offset_m, echo_order   as PredictPaths
/// @param stamps_m               the microphone's stamps (m)
/// @param P                      the state covariance (m^2), layout as `layout`
/// @param range_var_m2           one stamp's variance (m^2)
/// @param unpaired_paths         if given, gains the number of predicted paths left without a stamp
std::vector<AssociatedPath> AssociateMicrophone(std::span<const geometry::Reflector3> reflectors, const Vec3& sender_m,
                                                const Vec3& mic_m, double offset_m, int echo_order,
                                                std::span<const double> stamps_m, const Eigen::MatrixXd& P,
                                                const PathStateLayout& layout, double range_var_m2,
                                                double detection_probability, double clutter_density_per_m,
                                                int* unpaired_paths = nullptr);

}  // namespace mirage::methods::acoustic
