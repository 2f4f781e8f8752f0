// SPDX-License-Identifier: MIT
// One step of the cooperative EKF (Kulmer et al. Algorithm 1: prediction, expected paths by ray
// tracing, association, stacked update, amplitude bookkeeping) for M = 2 agents with S walls in
// the state (M = 2 with 30 walls is the size of interest; S = 10 and 60 show how the cost grows
// with the state size 4M + S). The room is an irregular S-gon of radius 3.4-4.6 m, so that every wall reflects
// and none is collinear with another; the links' signals are the exact path lengths (no CIRs, no
// extraction), precomputed for a 200-step walk, so that only the filter is timed.
#include <cmath>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "mirage/core/constants.h"
#include "mirage/geometry/floor_plan.h"
#include "mirage/geometry/image_source.h"
#include "mirage/methods/coop/coop_tracker.h"

namespace mirage::bench {
namespace {

using methods::coop::LinkSignal;

constexpr int kSteps = 200;

class FixedSignal final : public LinkSignal {
 public:
  explicit FixedSignal(std::vector<double> ranges) : ranges_(std::move(ranges)) {}
  [[nodiscard]] std::vector<double> Ranges(int count) const override {
    std::vector<double> out = ranges_;
    if (static_cast<int>(out.size()) > count) out.resize(static_cast<std::size_t>(count));
    return out;
  }
  [[nodiscard]] double AmplitudeAt(double range_m) const override { return 1.0 / range_m; }

 private:
  std::vector<double> ranges_;
};

// Vertex i at radius 4 m + 0.6 m sin(2.3 i): irregular, so that paths of different walls do not
// share a length by symmetry (a regular polygon's would, and the ambiguity pruning would drop them).
Vec2 Vertex(int i, int sides) {
  const double angle = 2.0 * core::kPi * i / sides;
  const double radius_m = 4.0 + 0.6 * std::sin(2.3 * (i % sides));
  return radius_m * Vec2(std::cos(angle), std::sin(angle));
}

geometry::FloorPlan Polygon(int sides) {
  std::vector<geometry::Wall> walls;
  for (int i = 0; i < sides; ++i) walls.push_back({Vertex(i, sides), Vertex(i + 1, sides), 0.5, ""});
  return geometry::FloorPlan(std::move(walls), {});
}

void BM_CoopStepTwoAgents(benchmark::State& state) {
  const int walls = static_cast<int>(state.range(0));
  const geometry::FloorPlan plan = Polygon(walls);
  const auto links = methods::coop::EnumerateLinks(2, false);
  const methods::coop::AntennaLayout antennas;
  // Two agents on straight walks at 2.5 and 2 cm per step.
  std::vector<std::vector<Vec2>> truth;
  for (int n = 0; n <= kSteps; ++n) truth.push_back({Vec2(-2.0 + 0.025 * n, -1.0), Vec2(1.5, 2.0 - 0.02 * n)});
  std::vector<std::vector<FixedSignal>> signals(kSteps + 1);
  for (int n = 1; n <= kSteps; ++n) {
    for (const auto& link : links) {
      const auto ends = methods::coop::AntennaPositions(link, truth[static_cast<std::size_t>(n)], Vec2::Zero(), antennas);
      std::vector<double> ranges;
      for (const auto& seq : geometry::VisibleImagePaths(plan, ends.tx_m, ends.rx_m, 2)) {
        ranges.push_back(geometry::ComputeImagePath(plan, seq, ends.tx_m, ends.rx_m).length_m);
      }
      signals[static_cast<std::size_t>(n)].emplace_back(std::move(ranges));
    }
  }
  methods::coop::CoopTracker tracker(methods::coop::CoopOptions{}, plan, links, antennas, std::nullopt,
                                     methods::coop::PulseFacts{0.5e-9, 0.063, core::Medium{}});
  tracker.Initialize(truth.front(), 0.0);
  int n = 0;
  int rows = 0;
  for (auto _ : state) {
    if (++n > kSteps) {
      state.PauseTiming();
      tracker.Initialize(truth.front(), 0.0);
      n = 1;
      state.ResumeTiming();
    }
    std::vector<const LinkSignal*> pointers;
    for (const auto& s : signals[static_cast<std::size_t>(n)]) pointers.push_back(&s);
    const auto info = tracker.Step(n, pointers);
    for (const auto& l : info.links) rows += l.associated;
    benchmark::DoNotOptimize(tracker.state().mean().data());
  }
  state.counters["state_size"] = tracker.state().dimension();
  state.counters["ranges_per_step"] = benchmark::Counter(rows, benchmark::Counter::kAvgIterations);
  state.counters["steps_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CoopStepTwoAgents)->Arg(10)->Arg(30)->Arg(60)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mirage::bench
