// ARC_FEED: the 3D arc and rs274's plane-relative arguments.

#include <gtest/gtest.h>

#include <ostream>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/trace.hpp"

namespace ncpost::canon {

// Readable failures instead of gtest's byte dump.
void PrintTo(const PlaneArc& p, std::ostream* os) {
  *os << name(p.plane) << " (" << p.first_end << ", " << p.second_end << ", " << p.first_axis
      << ", " << p.second_axis << ", " << p.rotation << ", " << p.axis_end_point << ")";
}

namespace {

ArcFeed arc(Point end, Point centre, Direction normal, int turns) {
  return ArcFeed{{end.x, end.y, end.z, {}, {}}, centre, normal, turns};
}

// The cases below are the arcs of `rs274 -g` on
//   G0 X1 Y2 Z3 / G1 X10 / G2 X20 Y2 I5 J0 / G18 G2 X30 Z3 I5 K0 / G19 G2 Y10 Z3 J4 K0
// whose ARC_FEED lines are, in order,
//   ARC_FEED(20.0000, 2.0000, 15.0000, 2.0000, -1, 3.0000, ...)
//   ARC_FEED(3.0000, 30.0000, 3.0000, 25.0000, -1, 2.0000, ...)
//   ARC_FEED(10.0000, 3.0000, 6.0000, 3.0000, -1, 30.0000, ...)
TEST(CanonArc, XyPlane) {
  const auto p = plane_arc(arc({20, 2, 3}, {15, 2, 3}, {0, 0, 1}, -1));
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, (PlaneArc{Plane::Xy, 20, 2, 15, 2, -1, 3}));
}

TEST(CanonArc, XzPlaneOrdersZThenX) {
  // G18 G2: clockwise seen from +Y. Stored about +Y with turns -1.
  const auto p = plane_arc(arc({30, 2, 3}, {25, 2, 3}, {0, 1, 0}, -1));
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, (PlaneArc{Plane::Xz, 3, 30, 3, 25, -1, 2}));
}

TEST(CanonArc, YzPlane) {
  const auto p = plane_arc(arc({30, 10, 3}, {30, 6, 3}, {1, 0, 0}, -1));
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, (PlaneArc{Plane::Yz, 10, 3, 6, 3, -1, 30}));
}

TEST(CanonArc, NegativeNormalFlipsTheRotation) {
  // Counter-clockwise about -Z is clockwise about +Z (G2).
  const auto p = plane_arc(arc({20, 2, 3}, {15, 2, 3}, {0, 0, -1}, 1));
  ASSERT_TRUE(p);
  EXPECT_EQ(p->rotation, -1);
  const auto q = plane_arc(arc({30, 2, 3}, {25, 2, 3}, {0, -2.5, 0}, 3));  // not unit length
  ASSERT_TRUE(q);
  EXPECT_EQ(q->plane, Plane::Xz);
  EXPECT_EQ(q->rotation, -3);
}

TEST(CanonArc, HelixCarriesTheAxisEndPointAndTurns) {
  // G2 X20 Y10 I-5 J0 Z-1 P3 from (25, 10, 2): rs274 prints
  // ARC_FEED(20.0000, 10.0000, 25.0000, 10.0000, -3, -1.0000, ...). The centre's height does
  // not matter.
  const auto p = plane_arc(arc({20, 10, -1}, {25, 10, 2}, {0, 0, 1}, -3));
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, (PlaneArc{Plane::Xy, 20, 10, 25, 10, -3, -1}));
  EXPECT_EQ(format_call(arc({20, 10, -1}, {25, 10, 2}, {0, 0, 1}, -3)),
            "ARC_FEED(20.0000, 10.0000, 25.0000, 10.0000, -3, -1.0000)");
  // A helix about X in the YZ plane.
  const auto yz = plane_arc(arc({7, 0, 5}, {0, 0, 0}, {1, 0, 0}, 2));
  ASSERT_TRUE(yz);
  EXPECT_EQ(*yz, (PlaneArc{Plane::Yz, 0, 5, 0, 0, 2, 7}));
}

TEST(CanonArc, TiltedOrDegenerateNormalsHaveNoPlaneForm) {
  EXPECT_FALSE(plane_arc(arc({1, 1, 1}, {0, 0, 0}, {0, 1, 1}, 1)));
  EXPECT_FALSE(plane_arc(arc({1, 1, 1}, {0, 0, 0}, {0, 0, 0}, 1)));
  EXPECT_FALSE(plane_arc(arc({1, 1, 1}, {0, 0, 0}, {1e-6, 0, 1}, 1)));
  // Within the tolerance counts as parallel.
  EXPECT_TRUE(plane_arc(arc({1, 1, 1}, {0, 0, 0}, {1e-12, 0, 1}, 1)));
}

TEST(CanonArc, FromPlaneRoundTrips) {
  for (const PlaneArc& p :
       {PlaneArc{Plane::Xy, 20, 2, 15, 2, -1, 3}, PlaneArc{Plane::Xz, 3, 30, 3, 25, -1, 2},
        PlaneArc{Plane::Yz, 10, 3, 6, 3, 2, 30}}) {
    const ArcFeed a = arc_from_plane(p);
    const auto back = plane_arc(a);
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, p);
  }
  const ArcFeed a = arc_from_plane(PlaneArc{Plane::Xz, 3, 30, 3, 25, -1, 2});
  EXPECT_EQ(a.end.x, 30);
  EXPECT_EQ(a.end.y, 2);
  EXPECT_EQ(a.end.z, 3);
  EXPECT_EQ(a.centre, (Point{25, 2, 3}));
  EXPECT_EQ(a.normal, (Direction{0, 1, 0}));
}

TEST(CanonArc, NurbsValidity) {
  NurbsFeed n{.degree = 2,
              .points = {{0, 0, 0, 1}, {1, 2, 0, 0.5}, {3, 0, 0, 1}},
              .knots = {0, 0, 0, 1, 1, 1}};
  EXPECT_TRUE(valid(n));
  NurbsFeed bad = n;
  bad.knots.pop_back();
  EXPECT_FALSE(valid(bad));
  bad = n;
  bad.knots = {0, 0, 1, 0, 1, 1};
  EXPECT_FALSE(valid(bad));
  bad = n;
  bad.points[1].weight = 0;
  EXPECT_FALSE(valid(bad));
  bad = n;
  bad.degree = 0;
  EXPECT_FALSE(valid(bad));
}

}  // namespace
}  // namespace ncpost::canon
