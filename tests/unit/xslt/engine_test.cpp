// The engine: compile once, transform per job; output as xsl:output says; compile and input
// errors as diagnostics at the right file:line; parameters; messages.

#include <gtest/gtest.h>

#include "support.hpp"

namespace ncpost::xslt::test {
namespace {

// A small FANUC-style profile: block numbers, modal G codes, formatted words, R arcs, comments.
constexpr std::string_view kFanucBody = R"x(
<xsl:template match="/"><xsl:apply-templates select="chunk/workingstep"/></xsl:template>
<xsl:template name="block">
  <xsl:param name="words"/>
  <xsl:value-of select="ext:line(normalize-space(concat('N', ext:block(), ' ', $words)))"/>
  <xsl:text>&#10;</xsl:text>
</xsl:template>
<xsl:template match="workingstep">
  <xsl:call-template name="block">
    <xsl:with-param name="words" select="concat('(', ext:comment(@name), ')')"/>
  </xsl:call-template>
  <xsl:apply-templates select="*"/>
</xsl:template>
<xsl:template match="SET_FEED_RATE"/>
<xsl:template name="xyz">
  <xsl:value-of select="concat(' X', ext:format(@x, 'length'), ' Y', ext:format(@y, 'length'),
                               ' Z', ext:format(@z, 'length'))"/>
</xsl:template>
<xsl:template match="STRAIGHT_TRAVERSE">
  <xsl:call-template name="block">
    <xsl:with-param name="words"><xsl:value-of select="ext:modal('motion', 'G0')"/><xsl:call-template name="xyz"/></xsl:with-param>
  </xsl:call-template>
  <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
</xsl:template>
<xsl:template match="STRAIGHT_FEED">
  <xsl:call-template name="block">
    <xsl:with-param name="words">
      <xsl:value-of select="ext:modal('motion', 'G1')"/><xsl:call-template name="xyz"/>
      <xsl:value-of select="ext:modal('feed', concat(' F', ext:format(preceding-sibling::SET_FEED_RATE[1]/@rate, 'feed')))"/>
    </xsl:with-param>
  </xsl:call-template>
  <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
</xsl:template>
<xsl:template match="ARC_FEED">
  <xsl:variable name="r" select="ext:arc-r(ext:position('x'), ext:position('y'), @x, @y, @cx, @cy, @turns)"/>
  <xsl:call-template name="block">
    <xsl:with-param name="words" select="concat(ext:modal('motion', substring('G2G3', 1 + 2 * number(@turns > 0), 2)),
        ' X', ext:format(@x, 'length'), ' Y', ext:format(@y, 'length'), ' R', ext:format($r, 'length'))"/>
  </xsl:call-template>
  <xsl:value-of select="ext:moved-to(@x, @y, @z)"/>
</xsl:template>
<xsl:template match="COMMENT">(<xsl:value-of select="ext:comment(.)"/>)<xsl:text>&#10;</xsl:text></xsl:template>
)x";

constexpr std::string_view kFanucOutput =
    "N10 (WS FINISH PLANAR FACE1)\n"
    "N20 G0 X0. Y0. Z10.\n"
    "N30 G1 X91.9 Y-13.5 Z2.5 F500.\n"
    "N40 X10. Y2. Z3.\n"
    "N50 G2 X20. Y2. R5.\n"
    "(FINISH  FACE)\n";

JobConfig fanuc_config() {
  JobConfig config;
  config.comment.upper_case = true;
  return config;
}

TEST_F(XsltTest, RendersACanonChunk) {
  auto compiled = compile_ok(tree_, sheet(kFanucBody));
  ASSERT_TRUE(compiled);
  EXPECT_EQ(compiled->output_method(), "text");
  JobState job(fanuc_config());
  TransformResult r = transform(*compiled, kChunk, job);
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, kFanucOutput);
  EXPECT_TRUE(r.diagnostics.empty()) << all_messages(r.diagnostics);
}

TEST_F(XsltTest, StateCarriesAcrossTransformsOfOneJobOnly) {
  auto compiled = compile_ok(tree_, sheet(kFanucBody));
  ASSERT_TRUE(compiled);
  JobState job(fanuc_config());
  ASSERT_TRUE(transform(*compiled, kChunk, job).ok);
  // The second chunk of the same job continues the numbering and the modal state.
  TransformResult second = transform(*compiled, kChunk, job);
  ASSERT_TRUE(second.ok) << all_messages(second.diagnostics);
  EXPECT_EQ(second.output.substr(0, 36), "N60 (WS FINISH PLANAR FACE1)\nN70 G0 ");
  EXPECT_NE(second.output.find("N90 X10. Y2. Z3.\n"), std::string::npos)
      << second.output;  // G1 and F are modal
  // A new job starts afresh.
  JobState other(fanuc_config());
  EXPECT_EQ(transform(*compiled, kChunk, other).output, kFanucOutput);
  job.reset();
  EXPECT_EQ(transform(*compiled, kChunk, job).output, kFanucOutput);
}

TEST_F(XsltTest, XmlOutputFollowsXslOutput) {
  auto compiled = compile_ok(
      tree_,
      sheet(R"x(<xsl:template match="/"><out n="{count(//STRAIGHT_FEED)}"/></xsl:template>)x",
            R"x(<xsl:output method="xml" omit-xml-declaration="yes"/>)x"));
  ASSERT_TRUE(compiled);
  EXPECT_EQ(compiled->output_method(), "xml");
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "<out n=\"2\"/>\n");

  auto declared =
      compile_ok(tree_, sheet(R"x(<xsl:template match="/"><out/></xsl:template>)x", ""));
  ASSERT_TRUE(declared);
  EXPECT_EQ(transform(*declared, kChunk, job).output, "<?xml version=\"1.0\"?>\n<out/>\n");
}

TEST_F(XsltTest, ParametersArePassedAsStrings) {
  auto compiled =
      compile_ok(tree_, sheet(R"x(<xsl:param name="program"/><xsl:param name="n" select="'none'"/>
<xsl:template match="/"><xsl:value-of select="concat($program, '|', $n)"/></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  // Quotes of both kinds and XPath syntax stay text.
  TransformResult r =
      transform(*compiled, kChunk, job, {{"program", R"x(O1000 "it's" count(//*))x"}});
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, R"x(O1000 "it's" count(//*)|none)x");
}

TEST_F(XsltTest, ImportsFromTheProfileAndCommonFolders) {
  tree_.write("common/words.xsl", sheet(R"x(<xsl:template name="hello">common</xsl:template>)x"));
  tree_.write("profile/lib/local.xsl",
              sheet(R"x(<xsl:template name="local">local</xsl:template>)x"));
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:import href="../common/words.xsl"/>
<xsl:include href="lib/local.xsl"/>
<xsl:template match="/"><xsl:call-template name="hello"/>+<xsl:call-template name="local"/></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "common+local");
}

TEST_F(XsltTest, CompileTextUsesTheGivenNameAndFolder) {
  tree_.write("common/words.xsl", sheet(R"x(<xsl:template name="hello">common</xsl:template>)x"));
  const auto as_file = tree_.profile() / "uploaded.xsl";  // not on disk
  CompileResult r = compile_text(sheet(R"x(<xsl:import href="../common/words.xsl"/>
<xsl:template match="/"><xsl:call-template name="hello"/></xsl:template>)x"),
                                 as_file, tree_.roots());
  ASSERT_TRUE(r.ok()) << all_messages(r.diagnostics);
  JobState job;
  EXPECT_EQ(transform(*r.stylesheet, "<a/>", job).output, "common");
}

TEST_F(XsltTest, XPathCompileErrorPointsAtTheStylesheetLine) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n"                                                              // 1
      "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"  // 2
      "<xsl:template match=\"/\">\n"                                                           // 3
      "  <xsl:value-of select=\"1 +\"/>\n"                                                     // 4
      "</xsl:template>\n"
      "</xsl:stylesheet>\n";
  CompileResult r = tree_.compile_sheet(text);
  ASSERT_FALSE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty());
  const FileDiagnostic& d = r.diagnostics.front();
  EXPECT_EQ(d.diagnostic.code_id(), "XSLT-002") << all_messages(r.diagnostics);
  EXPECT_EQ(d.diagnostic.line, 4u) << all_messages(r.diagnostics);
  EXPECT_EQ(std::filesystem::path(d.file).filename(), "post.xsl");
  EXPECT_NE(d.diagnostic.message.find("1 +"), std::string::npos) << d.diagnostic.message;
}

TEST_F(XsltTest, XsltErrorPointsAtTheStylesheetLine) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"
      "<xsl:template match=\"/\">\n"
      "  <xsl:value-of select=\"1\"/>\n"
      "  <xsl:for-each/>\n"  // 5: select is required
      "</xsl:template>\n"
      "</xsl:stylesheet>\n";
  CompileResult r = tree_.compile_sheet(text);
  ASSERT_FALSE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-002");
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 5u) << all_messages(r.diagnostics);
  EXPECT_EQ(format(r.diagnostics.front())
                .find((tree_.profile() / "post.xsl").string() + ":5:0: error: XSLT-002: "),
            0u)
      << format(r.diagnostics.front());
}

TEST_F(XsltTest, MalformedStylesheetPointsAtLineAndColumn) {
  CompileResult r = tree_.compile_sheet(
      "<?xml version=\"1.0\"?>\n<xsl:stylesheet version=\"1.0\"\n"
      "  xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n<a></b>\n</xsl:stylesheet>\n");
  ASSERT_FALSE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-001");
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 4u) << all_messages(r.diagnostics);
  EXPECT_GT(r.diagnostics.front().diagnostic.column, 0u);
}

TEST_F(XsltTest, ErrorsInAnImportedFilePointAtThatFile) {
  tree_.write("common/bad.xsl",
              "<?xml version=\"1.0\"?>\n<xsl:stylesheet version=\"1.0\" "
              "xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n\n"
              "<xsl:template match=\"x\"><xsl:value-of select=\"((\"/></xsl:template>\n"
              "</xsl:stylesheet>\n");
  CompileResult r = tree_.compile_sheet(sheet(R"x(<xsl:import href="../common/bad.xsl"/>)x"));
  ASSERT_FALSE(r.ok());
  ASSERT_FALSE(r.diagnostics.empty()) << all_messages(r.diagnostics);
  EXPECT_EQ(std::filesystem::path(r.diagnostics.front().file).filename(), "bad.xsl")
      << all_messages(r.diagnostics);
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 4u) << all_messages(r.diagnostics);
}

TEST_F(XsltTest, WarningsDoNotStopTheCompile) {
  CompileResult r = tree_.compile_sheet(sheet(R"x(<xsl:strip-space/>
<xsl:template match="/">ok</xsl:template>)x"));
  ASSERT_TRUE(r.ok()) << all_messages(r.diagnostics);
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].diagnostic.code_id(), "XSLT-003");
  EXPECT_EQ(r.diagnostics[0].diagnostic.severity, diag::Severity::Warning);
  EXPECT_EQ(r.diagnostics[0].diagnostic.line, 6u);
  JobState job;
  EXPECT_EQ(transform(*r.stylesheet, "<a/>", job).output, "ok");
}

TEST_F(XsltTest, ListsTheFilesItWasReadFrom) {
  tree_.write("common/words.xsl", sheet(R"x(<xsl:template name="hello">common</xsl:template>)x"));
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:import href="../common/words.xsl"/>)x"));
  ASSERT_TRUE(compiled);
  ASSERT_EQ(compiled->files().size(), 2u);
  EXPECT_EQ(compiled->files()[0], std::filesystem::canonical(tree_.profile() / "post.xsl"));
  EXPECT_EQ(compiled->files()[1],
            std::filesystem::canonical(tree_.root() / "common" / "words.xsl"));
  EXPECT_EQ(compiled->file(), compiled->files()[0]);
}

TEST_F(XsltTest, NotAStylesheet) {
  CompileResult r = tree_.compile_sheet("<html/>");
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(has_errors(r.diagnostics)) << all_messages(r.diagnostics);
  CompileResult missing = compile(tree_.profile() / "absent.xsl", tree_.roots());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.diagnostics.front().diagnostic.code_id(), "XSLT-004")
      << all_messages(missing.diagnostics);
}

TEST_F(XsltTest, StylesheetSizeLimit) {
  Limits limits;
  limits.max_stylesheet_bytes = 100;
  CompileResult r =
      tree_.compile_sheet(sheet(R"x(<xsl:template match="/">x</xsl:template>)x"), limits);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-005") << all_messages(r.diagnostics);
}

TEST_F(XsltTest, TooManyImportedFiles) {
  // a0 imports a1 imports a2 ...: 10 files with a limit of 5.
  for (int n = 0; n < 10; ++n) {
    tree_.write(
        "profile/a" + std::to_string(n) + ".xsl",
        sheet(n < 9 ? "<xsl:import href=\"a" + std::to_string(n + 1) + ".xsl\"/>" : std::string()));
  }
  Limits limits;
  limits.max_stylesheet_files = 5;
  CompileResult r = compile(tree_.profile() / "a0.xsl", tree_.roots(), limits);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-005")) << all_messages(r.diagnostics);
  EXPECT_TRUE(compile(tree_.profile() / "a0.xsl", tree_.roots()).ok());
}

TEST_F(XsltTest, MalformedInputIsAJobError) {
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:template match="/">ok</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, "<chunk>\n<a></chunk>", job, {}, "chunk-7.xml");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.output.empty());
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-010");
  EXPECT_EQ(r.diagnostics.front().file, "chunk-7.xml");
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 2u) << all_messages(r.diagnostics);
  // And the next job is fine.
  TransformResult next = transform(*compiled, kChunk, job);
  EXPECT_TRUE(next.ok) << all_messages(next.diagnostics);
  EXPECT_EQ(next.output, "ok");
}

TEST_F(XsltTest, InputSizeLimit) {
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:template match="/">ok</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  Limits limits;
  limits.max_input_bytes = 10;
  JobState job({}, limits);
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-010")) << all_messages(r.diagnostics);
}

TEST_F(XsltTest, MessagesAreNotesAndTerminateIsAnError) {
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:template match="/">
  <xsl:message>checking <xsl:value-of select="count(//STRAIGHT_FEED)"/></xsl:message>
  <xsl:text>done</xsl:text>
</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  ASSERT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "done");
  ASSERT_EQ(r.diagnostics.size(), 1u) << all_messages(r.diagnostics);
  EXPECT_EQ(r.diagnostics[0].diagnostic.code_id(), "XSLT-013");
  EXPECT_EQ(r.diagnostics[0].diagnostic.message, "checking 2");
  EXPECT_EQ(r.diagnostics[0].diagnostic.line, 7u);

  auto stopping = compile_ok(tree_, sheet(R"x(<xsl:template match="/">
  <xsl:message terminate="yes">unsupported call</xsl:message>
</xsl:template>)x"));
  ASSERT_TRUE(stopping);
  TransformResult s = transform(*stopping, kChunk, job);
  EXPECT_FALSE(s.ok);
  EXPECT_TRUE(has_code(s.diagnostics, "XSLT-014")) << all_messages(s.diagnostics);
}

TEST_F(XsltTest, RuntimeErrorsAreJobErrors) {
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:template match="/">
  <xsl:value-of select="my:unknown()"/>
</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.front().diagnostic.code_id(), "XSLT-011") << all_messages(r.diagnostics);
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 7u) << all_messages(r.diagnostics);
}

TEST_F(XsltTest, DocumentOfTheStylesheetItselfIsServedFromMemory) {
  // The lookup-table idiom: data embedded in the stylesheet, read with document('').
  auto compiled = compile_ok(tree_, sheet(R"x(<my:tools><tool slot="3">T3 D12</tool></my:tools>
<xsl:template match="/"><xsl:value-of select="document('')/*/my:tools/tool[@slot=3]"/></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "T3 D12");
}

TEST(XsltDiagnostics, FormatAndErrors) {
  const std::vector<FileDiagnostic> items{
      {"post.xsl", diag::make(diag::Code::XsltMessage, 3, 0, "hello")},
      {"post.xsl", diag::make(diag::Code::XsltRuntimeError, 4, 0, "bad")}};
  EXPECT_EQ(format(items[1]), "post.xsl:4:0: error: XSLT-011: bad");
  EXPECT_FALSE(has_errors(std::span(items).first(1)));
  EXPECT_TRUE(has_errors(items));
}

}  // namespace
}  // namespace ncpost::xslt::test
