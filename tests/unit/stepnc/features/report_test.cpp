// The findings readers and planners report (features/report.hpp): how they name instances and
// word the messages every kind shares.

#include "features/report.hpp"

#include <gtest/gtest.h>

#include "plan_support.hpp"

namespace ncpost::stepnc::features {
namespace {

using test::subject;

TEST(FeatureReport, SubjectsAreNamedByIdAndType) {
  const p21::Instance tool{113};
  EXPECT_EQ(subject(tool, "MILLING_CUTTING_TOOL").name(), "#113 (MILLING_CUTTING_TOOL)");
  EXPECT_EQ(Subject{}.name(), "$");  // an unset attribute
  EXPECT_FALSE(Subject{});
  EXPECT_TRUE(subject(tool, "MILLING_CUTTING_TOOL"));
}

TEST(FeatureReport, FindingsKeepTheirOrderCodeAndPlace) {
  const p21::Instance ws{10};
  const p21::Instance tool{113};
  Findings report(subject(ws, "MACHINING_WORKINGSTEP"));
  EXPECT_FALSE(report.unfit(subject(tool, "TAP"), "too large"));
  report.note(subject(tool, "TAP"), "read so");
  EXPECT_FALSE(report.not_implemented("#5 (BORING) with a test cut"));
  EXPECT_FALSE(report.limit_reached(7));
  ASSERT_EQ(report.all().size(), 4u);
  EXPECT_EQ(report.all()[0].code, diag::Code::StepncToolUnfit);
  EXPECT_EQ(report.all()[0].at.instance, &tool);
  EXPECT_EQ(report.all()[1].code, diag::Code::StepncNote);
  // What cannot be generated at all is said at the workingstep, which the message names.
  EXPECT_EQ(report.all()[2].code, diag::Code::StepncFeatureNotImplemented);
  EXPECT_EQ(report.all()[2].at.instance, &ws);
  EXPECT_EQ(report.all()[2].message,
            "#10 (MACHINING_WORKINGSTEP): #5 (BORING) with a test cut is not implemented; nothing "
            "is generated");
  EXPECT_EQ(report.all()[3].code, diag::Code::StepncFeatureData);
  EXPECT_EQ(report.all()[3].message,
            "#10 (MACHINING_WORKINGSTEP): the generated path needs more than 7 motions "
            "(FeatureOptions::max_moves); check the stepover and depths");
}

// What a reader assumes where a file leaves a value implicit is a note naming the instance and
// the value (issue 17 reads implicit depths this way).
TEST(FeatureReport, AnAssumptionNamesTheInstanceAndTheValue) {
  const p21::Instance ws{10};
  const p21::Instance hole{150};
  Findings report(subject(ws, "MACHINING_WORKINGSTEP"));
  report.assumed(subject(hole, "ROUND_HOLE"), "depth", 30.25, "the workpiece's thickness");
  ASSERT_EQ(report.all().size(), 1u);
  EXPECT_EQ(report.all()[0].code, diag::Code::StepncNote);
  EXPECT_EQ(report.all()[0].at.instance, &hole);
  EXPECT_EQ(report.all()[0].message,
            "#150 (ROUND_HOLE): depth taken as 30.25 (the workpiece's thickness)");
}

TEST(FeatureReport, NumbersInMessagesDropTrailingZeros) {
  EXPECT_EQ(fmt(2.5), "2.5");
  EXPECT_EQ(fmt(10), "10");
  EXPECT_EQ(fmt(-0.00001), "0");
  EXPECT_EQ(fmt(1.23456), "1.2346");
}

}  // namespace
}  // namespace ncpost::stepnc::features
