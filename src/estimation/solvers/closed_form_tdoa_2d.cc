// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/closed_form_tdoa_2d.h"

#include <cmath>
#include <utility>

namespace mirage::estimation {
namespace {

// |det [a_1; a_2]| below this fraction of |a_1| |a_2| (the sine of the angle between the two
// baselines) means the receivers' xy are collinear: x, y are then not linear in r_0.
constexpr double kMinBaselineSine = 1e-9;

}  // namespace

TdoaRoots2d SolveTdoa2d(const std::array<Vec3, 3>& receivers_m, const std::array<double, 2>& differences_m,
                        double sender_height_m) {
  TdoaRoots2d out;
  if (!receivers_m[0].allFinite() || !receivers_m[1].allFinite() || !receivers_m[2].allFinite() ||
      !std::isfinite(differences_m[0]) || !std::isfinite(differences_m[1]) || !std::isfinite(sender_height_m)) {
    out.status = SolverStatus::kInvalidInput;
    return out;
  }
  // Coordinates relative to M_0 in the plane: p = S_xy - M_0,xy, a_i = M_i,xy - M_0,xy,
  // h_i = z - z_i. Subtracting r_0^2 = |p|^2 + h_0^2 from r_i^2 = |p - a_i|^2 + h_i^2 and using
  // r_i = r_0 + d_i gives 2 a_i . p = g_i - 2 d_i r_0 with g_i = |a_i|^2 + h_i^2 - h_0^2 - d_i^2.
  const Vec3& m0 = receivers_m[0];
  const Vec2 a1 = (receivers_m[1] - m0).head<2>();
  const Vec2 a2 = (receivers_m[2] - m0).head<2>();
  const double det = a1.x() * a2.y() - a1.y() * a2.x();
  if (!(std::abs(det) > kMinBaselineSine * a1.norm() * a2.norm())) {
    out.status = SolverStatus::kCollinearReceivers;
    return out;
  }
  const double h0 = sender_height_m - m0.z();
  const double h1 = sender_height_m - receivers_m[1].z();
  const double h2 = sender_height_m - receivers_m[2].z();
  const double d1 = differences_m[0];
  const double d2 = differences_m[1];
  const double g1 = a1.squaredNorm() + h1 * h1 - h0 * h0 - d1 * d1;
  const double g2 = a2.squaredNorm() + h2 * h2 - h0 * h0 - d2 * d2;
  // [a_1; a_2]^-1 = [a2y -a1y; -a2x a1x] / det, applied to (g/2 - d r_0): p = u + v r_0.
  const auto solve = [&](double b1, double b2) {
    return Vec2((a2.y() * b1 - a1.y() * b2) / det, (-a2.x() * b1 + a1.x() * b2) / det);
  };
  const Vec2 u = solve(0.5 * g1, 0.5 * g2);
  const Vec2 v = solve(-d1, -d2);
  // |u + v r_0|^2 + h_0^2 = r_0^2  ->  qa r_0^2 + qb r_0 + qc = 0.
  const double qa = v.squaredNorm() - 1.0;
  const double qb = 2.0 * u.dot(v);
  const double qc = u.squaredNorm() + h0 * h0;
  std::array<double, 2> roots{};
  int n_roots = 0;
  if (qa == 0.0) {
    // |v| = 1 exactly: the sender direction is along an asymptote; one (linear) root.
    if (qb != 0.0) roots[n_roots++] = -qc / qb;
  } else {
    double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0 && disc > -1e-12 * (qb * qb + std::abs(4.0 * qa * qc))) disc = 0.0;
    if (disc >= 0.0) {
      // Stable pair: q = -(qb + sign(qb) sqrt(disc)) / 2, roots q / qa and qc / q (no
      // cancellation when |qa| is small and one root is far away).
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      roots[n_roots++] = q / qa;
      if (disc > 0.0 && q != 0.0) roots[n_roots++] = qc / q;
    }
  }
  if (n_roots == 2 && roots[1] < roots[0]) std::swap(roots[0], roots[1]);
  for (int k = 0; k < n_roots; ++k) {
    const double r0 = roots[static_cast<std::size_t>(k)];
    if (!(r0 >= 0.0 && r0 + d1 >= 0.0 && r0 + d2 >= 0.0)) continue;
    const Vec2 p = u + v * r0;
    const auto slot = static_cast<std::size_t>(out.count++);
    out.positions_m[slot] = Vec3(m0.x() + p.x(), m0.y() + p.y(), sender_height_m);
    out.reference_range_m[slot] = r0;
  }
  out.status = out.count > 0 ? SolverStatus::kOk : SolverStatus::kNoAdmissibleRoot;
  return out;
}

TdoaRoots2d SolveTdoa2dFromPseudoRanges(const std::array<Vec3, 3>& receivers_m,
                                        const std::array<double, 3>& pseudo_ranges_m, double sender_height_m) {
  return SolveTdoa2d(receivers_m, {pseudo_ranges_m[1] - pseudo_ranges_m[0], pseudo_ranges_m[2] - pseudo_ranges_m[0]},
                     sender_height_m);
}

}  // namespace mirage::estimation
