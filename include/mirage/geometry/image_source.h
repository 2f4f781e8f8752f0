// SPDX-License-Identifier: MIT
// The image-source engine: the one place that mirrors points at walls, builds the images of a
// source for a wall sequence, ray-traces the path they stand for and gives its length with
// derivatives. Virtual anchors are a cache of it for fixed anchors (Lafer 2014 Sec. 3.1, 4.3.2;
// virtual_anchor.h, visibility.h); the cooperative tracker uses it for moving transmitters
// (Kulmer et al., "Anchorless cooperative tracking using multipath channel information",
// Sec. II-B, Eq. (18)-(20), App. A-C; digest anchorless_coop_kulmer.md Sec. 2.2).
//
// Mirror. A wall s is the line through its start point a_s with unit normal n_s = U e_s (e_s the
// direction start -> end, U the +90 degree rotation). Its mirror is
//   f_s(x) = x - 2 ((x - a_s)^T n_s) n_s,
// Kulmer's Eq. (18) f_s(x) = x - 2 n_s (n_s^T x - c_s) with c_s = n_s^T a_s, evaluated in the form
// the virtual anchors have always used (both round identically for axis-aligned walls).
//
// Path. A wall sequence [s_1 .. s_I] lists the walls in the order the signal meets them from the
// source (transmitter). The images are a_0 = tx, a_k = f_{s_k}(a_{k-1}); the path is as long as
// the straight line rx -> a_I (Eq. 19). With u = (rx - a_I) / |rx - a_I|, A_s = I - 2 n_s n_s^T,
// Phi = A_{s_I}...A_{s_1} and Psi_i = A_{s_I}...A_{s_{i+1}} (digest Sec. 2.2, our derivation):
//   d length / d rx = u,   d length / d tx = -Phi^T u,
//   d length / d c_{s_i} = -2 n_{s_i}^T Psi_i^T u   (c the wall's offset along its normal).
// Only the normal offset of a wall enters a path length (digest Sec. 2.2 "Consequence"), which is
// why the cooperative filter keeps one offset per wall in its state.
//
// Trace (Lafer 2014 Sec. 4.3.2, Fig. 4.17): from the receiver the ray towards a_I must hit the
// finite segment of s_I; from that reflection point the ray towards a_{I-1} must hit s_{I-1}, and
// so on down to the source; no leg may cross another wall (the walls a leg starts or ends on are
// skipped) or an obstacle (FloorPlan::IsLegClear).
//
// Third dimension (2.5-D plans). Walls are vertical and span the floor to the ceiling, so a wall
// mirrors (x, y) and keeps z, the images of tx = (x, z) are (a_k, z), and the path unfolds into
// the straight 3-D line rx -> (a_I, z_tx) of length sqrt(l_xy^2 + dz^2). A reflection point's
// height is interpolated linearly along that line; a path whose reflection point lies below the
// floor or above the ceiling does not exist. The Vec2 functions work in the plane and do no 3-D
// work; the Vec3 overloads add the heights on top of the same planar trace.
//
// Tolerances, one set for every function here:
//   - kOnLineTolerance_m (1 nm): a point this close to a wall's line lies on it, and mirroring it
//     there gives itself; a wall whose end points are this close to another wall's line is
//     collinear with it; an order-0 path this short (tx at rx) does not exist: a receiver on top
//     of the transmitter has no line of sight, only antenna coupling or the near field.
//   - kLegFractionTolerance (1e-9): a reflection point must split the leg from the previous vertex
//     towards its image at a fraction t in (1e-9, 1 - 1e-9). t at 0 is a path through a corner or
//     a receiver on the wall, t at 1 an image on its own wall (its source lay on the wall line).
//   - legs: FloorPlan::IsLegClear ignores touching a wall within 1 nm of either end of a leg.
//
// Floor and ceiling as reflectors (acoustics, not built yet). A SurfaceId will also name the two
// horizontal planes, with reserved negative ids (-2 floor, -3 ceiling; -1 stays "no surface").
// A horizontal plane z = h mirrors z -> 2 h - z and keeps (x, y), so it commutes with the wall
// mirrors; the 3-D trace will find its reflection point where the unfolded line crosses z = h and
// require that point to lie inside the walls (FloorPlan::Encloses); its derivative adds d/dh.
// The Vec2 functions will keep rejecting such sequences: 2-D methods never see them.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::geometry {

/// Highest reflection order the engine traces (orders above 3 are rarely above the noise indoors).
inline constexpr int kMaxImageOrder = 6;
/// A point this close to a wall's line (m) lies on it; see the file comment.
inline constexpr double kOnLineTolerance_m = 1e-9;
/// A reflection point must split its leg at a fraction in (this, 1 - this); see the file comment.
inline constexpr double kLegFractionTolerance = 1e-9;

/// A reflecting surface of a FloorPlan: the index of a wall in FloorPlan::walls() (>= 0). The
/// floor and the ceiling will get reserved negative ids (see the file comment).
using SurfaceId = int;

/// The surfaces of one path in the order the signal meets them, from the source on.
using WallSequence = std::vector<SurfaceId>;

/// The unit normal n_s = U e_s of a wall (e_s the direction start -> end, U the +90 degree
/// rotation): the direction in which an offset c_s moves the wall. The wall must have length.
Vec2 WallNormal(const Wall& wall);

/// The mirror image f_s(point) of a point (m) at the wall's infinite line.
Vec2 MirrorAtWall(const Wall& wall, const Vec2& point_m);
/// The mirror image of a 3-D point (m) at the vertical wall: (x, y) mirrored, z kept.
Vec3 MirrorAtWall(const Wall& wall, const Vec3& point_m);

/// The generation rules: true if the image image_m, last mirrored at previous_wall (-1 for the
/// source itself), mirrored at wall can stand for a physical path. False when wall is
/// previous_wall (the image returns to its parent), when wall is collinear with previous_wall (the
/// image returns to its grandparent) and when image_m lies on the wall's line (the image is
/// image_m itself). Only (x, y) matter, so 3-D callers pass the planar part.
bool CanMirror(const FloorPlan& plan, SurfaceId previous_wall, SurfaceId wall, const Vec2& image_m);

/// The images of a source for a wall sequence: images[0] = source_m, images[k] = f_{walls[k-1]}(
/// images[k-1]) (m); walls.size() + 1 points. Plain mirroring: the generation rules are not
/// applied. walls.size() must be at most kMaxImageOrder.
std::vector<Vec2> ImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec2& source_m);
/// The same in 3-D: every image keeps the source's height.
std::vector<Vec3> ImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec3& source_m);

/// Back-traces the path of an image chain from the receiver (see the file comment).
/// @param walls      the sequence, walls.size() <= kMaxImageOrder.
/// @param images_m   its image chain (ImageChain, or a cache of it), walls.size() + 1 points (m).
/// @param rx_m       the receiver (m).
/// @param vertices_m walls.size() + 2 points, written in back-trace order: rx, the reflection
///                   points on walls.back() .. walls.front(), the source (m). Left partly
///                   written when the path does not exist.
/// @return true if the path exists.
bool TraceImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, std::span<const Vec2> images_m,
                     const Vec2& rx_m, std::span<Vec2> vertices_m);
/// The same in 3-D: the images keep the source's height images_m[0].z(); the reflection points'
/// heights are interpolated along the unfolded path and must lie within [floor_z_m, ceiling_z_m].
bool TraceImageChain(const FloorPlan& plan, std::span<const SurfaceId> walls, std::span<const Vec3> images_m,
                     const Vec3& rx_m, std::span<Vec3> vertices_m);

/// Length of one specular path (planar) and its derivatives.
struct ImagePath {
  double length_m = 0.0;        ///< |rx - a_I| (m)
  Vec2 image_m = Vec2::Zero();  ///< the transmitter's image a_I (m)
  Vec2 d_rx = Vec2::Zero();     ///< d length / d rx (unitless)
  Vec2 d_tx = Vec2::Zero();     ///< d length / d tx (unitless)
  /// d length / d c_s for each wall of the sequence, in sequence order (a wall met twice, e.g.
  /// s1 s2 s1, appears twice; the caller sums).
  std::vector<double> d_offset;
};

/// Length of one specular path in 3-D, sqrt(l_xy^2 + dz^2), and its derivatives.
struct ImagePath3 {
  double length_m = 0.0;        ///< |rx - (a_I, z_tx)| (m)
  Vec3 image_m = Vec3::Zero();  ///< the transmitter's image (a_I, z_tx) (m)
  Vec3 d_rx = Vec3::Zero();     ///< d length / d rx (unitless)
  Vec3 d_tx = Vec3::Zero();     ///< d length / d tx (unitless)
  /// d length / d c_s for each wall of the sequence, in sequence order (as ImagePath::d_offset).
  std::vector<double> d_offset;
};

/// The image-source length of tx -> walls[0] -> ... -> walls.back() -> rx and its derivatives.
/// Self channel: tx == rx (then the total derivative with respect to the agent is d_rx + d_tx).
/// Wall indices must be valid for plan, at most kMaxImageOrder of them. At zero length the
/// direction is undefined and the derivatives are zero.
ImagePath ComputeImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec2& tx_m,
                           const Vec2& rx_m);
/// The same in 3-D (tx_m, rx_m in m).
ImagePath3 ComputeImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls, const Vec3& tx_m,
                            const Vec3& rx_m);

/// The traced path tx -> walls -> rx: the vertices tx, the reflection points in sequence order, rx
/// (m); std::nullopt when the path does not exist: a mirror breaks the generation rules
/// (CanMirror), the trace fails (TraceImageChain) or it is a line of sight of zero length.
/// At most kMaxImageOrder walls.
std::optional<std::vector<Vec2>> TraceImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls,
                                                const Vec2& tx_m, const Vec2& rx_m);
/// The same in 3-D.
std::optional<std::vector<Vec3>> TraceImagePath(const FloorPlan& plan, std::span<const SurfaceId> walls,
                                                const Vec3& tx_m, const Vec3& rx_m);

/// All wall sequences of order 0 .. max_order whose paths exist between tx and rx (m), i.e. for
/// which TraceImagePath succeeds, ordered by order, then by wall indices. max_order must be in
/// [0, kMaxImageOrder]; the cost grows as walls^max_order.
std::vector<WallSequence> VisibleImagePaths(const FloorPlan& plan, const Vec2& tx_m, const Vec2& rx_m, int max_order);
/// The same in 3-D.
std::vector<WallSequence> VisibleImagePaths(const FloorPlan& plan, const Vec3& tx_m, const Vec3& rx_m, int max_order);

/// The sequence of the same path in the other direction (reciprocity, Kulmer App. B, Eq. 22):
/// the reversed list. The lengths of (tx, rx, s) and (rx, tx, reversed s) are equal.
WallSequence Reversed(const WallSequence& walls);

}  // namespace mirage::geometry
