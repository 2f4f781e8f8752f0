// SPDX-License-Identifier: MIT
#include "mirage/eval/dop.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace mirage::eval {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A per-receiver vector holds one value for all receivers or one per receiver.
bool SizeFits(std::size_t size, std::size_t receivers) { return size == 1 || size == receivers; }

double PerReceiver(const std::vector<double>& values, std::size_t i) {
  return values.size() == 1 ? values.front() : values[i];
}

bool SigmasValid(const std::vector<double>& sigmas) {
  for (const double s : sigmas) {
    if (!(s > 0.0 && std::isfinite(s))) return false;
  }
  return true;
}

bool InputValid(const DopInput& in) {
  const std::size_t n = in.receivers_m.size();
  if (in.sigma_m.empty() || (n > 0 && !SizeFits(in.sigma_m.size(), n)) || !SigmasValid(in.sigma_m)) return false;
  const bool any_echo = !in.ground_echo.empty();
  if (any_echo && (in.ground_echo.size() != n || in.ground_sigma_m.empty() ||
                   !SizeFits(in.ground_sigma_m.size(), n) || !SigmasValid(in.ground_sigma_m))) {
    return false;
  }
  if (!in.los.empty() && in.los.size() != n) return false;
  return in.min_eigen_ratio > 0.0 && in.min_eigen_ratio < 1.0 && std::isfinite(in.floor_z_m);
}

DopResult Degenerate(double sigma_n_m, int rows) {
  DopResult r;
  r.dop_3d = r.hdop = r.vdop = kInf;
  r.position_crlb_m2.setConstant(kInf);
  r.degenerate = true;
  r.sigma_n_m = sigma_n_m;
  r.rows = rows;
  return r;
}

}  // namespace

RangeRows BuildRangeRows(const DopInput& input) {
  const std::size_t n = input.receivers_m.size();
  std::vector<Vec3> points;
  std::vector<double> sigmas;
  for (std::size_t i = 0; i < n; ++i) {
    if (!input.los.empty() && !input.los[i]) continue;
    points.push_back(input.receivers_m[i]);
    sigmas.push_back(PerReceiver(input.sigma_m, i));
  }
  for (std::size_t i = 0; i < input.ground_echo.size() && i < n; ++i) {
    if (!input.ground_echo[i]) continue;
    const Vec3& m = input.receivers_m[i];
    points.emplace_back(m.x(), m.y(), 2.0 * input.floor_z_m - m.z());
    sigmas.push_back(PerReceiver(input.ground_sigma_m, i));
  }
  RangeRows rows;
  const auto count = static_cast<Eigen::Index>(points.size());
  rows.J_range_sender.setZero(count, 3);
  rows.sigma_m.resize(count);
  rows.points_m.resize(count, 3);
  for (Eigen::Index k = 0; k < count; ++k) {
    const Vec3 d = input.sender_m - points[static_cast<std::size_t>(k)];
    const double range_m = d.norm();
    rows.points_m.row(k) = points[static_cast<std::size_t>(k)].transpose();
    rows.sigma_m(k) = sigmas[static_cast<std::size_t>(k)];
    // Eq. 8.15: u_k = (S - M_k) / R_k; undefined when the sender sits on the receiver.
    if (range_m > 0.0) {
      rows.J_range_sender.row(k) = (d / range_m).transpose();
    } else {
      rows.sender_on_receiver = true;
    }
  }
  return rows;
}

Eigen::MatrixXd FisherInformation(const DopInput& input) {
  const RangeRows rows = BuildRangeRows(input);
  const Eigen::Index n = rows.J_range_sender.rows();
  const Eigen::VectorXd variance_m2 = rows.sigma_m.array().square();
  switch (input.model) {
    case DopModel::kToa: {
      // Eq. 8.17: A = H^T R^-1 H with R diagonal (sigma_k^-2 once per row; typo item 10).
      return rows.J_range_sender.transpose() * variance_m2.cwiseInverse().asDiagonal() * rows.J_range_sender;
    }
    case DopModel::kPseudoRange: {
      // Eq. 8.60-8.62: m_k = |M_k - S| + d_0, columns [u, 1].
      Eigen::MatrixXd H(n, 4);
      H.leftCols(3) = rows.J_range_sender;
      H.col(3).setOnes();
      return H.transpose() * variance_m2.cwiseInverse().asDiagonal() * H;
    }
    case DopModel::kTdoa: {
      const Eigen::Index ref = input.tdoa_reference_row;
      if (n < 1 || ref < 0 || ref >= n) return {};
      // Eq. 8.54: D = [-1 | I] with the -1 column at the reference row; R_TD = D R D^T (8.55).
      Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n - 1, n);
      for (Eigen::Index k = 0, r = 0; k < n; ++k) {
        if (k == ref) continue;
        D(r, k) = 1.0;
        D(r, ref) = -1.0;
        ++r;
      }
      if (n == 1) return Eigen::Matrix3d::Zero();
      const Eigen::MatrixXd H = D * rows.J_range_sender;
      const Eigen::MatrixXd R = D * variance_m2.asDiagonal() * D.transpose();
      // R is positive definite for positive sigmas (D has full row rank).
      return H.transpose() * R.llt().solve(H);  // Eq. 8.56
    }
  }
  return {};
}

DopResult ComputeDop(const DopInput& input) {
  if (!InputValid(input)) return Degenerate(input.sigma_n_m, 0);
  const double sigma_n_m = input.sigma_n_m > 0.0 ? input.sigma_n_m : input.sigma_m.front();
  const RangeRows rows = BuildRangeRows(input);
  const int row_count = static_cast<int>(rows.J_range_sender.rows());
  if (rows.sender_on_receiver) return Degenerate(sigma_n_m, row_count);
  const Eigen::MatrixXd A = FisherInformation(input);
  if (A.rows() == 0) return Degenerate(sigma_n_m, row_count);

  // A is symmetric PSD: its small eigenvalues' eigenvectors are the unidentifiable directions.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
  const Eigen::MatrixXd& V = eig.eigenvectors();
  const double lambda_max = lambda(lambda.size() - 1);
  Eigen::MatrixXd pinv = Eigen::MatrixXd::Zero(A.rows(), A.cols());
  Eigen::Vector3d null_weight = Eigen::Vector3d::Zero();  // squared null components per coordinate
  bool degenerate = !(lambda_max > 0.0);
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    if (lambda_max > 0.0 && lambda(k) > input.min_eigen_ratio * lambda_max) {
      pinv += V.col(k) * V.col(k).transpose() / lambda(k);
    } else {
      degenerate = true;
      null_weight += V.col(k).head<3>().cwiseAbs2();
    }
  }

  DopResult result;
  result.degenerate = degenerate;
  result.sigma_n_m = sigma_n_m;
  result.rows = row_count;
  result.position_crlb_m2 = pinv.topLeftCorner<3, 3>();
  // A coordinate touched by a null direction has no finite bound. 1e-6: the null vectors are unit
  // vectors, so this is a 0.1 % component, far above rounding and far below a real coupling.
  std::array<bool, 3> unidentifiable{};
  for (int c = 0; c < 3; ++c) {
    unidentifiable[static_cast<std::size_t>(c)] = null_weight(c) > 1e-6;
    if (unidentifiable[static_cast<std::size_t>(c)]) {
      result.position_crlb_m2.row(c).setConstant(kInf);
      result.position_crlb_m2.col(c).setConstant(kInf);
    }
  }
  const Eigen::Matrix3d& P = result.position_crlb_m2;
  const double var_xy = P(0, 0) + P(1, 1);
  result.hdop = std::sqrt(var_xy) / sigma_n_m;
  result.vdop = std::sqrt(P(2, 2)) / sigma_n_m;
  result.dop_3d = std::sqrt(var_xy + P(2, 2)) / sigma_n_m;
  return result;
}

}  // namespace mirage::eval
