// SPDX-License-Identifier: MIT
// One full per-anchor MINT step on the seminar-room defaults: MPC extraction of one CIR
// (K = 20), visibility of the known VAs, association and the EKF update (the target is at least
// 10,000 such steps per second on one core).
#include <benchmark/benchmark.h>

#include "bench_fixture.h"
#include "mirage/methods/mint/mint_tracker.h"

namespace mirage::bench {
namespace {

void RunSteps(benchmark::State& state, const methods::mint::MintOptions& mint, const dsp::MpcExtractorOptions& mpc) {
  const auto& d = SeminarRoom();
  const auto& config = d.scenario.variants.front().experiment;
  const dsp::MpcExtractor extractor(mpc, d.synthesizer->pulse(), d.synthesizer->sample_count(),
                                    config.channel.sample_period_s, config.channel.medium);
  const double sigma1 = d.synthesizer->pulse().range_sigma_at_unit_sinr_m(d.synthesizer->options().medium.speed_mps);
  const int anchors = static_cast<int>(config.anchors.size());
  methods::mint::MintTracker tracker(mint, d.vas, config.plan, sigma1);
  std::size_t step = 0;
  tracker.Initialize(d.samples.front().t_s, d.samples.front().position_m);
  std::vector<core::RangeSet> one(1);
  for (auto _ : state) {
    if (step == d.samples.size()) {
      // Start the trajectory again (outside the measured region would be as fair, but this is
      // simpler and the restart costs nothing).
      step = 0;
      tracker.Initialize(d.samples.front().t_s, d.samples.front().position_m);
    }
    // One iteration = one time step with every anchor, each anchor processed separately.
    std::vector<core::RangeSet> all(static_cast<std::size_t>(anchors));
    for (int a = 0; a < anchors; ++a) {
      all[static_cast<std::size_t>(a)].anchor_index = a;
      for (const auto& m : extractor.Extract(d.cirs[step][static_cast<std::size_t>(a)])) {
        all[static_cast<std::size_t>(a)].ranges.push_back({m.range_m, std::abs(m.amplitude)});
      }
    }
    benchmark::DoNotOptimize(tracker.Step(d.samples[step].t_s, all));
    ++step;
  }
  state.SetItemsProcessed(state.iterations() * anchors);
  state.counters["anchor_steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * anchors), benchmark::Counter::kIsRate);
}

// The scenario's MINT options (its method section).
const methods::mint::MintOptions& ScenarioMint() {
  return *static_cast<const methods::mint::MintOptions*>(SeminarRoom().scenario.variants.front().experiment.method.options.get());
}

void BM_MintAnchorStep(benchmark::State& state) {
  RunSteps(state, ScenarioMint(), SeminarRoom().scenario.variants.front().experiment.mpc);
}
BENCHMARK(BM_MintAnchorStep)->Unit(benchmark::kMicrosecond);

void BM_MintAnchorStepNoSafeguards(benchmark::State& state) {
  auto mint = ScenarioMint();
  mint.reassociate = false;
  mint.innovation_gate_chi2 = 0.0;
  mint.relocalization.enabled = false;
  mint.constrain_to_room = false;
  RunSteps(state, mint, SeminarRoom().scenario.variants.front().experiment.mpc);
}
BENCHMARK(BM_MintAnchorStepNoSafeguards)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mirage::bench
