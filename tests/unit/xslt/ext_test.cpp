// The urn:ncpost:ext functions, each called from a small stylesheet.

#include <gtest/gtest.h>

#include <tuple>

#include "support.hpp"

namespace ncpost::xslt::test {
namespace {

class ExtTest : public XsltTest {
 protected:
  // The string value of `expression` (one transform of `job`).
  TransformResult run(std::string_view expression, JobState& job, std::string_view xml = "<a/>") {
    auto compiled = compile_ok(tree_, sheet("<xsl:template match=\"/\">\n<xsl:value-of select=\"" +
                                            std::string(expression) + "\"/>\n</xsl:template>"));
    if (!compiled) return {};
    return transform(*compiled, xml, job);
  }
  std::string eval(std::string_view expression, JobState& job, std::string_view xml = "<a/>") {
    TransformResult r = run(expression, job, xml);
    EXPECT_TRUE(r.ok) << expression << "\n" << all_messages(r.diagnostics);
    return r.output;
  }
  std::string eval(std::string_view expression, const JobConfig& config = {}) {
    JobState job(config);
    return eval(expression, job);
  }
  // `expression` must fail with XSLT-030 at the line of its xsl:value-of (7).
  std::string fails(std::string_view expression, const JobConfig& config = {}) {
    JobState job(config);
    TransformResult r = run(expression, job);
    EXPECT_FALSE(r.ok) << expression;
    EXPECT_TRUE(r.output.empty());
    if (r.diagnostics.empty()) {
      ADD_FAILURE() << expression << ": no diagnostic";
      return {};
    }
    EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-030")
        << all_messages(r.diagnostics);
    EXPECT_EQ(r.diagnostics.front().diagnostic.line, 7u) << all_messages(r.diagnostics);
    return r.diagnostics.front().diagnostic.message;
  }
};

// ---- block numbers ----

TEST_F(ExtTest, BlockNumbersCountWrapAndReset) {
  JobConfig config;
  config.block = {10, 10, 50};
  JobState job(config);
  EXPECT_EQ(eval("concat(ext:block(), ',', ext:block(), ',', ext:block())", job), "10,20,30");
  // The count goes on in the next transform of the same job, and wraps after the maximum.
  EXPECT_EQ(eval("concat(ext:block(), ',', ext:block(), ',', ext:block())", job), "40,50,10");
  EXPECT_EQ(eval("concat(ext:block(), ext:block-reset(), ',', ext:block())", job), "20,10");
  JobConfig ones;
  ones.block = {1, 1, 3};
  EXPECT_EQ(eval("concat(ext:block(), ext:block(), ext:block(), ext:block())", ones), "1231");
}

// ---- number formatting ----

TEST_F(ExtTest, FormatDefaults) {
  // length: 3 decimals, decimal point, leading zero, no trailing zeros.
  EXPECT_EQ(eval("ext:format(10, 'length')"), "10.");
  EXPECT_EQ(eval("ext:format(1.5, 'length')"), "1.5");
  EXPECT_EQ(eval("ext:format(0.5, 'length')"), "0.5");
  EXPECT_EQ(eval("ext:format(-13.5, 'length')"), "-13.5");
  EXPECT_EQ(eval("ext:format(1.23456, 'length')"), "1.235");
  EXPECT_EQ(eval("ext:format(-0.0001, 'length')"), "0.");   // no "-0."
  EXPECT_EQ(eval("ext:format('91.9', 'length')"), "91.9");  // strings (attributes) convert
  // Rounded as printf rounds the exact binary value: 1.0005 is 1.000499999...
  EXPECT_EQ(eval("ext:format(1.0005, 'length')"), "1.");
  // speed: whole numbers, no point.
  EXPECT_EQ(eval("ext:format(1200.4, 'speed')"), "1200");
  EXPECT_EQ(eval("ext:format(1500, 'feed')"), "1500.");
}

TEST_F(ExtTest, FormatFanucStyle) {
  JobConfig config;
  config.length = {3, true, false, false, 1.0};  // forced point, leading zero suppressed
  EXPECT_EQ(eval("ext:format(0.5, 'length')", config), ".5");
  EXPECT_EQ(eval("ext:format(-0.5, 'length')", config), "-.5");
  EXPECT_EQ(eval("ext:format(10, 'length')", config), "10.");
  EXPECT_EQ(eval("ext:format(0, 'length')", config), "0.");
  EXPECT_EQ(eval("ext:format(0.0004, 'length')", config), "0.");
}

TEST_F(ExtTest, FormatTrailingZerosAndNoPoint) {
  JobConfig config;
  config.length = {3, true, true, true, 1.0};
  EXPECT_EQ(eval("ext:format(1.5, 'length')", config), "1.500");
  EXPECT_EQ(eval("ext:format(-2, 'length')", config), "-2.000");
  config.length = {0, false, true, false, 1.0};
  // Exact binary ties go to even, as printf rounds.
  EXPECT_EQ(eval("ext:format(12.5, 'length')", config), "12");
  EXPECT_EQ(eval("ext:format(11.5, 'length')", config), "12");
  EXPECT_EQ(eval("ext:format(11.51, 'length')", config), "12");
  config.length = {2, false, true, false, 1.0};
  EXPECT_EQ(eval("ext:format(10, 'length')", config), "10");
  EXPECT_EQ(eval("ext:format(10.25, 'length')", config), "10.25");
}

TEST_F(ExtTest, FormatInches) {
  JobConfig config;
  config.units = Units::Inch;
  config.length = {4, true, true, false, 1.0};
  EXPECT_EQ(eval("ext:format(25.4, 'length')", config), "1.");
  EXPECT_EQ(eval("ext:format(12.7, 'length')", config), "0.5");
  EXPECT_EQ(eval("ext:format(254, 'feed')", config), "10.");
  EXPECT_EQ(eval("ext:format(90, 'angle')", config), "90.");  // angles and speeds are not lengths
  EXPECT_EQ(eval("ext:format(1000, 'speed')", config), "1000");
  EXPECT_EQ(eval("ext:units()", config), "inch");
  EXPECT_EQ(eval("ext:units()"), "mm");
  // A program written in inches, posted in inches: no conversion.
  JobState job(config);
  EXPECT_EQ(eval("concat(ext:program-units('inch'), ext:format(1.25, 'length'))", job), "1.25");
  // ... and posted in millimetres.
  JobState metric;
  EXPECT_EQ(eval("concat(ext:program-units('inch'), ext:format(1.25, 'length'))", metric), "31.75");
  EXPECT_EQ(eval("ext:format(2, 'length')", metric), "50.8");  // the units stay for the job
  EXPECT_EQ(eval("concat(ext:program-units('cm'), ext:format(2, 'length'))", metric), "20.");
}

TEST_F(ExtTest, FormatScaleForMilliseconds) {
  JobConfig config;
  config.dwell = {0, false, true, false, 1000.0};
  EXPECT_EQ(eval("ext:format(1.5, 'dwell')", config), "1500");
}

TEST_F(ExtTest, FormatErrors) {
  EXPECT_NE(fails("ext:format('abc', 'length')").find("not a finite number"), std::string::npos);
  EXPECT_NE(fails("ext:format(1, 'weight')").find("unknown quantity 'weight'"), std::string::npos);
  EXPECT_NE(fails("ext:format(1)").find("takes 2 argument(s), not 1"), std::string::npos);
  EXPECT_NE(fails("ext:program-units('furlong')").find("unknown units"), std::string::npos);
}

// ---- modal suppression ----

TEST_F(ExtTest, ModalWordsAppearOnlyWhenChanged) {
  JobState job;
  EXPECT_EQ(eval("concat(ext:modal('motion', 'G1'), '|', ext:modal('motion', 'G1'), '|', "
                 "ext:modal('motion', 'G0'))",
                 job),
            "G1||G0");
  // Groups are independent; the memory lasts for the job.
  EXPECT_EQ(eval("concat(ext:modal('plane', 'G17'), '|', ext:modal('motion', 'G0'))", job), "G17|");
  EXPECT_EQ(eval("concat(ext:modal-reset('motion'), ext:modal('motion', 'G0'), '|', "
                 "ext:modal('plane', 'G17'))",
                 job),
            "G0|");
  EXPECT_EQ(
      eval("concat(ext:modal-reset(), ext:modal('motion', 'G0'), '|', ext:modal('plane', 'G17'))",
           job),
      "G0|G17");
  // A new job remembers nothing.
  JobState fresh;
  EXPECT_EQ(eval("ext:modal('motion', 'G0')", fresh), "G0");
}

TEST_F(ExtTest, ModalGroupLimit) {
  JobConfig config;
  config.max_modal_groups = 2;
  EXPECT_NE(fails("concat(ext:modal('a', '1'), ext:modal('b', '1'), ext:modal('c', '1'))", config)
                .find("modal groups"),
            std::string::npos);
}

// ---- machine set-up transform ----

TEST_F(ExtTest, SetupOfTheXsltPaper) {
  // The paper's CoordinatesFormat: machine axes turned 90 degrees about Z, Z shifted by -14.7 mm:
  // x' = y, y' = -x, z' = z - 14.7, written with four decimals.
  JobConfig config;
  config.setup = SetupTransform::from_rotation({0, 0, 1}, 90, {0, 0, -14.7});
  config.length = {4, true, true, true, 1.0};
  EXPECT_EQ(eval("concat('X', ext:format(ext:setup-x(10, 20, 30), 'length'),"
                 "       ' Y', ext:format(ext:setup-y(10, 20, 30), 'length'),"
                 "       ' Z', ext:format(ext:setup-z(10, 20, 30), 'length'))",
                 config),
            "X20.0000 Y-10.0000 Z15.3000");
  // Directions turn but do not move.
  EXPECT_EQ(
      eval("concat(ext:setup-i(1, 0, 0), ',', ext:setup-j(1, 0, 0), ',', ext:setup-k(1, 0, 0))",
           config),
      "0,-1,0");
}

TEST_F(ExtTest, SetupIdentityAndMatrix) {
  EXPECT_EQ(
      eval("concat(ext:setup-x(1, 2, 3), ',', ext:setup-y(1, 2, 3), ',', ext:setup-z(1, 2, 3))"),
      "1,2,3");
  JobConfig config;
  config.setup.matrix = {0, 0, 1, 0, 1, 0, -1, 0, 0};  // x' = z, y' = y, z' = -x
  config.setup.translation = {100, 0, 0};
  EXPECT_EQ(
      eval("concat(ext:setup-x(1, 2, 3), ',', ext:setup-y(1, 2, 3), ',', ext:setup-z(1, 2, 3))",
           config),
      "103,2,-1");
  const SetupTransform half = SetupTransform::from_rotation({0, 0, 2}, 180);
  EXPECT_EQ(half.matrix, (std::array<double, 9>{-1, 0, 0, 0, -1, 0, 0, 0, 1}));
  const SetupTransform about_x = SetupTransform::from_rotation({1, 0, 0}, -90);
  // Machine axes turned -90 degrees about X: program +Y is machine +Z.
  EXPECT_EQ(about_x.matrix, (std::array<double, 9>{1, 0, 0, 0, 0, -1, 0, 1, 0}));
  EXPECT_NE(fails("ext:setup-x(1, 2)").find("takes 3"), std::string::npos);
  EXPECT_NE(fails("ext:setup-x(1, 2, 'z')").find("not a finite number"), std::string::npos);
}

// ---- arcs ----

TEST_F(ExtTest, ArcRadiusIsNegativeOver180Degrees) {
  // Quarter circle counter-clockwise from (10, 0) to (0, 10) about the origin, and the other
  // way round (270 degrees clockwise).
  EXPECT_EQ(eval("ext:arc-r(10, 0, 0, 10, 0, 0, 1)"), "10");
  EXPECT_EQ(eval("ext:arc-r(10, 0, 0, 10, 0, 0, -1)"), "-10");
  EXPECT_EQ(eval("ext:arc-r(10, 0, -10, 0, 0, 0, 1)"), "10");  // exactly 180: positive
  EXPECT_EQ(eval("ext:arc-sweep(10, 0, 0, 10, 0, 0, 1)"), "90");
  EXPECT_EQ(eval("ext:arc-sweep(10, 0, 0, 10, 0, 0, -1)"), "-270");
  EXPECT_EQ(eval("ext:arc-sweep(10, 0, 0, 10, 0, 0, 2)"), "450");
  EXPECT_EQ(eval("ext:arc-sweep(10, 0, 10, 0, 0, 0, -1)"), "-360");
  EXPECT_NE(fails("ext:arc-r(10, 0, 10, 0, 0, 0, 1)").find("full circle"), std::string::npos);
  EXPECT_NE(fails("ext:arc-r(10, 0, 0, 10, 0, 0, 2)").find("full circle"), std::string::npos);
  EXPECT_NE(fails("ext:arc-r(10, 0, 0, 10, 0, 0, 0)").find("turns"), std::string::npos);
  EXPECT_NE(fails("ext:arc-r(10, 0, 0, 10, 0, 0, 1.5)").find("turns"), std::string::npos);
  EXPECT_NE(fails("ext:arc-sweep(0, 0, 0, 10, 0, 0, 1)").find("centre"), std::string::npos);
}

TEST_F(ExtTest, ArcIncrementalCentre) {
  EXPECT_EQ(eval("concat(ext:arc-i(10, 0), ',', ext:arc-j(0, 0), ',', ext:arc-k(2, 7.5))"),
            "-10,0,5.5");
}

TEST_F(ExtTest, ArcCentreFromR) {
  const auto centre = [this](std::string_view args) {
    return eval("concat(ext:format(ext:arc-centre-x(" + std::string(args) +
                "), 'length'), ',', ext:format(ext:arc-centre-y(" + std::string(args) +
                "), 'length'))");
  };
  EXPECT_EQ(centre("10, 0, 0, 10, 10, 'ccw'"), "0.,0.");
  EXPECT_EQ(centre("10, 0, 0, 10, -10, 'ccw'"), "10.,10.");
  EXPECT_EQ(centre("10, 0, 0, 10, 10, 'cw'"), "10.,10.");
  EXPECT_EQ(centre("10, 0, 0, 10, -10, -1"), "0.,0.");
  EXPECT_EQ(centre("10, 0, -10, 0, 10, 'CW'"), "0.,0.");  // half circle
  EXPECT_NE(fails("ext:arc-centre-x(10, 0, 0, 10, 1, 'cw')").find("no circle"), std::string::npos);
  EXPECT_NE(fails("ext:arc-centre-x(10, 0, 0, 10, 10, 'up')").find("direction"), std::string::npos);
}

constexpr std::string_view kPoints = R"x(<xsl:template match="/">
  <xsl:for-each select="ext:arc-split-quadrants(10, 0, 0, -10, 0, 4, 0, 0, 1)">
    <xsl:value-of select="concat(@x, ',', @y, ',', @z, ';')"/>
  </xsl:for-each>
  <xsl:text>|</xsl:text>
  <xsl:variable name="pieces" select="ext:arc-split(10, 0, 0, 0, -10, -3, 0, 0, 1, 100)"/>
  <xsl:value-of select="count($pieces)"/>
  <xsl:for-each select="$pieces">
    <xsl:value-of select="concat(';', format-number(@x, '0.###'), ',', format-number(@y, '0.###'), ',', @z)"/>
  </xsl:for-each>
  <xsl:text>|</xsl:text>
  <xsl:for-each select="ext:arc-split-quadrants(7, 7, 0, 7, -7, 0, 0, 0, -1)">
    <xsl:value-of select="concat(format-number(@x, '0.###'), ',', format-number(@y, '0.###'), ';')"/>
  </xsl:for-each>
  <xsl:text>|</xsl:text>
  <xsl:value-of select="count(ext:arc-split-quadrants(10, 0, 0, 10, 0, 0, 0, 0, 1))"/>
</xsl:template>)x";

TEST_F(ExtTest, ArcSplitting) {
  auto compiled = compile_ok(tree_, sheet(kPoints));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, "<a/>", job);
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output,
            // half circle: ends at 90 degrees (z halfway) and at the end point
            "0,10,2;-10,0,4;"
            // 270 degrees in pieces of at most 100: three of 90 degrees, z linear
            "|3;0,10,-1;-10,0,-2;0,-10,-3"
            // clockwise from 45 to -45 degrees crosses 0 degrees once
            "|9.899,0;7,-7;"
            // a full circle: four quadrants
            "|4");
  EXPECT_NE(fails("ext:arc-split(10, 0, 0, 0, 10, 0, 0, 0, 1, 0)").find("max-sweep"),
            std::string::npos);
  EXPECT_NE(fails("ext:arc-split(10, 0, 0, 0, 10, 0, 0, 0, 1, 0.0001)").find("cannot be split"),
            std::string::npos);
}

// ---- rotary axes ----

TEST_F(ExtTest, RotaryAnglesAC) {
  const auto angles = [this](std::string_view v) {
    JobState job;
    return eval("concat(ext:format(ext:rotary(" + std::string(v) +
                    ", 'AC', 'A'), 'angle'), ' ', ext:format(ext:rotary(" + std::string(v) +
                    ", 'AC', 'C'), 'angle'))",
                job);
  };
  EXPECT_EQ(angles("1, 0, 0"), "90. 90.");
  EXPECT_EQ(angles("0, -1, 0"), "90. 0.");
  EXPECT_EQ(angles("0, 1, 0"), "90. 180.");
  EXPECT_EQ(angles("-1, 0, 0"), "90. -90.");
  // The 30 degree head of the CLS paper: K = 0.8660254.
  EXPECT_EQ(angles("0, -0.5, 0.8660254"), "30. 0.");
  // Not normalised: the direction counts.
  EXPECT_EQ(angles("0, -2, 0"), "90. 0.");
  EXPECT_EQ(angles("0, 0, 1"), "0. 0.");
  EXPECT_EQ(angles("0, 0, -1"), "180. 0.");
}

TEST_F(ExtTest, RotaryAnglesBC) {
  JobState job;
  EXPECT_EQ(
      eval("concat(ext:rotary(1, 0, 0, 'BC', 'B'), ' ', ext:rotary(1, 0, 0, 'BC', 'C'))", job),
      "90 0");
  EXPECT_EQ(
      eval("concat(ext:rotary(0, 1, 0, 'BC', 'B'), ' ', ext:rotary(0, 1, 0, 'BC', 'C'))", job),
      "90 90");
}

TEST_F(ExtTest, RotaryKeepsCWhenTheAxisIsVertical) {
  JobState job;
  EXPECT_EQ(eval("ext:format(ext:rotary(-1, 0, 0, 'AC', 'C'), 'angle')", job), "-90.");
  // Vertical tool axis: C is undefined, the last C of the job stays.
  EXPECT_EQ(eval("ext:format(ext:rotary(0, 0, 1, 'AC', 'C'), 'angle')", job), "-90.");
  EXPECT_EQ(eval("ext:format(ext:rotary(0, 0, 1, 'AC', 'A'), 'angle')", job), "0.");
  job.reset();
  EXPECT_EQ(eval("ext:format(ext:rotary(0, 0, 1, 'AC', 'C'), 'angle')", job), "0.");
}

TEST_F(ExtTest, RotaryErrors) {
  EXPECT_NE(fails("ext:rotary(0, 0, 1, 'XY', 'A')").find("kinematics"), std::string::npos);
  EXPECT_NE(fails("ext:rotary(0, 0, 1, 'AC', 'B')").find("axis 'B'"), std::string::npos);
  EXPECT_NE(fails("ext:rotary(0, 0, 0, 'AC', 'A')").find("no direction"), std::string::npos);
}

// ---- comments and lines ----

TEST_F(ExtTest, CommentsCannotCloseEarly) {
  EXPECT_EQ(eval("ext:comment('Face (rough)&#9;pass; ok')"), "Face  rough  pass  ok");
  EXPECT_EQ(eval("ext:comment(')M30(')"), "M30");
  JobConfig dropping;
  dropping.comment.replacement = "";
  EXPECT_EQ(eval("ext:comment('Face (rough)&#9;pass; ok')", dropping), "Face roughpass ok");
  // UTF-8 characters are replaced whole, not byte by byte.
  EXPECT_EQ(eval("ext:comment('&#216;10 bore &#8212; deep')"), "10 bore   deep");
  JobConfig config;
  config.comment.upper_case = true;
  config.comment.replacement = "";
  config.comment.max_length = 12;
  EXPECT_EQ(eval("ext:comment('Face (rough) pass')", config), "FACE ROUGH P");
  config.comment = CommentRules{};
  config.comment.replacement = "(x)";  // a replacement with parentheses is cleaned too
  EXPECT_EQ(eval("ext:comment('a(b')", config), "axb");
  config.comment = CommentRules{};
  config.comment.allowed = "ABC";
  EXPECT_EQ(eval("ext:comment('CAB-cab')", config), "CAB");
}

TEST_F(ExtTest, LongLinesAreWarnings) {
  JobConfig config;
  config.max_line_length = 10;
  JobState job(config);
  TransformResult r = run("ext:line('N10 G1 X100. Y200.')", job);
  EXPECT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "N10 G1 X100. Y200.");  // not split: splitting would change the block
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].diagnostic.code_id(), "XSLT-031");
  EXPECT_EQ(r.diagnostics[0].diagnostic.severity, diag::Severity::Warning);
  EXPECT_EQ(r.diagnostics[0].diagnostic.line, 7u);
  EXPECT_NE(r.diagnostics[0].diagnostic.message.find("18 characters"), std::string::npos)
      << r.diagnostics[0].diagnostic.message;
  TransformResult short_line = run("ext:line('N10 G1')", job);
  EXPECT_TRUE(short_line.ok);
  EXPECT_TRUE(short_line.diagnostics.empty());
  JobState unlimited;
  EXPECT_TRUE(run("ext:line('N10 G1 X100. Y200.')", unlimited).diagnostics.empty());
}

// ---- current position ----

TEST_F(ExtTest, PositionIsRememberedForTheJob) {
  JobState job;
  EXPECT_NE(fails("ext:position('x')").find("no position yet"), std::string::npos);
  EXPECT_EQ(eval("ext:moved-to(1, 2.5, -3)", job), "");
  EXPECT_EQ(eval("concat(ext:position('x'), ',', ext:position('y'), ',', ext:position('z'))", job),
            "1,2.5,-3");
  EXPECT_NE(fails("ext:position('w')").find("not x, y or z"), std::string::npos);
}

TEST_F(ExtTest, AnErrorStopsTheTransform) {
  // The first error of an ext: function ends the job: nothing after it runs.
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:template match="/">
  <xsl:value-of select="ext:format(1, 'nope')"/>
  <xsl:message>after</xsl:message>
</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, "<a/>", job);
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.diagnostics.size(), 1u) << all_messages(r.diagnostics);
  EXPECT_EQ(r.diagnostics[0].diagnostic.code_id(), "XSLT-030");
}

// ---- words (ext_words.cpp) ----

class WordsTest : public ExtTest {
 protected:
  // Applies `templates` to the children of the root element of `xml`.
  TransformResult apply(std::string_view templates, std::string_view xml, JobState& job,
                        const Params& params = {}) {
    auto compiled = compile_ok(tree_, sheet(R"x(<xsl:param name="form" select="'ijk'"/>
<xsl:template match="/"><xsl:apply-templates select="*/*"/></xsl:template>
)x" + std::string(templates)));
    if (!compiled) return {};
    return transform(*compiled, xml, job, params);
  }
  static JobConfig fanuc() {
    JobConfig config;
    config.length = {3, true, false, false, 1.0};
    config.angle = {3, true, false, false, 1.0};
    return config;
  }
};

constexpr std::string_view kWordTemplates = R"x(
<xsl:template match="STRAIGHT_FEED | STRAIGHT_TRAVERSE"><xsl:value-of select="ext:motion-words()"/>|</xsl:template>
<xsl:template match="ARC_FEED"><xsl:value-of select="ext:arc-words($form)"/>|</xsl:template>)x";

// The same words written with the single functions, as ncpost-common.xsl did before.
constexpr std::string_view kSingleFunctionTemplates = R"x(
<xsl:template match="STRAIGHT_FEED | STRAIGHT_TRAVERSE">
  <xsl:value-of select="concat(' X', ext:format(ext:setup-x(@x, @y, @z), 'length'),
      ' Y', ext:format(ext:setup-y(@x, @y, @z), 'length'), ' Z', ext:format(ext:setup-z(@x, @y, @z), 'length'))"/>
  <xsl:if test="@a"><xsl:value-of select="concat(' A', ext:format(@a, 'angle'))"/></xsl:if>
  <xsl:if test="@c"><xsl:value-of select="concat(' C', ext:format(@c, 'angle'))"/></xsl:if>
  <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>|</xsl:template>
<xsl:template match="ARC_FEED">
  <xsl:variable name="sx" select="ext:position('x')"/>
  <xsl:variable name="sy" select="ext:position('y')"/>
  <xsl:variable name="sz" select="ext:position('z')"/>
  <xsl:value-of select="concat(' X', ext:format(ext:setup-x(@x, @y, @z), 'length'),
      ' Y', ext:format(ext:setup-y(@x, @y, @z), 'length'), ' Z', ext:format(ext:setup-z(@x, @y, @z), 'length'))"/>
  <xsl:choose>
    <xsl:when test="$form = 'r' and @plane = 'xy' and (@rotation = 1 or @rotation = -1) and
                    ext:arc-sweep($sx, $sy, @x, @y, @cx, @cy, @rotation) &lt; 359.999 and
                    ext:arc-sweep($sx, $sy, @x, @y, @cx, @cy, @rotation) &gt; -359.999">
      <xsl:value-of select="concat(' R', ext:format(ext:arc-r($sx, $sy, @x, @y, @cx, @cy, @rotation), 'length'))"/>
    </xsl:when>
    <xsl:otherwise>
      <xsl:variable name="i" select="ext:format(ext:arc-i(ext:setup-x($sx, $sy, $sz), ext:setup-x(@cx, @cy, @cz)), 'length')"/>
      <xsl:variable name="j" select="ext:format(ext:arc-j(ext:setup-y($sx, $sy, $sz), ext:setup-y(@cx, @cy, @cz)), 'length')"/>
      <xsl:variable name="k" select="ext:format(ext:arc-k(ext:setup-z($sx, $sy, $sz), ext:setup-z(@cx, @cy, @cz)), 'length')"/>
      <xsl:choose>
        <xsl:when test="@plane = 'yz'"><xsl:value-of select="concat(' J', $j, ' K', $k)"/></xsl:when>
        <xsl:when test="@plane = 'xz'"><xsl:value-of select="concat(' I', $i, ' K', $k)"/></xsl:when>
        <xsl:otherwise><xsl:value-of select="concat(' I', $i, ' J', $j)"/></xsl:otherwise>
      </xsl:choose>
    </xsl:otherwise>
  </xsl:choose>
  <xsl:if test="@rotation &gt; 1 or @rotation &lt; -1"><xsl:value-of select="concat(' P', translate(@rotation, '-', ''))"/></xsl:if>
  <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>|</xsl:template>)x";

constexpr std::string_view kArcs = R"x(<c>
  <STRAIGHT_FEED x="10" y="2" z="3"/>
  <ARC_FEED x="20" y="2" z="3" cx="15" cy="2" cz="3" plane="xy" rotation="-1"/>
  <ARC_FEED x="20" y="2" z="1" cx="15" cy="2" cz="1" plane="xy" rotation="2"/>
  <ARC_FEED x="20" y="2" z="1" cx="17.5" cy="-1.25" cz="1" plane="xy" rotation="1"/>
  <STRAIGHT_TRAVERSE x="0" y="0" z="0" a="45" c="-90.0004"/>
  <ARC_FEED x="0" y="10" z="10" cx="0" cy="0" cz="10" plane="yz" rotation="1"/>
  <ARC_FEED x="-10" y="10" z="20" cx="-10" cy="10" cz="10" plane="xz" rotation="-3"/>
  <STRAIGHT_FEED x="0.0004" y="-0.0004" z="123456.78951"/>
</c>)x";

TEST_F(WordsTest, MotionAndArcWordsEqualTheSingleFunctions) {
  JobConfig rotated = fanuc();
  rotated.setup = SetupTransform::from_rotation({0, 0, 1}, 90, {0, 0, -14.7});
  JobConfig tilted = fanuc();
  tilted.setup = SetupTransform::from_rotation({1, 1, 0.5}, 33.3, {2.5, -1, 7});
  for (const JobConfig& config : {fanuc(), rotated, tilted, JobConfig{}}) {
    for (const char* form : {"ijk", "r"}) {
      SCOPED_TRACE(form);
      JobState words_job(config), single_job(config);
      const Params params{{"form", form}};
      TransformResult words = apply(kWordTemplates, kArcs, words_job, params);
      TransformResult single = apply(kSingleFunctionTemplates, kArcs, single_job, params);
      ASSERT_TRUE(words.ok) << all_messages(words.diagnostics);
      ASSERT_TRUE(single.ok) << all_messages(single.diagnostics);
      EXPECT_EQ(words.output, single.output);
    }
  }
}

// Near a half circle R's rounding moves the centre far (here 0.11 mm: R 12.663 written for
// 12.6625, over a chord of 25.325): the centre goes out as I J instead. A half circle whose
// written numbers are exact (the docs' example below) keeps its R.
TEST_F(WordsTest, RIsNotWrittenWhereItsRoundingMovesTheCentre) {
  constexpr std::string_view kHalfCircle = R"x(<c>
  <STRAIGHT_FEED x="-80" y="-24.375" z="-1"/>
  <ARC_FEED x="-80" y="0.949999988079071" z="-1" cx="-80" cy="-11.712499618530273" cz="-1"
            plane="xy" rotation="-1"/>
</c>)x";
  JobState job(fanuc());
  TransformResult r = apply(kWordTemplates, kHalfCircle, job, {{"form", "r"}});
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, " X-80. Y-24.375 Z-1.| X-80. Y.95 Z-1. I0. J12.663|");
}

TEST_F(WordsTest, FanucWordsAsTheDocsShowThem) {
  for (const auto& [form, arc] :
       {std::pair{"r", " X20. Y2. Z3. R5."}, {"ijk", " X20. Y2. Z3. I5. J0."}}) {
    JobState job(fanuc());
    TransformResult r = apply(kWordTemplates, kArcs, job, {{"form", form}});
    ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
    EXPECT_EQ(r.output.substr(0, r.output.find('|', 15) + 1),
              std::string(" X10. Y2. Z3.|") + arc + "|")
        << r.output;
    // Two turns: I J and the turn count, also when R is asked for.
    EXPECT_NE(r.output.find("| X20. Y2. Z1. I-5. J0. P2|"), std::string::npos) << r.output;
    // Rotary words, and the end recorded for the next arc (a YZ arc: J K).
    EXPECT_NE(r.output.find("| X0. Y0. Z0. A45. C-90.|"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("| X0. Y10. Z10. J0. K10.|"), std::string::npos) << r.output;
  }
}

TEST_F(WordsTest, ErrorsAreJobErrors) {
  const std::string polar =
      R"x(<xsl:template match="*"><xsl:value-of select="ext:arc-words('polar')"/></xsl:template>)x";
  const std::tuple<std::string_view, std::string_view, std::string_view> cases[] = {
      {kWordTemplates, R"(<c><STRAIGHT_FEED x="1" y="2"/></c>)", "x, y and z"},
      {kWordTemplates, R"(<c><STRAIGHT_FEED x="1" y="2" z="NaN"/></c>)", "not finite"},
      {kWordTemplates,
       R"(<c><ARC_FEED x="1" y="2" z="0" cx="0" cy="0" cz="0" plane="xy" rotation="1"/></c>)",
       "no position yet"},
      {kWordTemplates, R"(<c><STRAIGHT_FEED x="1" y="2" z="0"/><ARC_FEED x="1" y="2" z="0"/></c>)",
       "cx, cy, cz, rotation"},
      {polar, "<c><ARC_FEED/></c>", "form 'polar'"}};
  for (const auto& [templates, xml, expected] : cases) {
    JobState job;
    TransformResult r = apply(templates, xml, job);
    EXPECT_FALSE(r.ok) << xml;
    ASSERT_FALSE(r.diagnostics.empty()) << xml;
    EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-030");
    EXPECT_NE(r.diagnostics.front().diagnostic.message.find(expected), std::string::npos)
        << all_messages(r.diagnostics);
  }
}

TEST_F(WordsTest, BlockLineFollowsTheProfilesNumbering) {
  JobConfig numbered;
  numbered.block = {10, 10, 99999, true};
  numbered.max_line_length = 12;
  JobState job(numbered);
  TransformResult r = run(
      "concat(ext:block-numbering(), '|', ext:block-line('G1 X1.'), '|', ext:numbered-line('M3'), "
      "'|', ext:block-line('G1 X100. Y200.'))",
      job);
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "yes|N10 G1 X1.|N20 M3|N30 G1 X100. Y200.");
  ASSERT_EQ(r.diagnostics.size(), 1u);  // the last block is too long: a warning
  EXPECT_EQ(r.diagnostics[0].diagnostic.code_id(), "XSLT-031");
  JobState plain;
  EXPECT_EQ(eval("concat(ext:block-numbering(), '|', ext:block-line('G1 X1.'))", plain),
            "no|G1 X1.");
}

}  // namespace
}  // namespace ncpost::xslt::test
