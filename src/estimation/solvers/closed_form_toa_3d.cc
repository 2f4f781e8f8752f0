// SPDX-License-Identifier: MIT
#include "mirage/estimation/solvers/closed_form_toa_3d.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Dense>

#include "mirage/estimation/solvers/linear_toa.h"
#include "mirage/estimation/solvers/toa_nlls.h"

namespace mirage::estimation {
namespace {

bool Valid(std::span<const Vec3> receivers_m, std::span<const double> values_m) {
  if (values_m.size() != receivers_m.size()) return false;
  for (std::size_t i = 0; i < receivers_m.size(); ++i) {
    if (!receivers_m[i].allFinite() || !std::isfinite(values_m[i])) return false;
  }
  return true;
}

// The receivers' centroid, scatter and its eigenvalues (decreasing); the principal axes (columns,
// by decreasing spread) only for coplanar receivers, where they are needed (the eigenvectors are
// a fifth of a fix's cost).
struct Layout {
  Vec3 centre = Vec3::Zero();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  Vec3 variance = Vec3::Zero();  // decreasing

  [[nodiscard]] Eigen::Matrix3d Axes() const {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(scatter);  // closed-form 3 x 3; increasing eigenvalues
    Eigen::Matrix3d axes;
    for (int k = 0; k < 3; ++k) axes.col(k) = eig.eigenvectors().col(2 - k);
    return axes;
  }
};

Layout Analyse(std::span<const Vec3> receivers_m) {
  Layout layout;
  for (const Vec3& m : receivers_m) layout.centre += m;
  layout.centre /= static_cast<double>(receivers_m.size());
  for (const Vec3& m : receivers_m) layout.scatter += (m - layout.centre) * (m - layout.centre).transpose();
  layout.scatter /= static_cast<double>(receivers_m.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(layout.scatter, Eigen::EigenvaluesOnly);
  for (int k = 0; k < 3; ++k) layout.variance(k) = std::max(eig.eigenvalues()(2 - k), 0.0);
  return layout;
}

// Root bookkeeping: assess a candidate in world coordinates and keep it when admissible.
class Roots {
 public:
  Roots(std::span<const Vec3> receivers_m, std::span<const double> values_m, bool with_offset)
      : receivers_m_(receivers_m), values_m_(values_m), with_offset_(with_offset) {}

  // least_squares: the fix of an overdetermined LS (not an exact root), whose noise may leave a
  // range slightly negative for a sender next to a receiver: allowed 3 rms more.
  void Add(const Vec3& position_m, double offset_m, SolverStatus root_status, bool least_squares = false) {
    if (out_.count >= 2) return;
    // Causality (Eq. 5.4): every range rho_i - b must be >= 0, within the noise allowance.
    // The LS fits the squared rows, blind to the sign of rho_i - b: its noise allowance is 3 rms
    // of the sign-blind residuals |rho_i - b| - |S - M_i|.
    double max_value = 0.0;
    double sum_blind2 = 0.0;
    for (std::size_t i = 0; i < values_m_.size(); ++i) {
      max_value = std::max(max_value, std::abs(values_m_[i]));
      const double blind = std::abs(values_m_[i] - offset_m) - (position_m - receivers_m_[i]).norm();
      sum_blind2 += blind * blind;
    }
    const double blind_rms = std::sqrt(sum_blind2 / static_cast<double>(values_m_.size()));
    const double allowance = (least_squares ? 3.0 * blind_rms : 0.0) + 1e-9 * (1.0 + max_value);
    for (const double v : values_m_) {
      if (v - offset_m < -allowance) return;
    }
    // Assessed only when admissible (the covariance is most of a fix's cost).
    NllsProblem problem;
    problem.model = with_offset_ ? RowModel::kToa : RowModel::kRange;
    problem.receivers_m = receivers_m_;
    problem.values_m = values_m_;
    SolverFix fix = AssessFix(problem, position_m, offset_m, std::nullopt);
    if (fix.status == SolverStatus::kInvalidInput) return;
    if (fix.status == SolverStatus::kOk) fix.status = root_status;
    fix.converged = true;
    out_.fixes[static_cast<std::size_t>(out_.count++)] = fix;
  }

  ToaRoots3d Finish(SolverStatus ok_status) {
    if (out_.count == 2) {
      const SolverFix& a = out_.fixes[0];
      const SolverFix& b = out_.fixes[1];
      const double tie = 1e-9 * (1.0 + std::max(a.rms_m, b.rms_m));
      const bool swap = std::abs(a.rms_m - b.rms_m) > tie ? b.rms_m < a.rms_m : b.position_m.z() < a.position_m.z();
      if (swap) std::swap(out_.fixes[0], out_.fixes[1]);
    }
    out_.status = out_.count > 0 ? ok_status : SolverStatus::kNoAdmissibleRoot;
    return out_;
  }

 private:
  std::span<const Vec3> receivers_m_;
  std::span<const double> values_m_;
  bool with_offset_;
  ToaRoots3d out_;
};

ToaRoots3d WithStatus(SolverStatus status) {
  ToaRoots3d out;
  out.status = status;
  return out;
}

// Coplanar receivers: in-plane position (and b) from the linear solver in the plane's frame
// (receivers at height 0 exactly, known height 0: the true height only moves lambda), then the
// height from the mean squared row.
ToaRoots3d SolveCoplanar(std::span<const Vec3> receivers_m, std::span<const double> values_m, bool with_offset,
                         const Layout& layout) {
  const std::size_t n = receivers_m.size();
  const Eigen::Matrix3d axes = layout.Axes();
  std::vector<Vec3> in_plane(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = receivers_m[i] - layout.centre;
    in_plane[i] = Vec3(axes.col(0).dot(d), axes.col(1).dot(d), 0.0);
  }
  const SolverFix planar = with_offset ? SolveLinearToa(in_plane, values_m, {}, 0.0)
                                       : SolveLinearRanges(in_plane, values_m, {}, 0.0);
  if (!planar.converged) return WithStatus(planar.status);
  const Vec2 s = planar.position_m.head<2>();
  const double b = planar.offset_m;
  double h2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = values_m[i] - b;
    h2 += r * r - (s - in_plane[i].head<2>()).squaredNorm();
  }
  h2 /= static_cast<double>(n);
  const double h = std::sqrt(std::max(h2, 0.0));
  const Vec3 foot = layout.centre + axes.col(0) * s.x() + axes.col(1) * s.y();
  const Vec3 normal = axes.col(2);
  Roots roots(receivers_m, values_m, with_offset);
  roots.Add(foot + h * normal, b, SolverStatus::kCoplanarHeightMirror);
  if (h > 0.0) roots.Add(foot - h * normal, b, SolverStatus::kCoplanarHeightMirror);
  return roots.Finish(SolverStatus::kCoplanarHeightMirror);
}

// Pseudo-ranges, receivers not coplanar: S = u + w b from the mean-differenced squared rows, and
// the quadratic in b from the mean squared row (coordinates centred at the receivers' centroid,
// b at the mean pseudo-range).
ToaRoots3d SolveQuadraticInOffset(std::span<const Vec3> receivers_m, std::span<const double> values_m,
                                  const Layout& layout) {
  const auto n = static_cast<double>(receivers_m.size());
  double mean_value = 0.0;
  for (const double v : values_m) mean_value += v;
  mean_value /= n;
  double mean_m2 = 0.0;
  double mean_v2 = 0.0;
  for (std::size_t i = 0; i < receivers_m.size(); ++i) {
    mean_m2 += (receivers_m[i] - layout.centre).squaredNorm();
    mean_v2 += (values_m[i] - mean_value) * (values_m[i] - mean_value);
  }
  mean_m2 /= n;
  mean_v2 /= n;
  // Rows: 2 m_i . S' - 2 v_i b' = (|m_i|^2 - mean |m|^2) - (v_i^2 - mean v^2).
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 y_u = Vec3::Zero();
  Vec3 y_w = Vec3::Zero();
  for (std::size_t i = 0; i < receivers_m.size(); ++i) {
    const Vec3 m = receivers_m[i] - layout.centre;
    const double v = values_m[i] - mean_value;
    const Vec3 a = 2.0 * m;
    A += a * a.transpose();
    y_u += a * ((m.squaredNorm() - mean_m2) - (v * v - mean_v2));
    y_w += a * (2.0 * v);
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);  // regular: the receivers are not coplanar
  const Vec3 u = ldlt.solve(y_u);
  const Vec3 w = ldlt.solve(y_w);
  // mean_i [(v_i - b')^2 - |S' - m_i|^2] = 0 with S' = u + w b' (sum of m_i and v_i is zero).
  const double qa = 1.0 - w.squaredNorm();
  const double qb = -2.0 * u.dot(w);
  const double qc = mean_v2 - mean_m2 - u.squaredNorm();
  std::array<double, 2> offsets{};
  int count = 0;
  if (qa == 0.0) {
    if (qb != 0.0) offsets[static_cast<std::size_t>(count++)] = -qc / qb;
  } else {
    double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0 && disc > -1e-12 * (qb * qb + std::abs(4.0 * qa * qc))) disc = 0.0;
    if (disc >= 0.0) {
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      offsets[static_cast<std::size_t>(count++)] = q / qa;
      if (disc > 0.0 && q != 0.0) offsets[static_cast<std::size_t>(count++)] = qc / q;
    }
  }
  Roots roots(receivers_m, values_m, true);
  for (int k = 0; k < count; ++k) {
    const double b = offsets[static_cast<std::size_t>(k)];
    roots.Add(layout.centre + u + w * b, mean_value + b, SolverStatus::kOk);
  }
  return roots.Finish(SolverStatus::kOk);
}

ToaRoots3d Solve(std::span<const Vec3> receivers_m, std::span<const double> values_m, bool with_offset,
                 const ClosedFormToaOptions& options) {
  if (!Valid(receivers_m, values_m) || !Validate(options).empty()) return WithStatus(SolverStatus::kInvalidInput);
  const std::size_t n = receivers_m.size();
  if (n < (with_offset ? 4u : 3u)) return WithStatus(SolverStatus::kTooFewRows);
  const Layout layout = Analyse(receivers_m);
  const double tol2 = options.coplanar_tolerance * options.coplanar_tolerance;
  if (!(layout.variance(1) > tol2 * layout.variance(0))) return WithStatus(SolverStatus::kCollinearReceivers);
  if (!(layout.variance(2) > tol2 * layout.variance(0))) {
    return SolveCoplanar(receivers_m, values_m, with_offset, layout);
  }
  if (!with_offset) {
    if (n < 4) return WithStatus(SolverStatus::kTooFewRows);
    const SolverFix fix = SolveLinearRanges(receivers_m, values_m, {}, std::nullopt);
    if (!fix.converged) return WithStatus(fix.status);
    Roots roots(receivers_m, values_m, false);
    roots.Add(fix.position_m, 0.0, SolverStatus::kOk, true);
    return roots.Finish(SolverStatus::kOk);
  }
  if (n >= 5) {
    const SolverFix fix = SolveLinearToa(receivers_m, values_m, {}, std::nullopt);
    if (fix.converged) {
      Roots roots(receivers_m, values_m, true);
      roots.Add(fix.position_m, fix.offset_m, SolverStatus::kOk, true);
      return roots.Finish(SolverStatus::kOk);
    }
    // b not separable linearly (e.g. a sender far outside the array): the quadratic still works.
  }
  return SolveQuadraticInOffset(receivers_m, values_m, layout);
}

}  // namespace

std::vector<std::string> Validate(const ClosedFormToaOptions& options) {
  std::vector<std::string> problems;
  if (!(options.coplanar_tolerance >= 0.0 && options.coplanar_tolerance < 1.0)) {
    problems.emplace_back("coplanar_tolerance must be in [0, 1)");
  }
  return problems;
}

ToaRoots3d SolveToa3dClosedForm(std::span<const Vec3> receivers_m, std::span<const double> pseudo_ranges_m,
                                const ClosedFormToaOptions& options) {
  return Solve(receivers_m, pseudo_ranges_m, true, options);
}

ToaRoots3d SolveRange3dClosedForm(std::span<const Vec3> receivers_m, std::span<const double> ranges_m,
                                  const ClosedFormToaOptions& options) {
  return Solve(receivers_m, ranges_m, false, options);
}

}  // namespace mirage::estimation
