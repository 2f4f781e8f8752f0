// SPDX-License-Identifier: MIT
// The UWB TDOA simulator: options descriptor and validation; noiseless rows equal to
// |p - a_j| - |p - a_i|; the noise's mean and sigma; the outlier fraction and bound; the NLOS
// bias on exactly the legs through a box, inside [min, max]; the slot grid (rate, steps of any
// length covering each slot once, missed packets); the pair choices; determinism and the
// independence of each row's numbers from the obstacle and the detection probability.
#include "mirage/channel/uwb_tdoa_simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"

namespace mirage::channel {
namespace {

using geometry::Reflector3;

// The room: 7 x 7 m, anchors in the corners alternately at 0.2 m and 2.5 m.
std::vector<Vec3> Anchors() {
  return {Vec3(0, 0, 0.2), Vec3(7, 0, 2.5), Vec3(7, 7, 0.2), Vec3(0, 7, 2.5),
          Vec3(0, 0, 2.5), Vec3(7, 0, 0.2), Vec3(7, 7, 2.5), Vec3(0, 7, 0.2)};
}

std::vector<std::string> Ids() { return {"A0", "A1", "A2", "A3", "A4", "A5", "A6", "A7"}; }

// A box [x0, x1] x [y0, y1] x [z0, z1] as its six faces.
std::vector<Reflector3> BoxFaces(const Vec3& lo, const Vec3& hi) {
  const Vec2 c((lo.x() + hi.x()) / 2, (lo.y() + hi.y()) / 2);
  const double hx = (hi.x() - lo.x()) / 2, hy = (hi.y() - lo.y()) / 2;
  return {geometry::HorizontalReflector("bottom", c, hx, hy, lo.z()),
          geometry::HorizontalReflector("top", c, hx, hy, hi.z()),
          geometry::VerticalReflector("y0", Vec2(lo.x(), lo.y()), Vec2(hi.x(), lo.y()), lo.z(), hi.z()),
          geometry::VerticalReflector("x1", Vec2(hi.x(), lo.y()), Vec2(hi.x(), hi.y()), lo.z(), hi.z()),
          geometry::VerticalReflector("y1", Vec2(hi.x(), hi.y()), Vec2(lo.x(), hi.y()), lo.z(), hi.z()),
          geometry::VerticalReflector("x0", Vec2(lo.x(), hi.y()), Vec2(lo.x(), lo.y()), lo.z(), hi.z())};
}

// A 0.6 x 0.6 x 1 m box at (1, 1) between the tag at (2, 2, 0.5) and anchor 0 at (0, 0, 0.2): that
// leg crosses it at (1, 1, 0.35). Anchor 4 stands above anchor 0, and its leg passes over the box
// top (z = 1.5 at (1, 1)); every other leg leaves (1, 1) more than 0.3 m aside.
std::vector<Reflector3> Box() { return BoxFaces(Vec3(0.7, 0.7, 0.0), Vec3(1.3, 1.3, 1.0)); }
const Vec3 kTagBehindBox(2.0, 2.0, 0.5);

UwbTdoaOptions Noiseless() {
  UwbTdoaOptions o;
  o.sigma_m = 0.0;
  o.outlier_probability = 0.0;
  return o;
}

std::vector<UwbTdoaSample> Static(const UwbTdoaOptions& o, std::span<const Reflector3> obstacles, const Vec3& tag_m,
                                  double t_end_s, core::Rng& rng) {
  const auto anchors = Anchors();
  const auto ids = Ids();
  return SimulateUwbTdoa(o, anchors, ids, obstacles, [&](double) { return tag_m; }, 0.0, t_end_s, rng);
}

void ExpectSameRow(const UwbTdoaSample& a, const UwbTdoaSample& b) {
  EXPECT_EQ(a.measurement.t_s, b.measurement.t_s);
  EXPECT_EQ(a.measurement.id_i, b.measurement.id_i);
  EXPECT_EQ(a.measurement.id_j, b.measurement.id_j);
  EXPECT_EQ(a.measurement.index_i, b.measurement.index_i);
  EXPECT_EQ(a.measurement.index_j, b.measurement.index_j);
  EXPECT_EQ(a.measurement.tdoa_m, b.measurement.tdoa_m);
  EXPECT_EQ(a.label.true_tdoa_m, b.label.true_tdoa_m);
  EXPECT_EQ(a.label.nlos_i, b.label.nlos_i);
  EXPECT_EQ(a.label.nlos_j, b.label.nlos_j);
  EXPECT_EQ(a.label.nlos_bias_i_m, b.label.nlos_bias_i_m);
  EXPECT_EQ(a.label.nlos_bias_j_m, b.label.nlos_bias_j_m);
  EXPECT_EQ(a.label.outlier, b.label.outlier);
}

TEST(UwbTdoaOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMember) {
  test::ExpectDescribesEveryMember(UwbTdoaOptionsDescriptor(),
                                   {"rate_hz", "sigma_m", "pair_selection", "nlos_bias_min_m", "nlos_bias_max_m",
                                    "outlier_probability", "outlier_max_m", "detection_probability"});
  EXPECT_TRUE(Validate(UwbTdoaOptions{}).empty());
  const UwbTdoaOptions d;
  EXPECT_EQ(d.rate_hz, 200.0);
  EXPECT_EQ(d.sigma_m, 0.15);
  EXPECT_EQ(d.pair_selection, UwbPairSelection::kRandom);
  EXPECT_EQ(d.outlier_probability, 0.01);
  EXPECT_EQ(d.outlier_max_m, 50.0);
}

TEST(UwbTdoaOptions, ValidateRejectsBadValues) {
  UwbTdoaOptions o;
  o.rate_hz = 0.0;
  o.sigma_m = -0.1;
  o.nlos_bias_min_m = 0.5;
  o.nlos_bias_max_m = 0.4;
  o.outlier_probability = 1.5;
  o.outlier_max_m = 0.0;
  o.detection_probability = -0.1;
  const auto problems = Validate(o);
  ASSERT_EQ(problems.size(), 6u);
  EXPECT_EQ(problems[0].rfind("rate_hz:", 0), 0u);
  EXPECT_EQ(problems[1].rfind("sigma_m:", 0), 0u);
  EXPECT_EQ(problems[2].rfind("outlier_probability:", 0), 0u);
  EXPECT_EQ(problems[3].rfind("outlier_max_m:", 0), 0u);
  EXPECT_EQ(problems[4].rfind("detection_probability:", 0), 0u);
  EXPECT_EQ(problems[5], "nlos_bias_max_m: 0.4 m must be at least nlos_bias_min_m (0.5 m)");

  UwbTdoaOptions fast;
  fast.rate_hz = 2e4;
  EXPECT_EQ(Validate(fast).size(), 1u);
}

TEST(SimulateUwbTdoa, NoiselessRowsAreTheExactDifferenceOfDistancesAlongAMovingTag) {
  const auto anchors = Anchors();
  const auto ids = Ids();
  // A tag flying a 1.5 m/s circle of radius 2 m round the room's centre at 1.2 m.
  const auto tag_at = [](double t_s) {
    const double w = 1.5 / 2.0;
    return Vec3(3.5 + 2.0 * std::cos(w * t_s), 3.5 + 2.0 * std::sin(w * t_s), 1.2);
  };
  core::Rng rng(7);
  const auto rows = SimulateUwbTdoa(Noiseless(), anchors, ids, {}, tag_at, 0.0, 2.0, rng);
  ASSERT_EQ(rows.size(), 400u);
  for (const auto& row : rows) {
    const auto& m = row.measurement;
    const auto i = static_cast<std::size_t>(m.index_i), j = static_cast<std::size_t>(m.index_j);
    ASSERT_NE(i, j);
    EXPECT_EQ(m.id_i, ids[i]);
    EXPECT_EQ(m.id_j, ids[j]);
    const Vec3 p = tag_at(m.t_s);
    const double expected_m = (p - anchors[j]).norm() - (p - anchors[i]).norm();
    EXPECT_NEAR(m.tdoa_m, expected_m, 1e-12);
    EXPECT_NEAR(row.label.true_tdoa_m, expected_m, 1e-12);
    EXPECT_FALSE(row.label.nlos_i || row.label.nlos_j || row.label.outlier);
  }
  // Golden: a tag nearer to a_i gives a positive TDOA.
  const std::vector<Vec3> two{Vec3(0, 0, 0), Vec3(4, 0, 0)};
  const std::vector<std::string> two_ids{"near", "far"};
  UwbTdoaOptions rr = Noiseless();
  rr.pair_selection = UwbPairSelection::kRoundRobin;
  const auto golden = SimulateUwbTdoaStep(rr, two, two_ids, {}, 0.0, 0.005, Vec3(1, 0, 0), rng);
  ASSERT_EQ(golden.size(), 1u);
  EXPECT_EQ(golden[0].measurement.id_i, "near");
  EXPECT_DOUBLE_EQ(golden[0].measurement.tdoa_m, 2.0);  // 3 - 1
}

TEST(SimulateUwbTdoa, ErrorsHaveZeroMeanAndTheStatedSigma) {
  UwbTdoaOptions o;
  o.outlier_probability = 0.0;
  core::Rng rng(11);
  const auto rows = Static(o, {}, Vec3(3.0, 4.0, 1.1), 100.0, rng);
  ASSERT_EQ(rows.size(), 20000u);
  double sum = 0.0, sum_sq = 0.0;
  for (const auto& row : rows) {
    const double e = row.measurement.tdoa_m - row.label.true_tdoa_m;
    sum += e;
    sum_sq += e * e;
  }
  const double n = static_cast<double>(rows.size());
  EXPECT_NEAR(sum / n, 0.0, 4.0 * 0.15 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum_sq / n - (sum / n) * (sum / n)), 0.15, 0.03 * 0.15);
}

TEST(SimulateUwbTdoa, OutliersAreAboutOnePercentAndUniformWithinTheBound) {
  UwbTdoaOptions o;
  o.sigma_m = 0.0;
  core::Rng rng(5);
  const auto rows = Static(o, {}, Vec3(3.0, 4.0, 1.1), 500.0, rng);  // 100000 rows
  const double n = static_cast<double>(rows.size());
  int outliers = 0, near_bound = 0;
  double sum = 0.0;
  for (const auto& row : rows) {
    if (!row.label.outlier) {
      EXPECT_EQ(row.measurement.tdoa_m, row.label.true_tdoa_m);
      continue;
    }
    ++outliers;
    EXPECT_LE(std::abs(row.measurement.tdoa_m), 50.0);
    sum += row.measurement.tdoa_m;
    if (std::abs(row.measurement.tdoa_m) > 40.0) ++near_bound;
  }
  EXPECT_NEAR(outliers / n, 0.01, 4.0 * std::sqrt(0.01 * 0.99 / n));
  // Uniform on [-50, 50]: mean 0 (sd 50 / sqrt(3 n_out)), a fifth beyond |40|.
  EXPECT_NEAR(sum / outliers, 0.0, 4.0 * 50.0 / std::sqrt(3.0 * outliers));
  EXPECT_NEAR(static_cast<double>(near_bound) / outliers, 0.2, 4.0 * std::sqrt(0.2 * 0.8 / outliers));
}

TEST(SimulateUwbTdoa, OnlyTheLegThroughTheBoxIsBiasedWithinTheInterval) {
  const auto anchors = Anchors();
  const auto box = Box();
  // Hand check of the set-up with the geometry helper.
  for (std::size_t a = 0; a < anchors.size(); ++a) {
    EXPECT_EQ(geometry::IsSegmentClear(box, kTagBehindBox, anchors[a]), a != 0) << a;
  }
  core::Rng rng(13);
  const auto rows = Static(Noiseless(), box, kTagBehindBox, 20.0, rng);
  double lo = 1e9, hi = -1e9;
  int blocked_rows = 0;
  for (const auto& row : rows) {
    const auto& m = row.measurement;
    const auto& l = row.label;
    EXPECT_EQ(l.nlos_i, m.index_i == 0);
    EXPECT_EQ(l.nlos_j, m.index_j == 0);
    for (const auto& [nlos, bias_m] : {std::pair{l.nlos_i, l.nlos_bias_i_m}, std::pair{l.nlos_j, l.nlos_bias_j_m}}) {
      if (!nlos) {
        EXPECT_EQ(bias_m, 0.0);
        continue;
      }
      EXPECT_GE(bias_m, 0.2);
      EXPECT_LE(bias_m, 1.0);
      lo = std::min(lo, bias_m);
      hi = std::max(hi, bias_m);
      ++blocked_rows;
    }
    // The bias lengthens leg j (tdoa up) or leg i (tdoa down).
    const double excess_m = m.tdoa_m - l.true_tdoa_m;
    if (m.index_j == 0) {
      EXPECT_NEAR(excess_m, l.nlos_bias_j_m, 1e-12);
    } else if (m.index_i == 0) {
      EXPECT_NEAR(excess_m, -l.nlos_bias_i_m, 1e-12);
    } else {
      EXPECT_EQ(excess_m, 0.0);
    }
  }
  // Anchor 0 is in a quarter of the random pairs (2 / 8): about 1000 of 4000 rows.
  EXPECT_GT(blocked_rows, 800);
  EXPECT_LT(lo, 0.25);
  EXPECT_GT(hi, 0.95);
}

TEST(SimulateUwbTdoa, TogglingTheBoxChangesOnlyTheRowsOfTheBlockedAnchor) {
  const UwbTdoaOptions o;  // defaults: noise and outliers on
  core::Rng with_rng(17), without_rng(17);
  const auto box = Box();
  const auto with = Static(o, box, kTagBehindBox, 5.0, with_rng);
  const auto without = Static(o, {}, kTagBehindBox, 5.0, without_rng);
  ASSERT_EQ(with.size(), without.size());
  int changed = 0;
  for (std::size_t r = 0; r < with.size(); ++r) {
    const auto& a = with[r].measurement;
    const auto& b = without[r].measurement;
    ASSERT_EQ(a.index_i, b.index_i);
    ASSERT_EQ(a.index_j, b.index_j);
    EXPECT_EQ(a.t_s, b.t_s);
    EXPECT_EQ(with[r].label.outlier, without[r].label.outlier);
    if (a.index_i == 0 || a.index_j == 0) {
      // Same noise draw: the rows differ by the bias alone.
      if (!with[r].label.outlier) {
        EXPECT_NEAR(a.tdoa_m - b.tdoa_m, with[r].label.nlos_bias_j_m - with[r].label.nlos_bias_i_m, 1e-12);
        EXPECT_GE(std::abs(a.tdoa_m - b.tdoa_m), 0.2 - 1e-12);
        ++changed;
      }
      continue;
    }
    ExpectSameRow(with[r], without[r]);
  }
  EXPECT_GT(changed, 100);
  EXPECT_EQ(with_rng.NextU64(), without_rng.NextU64());
}

TEST(SimulateUwbTdoa, MissedPacketsDropRowsWithoutShiftingTheOthers) {
  UwbTdoaOptions all;
  UwbTdoaOptions half = all;
  half.detection_probability = 0.5;
  core::Rng rng_all(19), rng_half(19);
  const auto rows_all = Static(all, {}, Vec3(1, 2, 1), 10.0, rng_all);
  const auto rows_half = Static(half, {}, Vec3(1, 2, 1), 10.0, rng_half);
  ASSERT_EQ(rows_all.size(), 2000u);
  EXPECT_NEAR(static_cast<double>(rows_half.size()), 1000.0, 4.0 * std::sqrt(2000 * 0.25));
  // Every received row is the row of its slot in the full run.
  std::map<double, const UwbTdoaSample*> by_time;
  for (const auto& row : rows_all) by_time[row.measurement.t_s] = &row;
  for (const auto& row : rows_half) {
    const auto it = by_time.find(row.measurement.t_s);
    ASSERT_NE(it, by_time.end());
    ExpectSameRow(row, *it->second);
  }
}

TEST(SimulateUwbTdoaStep, StepsOfAnyLengthCoverEverySlotOnceAtTheRate) {
  const auto anchors = Anchors();
  const auto ids = Ids();
  const Vec3 tag(2.5, 3.0, 1.0);
  core::Rng whole_rng(23);
  const auto whole = Static(UwbTdoaOptions{}, {}, tag, 1.0, whole_rng);
  ASSERT_EQ(whole.size(), 200u);
  for (std::size_t k = 0; k < whole.size(); ++k) {
    EXPECT_NEAR(whole[k].measurement.t_s, static_cast<double>(k) / 200.0, 1e-12);
  }
  // 10 ms epochs whose bounds are computed as e * dt (not by accumulation), 12.3 ms epochs, and
  // 1 ms epochs, most of which hold no slot.
  for (const double dt_s : {0.01, 0.0123, 0.001}) {
    core::Rng rng(23);
    std::vector<UwbTdoaSample> stepped;
    for (int e = 0; e * dt_s < 1.0 - 1e-12; ++e) {
      const double t0_s = e * dt_s;
      const double t1_s = std::min(1.0, (e + 1) * dt_s);
      const auto rows = SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, ids, {}, t0_s, t1_s - t0_s, tag, rng);
      for (const auto& row : rows) {
        EXPECT_GE(row.measurement.t_s, t0_s - 1e-9);
        EXPECT_LT(row.measurement.t_s, t1_s - 1e-9);
      }
      stepped.insert(stepped.end(), rows.begin(), rows.end());
    }
    ASSERT_EQ(stepped.size(), whole.size()) << dt_s;
    for (std::size_t r = 0; r < whole.size(); ++r) ExpectSameRow(stepped[r], whole[r]);
  }
  // A step without a slot, fewer than two anchors, or no length: no rows and no draws.
  core::Rng rng(29);
  const core::Rng before = rng;
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, ids, {}, 0.0011, 0.003, tag, rng).empty());
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, std::span(anchors).first(1), std::span(ids).first(1), {}, 0.0,
                                  1.0, tag, rng)
                  .empty());
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, ids, {}, 0.0, 0.0, tag, rng).empty());
  // Bad input gives no rows either (no undefined slot arithmetic, no read past the ids): times
  // that are not finite or beyond any slot number, one id missing, invalid options.
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, ids, {}, 0.0, inf, tag, rng).empty());
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, ids, {}, std::nan(""), 1.0, tag, rng).empty());
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, ids, {}, 0.0, 1e300, tag, rng).empty());
  EXPECT_TRUE(SimulateUwbTdoaStep(UwbTdoaOptions{}, anchors, std::span(ids).first(ids.size() - 1), {}, 0.0, 1.0, tag, rng)
                  .empty());
  UwbTdoaOptions bad;
  bad.rate_hz = 0.0;
  EXPECT_TRUE(SimulateUwbTdoaStep(bad, anchors, ids, {}, 0.0, 1.0, tag, rng).empty());
  EXPECT_TRUE(SimulateUwbTdoa(UwbTdoaOptions{}, anchors, ids, {}, [&](double) { return tag; }, -inf, 1.0, rng).empty());
  core::Rng after = before;
  EXPECT_EQ(rng.NextU64(), after.NextU64());
}

TEST(SimulateUwbTdoa, RoundRobinPairsConsecutiveAnchorsBySlot) {
  UwbTdoaOptions o = Noiseless();
  o.pair_selection = UwbPairSelection::kRoundRobin;
  core::Rng rng(31);
  const auto anchors = Anchors();
  const auto ids = Ids();
  // Start at slot 13 to check that the pair follows the absolute slot, not the call.
  const auto rows = SimulateUwbTdoa(o, anchors, ids, {}, [](double) { return Vec3(3, 3, 1); }, 13.0 / 200.0,
                                    33.0 / 200.0, rng);
  ASSERT_EQ(rows.size(), 20u);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int k = 13 + static_cast<int>(r);
    EXPECT_EQ(rows[r].measurement.index_i, k % 8) << k;
    EXPECT_EQ(rows[r].measurement.index_j, (k + 1) % 8) << k;
  }
}

TEST(SimulateUwbTdoa, RandomPairsCoverEveryOrderedPairEvenlyAndNeverRepeatAnAnchor) {
  core::Rng rng(37);
  const auto rows = Static(UwbTdoaOptions{}, {}, Vec3(3, 3, 1), 100.0, rng);  // 20000 rows, 56 pairs
  std::map<std::pair<int, int>, int> counts;
  for (const auto& row : rows) {
    ASSERT_NE(row.measurement.index_i, row.measurement.index_j);
    ++counts[{row.measurement.index_i, row.measurement.index_j}];
  }
  ASSERT_EQ(counts.size(), 56u);
  const double expected = 20000.0 / 56.0;  // 357, binomial sd 18.7
  for (const auto& [pair, count] : counts) {
    EXPECT_NEAR(count, expected, 5.0 * std::sqrt(expected)) << pair.first << "," << pair.second;
  }
}

TEST(SimulateUwbTdoa, TheSameSeedGivesTheSameRows) {
  const UwbTdoaOptions o;
  const auto box = Box();
  core::Rng a(41), b(41), c(42);
  const auto first = Static(o, box, kTagBehindBox, 3.0, a);
  const auto second = Static(o, box, kTagBehindBox, 3.0, b);
  const auto other = Static(o, box, kTagBehindBox, 3.0, c);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t r = 0; r < first.size(); ++r) ExpectSameRow(first[r], second[r]);
  int differ = 0;
  for (std::size_t r = 0; r < first.size(); ++r) differ += first[r].measurement.tdoa_m != other[r].measurement.tdoa_m;
  EXPECT_GT(differ, 500);
}

}  // namespace
}  // namespace mirage::channel
