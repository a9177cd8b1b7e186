// White-box tests of the general-profile geometry of the feature generator: the Clipper wrapper
// (engine/stepnc/src/features/polygons.hpp) and the tessellation of outlines on the side away
// from the material (outline.hpp), with numbers worked out by hand.

#include "features/polygons.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "features/outline.hpp"

namespace ncpost::stepnc::features {
namespace {

using poly::Area;
using poly::Areas;
using poly::P;
using poly::Ring;

constexpr double kTol = 0.001;

Areas box(double x0, double y0, double x1, double y1) {
  return {Area{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}}};
}

double segment_distance(P p, P a, P b) {
  const P d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.dot(d), 0.0, 1.0);
  return (a + d * t - p).length();
}

// The smallest distance from any vertex of `inner` to the boundary of `outer`.
double clearance(const Areas& inner, const Areas& outer) {
  double best = 1e300;
  for (const Area& a : inner)
    for (const P& p : a.outer) best = std::min(best, poly::distance_to_boundary(outer, p));
  return best;
}

TEST(FeaturePolygons, ShrinkAndGrowARectangle) {
  const poly::Polygons polygons(kTol);
  const auto in = polygons.offset(box(0, 0, 20, 10), -2);
  ASSERT_TRUE(in);
  ASSERT_EQ(in->size(), 1u);
  EXPECT_NEAR(poly::area(*in), 16 * 6, 1e-6);  // convex corners stay sharp
  const auto out = polygons.offset(box(0, 0, 20, 10), 2);
  ASSERT_TRUE(out);
  // Sides moved out by 2 and quarter circles of radius 2 at the corners: 200 + 60·2 + 4π,
  // less the round joins' chord segments (vertices on the arc, chords inside it).
  const double exact = 200 + 120 + 4 * std::numbers::pi;
  EXPECT_LT(poly::area(*out), exact + 1e-6);
  EXPECT_GT(poly::area(*out), exact - 2 * std::numbers::pi * 2 * kTol);
}

TEST(FeaturePolygons, ShrinkingAnLRoundsItsInnerCornerAndKeepsItsDistance) {
  const Areas ell{Area{{{0, 0}, {60, 0}, {60, 25}, {25, 25}, {25, 50}, {0, 50}}, {}}};
  const poly::Polygons polygons(kTol);
  const auto in = polygons.offset(ell, -5);
  ASSERT_TRUE(in);
  ASSERT_EQ(in->size(), 1u);
  // Every vertex 5 from the walls, up to the join's chords and the grid; none further in
  // than 5 from the inner corner (25, 25) that it goes round.
  EXPECT_NEAR(clearance(*in, ell), 5, kTol + 2 * poly::kResolution);
  double nearest_corner = 1e300;
  for (const P& p : in->front().outer)
    nearest_corner = std::min(nearest_corner, (p - P{25, 25}).length());
  EXPECT_NEAR(nearest_corner, 5, 2 * poly::kResolution);
}

TEST(FeaturePolygons, ANeckSplitsTheShrunkRegionIntoIslands) {
  // Two 40 × 40 lobes joined by a neck 16 wide: at 8 and beyond, two islands.
  const Areas twin{Area{{{0, 0},
                         {40, 0},
                         {40, 12},
                         {60, 12},
                         {60, 0},
                         {100, 0},
                         {100, 40},
                         {60, 40},
                         {60, 28},
                         {40, 28},
                         {40, 40},
                         {0, 40}},
                        {}}};
  const poly::Polygons polygons(kTol);
  EXPECT_EQ(polygons.offset(twin, -7.9)->size(), 1u);
  EXPECT_EQ(polygons.offset(twin, -8.1)->size(), 2u);
  EXPECT_TRUE(polygons.offset(twin, -20.1)->empty());
}

TEST(FeaturePolygons, SimpleRings) {
  EXPECT_TRUE(poly::simple({{0, 0}, {10, 0}, {10, 10}, {0, 10}}));
  EXPECT_TRUE(poly::simple({{0, 0}, {0, 10}, {10, 10}, {10, 0}}));   // either sense
  EXPECT_FALSE(poly::simple({{0, 0}, {10, 10}, {10, 0}, {0, 10}}));  // a bow tie
  EXPECT_FALSE(poly::simple({{0, 0}, {5, 0}, {10, 0}}));             // no area
  // Touching itself at a vertex: two squares sharing the corner (10, 10).
  EXPECT_FALSE(
      poly::simple({{0, 0}, {10, 0}, {10, 10}, {20, 10}, {20, 20}, {10, 20}, {10, 10}, {0, 10}}));
  EXPECT_FALSE(poly::simple({{0, 0}, {1, 0}}));
}

TEST(FeaturePolygons, LinesAreClippedToTheRegion) {
  const poly::Polygons polygons(kTol);
  // A U: the line y = 15 crosses both arms.
  const Areas u{
      Area{{{0, 0}, {30, 0}, {30, 20}, {20, 20}, {20, 10}, {10, 10}, {10, 20}, {0, 20}}, {}}};
  const auto pieces = polygons.clip({{{-5, 15}, {35, 15}}, {{-5, 5}, {35, 5}}}, u);
  ASSERT_TRUE(pieces);
  ASSERT_EQ(pieces->size(), 3u);
  double total = 0;
  for (const auto& c : *pieces) total += (c.back() - c.front()).length();
  EXPECT_NEAR(total, 10 + 10 + 30, 2 * poly::kResolution);
  EXPECT_TRUE(polygons.segment_inside({5, 5}, {25, 5}, u));
  EXPECT_FALSE(polygons.segment_inside({5, 15}, {25, 15}, u));  // across the gap of the U
  EXPECT_TRUE(poly::contains(u, {5, 15}));
  EXPECT_FALSE(poly::contains(u, {15, 15}));
}

TEST(FeaturePolygons, SweptBandCoversTheRegionAroundAPath) {
  const poly::Polygons polygons(kTol);
  // A disc of radius 5 swept along a 10 mm line: a stadium of 10 × 10 + 25π.
  const auto swept = polygons.sweep({}, {{{0, 0}, {10, 0}}}, 5);
  ASSERT_TRUE(swept);
  // (Less the chord segments of the two half circles, at most their length × the tolerance.)
  const double exact = 100 + 25 * std::numbers::pi;
  EXPECT_LT(poly::area(*swept), exact);
  EXPECT_GT(poly::area(*swept), exact - 2 * std::numbers::pi * 5 * kTol);
  const auto left = polygons.difference(box(1, -4, 9, 4), *swept);
  ASSERT_TRUE(left);
  EXPECT_TRUE(left->empty());
}

TEST(FeaturePolygons, OutOfRangeCoordinatesAreRefusedNotThrown) {
  const poly::Polygons polygons(kTol);
  EXPECT_FALSE(polygons.offset(box(0, 0, 1e300, 1), -1).has_value());
  EXPECT_FALSE(poly::simple({{0, 0}, {1e300, 0}, {0, 1e300}}));
}

TEST(FeatureOutlines, ArcsAreTessellatedAwayFromTheMaterial) {
  // A full circle of radius 10, counter-clockwise: inside is on the left.
  Outline circle;
  Element e;
  e.arc = true;
  e.start = e.end = {10, 0};
  e.centre = {0, 0};
  e.radius = 10;
  e.sweep = 2 * std::numbers::pi;
  circle.elements.push_back(e);
  // A pocket (material outside): chords inside the circle, never more than the tolerance in.
  const auto pocket = tessellate(circle, kTol, false, 100000);
  ASSERT_TRUE(pocket);
  double far = 0;
  double near = 1e300;
  for (std::size_t i = 0; i < pocket->size(); ++i) {
    const P a = (*pocket)[i];
    const P b = (*pocket)[(i + 1) % pocket->size()];
    far = std::max(far, a.length());
    near = std::min(near, segment_distance({0, 0}, a, b));
  }
  EXPECT_LE(far, 10 + 1e-9);
  EXPECT_GE(near, 10 - kTol - 1e-9);
  // A boss (material inside): tangent polyline outside the circle, within the tolerance.
  const auto boss = tessellate(circle, kTol, true, 100000);
  ASSERT_TRUE(boss);
  far = 0;
  near = 1e300;
  for (std::size_t i = 0; i < boss->size(); ++i) {
    const P a = (*boss)[i];
    const P b = (*boss)[(i + 1) % boss->size()];
    far = std::max(far, a.length());
    near = std::min(near, segment_distance({0, 0}, a, b));
  }
  EXPECT_GE(near, 10 - 1e-9);
  EXPECT_LE(far, 10 + kTol + 1e-9);
  // Too many points for the limit: refused.
  EXPECT_FALSE(tessellate(circle, 1e-9, false, 1000).has_value());
}

TEST(FeatureOutlines, CornersTurnLeftWhereConvex) {
  Outline square;
  const P v[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (int k = 0; k < 4; ++k) {
    Element e;
    e.start = v[k];
    e.end = v[(k + 1) % 4];
    square.elements.push_back(e);
  }
  const auto c = corners(square);
  ASSERT_EQ(c.size(), 4u);
  for (const Corner& corner : c) EXPECT_NEAR(corner.turn, std::numbers::pi / 2, 1e-12);
  reverse(square);
  for (const Corner& corner : corners(square))
    EXPECT_NEAR(corner.turn, -std::numbers::pi / 2, 1e-12);
}

}  // namespace
}  // namespace ncpost::stepnc::features
