// White-box tests of the feature toolpath generator's geometry (engine/stepnc/src/features):
// depth levels and contour-parallel rings, checked against numbers worked out by hand.

#include "features/shapes.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "features/spec.hpp"

namespace ncpost::stepnc::features {
namespace {

TEST(FeatureLevels, EqualLevelsEndingExactlyAtTheDepth) {
  // ex1's rough pocket: 30 - 0.5 allowance in steps of at most 6.5 → five of 5.9.
  const auto z = levels(29.5, 6.5);
  ASSERT_EQ(z.size(), 5u);
  for (std::size_t k = 0; k < z.size(); ++k) EXPECT_NEAR(z[k], -5.9 * double(k + 1), 1e-12);
  EXPECT_EQ(z.back(), -29.5);
  // A depth that is a whole number of steps gets no extra sliver level.
  EXPECT_EQ(levels(4.0, 2.0), (std::vector<double>{-2.0, -4.0}));
  EXPECT_EQ(levels(0.3 * 3, 0.3).size(), 3u);
  // No step: the whole depth at once.
  EXPECT_EQ(levels(5.0, std::nullopt), (std::vector<double>{-5.0}));
}

double signed_area(const Loop& loop) {
  // Shoelace over the span end points: the sign gives the sense (arcs only round the corners).
  double area = 0;
  Vec3 at = loop.start;
  for (const Span& s : loop.spans) {
    area += at.x * s.to.y - s.to.x * at.y;
    at = s.to;
  }
  return area / 2;
}

TEST(FeatureRings, RectangleAsEx1E) {
  // ex1's pocket: 80 × 50 (half 40 × 25), corner 10, Ø18 tool + allowance 1 → inset 10.
  const Rings r = contour_rings(Shape::rectangle(40, 25, 10), 10, 5);
  EXPECT_NEAR(r.start.x, -15, 1e-12);  // centre line from (-15, 0) to (15, 0)
  EXPECT_NEAR(r.line_length, 30, 1e-12);
  ASSERT_EQ(r.loops.size(), 3u);  // 15 mm of room in steps of 5
  const double starts[] = {20, 25, 30};
  for (std::size_t k = 0; k < 3; ++k) {
    const Loop& loop = r.loops[k];
    EXPECT_NEAR(loop.start.x, starts[k], 1e-12);
    EXPECT_NEAR(loop.start.y, 0, 1e-12);
    ASSERT_FALSE(loop.spans.empty());
    EXPECT_LT((loop.spans.back().to - loop.start).length(), 1e-12) << "ring " << k << " closed";
    EXPECT_GT(signed_area(loop), 0) << "counter-clockwise";
  }
  // The outermost ring has sharp corners (10 - 10 = 0): four lines plus the closing half side.
  for (const Span& s : r.loops.back().spans) EXPECT_FALSE(s.arc);
  EXPECT_EQ(r.loops.back().spans.size(), 5u);
}

TEST(FeatureRings, RoundedCornersShrinkWithTheOffset) {
  // Corner 10, inset 9 (finish, no allowance): outer ring corners r 1, centre (31 - 1, 16 - 1).
  const Rings r = contour_rings(Shape::rectangle(40, 25, 10), 9, 10);
  ASSERT_EQ(r.loops.size(), 2u);  // 16 of room in steps ≤ 10 → two of 8
  EXPECT_NEAR(r.loops[0].start.x, 23, 1e-12);
  const Loop& outer = r.loops.back();
  std::size_t arcs = 0;
  for (const Span& s : outer.spans) {
    if (!s.arc) continue;
    ++arcs;
    EXPECT_NEAR(std::abs(s.centre.x), 30, 1e-12);
    EXPECT_NEAR(std::abs(s.centre.y), 15, 1e-12);
    EXPECT_NEAR((s.to - s.centre).length(), 1, 1e-12);
  }
  EXPECT_EQ(arcs, 4u);
}

TEST(FeatureRings, CircleAndSquareStartAtTheCentre) {
  const Rings c = contour_rings(Shape::circle(25), 6, 5);
  EXPECT_EQ(c.line_length, 0);
  ASSERT_EQ(c.loops.size(), 4u);  // 19 of room, steps ≤ 5 → 4.75
  EXPECT_NEAR(c.loops[0].start.x, 4.75, 1e-12);
  EXPECT_NEAR(c.loops[3].start.x, 19, 1e-12);
  ASSERT_EQ(c.loops[3].spans.size(), 1u);
  EXPECT_TRUE(c.loops[3].spans[0].arc);
  // A tool that exactly fills the circle: the centre point only.
  EXPECT_TRUE(contour_rings(Shape::circle(5), 5, 2).loops.empty());
  // A square: the innermost is a point, and the rings are squares.
  const Rings s = contour_rings(Shape::rectangle(20, 20, 6), 6, 7);
  EXPECT_EQ(s.line_length, 0);
  EXPECT_EQ(s.loops.size(), 2u);
}

// A slot whose ends differ: a radiused end (corners = half width 8) on -x, a flat end on +x
// with corner_radius2 8 on the left (+y) and corner_radius1 5.5 on the right. Inset 5: the ring
// keeps each corner's own radius less the inset (the larger fillet must not be cut into).
TEST(FeatureRings, EachCornerItsOwnRadius) {
  Shape slot = Shape::rectangle(30, 8, 5.5);
  slot.corners = std::array<double, 4>{8, 8, 8, 5.5};
  const Rings r = contour_rings(slot, 5, 10);
  ASSERT_FALSE(r.loops.empty());
  const Loop& outer = r.loops.back();
  std::vector<std::pair<Vec3, double>> arcs;  // centre, radius
  for (const Span& sp : outer.spans)
    if (sp.arc) arcs.push_back({sp.centre, (sp.to - sp.centre).length()});
  ASSERT_EQ(arcs.size(), 4u);
  // Counter-clockwise from (+a, +b): radii 3, 3, 3 and 0.5 about (25 - 3, ...), ...
  EXPECT_NEAR(arcs[0].second, 3, 1e-12);
  EXPECT_NEAR(arcs[0].first.x, 22, 1e-12);
  EXPECT_NEAR(arcs[3].second, 0.5, 1e-12);
  EXPECT_NEAR(arcs[3].first.x, 24.5, 1e-12);
  EXPECT_NEAR(arcs[3].first.y, -2.5, 1e-12);
  // Raster lines end on each corner's own arc: the lines at |v| 3 touch the arcs at their
  // lowest (highest) point, x 22 under the radius-3 corner and 24.5 under the radius-0.5 one.
  const auto lines = raster(slot, 5, 10, true);
  ASSERT_GE(lines.size(), 2u);
  EXPECT_NEAR(lines.back().second.x, 22, 1e-12);     // v = +3
  EXPECT_NEAR(lines.front().second.x, 24.5, 1e-12);  // v = -3
  EXPECT_NEAR(lines.front().first.x, -22, 1e-12);    // the radiused end
}

}  // namespace
}  // namespace ncpost::stepnc::features
