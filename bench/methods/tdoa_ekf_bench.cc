// SPDX-License-Identifier: MIT
// The TDOA filter on run 0 of examples/uwb_tdoa_3d.yaml (200 Hz pairs, box NLOS, 1 % outliers):
// one iteration processes the run's 4000 epochs; the three updates side by side (0 rekf: IRLS
// over 6 prior rows and a 0.1 s window's ~20 rows; 1 gated_ekf and 2 ekf: one row per epoch).
// items_per_second is epochs per second.
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "mirage/io/scenario.h"
#include "mirage/methods/tdoa_ekf/tdoa_ekf.h"
#include "mirage/pipeline/uwb_tdoa_source.h"

namespace mirage::bench {
namespace {

struct TdoaRun {
  io::Scenario scenario;
  std::vector<core::Epoch> epochs;
  Vec3 start_m = Vec3::Zero();
};

const TdoaRun& Run0() {
  static const TdoaRun run = [] {
    TdoaRun r;
    r.scenario = io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/uwb_tdoa_3d.yaml");
    pipeline::UwbTdoaSource source(r.scenario.variants.front().experiment, 0, 0);
    r.start_m = source.TruthAt(0);
    while (auto step = source.Next()) r.epochs.push_back(step->epoch);
    return r;
  }();
  return run;
}

void BM_TdoaEkfRun(benchmark::State& state) {
  const TdoaRun& run = Run0();
  const char* updates[] = {"rekf", "gated_ekf", "ekf"};
  methods::tdoa_ekf::TdoaEkfOptions options;
  options.update = updates[state.range(0)];
  methods::World world;
  for (const auto& a : run.scenario.variants.front().experiment.anchors) world.anchors.push_back({a.id, a.position_m});
  world.agents = {"tag"};
  for (auto _ : state) {
    methods::tdoa_ekf::TdoaEkf filter(options, world);
    filter.Initialize({run.epochs.front().t_s, {run.start_m}});
    for (const auto& epoch : run.epochs) benchmark::DoNotOptimize(filter.Process(epoch));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(run.epochs.size()));
  state.SetLabel(options.update);
}
BENCHMARK(BM_TdoaEkfRun)->ArgName("update")->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mirage::bench
