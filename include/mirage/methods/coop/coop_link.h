// SPDX-License-Identifier: MIT
// The radio links of anchorless cooperative tracking (Kulmer et al., Sec. I, II, IV-D; digest
// anchorless_coop_kulmer.md Sec. 1.1, 2.9, 2.10): every agent measures its own channel (self
// link) and the channel to every other agent once per unordered pair (reciprocity, App. B); with
// a fixed anchor, every agent also measures the channel from the anchor.
//
// Antennas. An agent carries a transmit and a receive antenna side by side (Sec. IV-A). The
// paper's model puts both at the agent position; then a self path off a corner of two walls
// degenerates into the corner point. We keep the real geometry in both the simulator and the
// filter: the TX antenna sits at p + s/2 e_x and the RX antenna at p - s/2 e_x (s the antenna
// spacing, orientation fixed as on the paper's measurement trolley), so a self link is a short
// bistatic link whose "line of sight" is the antenna coupling, which the filter gates out.
// Relative links run from the TX antenna of the lower-indexed agent to the RX antenna of the
// other; anchor links from the anchor to the agent's RX antenna.
#pragma once

#include <string>
#include <vector>

#include "mirage/core/types.h"

namespace mirage::methods::coop {

/// What a link connects.
enum class LinkKind {
  kSelf,      ///< an agent's own channel (tx agent == rx agent)
  kRelative,  ///< agent tx -> agent rx, tx < rx
  kAnchor,    ///< the fixed anchor -> agent rx
};

/// One measured channel per step.
struct Link {
  LinkKind kind = LinkKind::kSelf;
  int tx_agent = 0;  ///< transmitting agent (-1 for the anchor)
  int rx_agent = 0;  ///< receiving agent
  /// "self 1", "rel 1-2", "anchor-2" (1-based agent numbers), for reports.
  [[nodiscard]] std::string Name() const;
};

/// The links of M agents, in the paper's stacking order (Eq. 12): self links, then relative links
/// (1,2), (1,3), ..., (M-1,M), then one anchor link per agent when with_anchor.
std::vector<Link> EnumerateLinks(int agents, bool with_anchor);

/// Antenna offsets from the agent position: TX at p + tx_offset, RX at p + rx_offset.
struct AntennaLayout {
  double spacing_m = 0.05;  ///< distance between an agent's TX and RX antennas (m), >= 0
  [[nodiscard]] Vec2 tx_offset() const { return Vec2(0.5 * spacing_m, 0.0); }
  [[nodiscard]] Vec2 rx_offset() const { return Vec2(-0.5 * spacing_m, 0.0); }
};

/// Transmit and receive antenna positions of a link for the given agent positions.
struct LinkEnds {
  Vec2 tx_m = Vec2::Zero();
  Vec2 rx_m = Vec2::Zero();
};
LinkEnds AntennaPositions(const Link& link, const std::vector<Vec2>& agents_m, const Vec2& anchor_m,
                          const AntennaLayout& antennas);

}  // namespace mirage::methods::coop
