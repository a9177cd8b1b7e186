// The round hole planner (features/holes.hpp): one canned cycle, or the motions it stands for.

#include <gtest/gtest.h>

#include <vector>

#include "features/holes.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

HoleSpec drill_20_deep() {
  HoleSpec spec;
  spec.cycle = Move::CycleKind::Drill;
  spec.retract_z = 5;
  spec.bottom_z = -20;
  spec.feed = 100;
  spec.spindle = -10;  // ISO rev/s, clockwise
  return spec;
}

class HolePlan : public test::Planning {
 protected:
  // The values of the moves of one kind, in order.
  std::vector<double> values(Move::Kind kind) const {
    std::vector<double> out;
    for (const Move& m : moves())
      if (m.kind == kind) out.push_back(m.value);
    return out;
  }
  std::vector<double> feed_depths() const {
    std::vector<double> out;
    for (const Move& m : moves())
      if (m.kind == Move::Kind::Feed) out.push_back(m.to.z);
    return out;
  }
};

TEST_F(HolePlan, ACycleWhenNothingElseIsAsked) {
  HoleSpec spec = drill_20_deep();
  spec.dwell = 0.5;
  ASSERT_TRUE(plan_hole(spec, draft_));
  ASSERT_EQ(moves().size(), 1u);
  const Move& cycle = moves()[0];
  EXPECT_EQ(cycle.kind, Move::Kind::Cycle);
  EXPECT_EQ(cycle.cycle, Move::CycleKind::Drill);
  EXPECT_EQ(cycle.to.z, 5);  // the R plane
  EXPECT_EQ(cycle.bottom, -20);
  EXPECT_EQ(cycle.feed, 100);
  EXPECT_EQ(cycle.dwell, 0.5);
}

// The first 2 mm at half the feed and 0.75 of the speed, the last 5 at 0.75 and 0.5: the
// descent is split at -2 and -15, each piece at its zone's values, which change only there.
TEST_F(HolePlan, StrategyZonesSplitTheDescent) {
  HoleSpec spec = drill_20_deep();
  spec.zones = {0.75, 0.5, 2, 0.5, 0.75, 5};
  ASSERT_TRUE(plan_hole(spec, draft_));
  EXPECT_EQ(moves().front().kind, Move::Kind::Rapid);
  EXPECT_EQ(feed_depths(), (std::vector<double>{-2, -15, -20}));
  // Each zone's feed and speed, then the technology's again for the way out.
  EXPECT_EQ(values(Move::Kind::FeedRate), (std::vector<double>{50, 100, 75, 100}));
  EXPECT_EQ(values(Move::Kind::Spindle), (std::vector<double>{-7.5, -10, -5, -10}));
  EXPECT_EQ(moves().back().kind, Move::Kind::Rapid);  // feed_on_retract unset: out at rapid
  EXPECT_EQ(moves().back().to.z, 5);
}

// A first peck of 6 and then 4 each, backing off 1 and dwelling between pecks: the pecks end
// at -6, -10 and -14; the drill backs off to -5 and -9.
TEST_F(HolePlan, PecksOfTheirOwnDepth) {
  HoleSpec spec = drill_20_deep();
  spec.cycle = Move::CycleKind::Peck;
  spec.bottom_z = -14;
  spec.peck = 4;
  spec.peck_retract = 1;
  spec.first_peck = 6;
  spec.peck_dwell = 0.25;
  ASSERT_TRUE(plan_hole(spec, draft_));
  std::vector<double> below;
  for (const double z : feed_depths())
    if (z < 0) below.push_back(z);
  EXPECT_EQ(below, (std::vector<double>{-6, -10, -14}));
  EXPECT_EQ(values(Move::Kind::Dwell), (std::vector<double>{0.25, 0.25}));
  std::vector<double> backed;
  for (const Move& m : moves())
    if (m.kind == Move::Kind::Rapid && m.to.z < 0) backed.push_back(m.to.z);
  EXPECT_EQ(backed, (std::vector<double>{-5, -9}));
}

TEST_F(HolePlan, ARetractAtAShareOfTheFeed) {
  HoleSpec spec = drill_20_deep();
  spec.feed_on_retract = 2;
  ASSERT_TRUE(plan_hole(spec, draft_));
  EXPECT_EQ(values(Move::Kind::FeedRate).back(), 100);  // back to the technology's feed
  const Move& out = moves()[moves().size() - 2];
  EXPECT_EQ(out.kind, Move::Kind::Feed);
  EXPECT_EQ(out.to.z, 5);
  const auto feeds = values(Move::Kind::FeedRate);
  EXPECT_EQ(feeds[feeds.size() - 2], 200);
}

}  // namespace
}  // namespace ncpost::stepnc::features
