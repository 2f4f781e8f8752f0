// SPDX-License-Identifier: MIT
// What a scenario tells an estimator about the world it runs in: what the estimator may know,
// not the truth. The anchors as surveyed, the floor plan as given (possibly wrong, possibly
// empty), the agents it tracks, the radio front end (pulse, sampling, extraction) and the
// scenario's physical facts, from which noise- and motion-dependent defaults are derived.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mirage/channel/cir_synthesizer.h"
#include "mirage/core/physical_keys.h"
#include "mirage/core/types.h"
#include "mirage/dsp/mpc_extractor.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::methods {

/// A known anchor (a fixed transmitter or receiver whose position is given).
struct Anchor {
  std::string id;
  Vec3 position_m = Vec3::Zero();
};

/// The estimator's knowledge of the world.
struct World {
  /// Anchors, in the order their range sets and links refer to (anchor_index).
  std::vector<Anchor> anchors;
  /// The floor plan the estimator is given; empty when the scenario has none.
  geometry::FloorPlan floor_plan;
  /// Names of the agents the estimator tracks: one for a single-agent method (one run per
  /// trajectory), all walking agents for a joint one.
  std::vector<std::string> agents;
  /// Known height of the agents (m), for methods that estimate positions in the plane: ranges
  /// to anchors at other heights are then 3-D. Empty: agents and anchors share one plane.
  std::optional<double> agent_height_m;
  /// The front end: the medium (the signal speed), the pulse (CRLB scale, pulse duration), the
  /// sampling and window of the CIRs.
  channel::ChannelOptions channel;
  /// Multipath-component extraction, for methods that consume CIRs.
  dsp::MpcExtractorOptions mpc;
  /// The records carry each emission's sending time (core::ToaStamps::emission_s): a simulation
  /// told so (measurements.emission_time_known). A recording's toa.csv has no such column.
  bool emission_times_known = false;
  /// The scenario's physical facts (range noise, step time, walking speed, detection, clutter):
  /// what defaults that depend on noise or motion are derived from.
  core::PhysicalKeys physical;
};

}  // namespace mirage::methods
