// SPDX-License-Identifier: MIT
// Reflectors in 3-D: planar rectangles of any orientation (the floor, the ceiling, walls,
// partitions of limited height, table tops) and the image-source paths between two points among
// them. This is the acoustic side of the image-source engine (Bordoy 2020 Sec. 3.2, Eq. 3.34-3.35
// and 8.68-8.69; Allen & Berkley): sound reflects off every large surface of a hall, horizontal
// ones included, and a finite partition both reflects (where the reflection point lies on it)
// and blocks (where a leg crosses it). The 2.5-D engine of image_source.h, whose walls span floor
// to ceiling, stays the radio methods' engine; ReflectorsFromPlan turns such a plan into
// reflectors so that both describe the same building.
//
// Mirror (Eq. 3.34 with the digest's sign fix, typo 2): a plane with unit normal n through the
// point o maps x to x - 2 ((x - o)^T n) n, whichever side n points to.
//
// Path. A surface sequence [s_1 .. s_I] lists the reflectors in the order the sound meets them
// from the source. The images are a_0 = tx, a_k = mirror_{s_k}(a_{k-1}); the path is as long as
// |rx - a_I|. The trace runs back from rx: the straight line towards a_I must cross the plane of
// s_I inside its rectangle, from there the line towards a_{I-1} must cross s_{I-1}, and so on to
// the source. No leg may cross a blocking reflector other than the ones it starts or ends on.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "mirage/core/types.h"
#include "mirage/geometry/floor_plan.h"

namespace mirage::geometry {

/// One planar rectangular reflector: the points origin + s u + t v with |s| <= u_half_m and
/// |t| <= v_half_m. u and v are orthogonal unit vectors; the normal is u x v.
struct Reflector3 {
  std::string name;                 ///< for reports and scenario references ("floor", "W1", "partition 2")
  Vec3 origin_m = Vec3::Zero();     ///< the rectangle's centre (m)
  Vec3 u = Vec3::UnitX();           ///< first in-plane axis (unit)
  Vec3 v = Vec3::UnitY();           ///< second in-plane axis (unit), orthogonal to u
  double u_half_m = 0.0;            ///< half extent along u (m), > 0
  double v_half_m = 0.0;            ///< half extent along v (m), > 0
  /// Pressure reflection coefficient in [0, 1] (concrete 0.9999 at 20 C, Bordoy Sec. 3.1; glass
  /// and wood lower). Simulators scale a path's detection by the product along it.
  double reflection_coeff = 1.0;
  /// The reflector stops sound that crosses it (partitions, walls). A table top reflects but a
  /// scenario may let legs pass it (false) when it stands for a thin or perforated surface.
  bool blocks = true;

  /// The unit normal u x v.
  [[nodiscard]] Vec3 normal() const { return u.cross(v); }
};

/// A horizontal rectangle at height z_m centred on centre_m (the floor, the ceiling, a table top).
Reflector3 HorizontalReflector(std::string name, const Vec2& centre_m, double x_half_m, double y_half_m, double z_m,
                               double reflection_coeff = 1.0);
/// A vertical rectangle above the segment a_m -> b_m in the plane, from z0_m to z1_m (> z0_m):
/// a wall or a partition.
Reflector3 VerticalReflector(std::string name, const Vec2& a_m, const Vec2& b_m, double z0_m, double z1_m,
                             double reflection_coeff = 1.0);
/// The six faces of the axis-aligned box [lo_m, hi_m] (lo_m < hi_m in every coordinate), named
/// "<name> bottom", "<name> top", "<name> y-", "<name> x+", "<name> y+", "<name> x-", blocking, with
/// reflection_coeff: an obstacle (a crate, a cabinet) that a straight leg crosses twice.
std::vector<Reflector3> BoxReflectors(const std::string& name, const Vec3& lo_m, const Vec3& hi_m,
                                      double reflection_coeff = 1.0);
/// A shoebox hall [0, length_x_m] x [0, length_y_m] x [0, height_m]: "floor", "ceiling" and the
/// walls "y=0", "x=max", "y=max", "x=0" in that order, all with reflection_coeff.
std::vector<Reflector3> ShoeboxReflectors(double length_x_m, double length_y_m, double height_m,
                                          double reflection_coeff = 1.0);
/// The reflectors of a 2.5-D floor plan: every wall from the floor to the ceiling (named "W<i+1>",
/// its reflection coefficient), then the floor and the ceiling over the walls' bounding box
/// ("floor", "ceiling", coefficient ceiling_floor_coeff). The plan must have a finite ceiling.
std::vector<Reflector3> ReflectorsFromPlan(const FloorPlan& plan, double ceiling_floor_coeff = 1.0);

/// The mirror image of point_m (m) at the reflector's infinite plane.
Vec3 MirrorAtPlane(const Reflector3& reflector, const Vec3& point_m);

/// Where the segment a_m -> b_m crosses the reflector's rectangle, as the fraction t in (0, 1)
/// along it (the point a + t (b - a)); empty if it does not (parallel, outside the rectangle, or
/// at an end within 1e-9 of the segment's length).
std::optional<double> CrossingFraction(const Reflector3& reflector, const Vec3& a_m, const Vec3& b_m);

/// True if no blocking reflector other than skip_a and skip_b (indices, -1 for none) crosses the
/// segment a_m -> b_m.
bool IsSegmentClear(std::span<const Reflector3> reflectors, const Vec3& a_m, const Vec3& b_m, int skip_a = -1,
                    int skip_b = -1);

/// One traced specular path.
struct SpecularPath3 {
  std::vector<int> surfaces;     ///< reflector indices from the source on; empty: the direct path
  double length_m = 0.0;         ///< |rx - a_I| (m)
  Vec3 image_m = Vec3::Zero();   ///< the source's last image a_I (m)
  std::vector<Vec3> vertices_m;  ///< tx, the reflection points in sequence order, rx (m)
  double reflection_gain = 1.0;  ///< product of the reflection coefficients along the path
};

/// The path tx -> surfaces -> rx, empty when it does not exist: a reflector repeated back to back,
/// tx or an image on a reflector's plane, a reflection point outside its rectangle, or a blocked
/// leg. Surfaces index into reflectors.
std::optional<SpecularPath3> TraceSpecularPath(std::span<const Reflector3> reflectors, std::span<const int> surfaces,
                                               const Vec3& tx_m, const Vec3& rx_m);

/// Every existing path of order 0 .. max_order (max_order in [0, 3]) between tx and rx, by order,
/// then by surface indices.
std::vector<SpecularPath3> SpecularPaths3(std::span<const Reflector3> reflectors, const Vec3& tx_m, const Vec3& rx_m,
                                          int max_order);

}  // namespace mirage::geometry
