// SPDX-License-Identifier: MIT
// The fix from all of one emission's stamps with the echo model: in a glass-walled room whose
// stamps are the direct paths and the echoes to order 2 (90 % detected, noise, clutter), with the
// direct paths of two microphones blocked so that their earliest stamps are echoes, the search over
// the whole room finds the sender and the emission offset, planar and in 3-D, at every sender
// position tried; with too few stamps it reports no fix.
#include "mirage/methods/acoustic/multipath_fix.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/core/rng.h"
#include "mirage/methods/acoustic/path_association.h"

namespace mirage::methods::acoustic {
namespace {

constexpr double kSigma_m = 0.034;  // 0.1 ms at 343 m/s
constexpr double kOffset_m = 1.7;   // b: the emission 1.7 m of sound before the stamps' reference

const std::vector<Vec3> kMics = {{0.5, 0.5, 2.8}, {4.0, 0.4, 2.8}, {7.5, 0.5, 2.8},
                                 {7.5, 5.5, 2.8}, {4.0, 5.6, 2.8}, {0.5, 5.5, 2.8}};

std::vector<geometry::Reflector3> Room() { return geometry::ShoeboxReflectors(8.0, 6.0, 3.0, 0.9); }

/// Per microphone the stamps of a sender at sender_m: every path to order 2 detected with
/// probability 0.9, Gaussian noise, two clutter stamps; microphones in `blocked` lose the direct path.
std::vector<std::vector<double>> Stamps(const Vec3& sender_m, const std::vector<int>& blocked, core::Rng& rng) {
  const auto room = Room();
  std::vector<std::vector<double>> stamps(kMics.size());
  for (std::size_t i = 0; i < kMics.size(); ++i) {
    for (const auto& path : PredictPaths(room, sender_m, kMics[i], kOffset_m, 2)) {
      const bool is_blocked = path.order == 0 && std::find(blocked.begin(), blocked.end(), static_cast<int>(i)) != blocked.end();
      if (is_blocked || rng.Uniform(0.0, 1.0) > 0.9) continue;
      stamps[i].push_back(path.predicted_m + rng.Normal(0.0, kSigma_m));
    }
    for (int k = 0; k < 2; ++k) stamps[i].push_back(kOffset_m + rng.Uniform(0.0, 30.0));
  }
  return stamps;
}

MultipathFixOptions Options() {
  MultipathFixOptions o;
  o.range_sigma_m = kSigma_m;
  o.echo_order = 2;
  o.detection_probability = 0.9;
  o.clutter_density_per_m = 2.0 / 30.0;
  return o;
}

TEST(FixFromAllStamps, FindsTheSenderWhoseEarliestStampsAreEchoesPlanarAndIn3d) {
  core::Rng rng(11);
  const std::vector<Vec3> senders = {{1.3, 1.2, 1.1}, {6.6, 1.4, 1.0}, {4.1, 3.0, 1.3}, {2.2, 4.7, 1.2}, {6.9, 4.9, 0.9}};
  const auto room = Room();
  for (const auto& sender : senders) {
    SCOPED_TRACE(testing::Message() << "sender " << sender.transpose());
    // The two microphones nearest the sender lose their direct paths (the body, a partition).
    std::vector<int> order(kMics.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return (kMics[a] - sender).norm() < (kMics[b] - sender).norm(); });
    const std::vector<int> blocked = {order[0], order[1]};
    const auto stamps = Stamps(sender, blocked, rng);
    // A blocked microphone's earliest stamp is an echo or clutter: a fix on the earliest stamps is wrong.
    int earliest_wrong = 0;
    for (const int i : blocked) {
      const auto& list = stamps[static_cast<std::size_t>(i)];
      const double direct_m = (kMics[static_cast<std::size_t>(i)] - sender).norm() + kOffset_m;
      earliest_wrong += std::abs(*std::min_element(list.begin(), list.end()) - direct_m) > 5.0 * kSigma_m ? 1 : 0;
    }
    EXPECT_GE(earliest_wrong, 1);

    MultipathSearchRegion planar;
    planar.lo_m = Vec3(0.0, 0.0, sender.z());
    planar.hi_m = Vec3(8.0, 6.0, sender.z());
    const MultipathFix fix2 = FixFromAllStamps(room, kMics, stamps, planar, Options());
    ASSERT_TRUE(fix2.found);
    EXPECT_LT((fix2.position_m - sender).norm(), 0.05);
    EXPECT_NEAR(fix2.offset_m, kOffset_m, 0.05);
    EXPECT_GE(fix2.explained_receivers, 6);

    MultipathSearchRegion volume;
    volume.lo_m = Vec3(0.0, 0.0, 0.0);
    volume.hi_m = Vec3(8.0, 6.0, 2.5);
    const MultipathFix fix3 = FixFromAllStamps(room, kMics, stamps, volume, Options());
    ASSERT_TRUE(fix3.found);
    EXPECT_LT((fix3.position_m - sender).norm(), 0.05);
    EXPECT_NEAR(fix3.offset_m, kOffset_m, 0.05);
    // The covariance is that of the rows used: centimetres, positive on the diagonal.
    for (int k = 0; k < 4; ++k) {
      EXPECT_GT(fix3.covariance(k, k), 0.0);
      EXPECT_LT(fix3.covariance(k, k), 0.05 * 0.05);
    }
  }
}

TEST(FixFromAllStamps, TooFewStampsGiveNoFix) {
  const auto room = Room();
  std::vector<std::vector<double>> stamps(kMics.size());
  const Vec3 sender(3.0, 2.0, 1.1);
  for (std::size_t i = 0; i < 2; ++i) stamps[i].push_back((kMics[i] - sender).norm() + kOffset_m);
  MultipathSearchRegion region;
  region.lo_m = Vec3(0.0, 0.0, 1.1);
  region.hi_m = Vec3(8.0, 6.0, 1.1);
  EXPECT_FALSE(FixFromAllStamps(room, kMics, stamps, region, Options()).found);
}

}  // namespace
}  // namespace mirage::methods::acoustic
