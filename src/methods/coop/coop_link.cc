// SPDX-License-Identifier: MIT
#include "mirage/methods/coop/coop_link.h"

#include <fmt/format.h>

namespace mirage::methods::coop {

std::string Link::Name() const {
  switch (kind) {
    case LinkKind::kSelf:
      return fmt::format("self {}", rx_agent + 1);
    case LinkKind::kRelative:
      return fmt::format("rel {}-{}", tx_agent + 1, rx_agent + 1);
    case LinkKind::kAnchor:
      return fmt::format("anchor-{}", rx_agent + 1);
  }
  return "?";
}

std::vector<Link> EnumerateLinks(int agents, bool with_anchor) {
  std::vector<Link> links;
  for (int m = 0; m < agents; ++m) links.push_back({LinkKind::kSelf, m, m});
  for (int a = 0; a < agents; ++a) {
    for (int b = a + 1; b < agents; ++b) links.push_back({LinkKind::kRelative, a, b});
  }
  if (with_anchor) {
    for (int m = 0; m < agents; ++m) links.push_back({LinkKind::kAnchor, -1, m});
  }
  return links;
}

LinkEnds AntennaPositions(const Link& link, const std::vector<Vec2>& agents_m, const Vec2& anchor_m,
                          const AntennaLayout& antennas) {
  LinkEnds ends;
  ends.rx_m = agents_m[static_cast<std::size_t>(link.rx_agent)] + antennas.rx_offset();
  ends.tx_m = link.kind == LinkKind::kAnchor ? anchor_m
                                             : agents_m[static_cast<std::size_t>(link.tx_agent)] + antennas.tx_offset();
  return ends;
}

}  // namespace mirage::methods::coop
