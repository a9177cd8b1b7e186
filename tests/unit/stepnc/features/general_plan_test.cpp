// The planner of pockets with general profiles (features/general.hpp), on a region built here
// from a square: what the reader would hand it for a 60 × 60 polyline pocket and a Ø10 tool.

#include <gtest/gtest.h>

#include <cmath>

#include "features/general.hpp"
#include "features/outline.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

class GeneralPlan : public test::Planning {
 protected:
  GeneralPocketSpec square_pocket() const {
    const poly::Areas square{poly::Area{{{0, 0}, {60, 0}, {60, 60}, {0, 60}}, {}}};
    const double base = 5 + region_margin(options_);
    const auto centres = poly::Polygons(options_.chord_tolerance).offset(square, -base);
    EXPECT_TRUE(centres && centres->size() == 1u);
    GeneralPocketSpec spec;
    spec.region = {centres.value_or(poly::Areas{}), square, square, 0, base};
    spec.stepover = 5;
    spec.levels = {-3};
    spec.entry.radius = 4;
    spec.entry.angle = radians(10);
    spec.exit.kind = Entry::Kind::Plunge;
    spec.tool = tool();
    spec.tool_radius = 5;
    spec.operation = operation();
    spec.feature = feature();
    return spec;
  }
  // Every point the tool centre goes to at depth stays where the region lets it.
  void expect_inside(double lo, double hi) const {
    for (const Move& m : moves()) {
      if (m.to.z >= 0) continue;
      EXPECT_GE(m.to.x, lo);
      EXPECT_LE(m.to.x, hi);
      EXPECT_GE(m.to.y, lo);
      EXPECT_LE(m.to.y, hi);
    }
  }
};

TEST_F(GeneralPlan, RingsStayInTheRegionAndStartWithAHelix) {
  ASSERT_TRUE(plan_general_pocket(square_pocket(), draft_));
  EXPECT_TRUE(report_.all().empty());
  expect_inside(5, 55);
  ASSERT_GE(moves().size(), 3u);
  EXPECT_EQ(moves()[0].kind, Move::Kind::Rapid);
  EXPECT_EQ(moves()[1].kind, Move::Kind::Arc);  // the helix down, about where there is room
  EXPECT_NEAR(moves()[1].to.z, -3, 1e-12);
  // The outermost ring runs along the walls, 5 (and the margin) inside them.
  double x_max = 0;
  for (const Move& m : moves()) x_max = std::max(x_max, m.to.x);
  EXPECT_NEAR(x_max, 55, 0.01);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

TEST_F(GeneralPlan, LinesThenTheWallRing) {
  GeneralPocketSpec spec = square_pocket();
  spec.pattern = GeneralPocketSpec::Pattern::LinesThenRing;
  ASSERT_TRUE(plan_general_pocket(spec, draft_));
  expect_inside(5, 55);
  // Lines along x, one every 5 mm at most across the 50 mm the centre may use.
  int lines = 0;
  Vec3 at = moves().front().to;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Feed && m.to.z == -3 && std::abs(m.to.y - at.y) < 1e-9 &&
        std::abs(m.to.x - at.x) > 40)
      ++lines;
    at = m.to;
  }
  EXPECT_GE(lines, 11);
}

TEST_F(GeneralPlan, AHelixWiderThanTheRoomIsRefusedWhereItWouldGoDown) {
  GeneralPocketSpec spec = square_pocket();
  spec.entry.explicit_entry = true;
  spec.entry.radius = 40;
  spec.entry.strategy = test::subject(strategy_, "PLUNGE_HELIX");
  EXPECT_FALSE(plan_general_pocket(spec, draft_));
  ASSERT_EQ(report_.all().size(), 1u);
  EXPECT_EQ(report_.all()[0].code, diag::Code::StepncToolUnfit);
  EXPECT_EQ(report_.all()[0].at.instance, &strategy_);
  EXPECT_EQ(report_.all()[0].message.rfind("#128 (PLUNGE_HELIX) radius 40 leaves no room for "
                                           "#112 (MILLING_CUTTING_TOOL) in #125 (CLOSED_POCKET)",
                                           0),
            0u);
}

}  // namespace
}  // namespace ncpost::stepnc::features
