// SPDX-License-Identifier: MIT
// The acoustic family's hot spots on input from the ch. 5 simulator at a fixed seed (Bordoy 2020
// Sec. 5.3 regime: 0.3 ms stamp noise, 40 % NLOS delayed by U(3, 13) ms) in the 15 m x 11 m hall
// with 12 microphones and first-order echoes, so that each microphone has about K = 2 stamps:
// the combinatorial LOS fix, one REKF update (IRLS over 6 prior and 12 stamp rows) and the two
// closed-form solvers. And the filters' start from all stamps (multipath_fix.h) on one emission of
// the hold-out's glass-walled room, and the ch. 8 floor-echo fix per tracked emission on the
// stamps of examples/acoustic_height.yaml.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "mirage/channel/acoustic_stamps.h"
#include "mirage/core/rng.h"
#include "mirage/estimation/meas/toa.h"
#include "mirage/estimation/robust/irls_update.h"
#include "mirage/estimation/solvers/closed_form_tdoa_2d.h"
#include "mirage/estimation/solvers/closed_form_toa_3d.h"
#include "mirage/geometry/reflector_3d.h"
#include "mirage/io/scenario.h"
#include "mirage/methods/acoustic/ground_echo_fix.h"
#include "mirage/methods/acoustic/los_identification.h"
#include "mirage/methods/acoustic/multipath_fix.h"
#include "mirage/pipeline/acoustic_source.h"

namespace mirage::bench {
namespace {

constexpr double kHeight_m = 1.2;

std::vector<Vec3> HallMics() {
  return {{1.5, 1.5, 4.851}, {7.5, 1.2, 4.824}, {13.5, 1.5, 4.879}, {1.2, 5.5, 4.835}, {7.5, 5.5, 4.860}, {13.8, 5.5, 4.862},
          {1.5, 9.5, 4.844}, {7.5, 9.8, 4.851}, {13.5, 9.5, 4.870}, {5.0, 4.0, 3.40},  {10.0, 7.0, 3.40}, {4.0, 8.5, 3.40}};
}

// One emission's stamps per microphone as pseudo-ranges c (T - t_emit) (m), the K = 2 earliest.
std::vector<std::vector<double>> Ch5Emission(const Vec3& sender_m, std::uint64_t seed) {
  channel::AcousticStampOptions o;
  o.max_order = 1;
  o.nlos_fraction = 0.4;
  const auto hall = geometry::ShoeboxReflectors(15.0, 11.0, 5.2, 0.95);
  core::Rng rng(seed);
  const auto mics = HallMics();
  const auto emission = channel::SimulateEmission(o, hall, mics, sender_m, Vec2::Zero(), 0.0, rng);
  const double c = channel::SoundSpeedMps(o.temperature_c);
  std::vector<std::vector<double>> out(mics.size());
  for (std::size_t m = 0; m < mics.size(); ++m) {
    for (const auto& s : emission.stamps[m]) {
      if (out[m].size() < 2) out[m].push_back(c * s.toa_s);
    }
  }
  return out;
}

// Argument 0: the default window vote; 1: the thesis's Cook vote (los_identification.h).
void BM_CombinatorialFix(benchmark::State& state) {
  const auto mics = HallMics();
  const auto stamps = Ch5Emission(Vec3(6.0, 4.0, kHeight_m), 7);
  methods::acoustic::LosIdentificationOptions options;
  options.cook_voting = state.range(0) == 1;
  bool found = false;
  for (auto _ : state) {
    auto result = methods::acoustic::IdentifyLos(mics, stamps, kHeight_m, options);
    found = result.found;
    benchmark::DoNotOptimize(result);
  }
  state.counters["found"] = found ? 1 : 0;
}
BENCHMARK(BM_CombinatorialFix)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_RekfUpdate(benchmark::State& state) {
  // The planar filter's 6 states [x, y, vx, vy, b, iota] and 12 stamp rows at the prediction.
  const auto mics = HallMics();
  const Vec3 sender(6.0, 4.0, kHeight_m);
  const auto stamps = Ch5Emission(sender, 7);
  const int n = 6;
  Eigen::MatrixXd P = Eigen::MatrixXd::Identity(n, n) * 0.01;
  P(4, 4) = 0.02;
  P(5, 5) = 1e-6;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(12, n);
  Eigen::VectorXd y(12);
  for (int i = 0; i < 12; ++i) {
    const auto p = estimation::PredictToa(sender + Vec3(0.05, -0.03, 0.0), mics[static_cast<std::size_t>(i)], 0.0);
    H.row(i).head(2) = p->d_sender.head<2>().transpose();
    H(i, 4) = 1.0;
    y(i) = stamps[static_cast<std::size_t>(i)].empty() ? 0.0 : stamps[static_cast<std::size_t>(i)].front() - p->predicted_m;
  }
  const Eigen::MatrixXd R = 0.103 * 0.103 * Eigen::MatrixXd::Identity(12, 12);
  const estimation::IrlsOptions options;
  for (auto _ : state) {
    auto result = estimation::IrlsUpdate(P, H, y, R, options);
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_RekfUpdate)->Unit(benchmark::kMicrosecond);

void BM_ClosedFormTdoa2d(benchmark::State& state) {
  const auto mics = HallMics();
  const Vec3 sender(6.0, 4.0, kHeight_m);
  const std::array<Vec3, 3> three{mics[0], mics[4], mics[8]};
  const std::array<double, 3> rho{(sender - three[0]).norm() + 3.0, (sender - three[1]).norm() + 3.0,
                                  (sender - three[2]).norm() + 3.0};
  for (auto _ : state) {
    auto roots = estimation::SolveTdoa2dFromPseudoRanges(three, rho, kHeight_m);
    benchmark::DoNotOptimize(roots);
  }
}
BENCHMARK(BM_ClosedFormTdoa2d)->Unit(benchmark::kNanosecond);

void BM_ClosedFormToa3d(benchmark::State& state) {
  const auto mics = HallMics();
  const Vec3 sender(6.0, 4.0, kHeight_m);
  const std::vector<Vec3> four{mics[0], mics[2], mics[9], mics[10]};
  std::vector<double> rho;
  for (const auto& m : four) rho.push_back((sender - m).norm() + 3.0);
  for (auto _ : state) {
    auto roots = estimation::SolveToa3dClosedForm(four, rho);
    benchmark::DoNotOptimize(roots);
  }
}
BENCHMARK(BM_ClosedFormToa3d)->Unit(benchmark::kNanosecond);

// The filters' start (multipath_fix.h) on one emission of the acoustic hold-out's room: 8 m x 6 m x
// 3 m, glass walls (0.9), six microphones at 2.8 m, echoes to order 2 predicted and simulated,
// 0.1 ms noise, P_d 0.95 falling with range, 0.5 false alarms per microphone (about 14 stamps per
// microphone): the search over the whole room, planar (arg 2) and in 3-D up to 2.5 m (arg 3).
void BM_MultipathStart(benchmark::State& state) {
  const std::vector<Vec3> mics = {{0.5, 0.5, 2.8}, {4.0, 0.4, 2.8}, {7.5, 0.5, 2.8},
                                  {7.5, 5.5, 2.8}, {4.0, 5.6, 2.8}, {0.5, 5.5, 2.8}};
  const auto room = geometry::ShoeboxReflectors(8.0, 6.0, 3.0, 0.9);
  channel::AcousticStampOptions o;
  o.max_order = 2;
  o.stamp_sigma_s = 0.1e-3;
  o.detection_probability = 0.95;
  o.false_alarm_rate = 0.5;
  core::Rng rng(7);
  const Vec3 sender(2.6, 1.8, 1.1);
  const auto emission = channel::SimulateEmission(o, room, mics, sender, Vec2::Zero(), 0.0, rng);
  const double c = channel::SoundSpeedMps(o.temperature_c);
  std::vector<std::vector<double>> stamps(mics.size());
  std::size_t count = 0;
  for (std::size_t m = 0; m < mics.size(); ++m) {
    for (const auto& s : emission.stamps[m]) stamps[m].push_back(c * s.toa_s);
    count += stamps[m].size();
  }
  methods::acoustic::MultipathFixOptions options;
  options.range_sigma_m = c * o.stamp_sigma_s;
  options.detection_probability = o.detection_probability;
  options.clutter_density_per_m = 0.025;
  methods::acoustic::MultipathSearchRegion region;
  region.lo_m = Vec3(0.0, 0.0, state.range(0) == 2 ? sender.z() : 0.0);
  region.hi_m = Vec3(8.0, 6.0, state.range(0) == 2 ? sender.z() : 2.5);
  double error_m = 0.0;
  for (auto _ : state) {
    const auto fix = methods::acoustic::FixFromAllStamps(room, mics, stamps, region, options);
    error_m = fix.found ? (fix.position_m - sender).norm() : -1.0;
    benchmark::DoNotOptimize(error_m);
  }
  state.counters["error_m"] = error_m;
  state.counters["stamps"] = static_cast<double>(count);
}
BENCHMARK(BM_MultipathStart)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

// The ch. 8 fix (ground_echo_fix.h) of examples/acoustic_height.yaml (nine ceiling microphones,
// first-order echoes, 0.5 false alarms per microphone, 0.044 ms): the fixer after the first 20
// emissions of run 0 (its full vote search done, the window full), timed over the next 40
// tracked emissions (the vote at the tracked t_0, the fits of every cluster), per emission. Arg:
// 0 t_0 from the vote (the default), 1 known, 2 unknown (TDOA).
void BM_GroundEchoFix(benchmark::State& state) {
  static const io::Scenario scenario =
      io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/acoustic_height.yaml");
  const pipeline::Experiment& experiment = scenario.variants.front().experiment;
  static const std::vector<core::Epoch> epochs = [&] {
    std::vector<core::Epoch> out;
    pipeline::AcousticSource source(experiment, 0, 0);
    while (out.size() < 60) {
      const auto step = source.Next();
      if (!step) break;
      out.push_back(step->epoch);
    }
    return out;
  }();
  if (epochs.size() <= 20) {
    state.SkipWithError("the example gave fewer than 21 emissions");
    return;
  }
  std::vector<Vec3> mics_m;
  for (const auto& anchor : experiment.anchors) mics_m.push_back(anchor.position_m);
  const double c_mps = experiment.medium.speed_mps;
  methods::acoustic::GroundEchoOptions options;
  options.sending_time = std::array<const char*, 3>{"estimated", "known", "unknown"}[static_cast<std::size_t>(state.range(0))];
  methods::acoustic::GroundEchoFixer warmed(mics_m, experiment.plan.floor_z_m(), c_mps,
                                            experiment.acoustic.stamp_sigma_s * c_mps,
                                            experiment.trajectories.front().dt_s, experiment.acoustic.clock_drift_ppm,
                                            options, experiment.plan.ceiling_z_m());
  for (std::size_t k = 0; k < 20; ++k) warmed.Process(epochs[k]);
  int fixes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    methods::acoustic::GroundEchoFixer fixer = warmed;
    fixes = 0;
    state.ResumeTiming();
    for (std::size_t k = 20; k < epochs.size(); ++k) fixes += fixer.Process(epochs[k]).found ? 1 : 0;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(epochs.size() - 20));
  state.counters["fixes"] = fixes;
}
BENCHMARK(BM_GroundEchoFix)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mirage::bench
