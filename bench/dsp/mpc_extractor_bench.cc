// SPDX-License-Identifier: MIT
// MPC extraction of one seminar-room CIR (1024 samples at 0.125 ns, K = 20), with and without
// the readjust step.
#include <benchmark/benchmark.h>

#include "bench_fixture.h"

namespace mirage::bench {
namespace {

void BM_MpcExtract(benchmark::State& state) {
  const auto& d = SeminarRoom();
  auto options = d.scenario.variants.front().experiment.mpc;
  options.readjust = state.range(0) != 0;
  const dsp::MpcExtractor extractor(options, d.synthesizer->pulse(), d.synthesizer->sample_count(),
                                    d.scenario.variants.front().experiment.channel.sample_period_s, d.scenario.variants.front().experiment.channel.medium);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(extractor.Extract(d.cirs[k % d.cirs.size()][k % 2]));
    ++k;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MpcExtract)->Arg(1)->Arg(0)->ArgName("readjust")->Unit(benchmark::kMicrosecond);

void BM_MatchedFilter(benchmark::State& state) {
  const auto& d = SeminarRoom();
  const dsp::MpcExtractor extractor(d.scenario.variants.front().experiment.mpc, d.synthesizer->pulse(), d.synthesizer->sample_count(),
                                    d.scenario.variants.front().experiment.channel.sample_period_s, d.scenario.variants.front().experiment.channel.medium);
  for (auto _ : state) benchmark::DoNotOptimize(extractor.MatchedFilter(d.cirs[0][0]));
}
BENCHMARK(BM_MatchedFilter)->Unit(benchmark::kMicrosecond);

void BM_VisibleVirtualAnchors(benchmark::State& state) {
  const auto& d = SeminarRoom();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(geometry::VisibleVirtualAnchors(d.vas, static_cast<int>(k % 2), d.scenario.variants.front().experiment.plan,
                                                             d.samples[k % d.samples.size()].position_m));
    ++k;
  }
}
BENCHMARK(BM_VisibleVirtualAnchors)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mirage::bench
