// SPDX-License-Identifier: MIT
#include "mirage/estimation/init/tdoa_position_fix.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <Eigen/Dense>

#include "mirage/estimation/meas/tdoa.h"
#include "mirage/estimation/robust/hampel.h"

namespace mirage::estimation {
namespace {

constexpr int kMaxIterations = 30;
constexpr double kStepTolerance_m = 1e-7;
constexpr double kInlierSigmas = 3.0;
constexpr int kMinInliers = 5;
constexpr int kMinAnchors = 4;
/// Smallest reciprocal condition number of the weighted normal matrix: below it the geometry
/// leaves a direction of p undetermined (coplanar anchors seen edge-on, all pairs sharing a
/// baseline direction).
constexpr double kMinReciprocalCondition = 1e-8;

struct Candidate {
  Vec3 position_m = Vec3::Zero();
  int inliers = 0;
  double inlier_cost = 0.0;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();  // J^T W J over the inliers, in 1 / sigma^2 units
};

// The anchors' best-fit plane: a point on it and its unit normal (pointing down, z <= 0).
struct Plane {
  Vec3 point_m = Vec3::Zero();
  Vec3 normal = -Vec3::UnitZ();
  [[nodiscard]] double Side(const Vec3& p_m) const { return (p_m - point_m).dot(normal); }  // > 0: below
};

// Robust Gauss-Newton from `start_m`: Hampel weights on the residuals in sigmas, with a = 1 and
// b = 4 fixed (the noise is known). With keep_side the search stays on the start's side of the
// anchors' plane: near the plane the height has almost no gradient and a full step can jump to
// the mirror image's side, which the other side's start explores. Returns the solution's inlier
// count and normal matrix.
std::optional<Candidate> Solve(std::span<const TdoaRow> rows, double sigma_m, const Vec3& start_m, const Plane& plane,
                               bool keep_side) {
  const double side = keep_side ? plane.Side(start_m) : 0.0;
  const HampelParameters hampel = HampelFromClippingPoint(1.0, 4.0);
  Vec3 p = start_m;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Vec3 g = Vec3::Zero();
    for (const auto& row : rows) {
      const auto pred = PredictTdoa(p, row.anchor_i_m, row.anchor_j_m);
      if (!pred) return std::nullopt;
      const double r = (row.tdoa_m - pred->predicted_m) / sigma_m;
      // The first iterations run unweighted (least squares, w = 1): from a far start every
      // residual is large and the weights would reject all of them.
      const double w = iteration < 3 ? 1.0 : HampelWeight(r, hampel);
      const Vec3 J = pred->d_sender / sigma_m;
      A += w * J * J.transpose();
      g += w * J * r;
    }
    // Levenberg-style damping keeps the step finite where the weights leave A singular.
    Vec3 step = (A + 1e-9 * Eigen::Matrix3d::Identity()).ldlt().solve(g);
    if (!step.allFinite()) return std::nullopt;
    // Halve a step that would cross the plane (at most 50 times: then it is below 1e-15 of it).
    for (int halving = 0; halving < 50 && side != 0.0 && plane.Side(p + step) * side <= 0.0; ++halving) step *= 0.5;
    p += step;
    if (step.norm() < kStepTolerance_m) break;
  }
  Candidate c;
  c.position_m = p;
  for (const auto& row : rows) {
    const auto pred = PredictTdoa(p, row.anchor_i_m, row.anchor_j_m);
    if (!pred) return std::nullopt;
    const double r = (row.tdoa_m - pred->predicted_m) / sigma_m;
    if (std::abs(r) > kInlierSigmas) continue;
    ++c.inliers;
    c.inlier_cost += r * r;
    const Vec3 J = pred->d_sender / sigma_m;
    c.normal += J * J.transpose();
  }
  return c;
}

}  // namespace

std::optional<TdoaPositionFix> FixPositionFromTdoas(std::span<const TdoaRow> rows, double sigma_m) {
  if (!(sigma_m > 0.0) || rows.size() < static_cast<std::size_t>(kMinInliers)) return std::nullopt;
  std::vector<Vec3> anchors_m;
  std::set<int> seen;
  for (const auto& row : rows) {
    if (!row.anchor_i_m.allFinite() || !row.anchor_j_m.allFinite() || !std::isfinite(row.tdoa_m)) return std::nullopt;
    if (seen.insert(row.index_i).second) anchors_m.push_back(row.anchor_i_m);
    if (seen.insert(row.index_j).second) anchors_m.push_back(row.anchor_j_m);
  }
  if (anchors_m.size() < static_cast<std::size_t>(kMinAnchors)) return std::nullopt;
  Vec3 centroid_m = Vec3::Zero();
  for (const auto& a : anchors_m) centroid_m += a;
  centroid_m /= static_cast<double>(anchors_m.size());
  // Starts off the anchors' best-fit plane, below it first: in the plane the rows' gradients
  // have no component along its normal, so from starts in it (all of them when the anchors are
  // coplanar, e.g. on a ceiling) Gauss-Newton never leaves it. The distance is the anchors' RMS
  // spread about their centroid, the room's scale.
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& a : anchors_m) scatter += (a - centroid_m) * (a - centroid_m).transpose();
  Plane plane;
  plane.point_m = centroid_m;
  plane.normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
  if (plane.normal.z() > 0.0) plane.normal = -plane.normal;
  const Vec3& normal = plane.normal;
  const double spread_m = std::sqrt(scatter.trace() / static_cast<double>(anchors_m.size()));
  // The two off-plane starts keep their side; the others roam.
  std::vector<std::pair<Vec3, bool>> starts = {
      {centroid_m + spread_m * normal, true}, {centroid_m - spread_m * normal, true}, {centroid_m, false}};
  for (const auto& a : anchors_m) starts.emplace_back(0.5 * (a + centroid_m), false);

  std::optional<Candidate> best;
  for (const auto& [start, keep_side] : starts) {
    const auto c = Solve(rows, sigma_m, start, plane, keep_side);
    if (!c || !c->position_m.allFinite()) continue;
    // A later start replaces an earlier solution only with more inliers or a cost lower by more
    // than 1 (one unit of chi-square: significant evidence), so that of two equally good mirror
    // images about coplanar anchors the one below them, found first, stays.
    if (!best || c->inliers > best->inliers || (c->inliers == best->inliers && c->inlier_cost < best->inlier_cost - 1.0)) {
      best = c;
    }
  }
  // The mirror rule: the image of the solution in the anchors' plane explains the rows as well
  // when they are coplanar (exactly, for coplanar anchors), and Gauss-Newton near the plane,
  // where the height has almost no gradient, may stop on either side. Of the two, the one below
  // the plane is kept unless the other explains more rows or costs more than 1 less.
  if (best) {
    const double side_m = plane.Side(best->position_m);
    if (side_m < 0.0) {
      const auto mirror = Solve(rows, sigma_m, best->position_m - 2.0 * side_m * normal, plane, true);
      if (mirror && mirror->position_m.allFinite() && plane.Side(mirror->position_m) > 0.0 &&
          (mirror->inliers > best->inliers ||
           (mirror->inliers == best->inliers && mirror->inlier_cost <= best->inlier_cost + 1.0))) {
        best = mirror;
      }
    }
  }
  if (!best || best->inliers < kMinInliers || 2 * best->inliers < static_cast<int>(rows.size())) return std::nullopt;
  std::set<int> spanned;
  for (const auto& row : rows) {
    const auto pred = PredictTdoa(best->position_m, row.anchor_i_m, row.anchor_j_m);
    if (pred && std::abs(row.tdoa_m - pred->predicted_m) <= kInlierSigmas * sigma_m) {
      spanned.insert(row.index_i);
      spanned.insert(row.index_j);
    }
  }
  if (spanned.size() < static_cast<std::size_t>(kMinAnchors)) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(best->normal);
  const Eigen::Vector3d lambda = eigen.eigenvalues();
  if (!(lambda(0) > kMinReciprocalCondition * lambda(2))) return std::nullopt;
  TdoaPositionFix out;
  out.fix.position_m = best->position_m;
  out.fix.covariance_m2 = best->normal.inverse();  // the normal matrix is in 1 / sigma^2 units: this is in m^2
  out.fix.rms_m = sigma_m * std::sqrt(best->inlier_cost / best->inliers);
  out.inliers = best->inliers;
  out.anchors = static_cast<int>(spanned.size());
  return out;
}

}  // namespace mirage::estimation
