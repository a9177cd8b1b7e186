// Control flow: LinuxCNC O-words (subroutines, if/elseif/else, while, do-while, repeat, break,
// continue, return values), FANUC-style M98/M99 in LinuxCNC, subprograms in other files, and
// the limits that keep a hostile program bounded (steps, nesting, cancel).

#include <gtest/gtest.h>

#include <atomic>

#include "gcode_support.hpp"

namespace ncpost::gcode {
namespace {

using test::read;

std::string xs(const test::Read& r) {
  // The X of each motion, space-separated.
  std::string out;
  for (const auto& c : r.calls) {
    if (const auto* t = std::get_if<canon::StraightTraverse>(&c))
      out += std::to_string(int(t->to.x)) + " ";
    if (const auto* f = std::get_if<canon::StraightFeed>(&c))
      out += std::to_string(int(f->to.x)) + " ";
  }
  return out;
}

TEST(Flow, SubroutineWithArgumentsAndReturnValue) {
  const auto r = read(
      "o<move> sub\n"
      "  G0 X#1\n"
      "  o<move> return [#1*2]\n"
      "o<move> endsub\n"
      "o<move> call [3]\n"
      "G0 X#<_value>\n"
      "#1=7\n"
      "o<move> call [1]\n"
      "G0 X#1\n"  // #1 is local to the call: 7 again
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(xs(r), "3 6 1 7 ");
}

TEST(Flow, IfElseifElse) {
  const auto r = read(
      "#1=2\n"
      "o1 if [#1 EQ 1]\n G0 X1\n"
      "o1 elseif [#1 EQ 2]\n G0 X2\n"
      "o1 else\n G0 X3\n"
      "o1 endif\n"
      "o2 if [0]\n G0 X8\no2 else\n G0 X9\no2 endif\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(xs(r), "2 9 ");
}

TEST(Flow, Loops) {
  const auto r = read(
      "#1=0\n"
      "o1 while [#1 LT 3]\n G0 X#1\n #1=[#1+1]\no1 endwhile\n"
      "o2 do\n G0 X#1\n #1=[#1+1]\no2 while [#1 LT 5]\n"
      "o3 repeat [2]\n G0 X9\no3 endrepeat\n"
      "#1=0\n"
      "o4 while [1]\n #1=[#1+1]\n o5 if [#1 EQ 2]\n  o4 continue\n o5 endif\n"
      " o6 if [#1 GT 3]\n  o4 break\n o6 endif\n G0 X[10+#1]\no4 endwhile\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(xs(r), "0 1 2 3 4 9 9 11 13 ");
}

TEST(Flow, FanucStyleSubprogramsInLinuxcnc) {
  // m98m99/05-M98-loops: L repeats, L0 calls nothing; params are global.
  const auto r = read(
      "#1=0\nM98 P1 L3\nM98 P1 L0\nG0 Y#1\nM30\n"
      "O1\n#1=[#1+1]\nG0 X#1\nM99\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(xs(r), "1 2 3 3 ");
}

TEST(Flow, SubroutineInAnotherFile) {
  ReadOptions o;
  o.subprograms.push_back({"subs/drill.ngc", "o<drill> sub\nG0 X#1\no<drill> endsub\nM2\n"});
  const auto r = read("o<drill> call [4]\nM2\n", "linuxcnc", o);
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(xs(r), "4 ");
  // Missing: refused naming it.
  const auto m = read("o<nowhere> call\nM2\n");
  EXPECT_TRUE(m.has(diag::Code::GcodeMissingProgram));
  EXPECT_NE(m.messages().find("<NOWHERE>"), std::string::npos) << m.messages();
  const auto f = read("M98 P1234\nM2\n");
  EXPECT_TRUE(f.has(diag::Code::GcodeMissingProgram));
  EXPECT_NE(f.messages().find("O1234"), std::string::npos) << f.messages();
}

TEST(Flow, DiagnosticsNameTheSubprogramFile) {
  ReadOptions o;
  o.subprograms.push_back({"bad.ngc", "o<bad> sub\nG0 X[1/0]\no<bad> endsub\n"});
  const auto r = read("o<bad> call\nM2\n", "linuxcnc", o);
  ASSERT_FALSE(r.result.diagnostics.empty());
  EXPECT_EQ(r.result.diagnostics[0].file, "bad.ngc");
  EXPECT_EQ(r.result.diagnostics[0].diagnostic.line, 2u);
}

TEST(Flow, EndlessLoopStopsAtTheStepLimit) {
  ReadOptions o;
  o.max_steps = 1000;
  const auto r = read("o1 while [1]\nG0 X1\no1 endwhile\nM2\n", "linuxcnc", o);
  EXPECT_TRUE(r.has(diag::Code::GcodeStepLimit));
  // The program is still whole: PROJECT_END last.
  ASSERT_FALSE(r.calls.empty());
  EXPECT_TRUE(std::holds_alternative<canon::End>(r.calls.back()));
}

TEST(Flow, RecursionStopsAtTheNestingLimit) {
  ReadOptions o;
  o.max_call_depth = 10;
  const auto r = read("o<r> sub\no<r> call\no<r> endsub\no<r> call\nM2\n", "linuxcnc", o);
  EXPECT_TRUE(r.has(diag::Code::GcodeNestingLimit));
}

TEST(Flow, UnmatchedStatements) {
  EXPECT_TRUE(read("o1 endwhile\nM2\n").has(diag::Code::GcodeBadFlow));
  EXPECT_TRUE(read("o1 if [1]\nG0 X1\n").has(diag::Code::GcodeNoProgramEnd));
  EXPECT_TRUE(read("o1 if [0]\nG0 X1\nM2\n").has(diag::Code::GcodeBadFlow));
  EXPECT_TRUE(
      read("o1 sub\no2 sub\no2 endsub\no1 endsub\no1 call\nM2\n").has(diag::Code::GcodeBadFlow));
}

TEST(Flow, Cancel) {
  std::atomic<bool> cancel{true};
  ReadOptions o;
  o.cancel = &cancel;
  std::string text;
  for (int i = 0; i < 5000; ++i) text += "G0 X" + std::to_string(i) + "\n";
  const auto r = read(text + "M2\n", "linuxcnc", o);
  EXPECT_TRUE(r.result.cancelled);
  EXPECT_FALSE(r.result.ok());
  EXPECT_LT(r.calls.size(), 1000u);
}

TEST(Flow, PercentDelimitsTheProgram) {
  const auto r = read("%\nG0 X1\n%\nG0 X2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(xs(r), "1 ");
}

TEST(Flow, BlockDeleteSwitch) {
  ReadOptions on;
  on.block_delete = true;
  EXPECT_EQ(xs(read("G0 X1\n/G0 X2\nM2\n", "linuxcnc", on)), "1 ");
  EXPECT_EQ(xs(read("G0 X1\n/G0 X2\nM2\n")), "1 2 ");
}

}  // namespace
}  // namespace ncpost::gcode
