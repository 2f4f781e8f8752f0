// SPDX-License-Identifier: MIT
#include "mirage/methods/acoustic/path_association.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

#include "mirage/estimation/meas/toa.h"

namespace mirage::methods::acoustic {

std::vector<PredictedPath> PredictPaths(std::span<const geometry::Reflector3> reflectors, const Vec3& sender_m,
                                        const Vec3& mic_m, double offset_m, int echo_order) {
  std::vector<PredictedPath> out;
  const auto direct = estimation::PredictToa(sender_m, mic_m, offset_m);
  if (!direct) return out;
  out.push_back({.order = 0, .predicted_m = direct->predicted_m, .d_sender = direct->d_sender});
  if (echo_order < 1 || reflectors.empty()) return out;
  for (const auto& path : geometry::SpecularPaths3(reflectors, sender_m, mic_m, echo_order)) {
    if (path.surfaces.empty()) continue;  // the direct path, already in
    const Vec3 first_leg = sender_m - path.vertices_m[1];
    const double leg_m = first_leg.norm();
    if (!(leg_m > estimation::kMinToaRange_m)) continue;  // the sender on a reflector
    out.push_back({.order = static_cast<int>(path.surfaces.size()),
                   .predicted_m = path.length_m + offset_m,
                   .d_sender = first_leg / leg_m});
  }
  return out;
}

double AssociationGate(double innovation_var_m2, double detection_probability, double clutter_density_per_m) {
  assert(innovation_var_m2 > 0.0 && detection_probability > 0.0 && detection_probability <= 1.0);
  if (detection_probability >= 1.0 || clutter_density_per_m <= 0.0) return std::numeric_limits<double>::infinity();
  const double ratio = detection_probability /
                       ((1.0 - detection_probability) * clutter_density_per_m *
                        std::sqrt(2.0 * std::numbers::pi * innovation_var_m2));
  return 2.0 * std::log(ratio);
}

std::vector<PathStampPair> AssociatePaths(std::span<const double> predicted_m, std::span<const double> innovation_var_m2,
                                          std::span<const double> stamps_m, double detection_probability,
                                          double clutter_density_per_m) {
  assert(predicted_m.size() == innovation_var_m2.size());
  struct Candidate {
    double nis;
    int path;
    int stamp;
  };
  std::vector<Candidate> candidates;
  for (std::size_t j = 0; j < predicted_m.size(); ++j) {
    const double gate = AssociationGate(innovation_var_m2[j], detection_probability, clutter_density_per_m);
    for (std::size_t k = 0; k < stamps_m.size(); ++k) {
      const double nu = stamps_m[k] - predicted_m[j];
      const double nis = nu * nu / innovation_var_m2[j];
      if (nis < gate) candidates.push_back({nis, static_cast<int>(j), static_cast<int>(k)});
    }
  }
  // Stable: among equal distances the earlier path (the direct path first) and stamp win.
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.nis < b.nis; });
  std::vector<bool> path_taken(predicted_m.size(), false), stamp_taken(stamps_m.size(), false);
  std::vector<PathStampPair> out;
  for (const auto& c : candidates) {
    if (path_taken[static_cast<std::size_t>(c.path)] || stamp_taken[static_cast<std::size_t>(c.stamp)]) continue;
    path_taken[static_cast<std::size_t>(c.path)] = stamp_taken[static_cast<std::size_t>(c.stamp)] = true;
    out.push_back({c.path, c.stamp});
  }
  return out;
}

std::vector<AssociatedPath> AssociateMicrophone(std::span<const geometry::Reflector3> reflectors, const Vec3& sender_m,
                                                const Vec3& mic_m, double offset_m, int echo_order,
                                                std::span<const double> stamps_m, const Eigen::MatrixXd& P,
                                                const PathStateLayout& layout, double range_var_m2,
                                                double detection_probability, double clutter_density_per_m,
                                                int* unpaired_paths) {
  const auto paths = PredictPaths(reflectors, sender_m, mic_m, offset_m, echo_order);
  std::vector<double> predicted_m, s_m2;
  std::vector<Eigen::RowVectorXd> h;
  for (const auto& path : paths) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(P.rows());
    row.head(layout.position_columns) = path.d_sender.head(layout.position_columns).transpose();
    row(layout.offset_column) = 1.0;
    predicted_m.push_back(path.predicted_m);
    s_m2.push_back((row * P * row.transpose())(0, 0) + range_var_m2);
    h.push_back(std::move(row));
  }
  const auto pairs = AssociatePaths(predicted_m, s_m2, stamps_m, detection_probability, clutter_density_per_m);
  if (unpaired_paths != nullptr) *unpaired_paths += static_cast<int>(paths.size() - pairs.size());
  std::vector<AssociatedPath> out;
  out.reserve(pairs.size());
  for (const auto& pair : pairs) {
    const auto j = static_cast<std::size_t>(pair.path);
    out.push_back({paths[j], pair.path, pair.stamp, s_m2[j], std::move(h[j])});
  }
  return out;
}

}  // namespace mirage::methods::acoustic
