// SPDX-License-Identifier: MIT
// Specular paths between two points of a room by the image-source model, for channels whose
// transmitter moves: an agent's own channel (transmitter and receiver side by side, the
// reflections return to it) and the channel between two agents (Kulmer et al., "Anchorless
// cooperative tracking using multipath channel information", Sec. II-B, Eq. (18)-(20), App. A-C;
// digest anchorless_coop_kulmer.md Sec. 2.2). Unlike virtual anchors, the images are not fixed:
// they are recomputed from the transmitter and the walls each time.
//
// A wall s is the line n_s^T x = c_s through its segment, n_s = U e_s the unit normal (e_s the
// direction start -> end, U the +90 degree rotation). The mirror operator is
// f_s(x) = x - 2 n_s (n_s^T x - c_s) (Eq. 18). A path with wall sequence [s_1 .. s_I] (in the
// order the signal meets them) has the image a = f_{s_I}(...f_{s_1}(tx)) and length |rx - a|
// (Eq. 19). Derivatives, with u = (rx - a) / |rx - a|, Phi = A_{s_I}...A_{s_1},
// Psi_i = A_{s_I}...A_{s_{i+1}}, A_s = I - 2 n_s n_s^T (digest Sec. 2.2, our derivation):
//   d length / d rx = u,   d length / d tx = -Phi^T u,
//   d length / d c_{s_i} = -2 n_{s_i}^T Psi_i^T u   (the wall's offset along its normal).
// Only the normal offset of a wall enters a path length: a wall's 2-D reference point has one
// observable coordinate (digest Sec. 2.2 "Consequence"), which is why the cooperative filter
// keeps one offset per wall in its state.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::geometry {

/// The unit normal n_s = U e_s of a wall (e_s the direction start -> end, U the +90 degree
/// rotation): the direction in which an offset c_s moves the wall.
Vec2 WallNormal(const Wall& wall);

/// Length of one specular path and its derivatives.
struct ImagePath {
  double length_m = 0.0;
  Vec2 image_m = Vec2::Zero();  ///< the transmitter's image a
  Vec2 d_rx = Vec2::Zero();     ///< d length / d rx
  Vec2 d_tx = Vec2::Zero();     ///< d length / d tx
  /// d length / d c_s for each wall of the sequence, in sequence order (a wall met twice, e.g.
  /// s1 s2 s1, appears twice; the caller sums).
  std::vector<double> d_offset;
};

/// The image-source length of tx -> walls[0] -> ... -> walls.back() -> rx and its derivatives.
/// Self channel: tx == rx (then the total derivative with respect to the agent is d_rx + d_tx).
/// Wall indices must be valid for plan; consecutive walls must differ.
ImagePath ComputeImagePath(const FloorPlan& plan, std::span<const int> walls, const Vec2& tx_m, const Vec2& rx_m);

/// Ray tracing of the same path: every reflection point must lie on its (finite) wall segment
/// with the incoming and outgoing legs on the same side, and no leg may cross another wall or an
/// obstacle. Returns the vertices tx, reflection points, rx, or std::nullopt when the path does
/// not exist. Order 0 is the line of sight (tx != rx).
std::optional<std::vector<Vec2>> TraceImagePath(const FloorPlan& plan, std::span<const int> walls, const Vec2& tx_m,
                                                const Vec2& rx_m);

/// A wall sequence.
using WallSequence = std::vector<int>;

/// All wall sequences of order 1 .. max_order (and the line of sight, order 0, unless tx == rx)
/// whose paths exist between tx and rx, ordered by order then wall indices. Throws std::invalid_argument unless max_order is in
/// [0, 3].
std::vector<WallSequence> VisibleImagePaths(const FloorPlan& plan, const Vec2& tx_m, const Vec2& rx_m, int max_order);

/// The sequence of the same path in the other direction (reciprocity, Kulmer App. B, Eq. 22):
/// the reversed list. The lengths of (tx, rx, s) and (rx, tx, reversed s) are equal.
WallSequence Reversed(const WallSequence& walls);

}  // namespace mirage::geometry
