// SPDX-License-Identifier: MIT
// The six faces of an axis-aligned box (BoxReflectors): their names, order, blocking flag and
// coefficient; each face's rectangle is exactly the box's face (its plane, its four corners); a
// straight segment through the box crosses exactly two faces at the expected fractions and is
// blocked, one passing above or beside it, or lying inside it, or ending on a face, crosses none.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "mirage/geometry/reflector_3d.h"

namespace mirage::geometry {
namespace {

constexpr double kTol = 1e-12;

// A crate 2 m x 3 m x 1.5 m standing on the floor: [1, 3] x [2, 5] x [0, 1.5].
const Vec3 kLo(1.0, 2.0, 0.0);
const Vec3 kHi(3.0, 5.0, 1.5);

// The four corners of a rectangle, origin +- u u_half +- v v_half, sorted.
std::vector<Vec3> Corners(const Reflector3& r) {
  std::vector<Vec3> out;
  for (const double s : {-1.0, 1.0}) {
    for (const double t : {-1.0, 1.0}) out.push_back(r.origin_m + s * r.u_half_m * r.u + t * r.v_half_m * r.v);
  }
  return out;
}

// The box corners with coordinate `axis` at `value`.
std::vector<Vec3> BoxFaceCorners(int axis, double value) {
  std::vector<Vec3> out;
  for (const double x : {kLo.x(), kHi.x()}) {
    for (const double y : {kLo.y(), kHi.y()}) {
      for (const double z : {kLo.z(), kHi.z()}) {
        const Vec3 c(x, y, z);
        if (c(axis) == value) out.push_back(c);
      }
    }
  }
  return out;
}

// Every corner in `a` matches one in `b` (both of size 4).
void ExpectSameCorners(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const std::string& name) {
  ASSERT_EQ(a.size(), 4u) << name;
  ASSERT_EQ(b.size(), 4u) << name;
  for (const auto& p : b) {
    const bool found = std::any_of(a.begin(), a.end(), [&](const Vec3& q) { return (p - q).norm() < kTol; });
    EXPECT_TRUE(found) << name << ": no corner at " << p.transpose();
  }
}

// The faces crossed by a -> b, by name.
std::vector<std::string> Crossed(const std::vector<Reflector3>& faces, const Vec3& a_m, const Vec3& b_m) {
  std::vector<std::string> out;
  for (const auto& f : faces) {
    if (CrossingFraction(f, a_m, b_m)) out.push_back(f.name);
  }
  return out;
}

TEST(BoxReflectors, GivesSixBlockingFacesWithTheDocumentedNamesAndCoefficient) {
  const auto faces = BoxReflectors("crate", kLo, kHi, 0.4);

  ASSERT_EQ(faces.size(), 6u);
  const std::array<std::string, 6> names{"crate bottom", "crate top", "crate y-", "crate x+", "crate y+", "crate x-"};
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(faces[k].name, names[k]);
    EXPECT_TRUE(faces[k].blocks) << faces[k].name;
    EXPECT_DOUBLE_EQ(faces[k].reflection_coeff, 0.4) << faces[k].name;
  }
  EXPECT_DOUBLE_EQ(BoxReflectors("b", kLo, kHi)[0].reflection_coeff, 1.0);  // the default
}

TEST(BoxReflectors, EachFaceCoversExactlyTheBoxFace) {
  const auto faces = BoxReflectors("crate", kLo, kHi, 1.0);
  ASSERT_EQ(faces.size(), 6u);
  // (axis, value) of each face in the documented order: bottom, top, y-, x+, y+, x-.
  const std::array<std::pair<int, double>, 6> planes{{{2, kLo.z()}, {2, kHi.z()}, {1, kLo.y()}, {0, kHi.x()},
                                                     {1, kHi.y()}, {0, kLo.x()}}};
  for (std::size_t k = 0; k < 6; ++k) {
    const Reflector3& f = faces[k];
    SCOPED_TRACE(f.name);
    const auto [axis, value] = planes[k];
    // Orthonormal in-plane axes, the normal along the face's axis, the centre on the face.
    EXPECT_NEAR(f.u.norm(), 1.0, kTol);
    EXPECT_NEAR(f.v.norm(), 1.0, kTol);
    EXPECT_NEAR(f.u.dot(f.v), 0.0, kTol);
    EXPECT_NEAR(std::abs(f.normal()(axis)), 1.0, kTol);
    EXPECT_NEAR(f.origin_m(axis), value, kTol);
    EXPECT_GT(f.u_half_m, 0.0);
    EXPECT_GT(f.v_half_m, 0.0);
    ExpectSameCorners(Corners(f), BoxFaceCorners(axis, value), f.name);
  }
}

TEST(BoxReflectors, ASegmentThroughTheBoxCrossesTwoOppositeFacesAndIsBlocked) {
  const auto faces = BoxReflectors("crate", kLo, kHi);

  // Along x through the middle: in at x = 1 (t = 1/4), out at x = 3 (t = 3/4).
  const Vec3 a(0.0, 3.5, 0.75), b(4.0, 3.5, 0.75);
  EXPECT_EQ(Crossed(faces, a, b), (std::vector<std::string>{"crate x+", "crate x-"}));
  ASSERT_TRUE(CrossingFraction(faces[5], a, b).has_value());
  ASSERT_TRUE(CrossingFraction(faces[3], a, b).has_value());
  EXPECT_NEAR(*CrossingFraction(faces[5], a, b), 0.25, 1e-12);
  EXPECT_NEAR(*CrossingFraction(faces[3], a, b), 0.75, 1e-12);
  EXPECT_FALSE(IsSegmentClear(faces, a, b));
  EXPECT_FALSE(IsSegmentClear(faces, b, a));

  // Vertically through bottom and top: z from -1.5 to 3, so t = 1/3 and 2/3.
  const Vec3 c(2.0, 3.0, -1.5), d(2.0, 3.0, 3.0);
  EXPECT_EQ(Crossed(faces, c, d), (std::vector<std::string>{"crate bottom", "crate top"}));
  EXPECT_NEAR(*CrossingFraction(faces[0], c, d), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(*CrossingFraction(faces[1], c, d), 2.0 / 3.0, 1e-12);
  EXPECT_FALSE(IsSegmentClear(faces, c, d));

  // Diagonally, in through y- and out through the top: from (2, 1, 0.5) to (2, 5, 2.5), the line
  // z = 0.5 + 0.5 (y - 1) meets y = 2 at z = 1 (inside) and z = 1.5 at y = 3 (inside).
  const Vec3 e(2.0, 1.0, 0.5), f(2.0, 5.0, 2.5);
  EXPECT_EQ(Crossed(faces, e, f), (std::vector<std::string>{"crate top", "crate y-"}));
  EXPECT_FALSE(IsSegmentClear(faces, e, f));
  // Skipping both faces it crosses clears it; skipping one does not.
  EXPECT_TRUE(IsSegmentClear(faces, e, f, 1, 2));
  EXPECT_FALSE(IsSegmentClear(faces, e, f, 1));
}

TEST(BoxReflectors, ASegmentPassingAboveBesideOrInsideTheBoxCrossesNone) {
  const auto faces = BoxReflectors("crate", kLo, kHi);
  struct Case {
    const char* what;
    Vec3 a, b;
  };
  const std::vector<Case> cases{
      {"above, along x", Vec3(0.0, 3.5, 1.6), Vec3(4.0, 3.5, 1.6)},
      {"beside, along y", Vec3(3.2, 0.0, 0.75), Vec3(3.2, 7.0, 0.75)},
      {"over a corner, diagonally", Vec3(0.0, 0.0, 2.0), Vec3(4.0, 6.0, 1.6)},
      {"inside the box", Vec3(1.5, 2.5, 0.5), Vec3(2.5, 4.5, 1.0)},
      {"from outside to a point on the x- face", Vec3(0.0, 3.5, 0.75), Vec3(1.0, 3.5, 0.75)},
      {"from a point on the top face upwards", Vec3(2.0, 3.0, 1.5), Vec3(2.0, 3.0, 2.5)},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    EXPECT_TRUE(Crossed(faces, c.a, c.b).empty());
    EXPECT_TRUE(IsSegmentClear(faces, c.a, c.b));
  }
  // Just over the top by 1 mm is clear; 1 mm below it is blocked.
  EXPECT_TRUE(IsSegmentClear(faces, Vec3(0.0, 3.5, 1.501), Vec3(4.0, 3.5, 1.501)));
  EXPECT_FALSE(IsSegmentClear(faces, Vec3(0.0, 3.5, 1.499), Vec3(4.0, 3.5, 1.499)));
}

}  // namespace
}  // namespace mirage::geometry
