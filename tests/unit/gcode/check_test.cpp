// The checks, each with its code and position: syntax (words, modal groups, unknown codes) and
// semantics (feed, spindle, arcs, tools, program end, limits), and going on after an error.

#include <gtest/gtest.h>

#include <filesystem>

#include "gcode_support.hpp"

namespace ncpost::gcode {
namespace {

using test::read;

TEST(Checks, Syntax) {
  EXPECT_EQ(read("G0 G1 X1\nM2\n").codes(), "GCODE-021 1:4\n");
  EXPECT_EQ(read("G0 X1 X2\nM2\n").codes(), "GCODE-020 1:7\n");
  EXPECT_EQ(read("G4\nM2\n").codes(), "GCODE-022 1:1\n");
  EXPECT_EQ(read("G61 R0.5\nM2\n").codes(), "GCODE-024 1:5\n");
  EXPECT_EQ(read("X1\nM2\n").codes(), "GCODE-024 1:1\n");
  EXPECT_EQ(read("G0 X1 $\nM2\n").codes(), "GCODE-010 1:7\n");
  EXPECT_EQ(read("G0.25 X1\nM2\n").codes(), "GCODE-025 1:1\n");
  EXPECT_EQ(read("G7.5 X1\nM2\n").codes(), "GCODE-025 1:1\n");
  EXPECT_EQ(read("M555\nM2\n").codes(), "GCODE-025 1:1\n");
  EXPECT_EQ(read("G0 X1 (open\nM2\n").codes(), "GCODE-012 1:7\n");
  EXPECT_EQ(read("G0 X\nM2\n").codes(), "GCODE-011 1:5\n");
  EXPECT_EQ(read("G2 X1 Y1 R1 I1 F1\nM2\n").codes(), "GCODE-023 1:10\n");
  EXPECT_EQ(read("g64 m19 r90 s0\nM2\n").codes(), "GCODE-023 1:9\n");
}

TEST(Checks, Semantics) {
  EXPECT_EQ(read("G1 X1\nM2\n").codes(), "GCODE-030 1:1\n");
  // Feed with the spindle stopped: a warning, once until the spindle starts.
  EXPECT_EQ(read("F10 G1 X1\nG1 X2\nM2\n").codes(), "GCODE-031 1:5\n");
  EXPECT_EQ(read("S100 M3 F10 G1 X1\nM2\n").codes(), "");
  // LinuxCNC's bad-arc.small.metric: end radius beyond the tolerance.
  EXPECT_TRUE(read("G21 F1\nG0 X0 Y0 Z0\nG2 X50 Y0 I[25 - [0.0101 * SQRT[2]]]\nM2\n")
                  .has(diag::Code::GcodeArcRadius));
  EXPECT_FALSE(read("G21 F1\nG0 X0 Y0 Z0\nG2 X50 Y0 I[25 - [0.0099 * SQRT[2]]]\nM2\n")
                   .has(diag::Code::GcodeArcRadius));
  EXPECT_TRUE(read("G0 X0 F1\nG2 X10 R2\nM2\n").has(diag::Code::GcodeArcGeometry));
  EXPECT_TRUE(read("G2 X1 F1\nM2\n").has(diag::Code::GcodeMissingWord));
  EXPECT_TRUE(read("G0 X1\n").has(diag::Code::GcodeNoProgramEnd));
  EXPECT_TRUE(read("F1 G81 X1 Y1 Z2 R1\nM2\n").has(diag::Code::GcodeCycleGeometry));
  EXPECT_TRUE(read("F1 G83 X1 Y1 Z-2 R1\nM2\n").has(diag::Code::GcodeCycleGeometry));
}

TEST(Checks, ToolTable) {
  ReadOptions o;
  o.tools = std::vector<int>{1, 2};
  EXPECT_EQ(read("T2 M6\nM2\n", "linuxcnc", o).codes(), "");
  EXPECT_EQ(read("T7 M6\nM2\n", "linuxcnc", o).codes(), "GCODE-035 1:1\n");
  EXPECT_EQ(read("T7 M6\nM2\n").codes(), "");  // no table given: any tool
}

TEST(Checks, Limits) {
  ReadOptions o;
  MachineLimits l;
  l.x = MachineLimits::Range{-100, 100};
  l.max_feed = 1000;
  l.max_spindle = 5000;
  l.max_tool = 20;
  o.limits = l;
  const auto r = read("S9000 M3\nT21 M6\nF2000 G1 X50\nG0 X150\nM2\n", "linuxcnc", o);
  EXPECT_EQ(r.codes(), "GCODE-036 1:1\nGCODE-036 2:1\nGCODE-036 3:7\nGCODE-036 4:1\n");
  EXPECT_TRUE(r.result.ok());  // warnings unless the limits say errors
  o.limits->errors = true;
  EXPECT_FALSE(read("G0 X150\nM2\n", "linuxcnc", o).result.ok());
  // A motion past the travel, where that is an error, is not made (the renderer would report it
  // again, without its line); the blocks after it go on from where it would have ended.
  const auto refused = read("G0 X50\nG0 X150\nG91 G0 X-60\nM2\n", "linuxcnc", o);
  EXPECT_EQ(refused.codes(), "GCODE-036 2:1\n");
  EXPECT_EQ(
      refused.motions(),
      "STRAIGHT_TRAVERSE(50.0000, 0.0000, 0.0000)\nSTRAIGHT_TRAVERSE(90.0000, 0.0000, 0.0000)\n");
}

TEST(Checks, RefusedByName) {
  const auto lathe = read("G71 X1\nM2\n");
  EXPECT_TRUE(lathe.has(diag::Code::GcodeLathe));
  EXPECT_NE(lathe.messages().find("stock-removal"), std::string::npos) << lathe.messages();
  EXPECT_TRUE(read("G7\nM2\n").has(diag::Code::GcodeLathe));
  const auto comp = read("G41 D1\nM2\n");
  EXPECT_TRUE(comp.has(diag::Code::GcodeUnsupported));
  EXPECT_NE(comp.messages().find("cutter radius compensation"), std::string::npos);
}

TEST(Checks, GoesOnAfterAnErrorUpToMaxErrors) {
  const auto r = read("G1 X1\nG0 X2\nG0 X[1/0]\nG0 X3\nM2\n");
  EXPECT_EQ(r.codes(), "GCODE-030 1:1\nGCODE-014 3:7\n");
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(2.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(3.0000, 0.0000, 0.0000)\n");
  ReadOptions o;
  o.max_errors = 3;
  std::string bad;
  for (int i = 0; i < 100; ++i) bad += "G0 X[1/0]\n";
  const auto many = read(bad + "M2\n", "linuxcnc", o);
  EXPECT_EQ(many.result.diagnostics.size(), 4u);  // three errors and the note that it stopped
  EXPECT_EQ(many.result.diagnostics.back().diagnostic.code, diag::Code::GcodeTooManyErrors);
}

TEST(Checks, WarningsInALoopAreReportedOnce) {
  const auto r = read("#1=0\no1 while [#1 LT 1000]\n#2=#5063\n#1=[#1+1]\no1 endwhile\nM2\n");
  EXPECT_EQ(r.codes(), "GCODE-042 3:0\n");
}

TEST(Checks, LineLengthLimit) {
  ReadOptions o;
  o.max_line_length = 100;
  const auto r = read("G0 X1\n(" + std::string(200, 'x') + ")\nG0 X2\nM2\n", "linuxcnc", o);
  EXPECT_EQ(r.codes(), "GCODE-017 2:1\n");
  EXPECT_EQ(r.motions(),
            "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000)\n"
            "STRAIGHT_TRAVERSE(2.0000, 0.0000, 0.0000)\n");
}

TEST(Checks, DetectsGcode) {
  EXPECT_TRUE(looks_like_gcode("%\nO0001 (PART)\nN10 G21 G90\nN20 G0 X1\n"));
  EXPECT_TRUE(looks_like_gcode("(comment)\nG0 X1 Y2\nM2\n"));
  EXPECT_TRUE(looks_like_gcode("; sinumerik\nN10 G17 G71\nR1=5\n"));
  EXPECT_TRUE(looks_like_gcode("0 BEGIN PGM PART MM\n1 L X+10 FMAX\n"));
  EXPECT_TRUE(looks_like_gcode("#1=5\nG0 X#1\n"));
  EXPECT_FALSE(looks_like_gcode("ISO-10303-21;\nHEADER;\n"));
  EXPECT_FALSE(looks_like_gcode("<?xml version=\"1.0\"?>\n<iso_10303_28/>\n"));
  EXPECT_FALSE(looks_like_gcode("PARTNO/BRACKET\nUNITS/MM\nGOTO/1,2,3\nFEDRAT/200\n"));
  EXPECT_FALSE(looks_like_gcode(""));
  EXPECT_FALSE(looks_like_gcode("hello world\nthis is text\n"));
  // A P21 file may open with a comment; '/' alone would be a block delete.
  EXPECT_FALSE(looks_like_gcode("/* made by hand */\nISO-10303-21;\nHEADER;\n"));
  EXPECT_TRUE(looks_like_gcode("/N10 G0 X1\nG1 X2 F100\n"));
}

// What format detection sees: the first 4 KB of every G-code program of the corpus and of every
// G-code profile's golden posts say G-code; those of every P21, P28 and APT/CL file do not.
TEST(Checks, DetectsGcodeInTheCorpusAndThePosts) {
  namespace fs = std::filesystem;
  auto head = [](const fs::path& f) { return ncpost::test::read_file(f).substr(0, 4096); };
  std::size_t gcode = 0, other = 0;
  for (const char* id : {"linuxcnc", "fanuc-0i", "haas-ngc", "mitsubishi-m80", "okuma-osp",
                         "hnc-21", "siemens-840d", "heidenhain-tnc640"}) {
    for (const auto& e :
         fs::directory_iterator(ncpost::test::source_dir() / "tests" / "golden" / "post" / id)) {
      if (e.path().extension() == ".stp") continue;
      EXPECT_TRUE(looks_like_gcode(head(e.path()))) << e.path();
      ++gcode;
    }
  }
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  for (const auto& e : fs::recursive_directory_iterator(corpus / "gcode")) {
    const auto ext = e.path().extension();
    if (!e.is_regular_file() || (ext != ".ngc" && ext != ".gcode")) continue;
    const std::string h = head(e.path());
    // A program that is only blank lines says nothing either way.
    if (h.find_first_not_of(" \t\r\n") == std::string::npos) continue;
    EXPECT_TRUE(looks_like_gcode(h)) << e.path();
    ++gcode;
  }
  for (const char* folder : {"p21", "p21-aim", "p21-syntax", "p28", "cls"}) {
    for (const auto& e : fs::recursive_directory_iterator(corpus / folder)) {
      if (!e.is_regular_file()) continue;
      EXPECT_FALSE(looks_like_gcode(head(e.path()))) << e.path();
      ++other;
    }
  }
  EXPECT_GT(gcode, 300u);
  EXPECT_GT(other, 50u);
}

// A line that normalising would leave as it is (upper case, numbers, blanks between words) is
// read in place; it must read exactly as its normalised form: the same calls, the same
// diagnostics at the same columns. Each pair: a plain line, and the same program written so
// that it must be normalised (lower case, a tab, blanks inside words).
TEST(Checks, PlainLinesReadAsTheirNormalisedForm) {
  const std::vector<std::pair<std::string, std::string>> linuxcnc = {
      {"G21 F100 S1000 M3\nG1 X1 Y2.5 Z-0.25\nG2 X3 Y2.5 I1 J0\nM2\n",
       "g21 f100 s1000 m3\ng1 x1 y2.5 z-0.25\ng2\tX 3 Y2.5 I1 J 0\nm2\n"},
      {"G0 X1 X2\nM2\n", "g0 x1 x2\nm2\n"},
      {"G0 X12 Y-1.5\nM2\n", "G0 X1 2 Y- 1.5\nM2\n"},
      {"G0 X1 Q5\nM2\n", "G0 x1 Q5\nM2\n"},
      {"N10 G0 X1\nN20 Y2\nM2\n", "n10 G0 X1\nN20 y2\nM2\n"},
      {"O100 SUB\nG0 X1\nO100 ENDSUB\nO100 CALL\nM2\n",
       "o100 sub\nG0 X1\no100 endsub\no100 call\nM2\n"},
      // A loop's lines are read again from the interpreter's cache of normalised lines.
      {"#1=0\nO100 WHILE [#1 LT 3]\nG1 X#1 Y[#1*2] F100\n#1=[#1+1]\nO100 ENDWHILE\nM2\n",
       "#1=0\no100 while [#1 lt 3]\ng1 x#1 y[#1*2] f100\n#1=[#1+1]\no100 endwhile\nm2\n"},
  };
  for (const auto& [plain, normalised] : linuxcnc) {
    const auto a = read(plain);
    const auto b = read(normalised);
    EXPECT_EQ(a.body(), b.body()) << plain;
    EXPECT_EQ(a.codes(), b.codes()) << plain;
  }
  const std::string loop = read(linuxcnc.back().second).motions();
  EXPECT_EQ(std::count(loop.begin(), loop.end(), '\n'), 3) << loop;
  EXPECT_NE(loop.find("2.0000, 4.0000"), std::string::npos) << loop;
  // Blanks kept where the dialect keeps them (Sinumerik): a plain line is its own text.
  const auto s = read("G0 X1 Y2\nG1 X3 F100\nM30\n", "siemens-840d");
  const auto t = read("g0 x1 y2\ng1 x3 f100\nm30\n", "siemens-840d");
  EXPECT_EQ(s.body(), t.body());
  EXPECT_EQ(s.codes(), t.codes());
  // Blanks inside a word are still dropped, so the word reads as one.
  EXPECT_EQ(read("G 1 X 1 0 . 5 F 1 0 0\nM2\n").motions(), read("G1 X10.5 F100\nM2\n").motions());
}

}  // namespace
}  // namespace ncpost::gcode
