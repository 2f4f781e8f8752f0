// SPDX-License-Identifier: MIT
// A radio link between two antennas, each mounted on an agent (at a fixed offset from its
// position) or on a fixed anchor: an anchor-agent channel, an agent's own channel (transmitter
// and receiver side by side on one agent, Kulmer et al. Sec. IV-A) or the channel between two
// agents. A method that consumes CIRs names the links it measures; the simulator synthesises one
// CIR per link and epoch.
#pragma once

#include <span>
#include <string>

#include "mirage/core/types.h"

namespace mirage::channel {

/// Where one end of a link sits.
struct LinkEnd {
  int agent = -1;                 ///< the carrying agent's index, or -1
  int anchor = -1;                ///< the anchor's index when agent is -1
  Vec2 offset_m = Vec2::Zero();   ///< antenna position relative to the agent (fixed orientation)
};

/// One measured link.
struct LinkSpec {
  std::string id;  ///< "self 1", "rel 1-2", "anchor-2", for reports and CSV files
  LinkEnd tx;
  LinkEnd rx;
  /// An agent's own channel: both ends on one agent.
  [[nodiscard]] bool self() const { return tx.agent >= 0 && tx.agent == rx.agent; }
};

/// The position of a link end for the given agent and anchor positions (m).
inline Vec2 EndPosition(const LinkEnd& end, std::span<const Vec2> agents_m, std::span<const Vec2> anchors_m) {
  if (end.agent >= 0) return agents_m[static_cast<std::size_t>(end.agent)] + end.offset_m;
  return anchors_m[static_cast<std::size_t>(end.anchor)];
}

}  // namespace mirage::channel
