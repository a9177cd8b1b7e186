// The planner of rounded-rectangle and circular regions (features/region.hpp): rectangular and
// circular pockets, straight U slots.

#include <gtest/gtest.h>

#include <cmath>

#include "features/region.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

class RegionPlan : public test::Planning {
 protected:
  // NIST ex1's pocket: 80 × 50, corner radius 10, a Ø18 tool with allowance 1 (inset 10),
  // rings 5 apart, one level 5 deep, the default helix (0.8 R at 10 degrees).
  RegionSpec ex1_pocket() const {
    RegionSpec spec;
    spec.shape = Shape::rectangle(40, 25, 10);
    spec.inset = 10;
    spec.stepover = 5;
    spec.finish = 5;
    spec.levels = {-5};
    spec.entry.radius = 0.8 * 9;
    spec.entry.angle = radians(10);
    spec.exit.kind = Entry::Kind::Plunge;
    spec.tool = tool();
    spec.feature = feature();
    return spec;
  }
};

// The innermost path is the centre line from (-15, 0) to (15, 0); the helix (radius 7.2, one
// turn for the 7 mm from 2 above the top) is about its start, and the rings are at insets 20,
// 15, 10 from the wall: sharp-cornered, 30, 35 and 40 mm half long.
TEST_F(RegionPlan, RingsFromTheCentreLineOutwards) {
  ASSERT_TRUE(plan_region(ex1_pocket(), draft_));
  EXPECT_TRUE(report_.all().empty());
  EXPECT_EQ(moves()[0].kind, Move::Kind::Rapid);
  EXPECT_NEAR(moves()[0].to.x, -15 + 7.2, 1e-12);
  EXPECT_NEAR(moves()[0].to.z, options_.clearance, 1e-12);
  const Move& helix = moves()[1];
  ASSERT_EQ(helix.kind, Move::Kind::Arc);
  EXPECT_EQ(helix.turns, 1);
  EXPECT_NEAR(helix.centre.x, -15, 1e-12);
  EXPECT_NEAR(helix.to.z, -5, 1e-12);
  EXPECT_NEAR(moves()[2].to.x, -15, 1e-12);  // into the centre
  EXPECT_NEAR(moves()[3].to.x, 15, 1e-12);   // along the centre line
  EXPECT_EQ(count(Move::Kind::Arc), 1u);     // the rings' corners are sharp
  double x_max = 0, y_max = 0;
  for (const Move& m : moves()) {
    if (m.kind != Move::Kind::Feed) continue;
    x_max = std::max(x_max, std::abs(m.to.x));
    y_max = std::max(y_max, std::abs(m.to.y));
  }
  EXPECT_NEAR(x_max, 30, 1e-12);  // 40 less the inset
  EXPECT_NEAR(y_max, 15, 1e-12);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

TEST_F(RegionPlan, ATooWideHelixThatTheOperationNamesIsRefused) {
  RegionSpec spec = ex1_pocket();
  spec.entry.explicit_entry = true;
  spec.entry.radius = 30;
  spec.entry.strategy = test::subject(strategy_, "PLUNGE_HELIX");
  EXPECT_FALSE(plan_region(spec, draft_));
  EXPECT_EQ(findings(), (std::vector<std::string>{
                            "STEPNC-102: #128 (PLUNGE_HELIX) radius 30 leaves no room for #112 "
                            "(MILLING_CUTTING_TOOL) in #125 (CLOSED_POCKET) (at most 15)"}));
  EXPECT_EQ(report_.all()[0].at.instance, &strategy_);
}

// A Ø10 tool in a Ø10 hole-like pocket: no room for the default helix, so it goes straight down
// the axis and says so.
TEST_F(RegionPlan, AToolThatFillsTheRegionPlunges) {
  RegionSpec spec = ex1_pocket();
  spec.shape = Shape::circle(5);
  spec.inset = 5;
  ASSERT_TRUE(plan_region(spec, draft_));
  ASSERT_EQ(report_.all().size(), 1u);
  EXPECT_EQ(report_.all()[0].code, diag::Code::StepncNote);
  EXPECT_EQ(count(Move::Kind::Arc), 0u);
  EXPECT_EQ(moves()[1].kind, Move::Kind::Feed);
  EXPECT_NEAR(moves()[1].to.z, -5, 1e-12);
}

// Sharp corners and lines back and forth: 30 mm across in steps of at most 5, seven lines
// along x, each joined to the next at its end.
TEST_F(RegionPlan, BackAndForthLines) {
  RegionSpec spec = ex1_pocket();
  spec.shape = Shape::rectangle(40, 25, 0);
  spec.pattern = RegionSpec::Pattern::Lines;
  ASSERT_TRUE(plan_region(spec, draft_));
  int lines = 0;
  double last_direction = 0;
  Vec3 at = moves().front().to;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Feed && m.to.z == -5 && at.z == -5 && m.to.y == at.y &&
        std::abs(m.to.x - at.x) > 50) {
      ++lines;
      const double direction = m.to.x - at.x;
      EXPECT_LT(direction * last_direction, 1e-9) << "line " << lines;
      last_direction = direction;
    }
    at = m.to;
  }
  EXPECT_EQ(lines, 7);
}

}  // namespace
}  // namespace ncpost::stepnc::features
