// SPDX-License-Identifier: MIT
// Shared data of the benchmarks: the seminar-room scenario with the CIRs of one simulated run of
// trajectory 1, so that every benchmark works on realistic signals (DM, noise, 2nd-order paths).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/channel/specular_path.h"
#include "mirage/core/rng.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/trajectory.h"
#include "mirage/geometry/virtual_anchor.h"
#include "mirage/geometry/visibility.h"
#include "mirage/io/scenario.h"

namespace mirage::bench {

/// The seminar-room scenario and one run's worth of CIRs per anchor.
struct SeminarRoomData {
  io::Scenario scenario;
  geometry::VirtualAnchorSet vas;
  std::unique_ptr<channel::CirSynthesizer> synthesizer;
  std::vector<geometry::TrajectorySample> samples;
  std::vector<std::vector<core::Cir>> cirs;  ///< [step][anchor]
};

/// Built once per process (the benchmarks only read it).
inline const SeminarRoomData& SeminarRoom() {
  static const SeminarRoomData data = [] {
    SeminarRoomData d;
    d.scenario = io::LoadScenario(std::string(MIRAGE_SOURCE_DIR) + "/examples/seminar_room.yaml");
    const auto& config = d.scenario.variants.front().experiment;
    std::vector<Vec2> anchors_m;
    for (const auto& a : config.anchors) anchors_m.push_back(a.position_m.head<2>());
    d.vas = geometry::VirtualAnchorSet::Generate(anchors_m, config.plan, config.channel_max_order);
    d.synthesizer = std::make_unique<channel::CirSynthesizer>(config.channel);
    const auto& spec = config.trajectories.front();
    d.samples = geometry::SampleTrajectory(spec.waypoints_m, spec.speed_mps, spec.dt_s);
    core::Rng rng(config.seed);
    core::Rng diffuse = rng.Substream("diffuse"), noise = rng.Substream("noise");
    for (const auto& s : d.samples) {
      std::vector<core::Cir> per_anchor;
      for (int a = 0; a < static_cast<int>(anchors_m.size()); ++a) {
        const auto paths = channel::ComputeSpecularPaths(d.vas, a, config.plan, s.position_m, config.channel.pulse.carrier_hz,
                                                         config.channel.medium);
        const double los_m = (s.position_m - anchors_m[static_cast<std::size_t>(a)]).norm();
        per_anchor.push_back(d.synthesizer->Synthesize(paths, los_m, diffuse, noise).cir);
      }
      d.cirs.push_back(std::move(per_anchor));
    }
    return d;
  }();
  return data;
}

}  // namespace mirage::bench
