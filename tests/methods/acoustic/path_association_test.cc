// SPDX-License-Identifier: MIT
// The echo paths' predictions and their association with stamps: an order-1 echo is the direct
// path of the receiver mirrored in the surface, the derivative of any path's length by the sender
// is its first leg's direction (checked against finite differences for orders 0-2), the
// likelihood-ratio gate opens with P_d = 1 or no clutter and narrows as the clutter grows, and
// global nearest neighbour pairs each path and each stamp once.
#include "mirage/methods/acoustic/path_association.h"

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace mirage::methods::acoustic {
namespace {

std::vector<geometry::Reflector3> Room() { return geometry::ShoeboxReflectors(8.0, 6.0, 3.0, 0.9); }

TEST(PredictPaths, AnOrderOneEchoIsTheDirectPathOfTheMirroredReceiver) {
  const auto room = Room();
  const Vec3 sender(2.0, 1.5, 1.1), mic(6.5, 4.0, 2.8);
  const double offset_m = 0.7;
  const auto paths = PredictPaths(room, sender, mic, offset_m, 1);
  ASSERT_GE(paths.size(), 5u);
  EXPECT_EQ(paths.front().order, 0);
  EXPECT_NEAR(paths.front().predicted_m, (sender - mic).norm() + offset_m, 1e-12);
  // The floor echo: the receiver mirrored at z = 0.
  const Vec3 floor_image(mic.x(), mic.y(), -mic.z());
  bool found = false;
  for (const auto& p : paths) {
    if (p.order == 1 && std::abs(p.predicted_m - ((sender - floor_image).norm() + offset_m)) < 1e-9) found = true;
  }
  EXPECT_TRUE(found);
  // Without reflectors or with echo_order 0: the direct path only.
  EXPECT_EQ(PredictPaths({}, sender, mic, offset_m, 2).size(), 1u);
  EXPECT_EQ(PredictPaths(room, sender, mic, offset_m, 0).size(), 1u);
}

TEST(PredictPaths, TheSenderDerivativeMatchesFiniteDifferencesUpToOrderTwo) {
  const auto room = Room();
  const Vec3 sender(2.3, 1.7, 1.2), mic(5.5, 4.2, 2.8);
  const auto paths = PredictPaths(room, sender, mic, 0.0, 2);
  ASSERT_GT(paths.size(), 10u);
  const double h = 1e-6;
  int checked = 0;
  for (std::size_t j = 0; j < paths.size(); ++j) {
    Vec3 numeric;
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 plus = sender, minus = sender;
      plus(axis) += h;
      minus(axis) -= h;
      const auto p_plus = PredictPaths(room, plus, mic, 0.0, 2);
      const auto p_minus = PredictPaths(room, minus, mic, 0.0, 2);
      ASSERT_EQ(p_plus.size(), paths.size());  // no path appears or vanishes this close
      ASSERT_EQ(p_minus.size(), paths.size());
      numeric(axis) = (p_plus[j].predicted_m - p_minus[j].predicted_m) / (2.0 * h);
    }
    EXPECT_NEAR((numeric - paths[j].d_sender).norm(), 0.0, 1e-6) << "path " << j << " of order " << paths[j].order;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(paths.size()));
}

TEST(AssociationGate, OpensWithoutClutterAndNarrowsAsClutterGrows) {
  EXPECT_TRUE(std::isinf(AssociationGate(0.01, 1.0, 1.0)));
  EXPECT_TRUE(std::isinf(AssociationGate(0.01, 0.9, 0.0)));
  // 2 ln(P_d / ((1 - P_d) lambda sqrt(2 pi s))).
  const double s = 0.04 * 0.04, pd = 0.9, lambda = 0.5;
  EXPECT_NEAR(AssociationGate(s, pd, lambda), 2.0 * std::log(pd / ((1.0 - pd) * lambda * std::sqrt(2.0 * M_PI * s))), 1e-12);
  EXPECT_LT(AssociationGate(s, pd, 2.0), AssociationGate(s, pd, 0.5));
  // So vague a prediction that any stamp is likelier clutter: nothing pairs.
  EXPECT_LT(AssociationGate(1e4, pd, lambda), 0.0);
}

TEST(AssociatePaths, PairsEachPathAndStampOnceByNearestNeighbour) {
  const std::vector<double> predicted{10.0, 10.5, 14.0};
  const std::vector<double> var(3, 0.05 * 0.05);
  // Stamp 1 is nearest to path 0 and to path 1; path 0 takes it (closer), path 1 takes stamp 2.
  const std::vector<double> stamps{9.0, 10.02, 10.56, 30.0};
  const auto pairs = AssociatePaths(predicted, var, stamps, 0.9, 0.2);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].path, 0);
  EXPECT_EQ(pairs[0].stamp, 1);
  EXPECT_EQ(pairs[1].path, 1);
  EXPECT_EQ(pairs[1].stamp, 2);
  // Path 2 has no stamp in its gate; with an open gate it takes the nearest remaining one.
  const auto open = AssociatePaths(predicted, var, stamps, 1.0, 0.2);
  ASSERT_EQ(open.size(), 3u);
  EXPECT_EQ(open[2].path, 2);
  EXPECT_EQ(open[2].stamp, 0);  // 9.0 is 5 m from 14, 30.0 is 16 m
}

// One microphone's association at a state: the innovation variance is h P h^T + sigma^2 with h the
// path's direction on the layout's position columns and 1 on its offset column (here a planar
// filter's [x, y, vx, vy, b] state), the pairs are those of AssociatePaths on the same numbers,
// and the predicted paths without a stamp are counted.
TEST(AssociateMicrophone, InnovationVarianceFollowsTheStateLayout) {
  const auto room = Room();
  const Vec3 sender(2.0, 1.5, 1.1), mic(6.5, 4.0, 2.8);
  const double offset_m = 0.7, range_var_m2 = 0.03 * 0.03;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(5, 5);
  P.diagonal() << 0.04, 0.09, 1.0, 1.0, 0.25;
  P(0, 4) = P(4, 0) = 0.01;
  const PathStateLayout layout{.position_columns = 2, .offset_column = 4};
  const auto paths = PredictPaths(room, sender, mic, offset_m, 1);
  // Stamps on the direct path and on the third path, 1 cm late.
  const std::vector<double> stamps{paths[0].predicted_m + 0.01, paths[2].predicted_m + 0.01};
  int unpaired = 0;
  const auto pairs = AssociateMicrophone(room, sender, mic, offset_m, 1, stamps, P, layout, range_var_m2, 0.9, 0.05,
                                         &unpaired);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(unpaired, static_cast<int>(paths.size()) - 2);
  for (const auto& a : pairs) {
    const Vec3& u = paths[static_cast<std::size_t>(a.path_index)].d_sender;
    const double expected = 0.04 * u.x() * u.x() + 0.09 * u.y() * u.y() + 0.25 + 2.0 * 0.01 * u.x() + range_var_m2;
    EXPECT_NEAR(a.innovation_var_m2, expected, 1e-12);
    ASSERT_EQ(a.h.size(), 5);
    EXPECT_DOUBLE_EQ(a.h(0), u.x());
    EXPECT_DOUBLE_EQ(a.h(1), u.y());
    EXPECT_EQ(a.h(2), 0.0);
    EXPECT_EQ(a.h(4), 1.0);
    EXPECT_NEAR(stamps[static_cast<std::size_t>(a.stamp)] - a.path.predicted_m, 0.01, 1e-12);
  }
  EXPECT_TRUE((pairs[0].path_index == 0 && pairs[1].path_index == 2) ||
              (pairs[0].path_index == 2 && pairs[1].path_index == 0));
}

}  // namespace
}  // namespace mirage::methods::acoustic
