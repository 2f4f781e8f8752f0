// SPDX-License-Identifier: MIT
// The acoustic stamp simulator: the sound-speed law; options descriptor and validation (facing
// episodes included); stamps centred on t_emit + d / c with the stated sigma and heavy tail;
// ground-truth labels and surfaces against hand-mirrored images; the detection law and the range
// cut; the body blocking microphones behind the sender only below its top; facing episodes
// leaving only the faced wall's echoes; the NLOS fraction and bias interval; false alarms;
// determinism and the independence of the noise from what is blocked.
#include "mirage/channel/acoustic_stamps.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/options_descriptor_expectations.h"

namespace mirage::channel {
namespace {

using geometry::Reflector3;

// Shoebox 10 x 8 x 4 m: floor 0, ceiling 1, y=0 2, x=max 3, y=max 4, x=0 5.
constexpr int kFloor = 0, kWallXMax = 3;

// Options with negligible noise and certain detection, to check the geometry of the stamps.
AcousticStampOptions Exact(int max_order) {
  AcousticStampOptions o;
  o.max_order = max_order;
  o.stamp_sigma_s = 1e-12;
  o.half_detection_range_m = 1e6;
  o.max_range_m = 1e3;
  return o;
}

double C() { return SoundSpeedMps(20.0); }

TEST(SoundSpeedMps, FollowsTheDryAirLaw) {
  EXPECT_NEAR(SoundSpeedMps(0.0), 331.3, 1e-12);
  EXPECT_NEAR(SoundSpeedMps(20.0), 343.2, 0.02);
  EXPECT_NEAR(SoundSpeedMps(-273.15), 0.0, 1e-12);
  EXPECT_NEAR(SoundSpeedMps(30.0), 331.3 * std::sqrt(303.15 / 273.15), 1e-12);
}

TEST(AcousticStampOptionsDescriptor, AcceptsTheDefaultsAndDescribesEveryMemberButTheEpisodes) {
  test::ExpectDescribesEveryMember(
      AcousticStampOptionsDescriptor(),
      {"temperature_c", "max_order", "stamp_sigma_s", "heavy_tail_fraction", "heavy_tail_scale",
       "detection_probability", "half_detection_range_m", "max_range_m", "false_alarm_rate", "nlos_fraction",
       "nlos_bias_min_s", "nlos_bias_max_s", "body_radius_m", "body_offset_m", "body_height_m", "clock_drift_ppm",
       "emission_time_known"});
  EXPECT_TRUE(Validate(AcousticStampOptions{}).empty());
}

TEST(AcousticStampOptions, ValidateRejectsBadValuesAndEpisodes) {
  AcousticStampOptions o;
  o.max_order = 4;
  o.stamp_sigma_s = 0.0;
  o.nlos_bias_min_s = 5e-3;
  o.nlos_bias_max_s = 4e-3;
  o.body_radius_m = 0.3;
  o.body_offset_m = 0.25;
  o.facing = {{1.0, 2.0, "x=max"}, {3.0, 3.0, "floor"}, {0.0, std::nan(""), "floor"}};
  const auto problems = Validate(o);
  ASSERT_EQ(problems.size(), 6u);
  EXPECT_EQ(problems[0].rfind("max_order:", 0), 0u);
  EXPECT_EQ(problems[1].rfind("stamp_sigma_s:", 0), 0u);
  EXPECT_EQ(problems[2].rfind("nlos_bias_max_s:", 0), 0u);
  EXPECT_EQ(problems[3].rfind("body_offset_m:", 0), 0u);
  EXPECT_EQ(problems[4], "facing[1].t_end_s: 3 s must exceed t_start_s (3 s)");
  EXPECT_EQ(problems[5].rfind("facing[2]:", 0), 0u);
}

TEST(SimulateEmission, StampsAreCentredOnTheFlightTimeWithTheStatedSigmaAndTail) {
  AcousticStampOptions o;
  o.max_order = 0;
  o.stamp_sigma_s = 0.3e-3;
  o.heavy_tail_fraction = 0.2;
  o.heavy_tail_scale = 5.0;
  o.half_detection_range_m = 1e6;  // every stamp detected
  const std::vector<Vec3> mics{Vec3(4, 3, 2), Vec3(-1, 2, 3)};
  const Vec3 sender(0.5, 0.5, 1.2);
  core::Rng rng(21);
  const int trials = 5000;
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  for (int k = 0; k < trials; ++k) {
    const double t_emit_s = 0.1 * k;
    const auto e = SimulateEmission(o, {}, mics, sender, Vec2::Zero(), t_emit_s, rng);
    for (std::size_t m = 0; m < mics.size(); ++m) {
      ASSERT_EQ(e.stamps[m].size(), 1u);
      EXPECT_EQ(e.stamps[m][0].label, StampLabel::kDirect);
      const double error_s = e.stamps[m][0].toa_s - (t_emit_s + (mics[m] - sender).norm() / C());
      sum += error_s;
      sum_sq += error_s * error_s;
      ++n;
    }
  }
  // Variance of the mixture: (0.8 + 0.2 * 25) sigma^2 = 5.8 sigma^2.
  const double sigma_mix_s = std::sqrt(5.8) * 0.3e-3;
  EXPECT_NEAR(sum / n, 0.0, 4.0 * sigma_mix_s / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum_sq / n), sigma_mix_s, 0.04 * sigma_mix_s);
}

TEST(SimulateEmission, LabelsTheDirectPathAndEveryEchoWithItsSurfaces) {
  const auto box = geometry::ShoeboxReflectors(10, 8, 4);
  const Vec3 sender(2, 3, 1.5), mic(7, 5, 2);
  core::Rng rng(3);
  const auto e = SimulateEmission(Exact(1), box, std::vector<Vec3>{mic}, sender, Vec2::Zero(), 2.0, rng);
  ASSERT_EQ(e.stamps[0].size(), 7u);
  EXPECT_TRUE(e.direct_visible[0]);
  int direct = 0;
  std::vector<int> seen;
  for (const auto& s : e.stamps[0]) {
    if (s.label == StampLabel::kDirect) {
      ++direct;
      EXPECT_TRUE(s.surfaces.empty());
      EXPECT_NEAR(s.toa_s, 2.0 + (mic - sender).norm() / C(), 1e-9);
      continue;
    }
    ASSERT_EQ(s.label, StampLabel::kEcho);
    ASSERT_EQ(s.surfaces.size(), 1u);
    const auto& r = box[static_cast<std::size_t>(s.surfaces[0])];
    EXPECT_NEAR(s.toa_s, 2.0 + (mic - geometry::MirrorAtPlane(r, sender)).norm() / C(), 1e-9) << r.name;
    seen.push_back(s.surfaces[0]);
  }
  EXPECT_EQ(direct, 1);
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  // The direct path is the shortest, so it comes first; the order is by time.
  EXPECT_EQ(e.stamps[0].front().label, StampLabel::kDirect);
  EXPECT_TRUE(std::is_sorted(e.stamps[0].begin(), e.stamps[0].end(),
                             [](const AcousticStamp& a, const AcousticStamp& b) { return a.toa_s < b.toa_s; }));

  const auto second = SimulateEmission(Exact(2), box, std::vector<Vec3>{mic}, sender, Vec2::Zero(), 2.0, rng);
  EXPECT_EQ(second.stamps[0].size(), 25u);  // 1 + 6 + 18 shoebox paths (geometry/reflector_3d_test.cc)
}

TEST(SimulateEmission, DetectionHalvesAtTheHalfRangeAndStopsAtTheMaximumRange) {
  AcousticStampOptions o;
  o.max_order = 0;
  o.detection_probability = 0.8;
  o.half_detection_range_m = 5.0;
  const Vec3 sender(0, 0, 1);
  const std::vector<Vec3> mics{Vec3(3, 4, 1)};  // 5 m away
  core::Rng rng(8);
  int detected = 0;
  const int trials = 4000;
  for (int k = 0; k < trials; ++k) {
    detected += static_cast<int>(SimulateEmission(o, {}, mics, sender, Vec2::Zero(), 0.0, rng).stamps[0].size());
  }
  EXPECT_NEAR(static_cast<double>(detected) / trials, 0.4, 0.03);  // 4 sigma of the binomial

  o.detection_probability = 1.0;
  o.max_range_m = 4.9;
  for (int k = 0; k < 100; ++k) {
    const auto e = SimulateEmission(o, {}, mics, sender, Vec2::Zero(), 0.0, rng);
    EXPECT_TRUE(e.stamps[0].empty());
    EXPECT_TRUE(e.direct_visible[0]);  // visible, only out of range
  }
}

TEST(SimulateEmission, TheBodyBlocksMicrophonesBehindTheSenderOnlyBelowItsTop) {
  const auto box = geometry::ShoeboxReflectors(10, 8, 5);
  AcousticStampOptions o = Exact(1);
  o.body_radius_m = 0.2;
  o.body_offset_m = 0.25;
  o.body_height_m = 1.8;
  const std::vector<Vec3> mics{Vec3(8, 4, 4.8), Vec3(1, 4, 4.8), Vec3(5, 6, 4.8)};  // front, behind, left
  const Vec3 sender(5, 4, 1.4);
  const Vec2 heading(1, 0);
  core::Rng rng(2);
  const auto e = SimulateEmission(o, box, mics, sender, heading, 0.0, rng);
  EXPECT_TRUE(e.direct_visible[0]);
  EXPECT_FALSE(e.direct_visible[1]);
  EXPECT_TRUE(e.direct_visible[2]);
  auto has = [](const std::vector<AcousticStamp>& stamps, std::vector<int> surfaces, StampLabel label) {
    return std::any_of(stamps.begin(), stamps.end(),
                       [&](const AcousticStamp& s) { return s.label == label && s.surfaces == surfaces; });
  };
  EXPECT_TRUE(has(e.stamps[0], {}, StampLabel::kDirect));
  EXPECT_FALSE(has(e.stamps[1], {}, StampLabel::kDirect));
  EXPECT_FALSE(has(e.stamps[1], {kFloor}, StampLabel::kEcho));     // leaves backwards, low
  EXPECT_TRUE(has(e.stamps[1], {kWallXMax}, StampLabel::kEcho));   // leaves forwards
  EXPECT_TRUE(has(e.stamps[0], {kFloor}, StampLabel::kEcho));

  // Held above the head, the phone sends over the body.
  const auto high = SimulateEmission(o, box, mics, Vec3(5, 4, 1.9), heading, 0.0, rng);
  EXPECT_TRUE(high.direct_visible[1]);
  // No heading: no body.
  const auto none = SimulateEmission(o, box, mics, sender, Vec2::Zero(), 0.0, rng);
  EXPECT_TRUE(none.direct_visible[1]);
  EXPECT_EQ(none.stamps[1].size(), 7u);
}

TEST(SimulateEmission, AFacingEpisodeLeavesOnlyPathsThatStartOnTheFacedWall) {
  const auto box = geometry::ShoeboxReflectors(10, 8, 4);
  AcousticStampOptions o = Exact(2);
  o.facing = {{5.0, 6.0, "y=0"}, {1.0, 2.0, "x=max"}};
  const std::vector<Vec3> mics{Vec3(7, 5, 3.5), Vec3(1, 1, 3.5)};
  const Vec3 sender(4, 4, 1.2);
  core::Rng rng(6);
  const auto during = SimulateEmission(o, box, mics, sender, Vec2::Zero(), 1.0, rng);
  for (std::size_t m = 0; m < mics.size(); ++m) {
    EXPECT_FALSE(during.direct_visible[m]);
    // x=max alone, then x=max followed by each surface it has a path with.
    const auto paths = geometry::SpecularPaths3(box, sender, mics[m], 2);
    const auto faced = std::count_if(paths.begin(), paths.end(), [](const geometry::SpecularPath3& p) {
      return !p.surfaces.empty() && p.surfaces.front() == kWallXMax;
    });
    EXPECT_GE(faced, 3);
    ASSERT_EQ(during.stamps[m].size(), static_cast<std::size_t>(faced));
    for (const auto& s : during.stamps[m]) {
      EXPECT_EQ(s.label, StampLabel::kEcho);
      ASSERT_FALSE(s.surfaces.empty());
      EXPECT_EQ(s.surfaces.front(), kWallXMax);
    }
  }
  const auto after = SimulateEmission(o, box, mics, sender, Vec2::Zero(), 2.0, rng);  // the end is exclusive
  EXPECT_TRUE(after.direct_visible[0]);
  EXPECT_EQ(after.stamps[0].size(), geometry::SpecularPaths3(box, sender, mics[0], 2).size());
}

TEST(SimulateEmission, DelaysTheStatedFractionOfDirectStampsByABiasInTheInterval) {
  AcousticStampOptions o = Exact(0);
  o.nlos_fraction = 0.4;
  const std::vector<Vec3> mics{Vec3(4, 3, 2), Vec3(-1, 2, 3), Vec3(2, -3, 4)};
  const Vec3 sender(0, 0, 1);
  core::Rng rng(13);
  int biased = 0, total = 0;
  double smallest = 1.0, largest = 0.0, sum = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const auto e = SimulateEmission(o, {}, mics, sender, Vec2::Zero(), 0.0, rng);
    for (std::size_t m = 0; m < mics.size(); ++m) {
      ASSERT_EQ(e.stamps[m].size(), 1u);
      ++total;
      const double bias_s = e.stamps[m][0].toa_s - (mics[m] - sender).norm() / C();
      if (e.stamps[m][0].label == StampLabel::kDirectBiased) {
        ++biased;
        smallest = std::min(smallest, bias_s);
        largest = std::max(largest, bias_s);
        sum += bias_s;
      } else {
        EXPECT_EQ(e.stamps[m][0].label, StampLabel::kDirect);
        EXPECT_NEAR(bias_s, 0.0, 1e-9);
      }
    }
  }
  EXPECT_NEAR(static_cast<double>(biased) / total, 0.4, 4.0 * std::sqrt(0.24 / total));
  EXPECT_GE(smallest, 3e-3);
  EXPECT_LE(largest, 13e-3);
  EXPECT_LT(smallest, 3.1e-3);
  EXPECT_GT(largest, 12.9e-3);
  EXPECT_NEAR(sum / biased, 8e-3, 4.0 * 10e-3 / std::sqrt(12.0 * biased));
}

TEST(SimulateEmission, FalseAlarmsArePoissonOverTheListeningWindow) {
  AcousticStampOptions o;
  o.max_order = 0;
  o.detection_probability = 0.0;
  o.false_alarm_rate = 2.5;
  o.max_range_m = 34.32;
  const std::vector<Vec3> mics{Vec3(4, 3, 2), Vec3(-1, 2, 3)};
  core::Rng rng(17);
  const int trials = 2000;
  int count = 0;
  double earliest = 1e9, latest = -1e9;
  for (int k = 0; k < trials; ++k) {
    const auto e = SimulateEmission(o, {}, mics, Vec3(0, 0, 1), Vec2::Zero(), 7.0, rng);
    for (const auto& stamps : e.stamps) {
      count += static_cast<int>(stamps.size());
      for (const auto& s : stamps) {
        EXPECT_EQ(s.label, StampLabel::kFalseAlarm);
        earliest = std::min(earliest, s.toa_s);
        latest = std::max(latest, s.toa_s);
      }
    }
  }
  const double n = 2.0 * trials;
  EXPECT_NEAR(count / n, 2.5, 4.0 * std::sqrt(2.5 / n));
  const double window_s = 34.32 / C();
  EXPECT_GE(earliest, 7.0);
  EXPECT_LT(earliest, 7.0 + 0.01 * window_s);
  EXPECT_LE(latest, 7.0 + window_s);
  EXPECT_GT(latest, 7.0 + 0.99 * window_s);
}

TEST(SimulateEmission, IsDeterministicAndTheNoiseDoesNotDependOnWhatIsBlocked) {
  const auto box = geometry::ShoeboxReflectors(10, 8, 5);
  AcousticStampOptions o;
  o.heavy_tail_fraction = 0.1;
  o.false_alarm_rate = 1.0;
  o.nlos_fraction = 0.3;
  o.detection_probability = 0.7;
  const std::vector<Vec3> mics{Vec3(8, 4, 4.8), Vec3(1, 4, 4.8), Vec3(5, 7, 4.8)};
  const Vec3 sender(5, 4, 1.4);
  auto run = [&](const AcousticStampOptions& opts, std::uint64_t seed) {
    core::Rng rng(seed);
    std::vector<AcousticEmission> out;
    for (int k = 0; k < 5; ++k) out.push_back(SimulateEmission(opts, box, mics, sender, Vec2(1, 0), 0.5 * k, rng));
    return out;
  };
  auto same = [](const std::vector<AcousticStamp>& a, const std::vector<AcousticStamp>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].toa_s != b[i].toa_s || a[i].label != b[i].label || a[i].surfaces != b[i].surfaces) return false;
    }
    return true;
  };
  const auto a = run(o, 99), b = run(o, 99), c = run(o, 100);
  bool differs = false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t m = 0; m < mics.size(); ++m) {
      EXPECT_TRUE(same(a[k].stamps[m], b[k].stamps[m]));
      differs = differs || !same(a[k].stamps[m], c[k].stamps[m]);
    }
  }
  EXPECT_TRUE(differs);

  // A body removes stamps but changes none of those that survive: every draw is made whether a
  // path is blocked or not.
  AcousticStampOptions with_body = o;
  with_body.body_radius_m = 0.2;
  const auto blocked = run(with_body, 99);
  std::size_t kept = 0, all = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (std::size_t m = 0; m < mics.size(); ++m) {
      all += a[k].stamps[m].size();
      kept += blocked[k].stamps[m].size();
      for (const auto& s : blocked[k].stamps[m]) {
        EXPECT_TRUE(std::any_of(a[k].stamps[m].begin(), a[k].stamps[m].end(), [&](const AcousticStamp& t) {
          return t.toa_s == s.toa_s && t.label == s.label && t.surfaces == s.surfaces;
        }));
      }
    }
  }
  EXPECT_LT(kept, all);
  EXPECT_GT(kept, all / 2);
}

}  // namespace
}  // namespace mirage::channel
