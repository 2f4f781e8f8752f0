// SPDX-License-Identifier: MIT
#include "mirage/eval/dop.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

namespace mirage::eval {
namespace {

double Deg(double deg) { return deg * std::numbers::pi / 180.0; }

/// Bordoy's Fig. 8.1 geometry as reconstructed here: the thesis gives only the heights (receivers
/// 2.5 m, target 1.5 m). Fitting the receivers' horizontal offsets to the six printed numbers
/// (Vol^2, sum Area^2, DOP_xy in both panels) gives, up to a rotation and reflection, horizontal
/// distances 6.0, 6.5 and 15.3 m at azimuths 0, 68 and 157 deg, the ground echo on the 6.0 m one.
/// The fit is unique up to those symmetries but its residual is ~0.5 % (the printed numbers are
/// rounded and not exactly consistent: 1.93 / 0.03 would give VDOP 8.02, not 8.57).
DopInput Fig81(bool with_ground_echo) {
  DopInput in;
  in.sender_m = Vec3(0.0, 0.0, 1.5);
  const double r[3] = {6.0, 6.5, 15.3};
  const double az[3] = {0.0, 68.0, 157.0};
  for (int i = 0; i < 3; ++i) {
    in.receivers_m.emplace_back(r[i] * std::cos(Deg(az[i])), r[i] * std::sin(Deg(az[i])), 2.5);
  }
  if (with_ground_echo) {
    in.los = {false, true, true};
    in.ground_echo = {true, false, false};
  }
  return in;
}

/// Squared parallelepiped volume and summed squared parallelogram areas of the xy projections of
/// the rows' unit vectors (Eq. 8.34-8.35), computed directly from geometry.
void VolumeAndAreas(const DopInput& in, double* vol2, double* area2) {
  const RangeRows rows = BuildRangeRows(in);
  const Eigen::MatrixXd& U = rows.J_range_sender;
  *vol2 = std::pow(Eigen::Matrix3d(U).determinant(), 2);
  *area2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) *area2 += std::pow(U(i, 0) * U(j, 1) - U(i, 1) * U(j, 0), 2);
  }
}

/// The 9-microphone layout: a 3 x 3 grid over 15 m x 11 m, ceiling heights 4.824-4.879 m.
std::vector<Vec3> NineMics() {
  const double heights[9] = {4.824, 4.879, 4.851, 4.866, 4.839, 4.872, 4.830, 4.858, 4.845};
  std::vector<Vec3> mics;
  for (int ix = 0; ix < 3; ++ix) {
    for (int iy = 0; iy < 3; ++iy) mics.emplace_back(7.5 * ix, 5.5 * iy, heights[3 * ix + iy]);
  }
  return mics;
}

/// A generic 3-D case with per-receiver sigmas and some echoes, for identities.
DopInput Generic() {
  DopInput in;
  in.sender_m = Vec3(2.3, 1.7, 1.1);
  in.receivers_m = {Vec3(0.0, 0.0, 2.9), Vec3(6.0, 0.5, 3.1), Vec3(5.0, 5.5, 2.6), Vec3(-0.5, 4.0, 3.3),
                    Vec3(3.0, -2.0, 2.8)};
  in.sigma_m = {0.01, 0.02, 0.015, 0.012, 0.03};
  in.ground_echo = {true, false, true, true, false};
  in.ground_sigma_m = {0.025, 0.04, 0.03, 0.05, 0.02};
  in.floor_z_m = 0.2;
  return in;
}

TEST(Dop, RangeRowsMatchCentralDifferencesOfLosAndEchoRanges) {
  const DopInput in = Generic();
  const RangeRows rows = BuildRangeRows(in);
  ASSERT_EQ(rows.J_range_sender.rows(), 5 + 3);
  // Echo row of receiver 0 is its mirror at the floor 0.2 m: z' = 0.4 - 2.9.
  EXPECT_NEAR(rows.points_m(5, 2), 0.4 - 2.9, 1e-15);
  EXPECT_NEAR(rows.sigma_m(5), 0.025, 1e-15);
  EXPECT_NEAR(rows.sigma_m(7), 0.05, 1e-15);
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < rows.J_range_sender.rows(); ++k) {
    const Vec3 point = rows.points_m.row(k).transpose();
    for (int c = 0; c < 3; ++c) {
      Vec3 plus = in.sender_m, minus = in.sender_m;
      plus(c) += h;
      minus(c) -= h;
      const double numeric = ((plus - point).norm() - (minus - point).norm()) / (2.0 * h);
      EXPECT_NEAR(rows.J_range_sender(k, c), numeric, 1e-8) << "row " << k << " col " << c;
    }
  }
}

TEST(Dop, ToaOnSixAxisReceiversIsHandComputed) {
  // u = +-e_x, +-e_y, +-e_z: A = 2 I / sigma^2, CRLB = sigma^2 / 2 I.
  DopInput in;
  in.sender_m = Vec3(1.0, 2.0, 3.0);
  for (int c = 0; c < 3; ++c) {
    for (const double s : {-2.0, 3.0}) {
      Vec3 m = in.sender_m;
      m(c) += s;
      in.receivers_m.push_back(m);
    }
  }
  in.sigma_m = {0.1};

  const DopResult r = ComputeDop(in);

  EXPECT_FALSE(r.degenerate);
  EXPECT_TRUE(r.position_crlb_m2.isApprox(0.005 * Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_NEAR(r.hdop, 1.0, 1e-12);
  EXPECT_NEAR(r.vdop, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(r.dop_3d, std::sqrt(1.5), 1e-12);
}

TEST(Dop, ReproducesFig81WithAndWithoutAGroundEcho) {
  double vol2 = 0.0, area2 = 0.0;

  const DopResult los = ComputeDop(Fig81(false));
  VolumeAndAreas(Fig81(false), &vol2, &area2);
  // Thesis (b): Vol^2 0.03, sum Area^2 1.93, VDOP 8.57, DOP_xy 2.02.
  EXPECT_NEAR(vol2, 0.03, 0.005);
  EXPECT_NEAR(area2, 1.93, 0.015);
  EXPECT_NEAR(los.vdop, 8.57, 0.015 * 8.57);
  EXPECT_NEAR(los.hdop, 2.02, 0.01 * 2.02);
  // Eq. 8.35 holds exactly for the matrix result.
  EXPECT_NEAR(los.vdop * los.vdop, area2 / vol2, 1e-9 * area2 / vol2);

  const DopResult echo = ComputeDop(Fig81(true));
  VolumeAndAreas(Fig81(true), &vol2, &area2);
  // Thesis (a): Vol^2 0.30, sum Area^2 1.67, VDOP 2.35, DOP_xy 1.48.
  EXPECT_NEAR(vol2, 0.30, 0.005);
  EXPECT_NEAR(area2, 1.67, 0.015);
  EXPECT_NEAR(echo.vdop, 2.35, 0.01 * 2.35);
  EXPECT_NEAR(echo.hdop, 1.48, 0.01 * 1.48);
  EXPECT_NEAR(echo.vdop * echo.vdop, area2 / vol2, 1e-9 * area2 / vol2);
}

TEST(Dop, VdopEqualsTheDeterminantRatioAndTheAreaSumWithPerRowSigmas) {
  // Eq. 8.23: sigma_n^2 VDOP^2 = det(A_12) / det(A); Eq. 8.30: det(A_12) = sum_{i<j} Area^2 s_i^-2 s_j^-2.
  const DopInput in = Generic();
  const Eigen::Matrix3d A = FisherInformation(in);
  const RangeRows rows = BuildRangeRows(in);
  double area_sum = 0.0;
  const Eigen::MatrixXd& U = rows.J_range_sender;
  for (Eigen::Index i = 0; i < U.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < U.rows(); ++j) {
      area_sum += std::pow(U(i, 0) * U(j, 1) - U(i, 1) * U(j, 0), 2) /
                  std::pow(rows.sigma_m(i) * rows.sigma_m(j), 2);
    }
  }
  const double det12 = A.topLeftCorner<2, 2>().determinant();

  const DopResult r = ComputeDop(in);

  EXPECT_NEAR(det12, area_sum, 1e-9 * area_sum);
  EXPECT_NEAR(r.sigma_n_m, 0.01, 0.0);
  const double lhs = std::pow(r.sigma_n_m * r.vdop, 2);
  EXPECT_NEAR(lhs, det12 / A.determinant(), 1e-9 * lhs);
  EXPECT_TRUE(r.position_crlb_m2.isApprox(A.inverse(), 1e-10));
}

TEST(Dop, SymmetricRingMatchesClosedFormsWithAndWithoutGroundEchoes) {
  // Eq. 8.42-8.44: sender at the centre of an even ring of equal-height receivers.
  const int n = 6;
  const double radius_m = 4.0, z_r = 4.84, s_z = 1.4, sigma_n = 0.02, sigma_r = 0.03;
  DopInput in;
  in.sender_m = Vec3(1.0, -2.0, s_z);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n + 0.3;
    in.receivers_m.push_back(in.sender_m + Vec3(radius_m * std::cos(a), radius_m * std::sin(a), z_r - s_z));
  }
  in.sigma_m = {sigma_n};
  const double r_los = std::hypot(radius_m, z_r - s_z);
  const double r_echo = std::hypot(radius_m, z_r + s_z);
  const double vdop_los = 1.0 / (std::abs(s_z - z_r) * std::sqrt(n / (r_los * r_los)));
  const double vdop_echo = 1.0 / std::sqrt(std::pow(s_z - z_r, 2) * n / (r_los * r_los) +
                                           std::pow(sigma_n / sigma_r, 2) * std::pow(s_z + z_r, 2) * n /
                                               (r_echo * r_echo));

  const DopResult los = ComputeDop(in);
  in.ground_echo.assign(n, true);
  in.ground_sigma_m = {sigma_r};
  const DopResult echo = ComputeDop(in);

  EXPECT_NEAR(los.vdop, vdop_los, 1e-12 * vdop_los);
  EXPECT_NEAR(echo.vdop, vdop_echo, 1e-12 * vdop_echo);
  // Eq. 8.44 with u*_z = (S_z - z_r) / R*, u'_z = (S_z + z_r) / R'.
  const double ratio = std::sqrt(1.0 + std::pow(sigma_n / sigma_r, 2) * std::pow((s_z + z_r) / r_echo, 2) /
                                           std::pow((s_z - z_r) / r_los, 2));
  EXPECT_NEAR(los.vdop / echo.vdop, ratio, 1e-12 * ratio);
  EXPECT_GT(ratio, 1.3);  // echoes help even with sigma_r = 1.5 sigma_n
}

TEST(Dop, TdoaDoesNotDependOnTheReferenceRow) {
  DopInput in = Generic();
  in.model = DopModel::kTdoa;
  in.tdoa_reference_row = 0;
  const DopResult first = ComputeDop(in);
  ASSERT_FALSE(first.degenerate);
  for (int ref = 1; ref < first.rows; ++ref) {
    in.tdoa_reference_row = ref;
    const DopResult r = ComputeDop(in);
    EXPECT_TRUE(r.position_crlb_m2.isApprox(first.position_crlb_m2, 1e-10)) << "reference " << ref;
  }
  // Differencing loses information: TDOA is never better than TOA with a known emission time.
  in.model = DopModel::kToa;
  EXPECT_LT(ComputeDop(in).dop_3d, first.dop_3d);
}

TEST(Dop, TdoaEqualsPseudoRangeForTheWholePositionBound) {
  // Shin & Sung, Eq. 8.59-8.67: eliminating d_0 equals differencing with R_TD = D R D^T.
  DopInput in = Generic();
  in.model = DopModel::kTdoa;
  in.tdoa_reference_row = 3;
  const DopResult tdoa = ComputeDop(in);
  in.model = DopModel::kPseudoRange;
  const DopResult pr = ComputeDop(in);

  EXPECT_TRUE(tdoa.position_crlb_m2.isApprox(pr.position_crlb_m2, 1e-10));
  EXPECT_NEAR(tdoa.vdop, pr.vdop, 1e-10 * pr.vdop);
  EXPECT_EQ(FisherInformation(in).rows(), 4);
}

TEST(Dop, TdoaAtOneHeightHasInfiniteVdopButFiniteHdopUnlessEchoesAreUsed) {
  // Eq. 8.57-8.58: receivers and sender at one height, LOS only: the z column of H is zero.
  DopInput in;
  in.sender_m = Vec3(3.0, 2.0, 2.5);
  in.receivers_m = {Vec3(0, 0, 2.5), Vec3(7, 0, 2.5), Vec3(7, 5, 2.5), Vec3(0, 5, 2.5)};
  in.sigma_m = {0.01};
  in.model = DopModel::kTdoa;

  const DopResult los = ComputeDop(in);

  EXPECT_TRUE(los.degenerate);
  EXPECT_TRUE(std::isinf(los.vdop));
  EXPECT_TRUE(std::isinf(los.dop_3d));
  ASSERT_TRUE(std::isfinite(los.hdop));
  // The x-y bound equals that of a 2-D TDOA problem (the z direction decouples exactly).
  DopInput planar = in;
  planar.model = DopModel::kPseudoRange;
  const Eigen::MatrixXd A4 = FisherInformation(planar);
  Eigen::Matrix3d A3;  // [x, y, d_0]
  const int keep[3] = {0, 1, 3};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) A3(i, j) = A4(keep[i], keep[j]);
  }
  const Eigen::Matrix3d P = A3.inverse();
  EXPECT_NEAR(los.hdop, std::sqrt(P(0, 0) + P(1, 1)) / 0.01, 1e-9 * los.hdop);
  EXPECT_TRUE(std::isinf(los.position_crlb_m2(2, 2)));

  in.ground_echo.assign(4, true);
  in.ground_sigma_m = {0.02};
  const DopResult echo = ComputeDop(in);
  EXPECT_FALSE(echo.degenerate);
  EXPECT_TRUE(std::isfinite(echo.vdop));
  EXPECT_LT(echo.vdop, 5.0);
}

TEST(Dop, ToaWithTheSenderAtReceiverHeightNeedsTheGroundEchoForHeight) {
  // Eq. 8.46-8.50: u*_z = 0, so LOS-only VDOP is infinite; the echoes' u'_z = 2 z_r / R' fix it.
  // The sender is at the rectangle's centre, so the echoes' sum u_x u_z and u_y u_z vanish too.
  DopInput in;
  in.sender_m = Vec3(3.5, 2.5, 2.5);
  in.receivers_m = {Vec3(0, 0, 2.5), Vec3(7, 0, 2.5), Vec3(7, 5, 2.5), Vec3(0, 5, 2.5)};
  in.sigma_m = {0.01};

  const DopResult los = ComputeDop(in);
  in.ground_echo.assign(4, true);
  in.ground_sigma_m = {0.01};
  const DopResult echo = ComputeDop(in);

  EXPECT_TRUE(los.degenerate);
  EXPECT_TRUE(std::isinf(los.vdop));
  EXPECT_TRUE(std::isfinite(los.hdop));
  EXPECT_FALSE(echo.degenerate);
  // z decouples from x-y, so VDOP = 1 / sqrt(A_zz) (in units of sigma_n = sigma_r).
  double a_zz = 0.0;
  for (const Vec3& m : in.receivers_m) {
    const Vec3 d = in.sender_m - Vec3(m.x(), m.y(), -m.z());
    a_zz += std::pow(d.z() / d.norm(), 2);
  }
  EXPECT_NEAR(echo.vdop, 1.0 / std::sqrt(a_zz), 1e-12);
}

TEST(Dop, GroundEchoesCutVdopForCeilingMicsInEveryModel) {
  // 9 ceiling mics (4.824-4.879 m), sender at 1.4 m, all echoes with sigma_r = sigma_n. Measured
  // at the centre / at (3, 2): TOA VDOP 0.65 -> 0.39 / 0.82 -> 0.43; TDOA and pseudo-range
  // 1.68 -> 0.39 / 3.35 -> 0.43. With echoes TDOA is nearly as good as TOA (Eq. 8.65-8.67).
  for (const Vec3& sender : {Vec3(7.5, 5.5, 1.4), Vec3(3.0, 2.0, 1.4)}) {
    double toa_echo_vdop = 0.0;
    for (const DopModel model : {DopModel::kToa, DopModel::kTdoa, DopModel::kPseudoRange}) {
      DopInput in;
      in.sender_m = sender;
      in.receivers_m = NineMics();
      in.sigma_m = {0.015};
      in.model = model;
      const DopResult los = ComputeDop(in);
      in.ground_echo.assign(9, true);
      in.ground_sigma_m = {0.015};
      const DopResult echo = ComputeDop(in);

      ASSERT_FALSE(los.degenerate);
      ASSERT_FALSE(echo.degenerate);
      const double factor = model == DopModel::kToa ? 0.7 : 0.3;
      EXPECT_LT(echo.vdop, factor * los.vdop) << "model " << static_cast<int>(model);
      EXPECT_LT(echo.hdop, los.hdop);
      if (model == DopModel::kToa) {
        toa_echo_vdop = echo.vdop;
      } else {
        EXPECT_NEAR(echo.vdop, toa_echo_vdop, 0.03 * toa_echo_vdop);
      }
    }
  }
}

TEST(Dop, ReportsDegenerateInsteadOfGarbage) {
  DopInput in;
  in.sender_m = Vec3(1, 1, 1);
  in.receivers_m = {Vec3(0, 0, 3), Vec3(4, 0, 3), Vec3(0, 4, 3)};
  in.model = DopModel::kPseudoRange;  // 3 rows, 4 unknowns
  EXPECT_TRUE(ComputeDop(in).degenerate);
  EXPECT_TRUE(std::isinf(ComputeDop(in).dop_3d));

  in.model = DopModel::kToa;
  EXPECT_FALSE(ComputeDop(in).degenerate);
  in.receivers_m[1] = in.sender_m;  // sender on a receiver
  EXPECT_TRUE(ComputeDop(in).degenerate);

  in.receivers_m[1] = Vec3(4, 0, 3);
  in.sigma_m = {0.1, 0.2};  // neither one nor one per receiver
  EXPECT_TRUE(ComputeDop(in).degenerate);
  in.sigma_m = {0.0};
  EXPECT_TRUE(ComputeDop(in).degenerate);

  in.sigma_m = {0.1};
  in.model = DopModel::kTdoa;
  in.tdoa_reference_row = 3;  // only rows 0..2
  EXPECT_TRUE(ComputeDop(in).degenerate);
  in.receivers_m.clear();
  EXPECT_TRUE(ComputeDop(in).degenerate);
}

}  // namespace
}  // namespace mirage::eval
