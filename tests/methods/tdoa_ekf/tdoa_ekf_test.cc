// SPDX-License-Identifier: MIT
// The TDOA filter's behaviour: the assembled H (rows at other times than the state's included)
// against central differences, the baseline bound, a gross row (the plain EKF jumps, the gate and
// the robust update do not), a wrong prediction (the gate locks it out, the robust update lets
// the rows outvote it), the robust update's window (deferred epochs), and self-initialisation.
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/methods/tdoa_ekf/tdoa_ekf.h"

namespace mirage::methods::tdoa_ekf {
namespace {

// 8 anchors of a 7 m x 7 m room, alternately low and high (as examples/uwb_tdoa_3d.yaml).
World RoomWorld() {
  World world;
  world.anchors = {{"A0", Vec3(0.3, 0.3, 0.2)}, {"A1", Vec3(3.5, 0.2, 2.5)}, {"A2", Vec3(6.7, 0.3, 0.2)},
                   {"A3", Vec3(6.8, 3.5, 2.5)}, {"A4", Vec3(6.7, 6.7, 0.2)}, {"A5", Vec3(3.5, 6.8, 2.5)},
                   {"A6", Vec3(0.3, 6.7, 0.2)}, {"A7", Vec3(0.2, 3.5, 2.5)}};
  world.agents = {"tag"};
  return world;
}

const Vec3 kTag(2.5, 4.0, 1.2);

core::TdoaMeasurement Row(const World& world, double t_s, int i, int j, const Vec3& tag_m, double error_m = 0.0) {
  core::TdoaMeasurement m;
  m.t_s = t_s;
  m.index_i = i;
  m.index_j = j;
  m.id_i = world.anchors[static_cast<std::size_t>(i)].id;
  m.id_j = world.anchors[static_cast<std::size_t>(j)].id;
  m.tdoa_m = (tag_m - world.anchors[static_cast<std::size_t>(j)].position_m).norm() -
             (tag_m - world.anchors[static_cast<std::size_t>(i)].position_m).norm() + error_m;
  return m;
}

// One epoch per 5 ms slot with one random pair, noise sigma_m, the tag at rest at tag_m.
std::vector<core::Epoch> StaticEpochs(const World& world, double t0_s, int count, const Vec3& tag_m, double sigma_m,
                                      core::Rng& rng) {
  std::vector<core::Epoch> epochs;
  const int n = static_cast<int>(world.anchors.size());
  for (int k = 0; k < count; ++k) {
    core::Epoch epoch;
    epoch.t_s = t0_s + 0.005 * k;
    const int i = static_cast<int>(rng.Uniform(0.0, n - 1e-9));
    int j = static_cast<int>(rng.Uniform(0.0, n - 1 - 1e-9));
    if (j >= i) ++j;
    epoch.tdoas.push_back(Row(world, epoch.t_s, i, j, tag_m, rng.Normal(0.0, sigma_m)));
    epochs.push_back(epoch);
  }
  return epochs;
}

Vec3 RunAll(TdoaEkf& filter, const std::vector<core::Epoch>& epochs) {
  Vec3 last = Vec3::Zero();
  for (const auto& epoch : epochs) last = filter.Process(epoch).agents.front().position_m;
  return last;
}

TEST(TdoaEkf, AssembledJacobianMatchesCentralDifferencesAlsoForRowsAtOtherTimes) {
  const World world = RoomWorld();
  TdoaEkf filter(TdoaEkfOptions{}, world);
  filter.Initialize({1.0, {kTag}});
  // A state with a velocity, so that the rows at other times than the state's see it.
  Eigen::VectorXd mean = filter.state().mean();
  mean.tail<3>() = Vec3(0.8, -0.5, 0.3);
  const estimation::State state(filter.state().layout(), mean, filter.state().covariance(), 1.0);
  const std::vector<core::TdoaMeasurement> rows = {Row(world, 0.95, 0, 3, kTag), Row(world, 1.0, 2, 7, kTag),
                                                   Row(world, 1.04, 5, 1, kTag), Row(world, 1.1, 6, 4, kTag)};
  const TdoaEkf::Stack stack = filter.Linearize(state, rows);
  ASSERT_EQ(stack.H.rows(), 4);
  ASSERT_EQ(stack.H.cols(), 6);
  // The prediction of row r is z - innovation; perturb every state coordinate.
  const auto predict = [&](const Eigen::VectorXd& x) {
    const estimation::State s(state.layout(), x, state.covariance(), state.t_s());
    const TdoaEkf::Stack at = filter.Linearize(s, rows);
    Eigen::VectorXd z(4);
    for (int r = 0; r < 4; ++r) z(r) = rows[static_cast<std::size_t>(r)].tdoa_m - at.innovation_m(r);
    return z;
  };
  const double step = 1e-6;
  for (int c = 0; c < 6; ++c) {
    Eigen::VectorXd plus = mean, minus = mean;
    plus(c) += step;
    minus(c) -= step;
    const Eigen::VectorXd numeric = (predict(plus) - predict(minus)) / (2.0 * step);
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(stack.H(r, c), numeric(r), 1e-7) << "row " << r << " column " << c;
  }
  // The row at the state's own time has no velocity entries; the others do.
  EXPECT_EQ(stack.H.row(1).tail<3>().norm(), 0.0);
  EXPECT_GT(stack.H.row(0).tail<3>().norm(), 0.0);
}

TEST(TdoaEkf, BaselineBoundDropsImpossibleDifferencesUnlessSwitchedOff) {
  const World world = RoomWorld();
  const double baseline_m = (world.anchors[0].position_m - world.anchors[4].position_m).norm();
  const std::vector<core::TdoaMeasurement> rows = {Row(world, 0.0, 0, 4, kTag),
                                                   Row(world, 0.0, 0, 4, kTag, baseline_m + 1.0 - Row(world, 0.0, 0, 4, kTag).tdoa_m)};
  TdoaEkfOptions options;
  TdoaEkf bounded(options, world);
  bounded.Initialize({0.0, {kTag}});
  const TdoaEkf::Stack kept = bounded.Linearize(bounded.state(), rows);
  EXPECT_EQ(kept.H.rows(), 1);
  EXPECT_EQ(kept.out_of_bound, 1);
  options.baseline_gate = false;
  TdoaEkf unbounded(options, world);
  unbounded.Initialize({0.0, {kTag}});
  EXPECT_EQ(unbounded.Linearize(unbounded.state(), rows).H.rows(), 2);
}

// A converged filter, then one row 5 m off (inside the room's largest baseline, so the bound
// keeps it): the plain EKF moves, the gate and the robust update hold.
Vec3 ErrorAfterGrossRow(const std::string& update) {
  const World world = RoomWorld();
  TdoaEkfOptions options;
  options.update = update;
  TdoaEkf filter(options, world);
  filter.Initialize({0.0, {kTag}});
  core::Rng rng(11);
  RunAll(filter, StaticEpochs(world, 0.005, 400, kTag, 0.15, rng));
  core::Epoch bad;
  bad.t_s = 2.005;
  bad.tdoas.push_back(Row(world, bad.t_s, 0, 4, kTag, -5.0));
  std::vector<core::Epoch> epochs = {bad};
  // The robust update needs its window: the row goes with its neighbours.
  for (const auto& e : StaticEpochs(world, 2.01, 25, kTag, 0.0, rng)) epochs.push_back(e);
  if (update != "rekf") epochs.resize(1);
  return RunAll(filter, epochs) - kTag;
}

TEST(TdoaEkf, AGrossRowMovesThePlainEkfButNotTheGatedOrRobustUpdate) {
  EXPECT_GT(ErrorAfterGrossRow("ekf").norm(), 0.05);
  EXPECT_LT(ErrorAfterGrossRow("gated_ekf").norm(), 0.05);
  EXPECT_LT(ErrorAfterGrossRow("rekf").norm(), 0.05);
}

// The filter is sure of a start 1 m off (sigma 2 cm): a gate rejects every row that would
// correct it; the robust update's rows outvote the prior rows of Eq. 5.26.
// After 0.5 s of rows (100 slots).
double ErrorFromAConfidentWrongStart(const std::string& update) {
  const World world = RoomWorld();
  TdoaEkfOptions options;
  options.update = update;
  options.initial_position_sigma_m = 0.02;
  options.initial_velocity_sigma_mps = 0.02;
  TdoaEkf filter(options, world);
  filter.Initialize({0.0, {kTag + Vec3(1.0, 0.0, 0.0)}});
  core::Rng rng(5);
  return (RunAll(filter, StaticEpochs(world, 0.005, 100, kTag, 0.15, rng)) - kTag).norm();
}

TEST(TdoaEkf, TheRobustUpdateRecoversFromAConfidentWrongPredictionThatLocksTheGateOut) {
  EXPECT_GT(ErrorFromAConfidentWrongStart("gated_ekf"), 0.5);
  EXPECT_LT(ErrorFromAConfidentWrongStart("rekf"), 0.1);
}

TEST(TdoaEkf, AllUpdatesConvergeOnCleanRows) {
  for (const std::string update : {"ekf", "gated_ekf", "rekf"}) {
    const World world = RoomWorld();
    TdoaEkfOptions options;
    options.update = update;
    TdoaEkf filter(options, world);
    filter.Initialize({0.0, {kTag + Vec3(0.3, -0.2, 0.2)}});
    core::Rng rng(3);
    EXPECT_LT((RunAll(filter, StaticEpochs(world, 0.005, 600, kTag, 0.15, rng)) - kTag).norm(), 0.05) << update;
  }
}

TEST(TdoaEkf, TheRobustUpdateDefersTheRowsOfItsWindow) {
  const World world = RoomWorld();
  TdoaEkfOptions options;
  options.window_s = 0.05;
  TdoaEkf filter(options, world);
  filter.Initialize({0.0, {kTag}});
  core::Rng rng(2);
  int deferred = 0, updates = 0;
  for (const auto& epoch : StaticEpochs(world, 0.005, 40, kTag, 0.15, rng)) {
    const StepOutput out = filter.Process(epoch);
    deferred += out.deferred ? 1 : 0;
    updates += out.deferred ? 0 : 1;
    if (!out.deferred) {
      EXPECT_GT(out.expected, 1);  // a window's rows, not one
    }
  }
  // 40 slots of 5 ms: a window closes when its rows span 50 ms, i.e. every 11 slots.
  EXPECT_EQ(updates, 3);
  EXPECT_EQ(deferred, 37);
}

TEST(TdoaEkf, StartsItselfFromTheDifferencesOfItsWindow) {
  const World world = RoomWorld();
  TdoaEkf filter(TdoaEkfOptions{}, world);
  core::Rng rng(9);
  const auto epochs = StaticEpochs(world, 0.0, 40, kTag, 0.05, rng);
  std::size_t k = 0;
  while (k < epochs.size() && !filter.InitializeFromEpoch(epochs[k])) ++k;
  ASSERT_LT(k, epochs.size());
  EXPECT_GE(k, 20u);  // a full window: rows spanning window_s (0.1 s, 21 slots of 5 ms)
  EXPECT_LT((filter.state().mean().head<3>() - kTag).norm(), 0.3);
  for (++k; k < epochs.size(); ++k) filter.Process(epochs[k]);
  EXPECT_LT((filter.state().mean().head<3>() - kTag).norm(), 0.1);
}

// Anchors on one ceiling (z = 2.5 m) see the tag and its mirror above them equally well; the
// noisy rows of one window must start the filter at the tag, below, for every seed.
TEST(TdoaEkf, StartsItselfBelowCoplanarCeilingAnchors) {
  World world;
  world.anchors = {{"C0", Vec3(0.3, 0.3, 2.5)}, {"C1", Vec3(6.7, 0.3, 2.5)}, {"C2", Vec3(6.7, 6.7, 2.5)},
                   {"C3", Vec3(0.3, 6.7, 2.5)}, {"C4", Vec3(3.5, 0.2, 2.5)}, {"C5", Vec3(3.5, 6.8, 2.5)}};
  world.agents = {"tag"};
  const Vec3 tag(2.0, 4.5, 1.2);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE(seed);
    TdoaEkf filter(TdoaEkfOptions{}, world);
    core::Rng rng(seed);
    bool started = false;
    for (const auto& epoch : StaticEpochs(world, 0.0, 200, tag, 0.15, rng)) {
      if ((started = filter.InitializeFromEpoch(epoch))) break;
    }
    ASSERT_TRUE(started);
    const Vec3 error_m = filter.state().mean().head<3>() - tag;
    const Eigen::Matrix3d P = filter.state().covariance().topLeftCorner<3, 3>();
    // Below the anchors, and where its own covariance says (the height is the weak direction
    // under a ceiling: a metre of sigma from 21 rows).
    EXPECT_LT(filter.state().mean()(2), 2.5);
    EXPECT_LT(error_m.dot(P.ldlt().solve(error_m)), 16.0) << error_m.transpose() << " sigma " << P.diagonal().cwiseSqrt().transpose();
  }
}

TEST(TdoaEkf, RejectsInvalidOptionsAndTooFewAnchors) {
  World world = RoomWorld();
  TdoaEkfOptions options;
  options.update = "kalman";
  EXPECT_THROW(TdoaEkf(options, world), std::invalid_argument);
  world.anchors.resize(3);
  EXPECT_THROW(TdoaEkf(TdoaEkfOptions{}, world), std::invalid_argument);
}

}  // namespace
}  // namespace mirage::methods::tdoa_ekf
