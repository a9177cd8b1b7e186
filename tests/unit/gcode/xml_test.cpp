// The XML intermediate form (write_xml): blocks, words with evaluated values, canonical calls
// and <error row= column= code=> elements, valid against engine/gcode/gcode.rng (libxml2).

#include <gtest/gtest.h>

#include "gcode_support.hpp"
#include "xml_check.hpp"

namespace ncpost::gcode {
namespace {

std::string xml(const std::string& text, const std::string& id = "linuxcnc",
                ReadOptions options = {}) {
  std::string out;
  options.program_name = "t.ngc";
  (void)write_xml(
      text, *test::dialect(id), [&](std::string_view s) { out += s; }, options);
  return out;
}

std::string rng() {
  return (ncpost::test::source_dir() / "engine" / "gcode" / "gcode.rng").string();
}

TEST(XmlForm, BlocksWordsValuesCalls) {
  const std::string out = xml("#1=2\nG0 X[#1*3] Y-1 (here)\nM2\n");
  EXPECT_EQ(ncpost::test::rng_errors(out, rng()), "") << out;
  EXPECT_NE(out.find("<gcode-program format=\"ncpost-gcode\" version=\"1\" dialect=\"linuxcnc\" "
                     "name=\"t.ngc\">"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("<block file=\"t.ngc\" row=\"2\">\n  <source>G0 X[#1*3] Y-1 (here)</source>\n"
                     "  <comment column=\"16\">here</comment>\n"
                     "  <word address=\"G\" text=\"G0\" value=\"0\" column=\"1\"/>\n"
                     "  <word address=\"X\" text=\"X[#1*3]\" value=\"6\" column=\"4\"/>\n"
                     "  <word address=\"Y\" text=\"Y-1\" value=\"-1\" column=\"12\"/>\n"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("<STRAIGHT_TRAVERSE x=\"6\" y=\"-1\" z=\"0\"/>"), std::string::npos) << out;
  EXPECT_NE(out.find("<PROJECT_END"), std::string::npos);
  EXPECT_EQ(out.substr(out.size() - 17), "</gcode-program>\n");
}

TEST(XmlForm, ErrorsStandInTheirBlock) {
  const std::string out = xml("G0 X1\nG0 G1 X2\nG0 X[1/0]\n");
  EXPECT_EQ(ncpost::test::rng_errors(out, rng()), "") << out;
  EXPECT_NE(out.find("<error file=\"t.ngc\" row=\"2\" column=\"4\" code=\"GCODE-021\" "
                     "severity=\"error\">"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("row=\"3\" column=\"7\" code=\"GCODE-014\""), std::string::npos) << out;
  // The missing program end belongs to no block.
  EXPECT_NE(out.find("</block>\n<error file=\"t.ngc\""), std::string::npos) << out;
}

TEST(XmlForm, LoopsAreBlocksOncePerPass) {
  const std::string out = xml("#1=0\no1 while [#1 LT 3]\nG0 X#1\n#1=[#1+1]\no1 endwhile\nM2\n");
  EXPECT_EQ(ncpost::test::rng_errors(out, rng()), "") << out;
  std::size_t count = 0;
  for (std::size_t p = out.find("<source>G0 X#1</source>"); p != std::string::npos;
       p = out.find("<source>G0 X#1</source>", p + 1))
    ++count;
  EXPECT_EQ(count, 3u);
  EXPECT_NE(out.find("<statement kind=\"o-word\">O1WHILE[#1LT3]</statement>"), std::string::npos)
      << out;
}

TEST(XmlForm, HostileTextStaysWellFormed) {
  const std::string out = xml("G0 X1 (<&\"\x01\xff>)\n(MSG,</block>)\nM2\n");
  EXPECT_EQ(ncpost::test::rng_errors(out, rng()), "") << out;
}

TEST(XmlForm, EveryGoldenProgramIsValid) {
  const auto root = ncpost::test::source_dir() / "tests" / "golden" / "gcode";
  int n = 0;
  for (const auto& folder : std::filesystem::directory_iterator(root)) {
    if (!folder.is_directory()) continue;
    for (const auto& e : std::filesystem::directory_iterator(folder.path())) {
      if (e.path().extension() == ".trace") continue;
      const std::string out =
          xml(ncpost::test::read_file(e.path()), folder.path().filename().string());
      EXPECT_EQ(ncpost::test::rng_errors(out, rng()), "") << e.path();
      ++n;
    }
  }
  EXPECT_GE(n, 5);
}

TEST(XmlForm, SameCallsAsRead) {
  // The calls of the XML form are the calls read() makes.
  const std::string text = ncpost::test::read_file(ncpost::test::source_dir() / "tests" / "golden" /
                                                   "gcode" / "fanuc-0i" / "bolt-circle.nc");
  const auto r = test::read(text, "fanuc-0i");
  const std::string out = xml(text, "fanuc-0i");
  std::size_t elements = 0;
  for (const std::string name : {"<DRILL_CYCLE ", "<STRAIGHT_TRAVERSE ", "<CHANGE_TOOL "}) {
    std::size_t in_xml = 0, in_read = 0;
    for (std::size_t p = out.find(name); p != std::string::npos; p = out.find(name, p + 1))
      ++in_xml;
    const std::string call = name.substr(1, name.size() - 2) + "(";
    for (const auto& c : r.calls)
      if (canon::format_call(c).rfind(call, 0) == 0) ++in_read;
    EXPECT_EQ(in_xml, in_read) << name;
    elements += in_xml;
  }
  EXPECT_GT(elements, 9u);
}

}  // namespace
}  // namespace ncpost::gcode
