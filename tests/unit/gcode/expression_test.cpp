// Expressions and parameters, evaluated before the block is checked (issue 19's `X[1+2]`,
// `YSIN[30]`): values taken from what LinuxCNC's rs274 prints for the same lines.

#include <gtest/gtest.h>

#include <charconv>
#include <random>

#include "gcode_support.hpp"

namespace ncpost::gcode {
namespace {

using test::read;

TEST(Expressions, OperatorsAndFunctionsAsLinuxcnc) {
  // rs274 2.9: STRAIGHT_TRAVERSE(-2, -2, -4), (64, 1, 4), (1, 2, 45), (2, 0.5, 45).
  const auto r = read(
      "#1=2\n"
      "G0 X-#1 Y[-#1] Z-[#1*2]\n"
      "G0 X[2**3**2] Y[1+2*3 GT 5] Z[-2**2]\n"
      "G0 X[10 MOD 3] Y[-7 MOD 3] Z[ATAN[1]/[1]]\n"
      "g0 x [ 1 + 1 ] y sin [30]\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(-2.0000, -2.0000, -4.0000)\n"
            "STRAIGHT_TRAVERSE(64.0000, 1.0000, 4.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 45.0000)\n"
            "STRAIGHT_TRAVERSE(2.0000, 0.5000, 45.0000)\n");
}

TEST(Expressions, Functions) {
  const auto r = read(
      "G0 X[ABS[-3]] Y[SQRT[16]] Z[ROUND[2.5]]\n"
      "G0 X[FIX[-1.5]] Y[FUP[1.2]] Z[COS[60]]\n"
      "G0 X[EXP[0]] Y[LN[1]] Z[TAN[45]]\n"
      "G0 X[ASIN[1]] Y[ACOS[1]] Z[ATAN[1]/[0]]\n"
      "G0 X[1 EQ 1.00001] Y[1 NE 2] Z[[1 LT 2] AND [2 LE 2] XOR [0 OR 0]]\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(3.0000, 4.0000, 3.0000)\n"
            "STRAIGHT_TRAVERSE(-2.0000, 2.0000, 0.5000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 1.0000)\n"
            "STRAIGHT_TRAVERSE(90.0000, 0.0000, 90.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 1.0000, 1.0000)\n");
}

TEST(Expressions, ParametersNumberedNamedIndirect) {
  const auto r = read(
      "#1=5 #2=1\n"
      "#<depth>=-2 #<_global>=7\n"
      "G0 X##2 Y#<depth> Z#<_global>\n"
      "#[#2+1]=9\n"  // #2 is 1: this sets #2
      "G0 X#2 Y#3\n"
      "#4=[#4+1] #4=[#4+1]\n"  // both read #4 before either is set: 1
      "G0 X#4 Y[EXISTS[#<depth>]] Z[EXISTS[#<nowhere>]]\n"
      "M2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(5.0000, -2.0000, 7.0000)\n"
            "STRAIGHT_TRAVERSE(9.0000, 0.0000, 7.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 1.0000, 0.0000)\n");
}

TEST(Expressions, SettingsTakeEffectAfterTheLine) {
  const auto r = read("#1=1\n#1=2 G0 X#1\nG0 Y#1\nM2\n");
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(1.0000, 2.0000, 0.0000)\n");
}

TEST(Expressions, StateParameters) {
  // #5420.. the current position; #<_x>; #5220 the coordinate system.
  const auto r = read("G0 X3 Y4\nG0 Z#5420\nG0 X#<_y>\nG55\nG0 X#5220\nM2\n");
  EXPECT_TRUE(r.result.ok()) << r.messages();
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(3.0000, 4.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(3.0000, 4.0000, 3.0000)\n"
            "STRAIGHT_TRAVERSE(4.0000, 4.0000, 3.0000)\n"
            "STRAIGHT_TRAVERSE(2.0000, 4.0000, 3.0000)\n");
}

TEST(Expressions, Errors) {
  EXPECT_TRUE(read("G0 X[1/0]\nM2\n").has(diag::Code::GcodeMathError));
  EXPECT_TRUE(read("G0 X[SQRT[-1]]\nM2\n").has(diag::Code::GcodeMathError));
  EXPECT_TRUE(read("G0 X[1+]\nM2\n").has(diag::Code::GcodeBadExpression));
  EXPECT_TRUE(read("G0 X[1+2\nM2\n").has(diag::Code::GcodeBadExpression));
  EXPECT_TRUE(read("G0 X#99999\nM2\n").has(diag::Code::GcodeBadParameter));
  EXPECT_TRUE(read("G0 X#<never>\nM2\n").has(diag::Code::GcodeBadParameter));
  EXPECT_TRUE(read("G0 X SIN 30\nM2\n").has(diag::Code::GcodeBadExpression));
  EXPECT_TRUE(read("G0 X EXISTS[#1+#2]\nM2\n").has(diag::Code::GcodeBadExpression));
  // The column points into the line as written (spaces included).
  const auto r = read("G0    X[1/0]\nM2\n");
  EXPECT_EQ(r.codes(), "GCODE-014 1:10\n");
}

TEST(Expressions, NestingIsBounded) {
  ReadOptions o;
  o.max_expression_depth = 8;
  std::string deep = "G0 X" + std::string(9, '[') + "1" + std::string(9, ']') + "\nM2\n";
  EXPECT_TRUE(read(deep, "linuxcnc", o).has(diag::Code::GcodeBadExpression));
  std::string ok = "G0 X" + std::string(8, '[') + "1" + std::string(8, ']') + "\nM2\n";
  EXPECT_TRUE(read(ok, "linuxcnc", o).result.ok());
  // A long chain of unary minus is bounded too (no recursion, bounded stacks).
  std::string minus = "G0 X[" + std::string(5000, '-') + "1]\nM2\n";
  EXPECT_TRUE(read(minus, "linuxcnc", o).has(diag::Code::GcodeBadExpression));
}

TEST(Expressions, MachineValuesWarnAndRefuseMotion) {
  // #5063: the probe's Z, which only the machine knows: read as 0 with a warning ...
  const auto a = read("#1=#5063\nM2\n");
  EXPECT_TRUE(a.result.ok()) << a.messages();
  EXPECT_TRUE(a.has(diag::Code::GcodeMachineValue));
  EXPECT_NE(a.messages().find("#5063"), std::string::npos) << a.messages();
  // ... but a motion that depends on it is an error saying so.
  const auto b = read("#1=[#5063+1]\nG0 Z#1\nM2\n");
  EXPECT_TRUE(b.has(diag::Code::GcodeMachineMotion)) << b.messages();
  const auto c = read("o1 if [#5070 GT 0]\nG0 X1\no1 endif\nM2\n");
  EXPECT_TRUE(c.has(diag::Code::GcodeMachineMotion)) << c.messages();
  const auto d = read("G0 X#<_hal[some.pin]>\nM2\n");
  EXPECT_TRUE(d.has(diag::Code::GcodeMachineMotion)) << d.messages();
}

// Numbers are read with a fast path for up to 15 digits; it must give exactly the double that
// std::from_chars gives (the correctly rounded one), for every placement of the point, signs,
// leading zeros and a leading '.', and beyond 15 digits (the slow path) too; at the end of a
// block (read byte by byte) and followed by more words (read eight bytes at a time).
TEST(Expressions, NumbersReadExactlyAsFromChars) {
  std::mt19937_64 random(19);
  std::vector<std::string> numbers = {"0",
                                      "0.",
                                      ".5",
                                      "-.25",
                                      "007.0700",
                                      "1.1",
                                      "0.1",
                                      "-0.3",
                                      "123456789012345",
                                      "1.23456789012345",
                                      "12345678901234567.5",
                                      ".1234567890123456"};
  for (int i = 0; i < 2000; ++i) {
    const int digits = 1 + static_cast<int>(random() % 24);
    std::string n;
    for (int d = 0; d < digits; ++d) n += static_cast<char>('0' + random() % 10);
    n.insert(random() % (n.size() + 1), ".");
    if (random() % 2) n.insert(0, "-");
    numbers.push_back(n);
  }
  std::string program = "G21 G90\n";
  for (const auto& n : numbers) program += "G0 X" + n + "\nG0 X" + n + " Y1.5 Z2.25\n";
  program += "M2\n";
  const auto r = read(program);
  ASSERT_TRUE(r.result.ok()) << r.messages();
  std::vector<double> xs;
  for (const auto& c : r.calls)
    if (const auto* t = std::get_if<canon::StraightTraverse>(&c)) xs.push_back(t->to.x);
  ASSERT_EQ(xs.size(), 2 * numbers.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    std::string n = numbers[i / 2];
    const bool negative = n.front() == '-';
    if (negative) n.erase(0, 1);
    if (n.front() == '.') n.insert(0, "0");
    double expected = 0;
    std::from_chars(n.data(), n.data() + n.size(), expected);
    if (negative) expected = -expected;
    EXPECT_EQ(xs[i], expected) << numbers[i / 2] << (i % 2 ? " followed by words" : " at the end");
  }
}

}  // namespace
}  // namespace ncpost::gcode
