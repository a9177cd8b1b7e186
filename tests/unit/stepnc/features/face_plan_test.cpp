// The planar face planner (features/face.hpp), driven by specs written by hand.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "features/face.hpp"
#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

// A face 100 long along +x and 40 wide to its right (-y), a Ø10 tool passing each side edge by
// the overlap 0.2 of its diameter (2 mm) and stepping over 8 mm: the first pass at y = -40 + 5
// - 2 = -37, then every 8 mm until the tool reaches 2 past y = 0, which the pass at 3 does.
FaceSpec face_100_by_40() {
  FaceSpec spec;
  spec.travel = {1, 0, 0};
  spec.length = 100;
  spec.width = 40;
  spec.feed = {1, 0, 0};
  spec.tool_radius = 5;
  spec.overlap = 0.2;
  spec.stepover = 8;
  spec.levels = {-2, -4};
  return spec;
}

class FacePlan : public test::Planning {};

TEST_F(FacePlan, BackAndForthPassesOvertravelAtBothEnds) {
  ASSERT_TRUE(plan_face(face_100_by_40(), draft_));
  EXPECT_TRUE(report_.all().empty());
  // From the air 1.5 R before the face, at the clearance plane (no retract plane).
  const Move& first = moves().front();
  EXPECT_EQ(first.kind, Move::Kind::Rapid);
  EXPECT_NEAR(first.to.x, -7.5, 1e-12);
  EXPECT_NEAR(first.to.y, -37, 1e-12);
  EXPECT_NEAR(first.to.z, options_.clearance, 1e-12);
  std::set<double> ys;
  int forward = 0, backward = 0;
  Vec3 at = first.to;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Feed && m.to.z == -2 && at.z == -2 && m.to.y == at.y) {
      ys.insert(m.to.y);
      (m.to.x > at.x ? forward : backward)++;
      EXPECT_NEAR(std::abs(m.to.x - at.x), 115, 1e-9);  // -7.5 to 107.5
    }
    at = m.to;
  }
  EXPECT_EQ(ys, (std::set<double>{-37, -29, -21, -13, -5, 3}));
  EXPECT_EQ(forward, 3);
  EXPECT_EQ(backward, 3);
  // Two levels of one plunge, six passes and five step-overs, each ended at the clearance plane.
  EXPECT_EQ(count(Move::Kind::Feed), 2u * 12u);
  EXPECT_EQ(count(Move::Kind::Rapid), 4u);
  EXPECT_NEAR(moves().back().to.z, options_.clearance, 1e-12);
}

TEST_F(FacePlan, OneWayPassesReturnAboveTheFace) {
  FaceSpec spec = face_100_by_40();
  spec.bidirectional = false;
  spec.levels = {-2};
  ASSERT_TRUE(plan_face(spec, draft_));
  Vec3 at = moves().front().to;
  for (const Move& m : moves()) {
    if (m.kind == Move::Kind::Feed && m.to.z == -2 && at.z == -2) {
      EXPECT_GT(m.to.x, at.x);
    }
    if (m.kind == Move::Kind::Rapid) {
      EXPECT_GE(m.to.z, options_.clearance);
    }
    at = m.to;
  }
}

TEST_F(FacePlan, ARetractPlaneAboveTheClearanceIsWhereTheToolStartsAndEnds) {
  FaceSpec spec = face_100_by_40();
  spec.retract_plane = 15;
  ASSERT_TRUE(plan_face(spec, draft_));
  EXPECT_NEAR(moves()[0].to.z, 15, 1e-12);
  EXPECT_NEAR(moves()[1].to.z, options_.clearance, 1e-12);  // rapid down to 2 above the face
  EXPECT_NEAR(moves().back().to.z, 15, 1e-12);
}

TEST_F(FacePlan, AHostileStepoverIsTheMotionLimit) {
  FaceSpec spec = face_100_by_40();
  spec.stepover = 1e-9;
  options_.max_moves = 1000;
  EXPECT_FALSE(plan_face(spec, draft_));
  ASSERT_EQ(report_.all().size(), 1u);
  EXPECT_EQ(report_.all()[0].code, diag::Code::StepncFeatureData);
  EXPECT_EQ(report_.all()[0].at.instance, &workingstep_);
}

}  // namespace
}  // namespace ncpost::stepnc::features
