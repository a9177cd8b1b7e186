// One test per error class: each gives one clear diagnostic at the right place, and reading
// resumes at the next instance, so nothing after the damage is lost.

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace ncpost::p21 {
namespace {

using test::codes;
using test::dump;
using test::kFirstDataLine;
using test::wrap;
using namespace std::string_literals;

// Reads `data` (placed in a DATA section) whose line 2 is a good instance #2, and checks that
// exactly `code` is reported, on `line` and `column` relative to the data, and that #2 survived.
void expect_one_error_and_recovery(const std::string& data, const std::string& code,
                                   std::uint32_t line, std::uint32_t column) {
  const auto r = read(wrap(data));
  ASSERT_EQ(codes(r), std::vector<std::string>{code}) << dump(r);
  EXPECT_EQ(r.diagnostics[0].line, kFirstDataLine + line - 1) << dump(r);
  EXPECT_EQ(r.diagnostics[0].column, column) << dump(r);
  const Instance* good = r.model.find(2);
  ASSERT_NE(good, nullptr) << "the instance after the damage was lost\n" << dump(r);
  EXPECT_EQ(r.model.type_name(*good), "GOOD");
}

TEST(ReaderErrors, NulByte) {
  expect_one_error_and_recovery("#1=A(1,\0\0,2);\n#2=GOOD(1);"s, "P21-001", 1, 8);
}

TEST(ReaderErrors, NulByteInsideString) {
  expect_one_error_and_recovery("#1=A('ab\0c',2);\n#2=GOOD(1);"s, "P21-001", 1, 9);
}

TEST(ReaderErrors, InvalidCharacter) {
  expect_one_error_and_recovery("#1=A(1,%,2);\n#2=GOOD(1);", "P21-002", 1, 8);
}

TEST(ReaderErrors, UnterminatedString) {
  expect_one_error_and_recovery("#1=A('never closed,2);\n#2=GOOD(1);", "P21-003", 1, 6);
}

TEST(ReaderErrors, UnterminatedStringAtEndOfFile) {
  const auto r = read("ISO-10303-21;HEADER;FILE_DESCRIPTION(('x");
  EXPECT_NE(test::find_code(r, "P21-003"), nullptr) << dump(r);
}

TEST(ReaderErrors, BadEscapeKeepsTheInstance) {
  const auto r = read(wrap("#1=A('\\X2\\00G1\\X0\\');\n#2=GOOD(1);"));
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-005"}) << dump(r);
  EXPECT_NE(r.model.find(1), nullptr);
}

TEST(ReaderErrors, MalformedNumberStandsInAsUnset) {
  // The literal's extent is sound, so the rest of the instance is still read and checked.
  const auto r = read(wrap("#1=A(-1.#INF,#9);\n#2=GOOD(1);"));
  EXPECT_EQ(codes(r), (std::vector<std::string>{"P21-007", "P21-040"})) << dump(r);
  ASSERT_NE(r.model.find(1), nullptr);
  EXPECT_TRUE(r.model.params(*r.model.find(1))[0].is_omitted());
}

TEST(ReaderErrors, NumberOutOfRange) {
  expect_one_error_and_recovery("#1=A(99999999999999999999);\n#2=GOOD(1);", "P21-008", 1, 6);
}

TEST(ReaderErrors, IdOutOfRange) {
  expect_one_error_and_recovery("#99999999999999999999=A(1);\n#2=GOOD(1);", "P21-009", 1, 1);
}

TEST(ReaderErrors, MissingSemicolonBeforeNextInstance) {
  const auto r = read(wrap("#1=A(1)\n#2=GOOD(1);"));
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-022"}) << dump(r);
  EXPECT_EQ(r.diagnostics[0].line, kFirstDataLine);
  EXPECT_EQ(r.diagnostics[0].column, 8u);  // right after the ')'
  EXPECT_NE(r.model.find(1), nullptr);     // nothing was lost, only the ';'
  EXPECT_NE(r.model.find(2), nullptr);
}

TEST(ReaderErrors, MissingSemicolonBeforeEndsec) {
  const auto r = read(wrap("#2=GOOD(1)"));
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-022"}) << dump(r);
  EXPECT_NE(r.model.find(2), nullptr);
}

TEST(ReaderErrors, UnbalancedOpenParenthesis) {
  expect_one_error_and_recovery("#1=A((1,2);\n#2=GOOD(1);", "P21-023", 1, 11);
}

TEST(ReaderErrors, UnbalancedCloseParenthesis) {
  expect_one_error_and_recovery("#1=A(1));\n#2=GOOD(1);", "P21-023", 1, 8);
}

TEST(ReaderErrors, NestingTooDeep) {
  std::string deep = "#1=A(";
  for (int i = 0; i < 100000; ++i) deep += '(';
  deep += "\n#2=GOOD(1);";
  const auto r = read(wrap(deep));
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-024"}) << dump(r);
  EXPECT_NE(r.model.find(2), nullptr);
}

TEST(ReaderErrors, NestingLimitIsConfigurable) {
  ReadOptions options;
  options.max_list_depth = 3;
  EXPECT_TRUE(read(wrap("#1=A(((1)));"), options).ok());
  EXPECT_FALSE(read(wrap("#1=A((((1))));"), options).ok());
}

TEST(ReaderErrors, EmptyParameter) {
  const auto r = read(wrap("#1=A(,#2,);\n#2=GOOD(1);"));
  EXPECT_EQ(codes(r), (std::vector<std::string>{"P21-027", "P21-027"})) << dump(r);
  ASSERT_NE(r.model.find(1), nullptr);
  EXPECT_EQ(r.model.params(*r.model.find(1)).size(), 3u);
}

TEST(ReaderErrors, DanglingReferenceIsNamed) {
  const auto r = read(wrap("#7=A(1,2,#12);\n#2=GOOD(1);"));
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-040"});
  EXPECT_EQ(r.diagnostics[0].message, "#12 used by #7 attribute 3 is not defined");
  EXPECT_EQ(r.diagnostics[0].line, kFirstDataLine);
  EXPECT_EQ(r.diagnostics[0].column, 1u);
}

TEST(ReaderErrors, DanglingReferenceInsideListsAndTypedValues) {
  const auto r = read(wrap("#7=A((#2,(#30)),X(#31));\n#2=GOOD(1);"));
  ASSERT_EQ(codes(r), (std::vector<std::string>{"P21-040", "P21-040"})) << dump(r);
  EXPECT_EQ(r.diagnostics[0].message, "#30 used by #7 attribute 1 is not defined");
  EXPECT_EQ(r.diagnostics[1].message, "#31 used by #7 attribute 2 is not defined");
}

TEST(ReaderErrors, DuplicateIdKeepsTheFirst) {
  const auto r = read(wrap("#2=GOOD(1);\n#2=BAD(2);"));
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-041"}) << dump(r);
  EXPECT_EQ(r.diagnostics[0].line, kFirstDataLine + 1);
  EXPECT_EQ(r.model.type_name(*r.model.find(2)), "GOOD");
}

TEST(ReaderErrors, MissingMagic) {
  const auto r =
      read("HEADER;FILE_DESCRIPTION((''),'2;1');ENDSEC;DATA;#1=A();ENDSEC;END-ISO-10303-21;");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics[0].code_id(), "P21-020");
  EXPECT_NE(r.model.find(1), nullptr);
}

TEST(ReaderErrors, MissingEndsecAndEnd) {
  const auto r = read(
      "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');"
      "FILE_NAME('','',(''),(''),'','','');FILE_SCHEMA(('S'));ENDSEC;"
      "DATA;#1=A();");
  EXPECT_EQ(codes(r), (std::vector<std::string>{"P21-025", "P21-026"})) << dump(r);
}

// Issue 23 (15): Part 21 requires the HEADER section; a file without one is refused at the
// place where 'HEADER;' was expected, and its data is still read for the report.
TEST(ReaderErrors, MissingHeader) {
  const auto r = read("ISO-10303-21;\nDATA;#1=A();ENDSEC;END-ISO-10303-21;");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(codes(r), std::vector<std::string>{"P21-047"}) << dump(r);
  EXPECT_EQ(r.diagnostics[0].line, 2u);
  EXPECT_EQ(r.diagnostics[0].column, 1u);
  EXPECT_NE(r.model.find(1), nullptr);
  const auto empty = read("ISO-10303-21;END-ISO-10303-21;");
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(codes(empty), (std::vector<std::string>{"P21-047", "P21-046"})) << dump(empty);
  EXPECT_EQ(empty.diagnostics[0].column, 14u);
}

TEST(ReaderErrors, HeaderOrder) {
  const auto r = read(
      "ISO-10303-21;HEADER;FILE_SCHEMA(('S'));FILE_NAME('','',(''),(''),'','','');"
      "ENDSEC;DATA;ENDSEC;END-ISO-10303-21;");
  EXPECT_TRUE(r.ok());
  // FILE_DESCRIPTION is missing, and FILE_SCHEMA is not third.
  EXPECT_EQ(codes(r), (std::vector<std::string>{"P21-042", "P21-042"})) << dump(r);
}

TEST(ReaderErrors, EmptyComplexInstance) {
  expect_one_error_and_recovery("#1=();\n#2=GOOD(1);", "P21-044", 1, 1);
}

TEST(ReaderErrors, TrailingContent) {
  const auto r = read(wrap("#2=GOOD(1);") + "garbage after the end");
  EXPECT_EQ(codes(r), std::vector<std::string>{"P21-030"}) << dump(r);
}

TEST(ReaderErrors, ErrorLimitStopsReading) {
  std::string data;
  for (int i = 0; i < 50; ++i) data += "#" + std::to_string(i + 10) + "=A(%);\n";
  ReadOptions options;
  options.max_errors = 10;
  const auto r = read(wrap(data), options);
  EXPECT_EQ(r.diagnostics.size(), 11u) << dump(r);
  EXPECT_EQ(r.diagnostics.back().code_id(), "P21-028");
}

TEST(ReaderErrors, ManyBrokenInstancesLoseNoGoodOnes) {
  // Broken and good instances alternate; recovery must find every good one.
  std::string data;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    data += "#" + std::to_string(2 * i + 100) + "=BROKEN((1,2);\n";
    data += "#" + std::to_string(2 * i + 101) + "=OK(" + std::to_string(i) + ");\n";
  }
  ReadOptions options;
  options.max_errors = n + 1;
  const auto r = read(wrap(data), options);
  EXPECT_EQ(r.diagnostics.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(r.model.instances().size(), static_cast<std::size_t>(n));
  EXPECT_EQ(r.model.as_integer(r.model.params(*r.model.find(2 * (n - 1) + 101))[0]), n - 1);
}

TEST(ReaderErrors, EmptyAndGarbageInputsNeverCrash) {
  const std::vector<std::string> inputs = {std::string(),
                                           "ISO-10303-21;",
                                           ";;;;",
                                           "((((((",
                                           "#1=#2=#3=",
                                           "DATA;#1=A(",
                                           std::string(1, '\0'),
                                           "ISO-10303-21;HEADER;ENDSEC;DATA;#1=A('\\X2\\"};
  for (const std::string& input : inputs) {
    const auto r = read(input);
    EXPECT_FALSE(r.ok()) << "input: " << input;
  }
}

}  // namespace
}  // namespace ncpost::p21
