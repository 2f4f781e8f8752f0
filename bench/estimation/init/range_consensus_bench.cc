// SPDX-License-Identifier: MIT
// One consensus search of the VA discovery's sweep (stage D'): 60 scans of a straight 3 m walk,
// each with the range of a far point (missed at every fourth scan, not at the proposing ones)
// among a Poisson number of clutter ranges uniform over 15 m; 60 % support needed. The proposals
// grow with the square of the ranges per scan (the range pairs of three pairs of scans), and each
// is dropped later when more clutter supports it. The seminar-room sweep sees about 15-20
// unexplained ranges per anchor and step and runs every 5 steps per anchor.
#include <algorithm>
#include <vector>

#include <benchmark/benchmark.h>

#include "mirage/core/rng.h"
#include "mirage/estimation/init/range_consensus.h"

namespace mirage::bench {
namespace {

void BM_RangeConsensus(benchmark::State& state) {
  const double clutter_per_scan = static_cast<double>(state.range(0));
  const Vec2 point_m(12.0, 3.0);
  core::Rng rng(3, 0);
  std::vector<estimation::RangeScan> scans;
  for (int k = 0; k < 60; ++k) {
    estimation::RangeScan scan;
    scan.position_m = Vec2(0.05 * k, 1.0);
    if (k % 4 != 1) scan.ranges_m.push_back((point_m - scan.position_m).norm() + rng.Normal(0.0, 0.01));
    const int clutter = rng.Poisson(clutter_per_scan);
    for (int c = 0; c < clutter; ++c) scan.ranges_m.push_back(rng.Uniform(0.0, 15.0));
    std::sort(scan.ranges_m.begin(), scan.ranges_m.end());
    scans.push_back(std::move(scan));
  }
  estimation::RangeConsensusOptions options;
  options.min_support = 36;
  bool found = false;
  for (auto _ : state) {
    auto result = estimation::FindRangeConsensus(scans, {}, options);
    found = result.has_value();
    benchmark::DoNotOptimize(result);
  }
  state.counters["found"] = found ? 1 : 0;
}
BENCHMARK(BM_RangeConsensus)->ArgName("clutter_per_scan")->Arg(5)->Arg(15)->Arg(30)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mirage::bench
