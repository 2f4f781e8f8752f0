// SPDX-License-Identifier: MIT
#include "mirage/geometry/segment.h"

#include <cmath>

#include <gtest/gtest.h>

namespace mirage::geometry {
namespace {

constexpr double kTol = 1e-12;

// ---------------------------------------------------------------------------------------------
// CrossSegments
// ---------------------------------------------------------------------------------------------

TEST(CrossSegments, FindsTheCrossingOfTwoDiagonalsAtTheirMidpoints) {
  // (0,0)->(2,2) and (0,2)->(2,0) cross at (1,1), half way along both.
  const auto crossing = CrossSegments(Vec2(0, 0), Vec2(2, 2), Vec2(0, 2), Vec2(2, 0));

  ASSERT_TRUE(crossing.has_value());
  EXPECT_NEAR(crossing->t, 0.5, kTol);
  EXPECT_NEAR(crossing->s, 0.5, kTol);
}

TEST(CrossSegments, ReportsDifferentParametersAlongEachSegment) {
  // p->q = (0,0)->(4,0) and a->b = (1,-3)->(1,1) cross at (1,0):
  // t = 1/4 along p->q (x from 0 to 4), s = 3/4 along a->b (y from -3 to 1).
  const Vec2 p(0, 0), q(4, 0), a(1, -3), b(1, 1);

  const auto crossing = CrossSegments(p, q, a, b);

  ASSERT_TRUE(crossing.has_value());
  EXPECT_NEAR(crossing->t, 0.25, kTol);
  EXPECT_NEAR(crossing->s, 0.75, kTol);
  // Both parametrisations give the same point.
  EXPECT_TRUE((p + crossing->t * (q - p)).isApprox(Vec2(1, 0), kTol));
  EXPECT_TRUE((a + crossing->s * (b - a)).isApprox(Vec2(1, 0), kTol));
}

TEST(CrossSegments, SwapsTheParametersWhenTheSegmentsAreSwapped) {
  // Same segments as above with the roles exchanged: t = 3/4, s = 1/4.
  const auto crossing = CrossSegments(Vec2(1, -3), Vec2(1, 1), Vec2(0, 0), Vec2(4, 0));

  ASSERT_TRUE(crossing.has_value());
  EXPECT_NEAR(crossing->t, 0.75, kTol);
  EXPECT_NEAR(crossing->s, 0.25, kTol);
}

TEST(CrossSegments, ReportsParallelSegmentsAsNotCrossing) {
  EXPECT_FALSE(CrossSegments(Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1)).has_value());
}

TEST(CrossSegments, ReportsOverlappingCollinearSegmentsAsNotCrossing) {
  // (0,0)->(2,0) and (1,0)->(3,0) overlap on [1,2] but are collinear.
  EXPECT_FALSE(CrossSegments(Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(3, 0)).has_value());
}

TEST(CrossSegments, CountsTouchingEndPointsAsACrossing) {
  // (0,0)->(1,0) ends exactly where (1,0)->(1,1) starts: t = 1, s = 0.
  const auto crossing = CrossSegments(Vec2(0, 0), Vec2(1, 0), Vec2(1, 0), Vec2(1, 1));

  ASSERT_TRUE(crossing.has_value());
  EXPECT_DOUBLE_EQ(crossing->t, 1.0);
  EXPECT_DOUBLE_EQ(crossing->s, 0.0);
}

TEST(CrossSegments, CountsAnEndPointOnTheOtherSegmentsInteriorAsACrossing) {
  // T junction: (2,0)->(2,3) starts on (0,0)->(4,0) at its midpoint: t = 0, s = 1/2.
  const auto crossing = CrossSegments(Vec2(2, 0), Vec2(2, 3), Vec2(0, 0), Vec2(4, 0));

  ASSERT_TRUE(crossing.has_value());
  EXPECT_DOUBLE_EQ(crossing->t, 0.0);
  EXPECT_DOUBLE_EQ(crossing->s, 0.5);
}

TEST(CrossSegments, RejectsACrossingOfTheLinesBeyondEitherSegment) {
  // The lines y = 0 and x = 2 meet at (2,0): t = 2 on (0,0)->(1,0), outside [0,1].
  EXPECT_FALSE(CrossSegments(Vec2(0, 0), Vec2(1, 0), Vec2(2, -1), Vec2(2, 1)).has_value());
  // The same lines, now (2,0) is at s = -1/2 on (2,1)->(2,3).
  EXPECT_FALSE(CrossSegments(Vec2(0, 0), Vec2(4, 0), Vec2(2, 1), Vec2(2, 3)).has_value());
}

TEST(CrossSegments, FindsACrossingOfNearlyParallelSegments) {
  // a->b = (0,-1e-6)->(1,1e-6) has slope 2e-6 (sin angle 2e-6 >> 1e-12) and crosses y = 0 at x = 0.5.
  const auto crossing = CrossSegments(Vec2(0, 0), Vec2(1, 0), Vec2(0, -1e-6), Vec2(1, 1e-6));

  ASSERT_TRUE(crossing.has_value());
  EXPECT_NEAR(crossing->t, 0.5, 1e-9);
  EXPECT_NEAR(crossing->s, 0.5, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// SegmentHitsCircle
// ---------------------------------------------------------------------------------------------

TEST(IntersectCircles, FindsBothPointsMirroredAtTheCentreLine) {
  // Circles of radius 5 around (0, 0) and (8, 0) meet at (4, +-3).
  const auto points = IntersectCircles(Vec2(0.0, 0.0), 5.0, Vec2(8.0, 0.0), 5.0);
  ASSERT_TRUE(points);
  EXPECT_LT(((*points)[0] - Vec2(4.0, 3.0)).norm(), 1e-12);
  EXPECT_LT(((*points)[1] - Vec2(4.0, -3.0)).norm(), 1e-12);
}

TEST(IntersectCircles, GivesOnePointTwiceWhereTheCirclesTouch) {
  const auto points = IntersectCircles(Vec2(0.0, 0.0), 3.0, Vec2(5.0, 0.0), 2.0);
  ASSERT_TRUE(points);
  EXPECT_LT(((*points)[0] - Vec2(3.0, 0.0)).norm(), 1e-9);
  EXPECT_LT(((*points)[1] - Vec2(3.0, 0.0)).norm(), 1e-9);
}

TEST(IntersectCircles, ReportsCirclesThatDoNotMeet) {
  EXPECT_FALSE(IntersectCircles(Vec2(0.0, 0.0), 1.0, Vec2(5.0, 0.0), 1.0));    // apart
  EXPECT_FALSE(IntersectCircles(Vec2(0.0, 0.0), 5.0, Vec2(1.0, 0.0), 1.0));    // one inside the other
  EXPECT_FALSE(IntersectCircles(Vec2(0.0, 0.0), 5.0, Vec2(0.0, 0.0), 5.0));    // same centre
  EXPECT_FALSE(IntersectCircles(Vec2(0.0, 0.0), std::nan(""), Vec2(1.0, 0.0), 1.0));  // not finite
}

TEST(SegmentHitsCircle, HitsADiscWhoseCentreIsCloserThanTheRadius) {
  // Centre (2,1) is at distance 1 from the segment (0,0)->(4,0).
  EXPECT_TRUE(SegmentHitsCircle(Vec2(0, 0), Vec2(4, 0), Vec2(2, 1), 1.5));
  EXPECT_FALSE(SegmentHitsCircle(Vec2(0, 0), Vec2(4, 0), Vec2(2, 1), 0.5));
}

TEST(SegmentHitsCircle, DoesNotCountATangentSegmentBecauseTheDiscIsOpen) {
  // Distance exactly 1 = radius: tangent.
  EXPECT_FALSE(SegmentHitsCircle(Vec2(0, 0), Vec2(4, 0), Vec2(2, 1), 1.0));
}

TEST(SegmentHitsCircle, MeasuresBeyondTheEndFromTheEndPoint) {
  // Centre (5,0) lies on the line of (0,0)->(4,0), 1 m past the end point (4,0).
  EXPECT_FALSE(SegmentHitsCircle(Vec2(0, 0), Vec2(4, 0), Vec2(5, 0), 0.9));
  EXPECT_TRUE(SegmentHitsCircle(Vec2(0, 0), Vec2(4, 0), Vec2(5, 0), 1.1));
}

// ---------------------------------------------------------------------------------------------
// MirrorPoint
// ---------------------------------------------------------------------------------------------

TEST(MirrorPoint, MirrorsAtAHorizontalAndAVerticalLine) {
  // y = 0: (1,2) -> (1,-2).   x = 4: (1,2) -> (2*4 - 1, 2) = (7,2).
  EXPECT_TRUE(MirrorPoint(Vec2(1, 2), Vec2(0, 0), Vec2(5, 0)).isApprox(Vec2(1, -2), kTol));
  EXPECT_TRUE(MirrorPoint(Vec2(1, 2), Vec2(4, 0), Vec2(4, 1)).isApprox(Vec2(7, 2), kTol));
}

TEST(MirrorPoint, MirrorsAtTheDiagonalBySwappingCoordinates) {
  // y = x: (3,1) -> (1,3).
  EXPECT_TRUE(MirrorPoint(Vec2(3, 1), Vec2(0, 0), Vec2(1, 1)).isApprox(Vec2(1, 3), kTol));
}

TEST(MirrorPoint, MirrorsAtAnObliqueLineIndependentlyOfTheChosenPointsAndDirection) {
  // y = x + 1: (x,y) -> (y - 1, x + 1), so (3,0) -> (-1,4). Midpoint (1,2) lies on the line and
  // (3,0) - (-1,4) = (4,-4) is normal to the direction (1,1).
  const Vec2 expected(-1, 4);

  EXPECT_TRUE(MirrorPoint(Vec2(3, 0), Vec2(0, 1), Vec2(1, 2)).isApprox(expected, kTol));
  EXPECT_TRUE(MirrorPoint(Vec2(3, 0), Vec2(2, 3), Vec2(-1, 0)).isApprox(expected, kTol));
}

TEST(MirrorPoint, MirrorsTheOriginAtTheLine3xPlus4yEquals12) {
  // Line through (4,0) and (0,3): unit normal (3,4)/5, distance of the origin 12/5 = 2.4, so the
  // image is 2 * 2.4 * (0.6, 0.8) = (2.88, 3.84).
  EXPECT_TRUE(MirrorPoint(Vec2(0, 0), Vec2(4, 0), Vec2(0, 3)).isApprox(Vec2(2.88, 3.84), kTol));
}

TEST(MirrorPoint, LeavesAPointOnTheLineInPlaceAndIsAnInvolution) {
  const Vec2 a(4, 0), b(0, 3);
  // (2, 1.5) is on 3x + 4y = 12.
  EXPECT_TRUE(MirrorPoint(Vec2(2, 1.5), a, b).isApprox(Vec2(2, 1.5), kTol));
  const Vec2 x(-0.7, 5.3);
  EXPECT_TRUE(MirrorPoint(MirrorPoint(x, a, b), a, b).isApprox(x, kTol));
}

TEST(LineNormal, TurnsTheUnitDirectionByPlusNinetyDegrees) {
  // (4,0) -> (0,3): direction (-0.8, 0.6), normal (-0.6, -0.8).
  EXPECT_TRUE(LineNormal(Vec2(4, 0), Vec2(0, 3)).isApprox(Vec2(-0.6, -0.8), kTol));
  EXPECT_EQ(LineNormal(Vec2(0, 0), Vec2(5, 0)), Vec2(0, 1));
}

TEST(MirrorAtLine, MirrorsAtTheLineThroughAPointWithAGivenNormal) {
  // y = 2 through (7, 2), normal (0, 1): (1, 5) -> (1, -1). MirrorPoint is this with LineNormal.
  EXPECT_TRUE(MirrorAtLine(Vec2(1, 5), Vec2(7, 2), Vec2(0, 1)).isApprox(Vec2(1, -1), kTol));
  const Vec2 a(4, 0), b(0, 3), x(-0.7, 5.3);
  EXPECT_EQ(MirrorAtLine(x, a, LineNormal(a, b)), MirrorPoint(x, a, b));
}

// ---------------------------------------------------------------------------------------------
// SignedDistanceToLine
// ---------------------------------------------------------------------------------------------

TEST(SignedDistanceToLine, IsPositiveOnTheLeftOfTheDirectedLine) {
  // a->b points east; left is north.
  EXPECT_DOUBLE_EQ(SignedDistanceToLine(Vec2(0.5, 2), Vec2(0, 0), Vec2(1, 0)), 2.0);
  EXPECT_DOUBLE_EQ(SignedDistanceToLine(Vec2(3, -1.5), Vec2(0, 0), Vec2(1, 0)), -1.5);
}

TEST(SignedDistanceToLine, ChangesSignWhenTheLineIsReversed) {
  EXPECT_DOUBLE_EQ(SignedDistanceToLine(Vec2(0.5, 2), Vec2(1, 0), Vec2(0, 0)), -2.0);
}

TEST(SignedDistanceToLine, MeasuresTheDistanceToAnObliqueLine) {
  // Line (4,0)->(0,3) heads north-west; the origin is on its left (south-west side) at 12/5.
  EXPECT_NEAR(SignedDistanceToLine(Vec2(0, 0), Vec2(4, 0), Vec2(0, 3)), 2.4, kTol);
  // (4,3) is on the right: |3*4 + 4*3 - 12| / 5 = 12/5.
  EXPECT_NEAR(SignedDistanceToLine(Vec2(4, 3), Vec2(4, 0), Vec2(0, 3)), -2.4, kTol);
  // A point on the line has distance 0.
  EXPECT_NEAR(SignedDistanceToLine(Vec2(2, 1.5), Vec2(4, 0), Vec2(0, 3)), 0.0, kTol);
}

// ---------------------------------------------------------------------------------------------
// DistanceToSegment
// ---------------------------------------------------------------------------------------------

TEST(DistanceToSegment, UsesThePerpendicularWhenTheFootLiesOnTheSegment) {
  EXPECT_DOUBLE_EQ(DistanceToSegment(Vec2(2, 3), Vec2(0, 0), Vec2(4, 0)), 3.0);
}

TEST(DistanceToSegment, UsesTheNearestEndPointBeyondEitherEnd) {
  // (7,4) - (4,0) = (3,4): 5.   (-3,-4) - (0,0): 5.
  EXPECT_DOUBLE_EQ(DistanceToSegment(Vec2(7, 4), Vec2(0, 0), Vec2(4, 0)), 5.0);
  EXPECT_DOUBLE_EQ(DistanceToSegment(Vec2(-3, -4), Vec2(0, 0), Vec2(4, 0)), 5.0);
}

TEST(DistanceToSegment, TreatsADegenerateSegmentAsAPoint) {
  // (4,5) - (1,1) = (3,4): 5.
  EXPECT_DOUBLE_EQ(DistanceToSegment(Vec2(4, 5), Vec2(1, 1), Vec2(1, 1)), 5.0);
}

TEST(DistanceToSegment, MeasuresTheDistanceToAnObliqueSegment) {
  // Segment (4,0)->(0,3); the foot of the origin is (1.44, 1.92), inside, at distance 2.4.
  EXPECT_NEAR(DistanceToSegment(Vec2(0, 0), Vec2(4, 0), Vec2(0, 3)), 2.4, kTol);
}

}  // namespace
}  // namespace mirage::geometry
