// Security: stylesheets read and write nothing at transform time, imports stay inside the
// allowed folders, inputs carry no DTD. Each refusal is a clean job error, and the next job
// runs as before.

#include <gtest/gtest.h>

#include <fstream>

#include "support.hpp"

namespace ncpost::xslt::test {
namespace {

constexpr std::string_view kPlain = R"x(<xsl:template match="/">fine</xsl:template>)x";

// The next job after a refused one still works.
void expect_next_job_works(const Tree& tree) {
  auto compiled = compile_ok(tree, sheet(kPlain));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "fine");
}

TEST_F(XsltTest, DocumentCannotReadFiles) {
  auto compiled = compile_ok(tree_, sheet(R"x(<xsl:template match="/">
  <xsl:text>[</xsl:text><xsl:copy-of select="document('/etc/passwd')"/><xsl:text>]</xsl:text>
  <xsl:value-of select="count(document('file:///etc/passwd'))"/>
</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.output.find("root:"), std::string::npos);
  const std::string messages = all_messages(r.diagnostics);
  EXPECT_EQ(messages.find("root:"), std::string::npos) << messages;
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-012")) << messages;
  // The refusal points at the instruction.
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 7u) << messages;
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, DocumentCannotReadTheProfileFolderEither) {
  tree_.write("profile/table.xml", "<tools><tool>secret</tool></tools>");
  auto compiled = compile_ok(
      tree_,
      sheet(
          R"x(<xsl:template match="/"><xsl:value-of select="document('table.xml')"/></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-012")) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output.find("secret"), std::string::npos);
}

TEST_F(XsltTest, DocumentCannotReachTheNetwork) {
  auto compiled = compile_ok(
      tree_,
      sheet(
          R"x(<xsl:template match="/"><xsl:value-of select="document('http://127.0.0.1:9/x.xml')"/></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-012")) << all_messages(r.diagnostics);
}

TEST_F(XsltTest, ExslDocumentCannotWriteFiles) {
  const std::filesystem::path target = tree_.root() / "written.txt";
  const std::filesystem::path nested = tree_.root() / "newdir" / "written.txt";
  auto compiled = compile_ok(
      tree_, sheet("<xsl:template match=\"/\">\n"
                   "  <exsl:document href=\"" +
                   target.string() +
                   "\" method=\"text\">pwned</exsl:document>\n"
                   "  <exsl:document href=\"" +
                   nested.string() +
                   "\" method=\"text\">pwned</exsl:document>\n"
                   "  <exsl:document href=\"relative.txt\" method=\"text\">pwned</exsl:document>\n"
                   "  <xsl:text>body</xsl:text>\n"
                   "</xsl:template>"));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_FALSE(std::filesystem::exists(nested.parent_path()));
  EXPECT_FALSE(std::filesystem::exists(tree_.profile() / "relative.txt"));
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::current_path() / "relative.txt"));
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-012")) << all_messages(r.diagnostics);
  EXPECT_EQ(r.diagnostics.front().diagnostic.line, 7u) << all_messages(r.diagnostics);
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, XslDocumentOfXslt11CannotWriteFiles) {
  const std::filesystem::path target = tree_.root() / "written11.txt";
  auto compiled = compile_ok(
      tree_,
      "<xsl:stylesheet version=\"1.1\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"
      "<xsl:template match=\"/\"><xsl:document href=\"" +
          target.string() + "\">x</xsl:document></xsl:template>\n</xsl:stylesheet>\n");
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-012")) << all_messages(r.diagnostics);
}

TEST_F(XsltTest, OtherWritingExtensionsCannotWriteFiles) {
  // libxslt's Saxon and Xalan compatibility elements write through the same code.
  const std::filesystem::path saxon = tree_.root() / "saxon.txt";
  const std::filesystem::path xalan = tree_.root() / "xalan.txt";
  const std::filesystem::path libxslt = tree_.root() / "libxslt.txt";
  auto compiled = compile_ok(
      tree_,
      "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\"\n"
      "  xmlns:saxon=\"http://icl.com/saxon\" "
      "xmlns:xalan=\"org.apache.xalan.xslt.extensions.Redirect\"\n"
      "  xmlns:libxslt=\"http://xmlsoft.org/XSLT/namespace\" extension-element-prefixes=\"saxon "
      "xalan libxslt\">\n"
      "<xsl:template match=\"/\">\n"
      "  <saxon:output href=\"" +
          saxon.string() +
          "\">x</saxon:output>\n"
          "  <xalan:write file=\"" +
          xalan.string() +
          "\">x</xalan:write>\n"
          "  <libxslt:document href=\"" +
          libxslt.string() +
          "\">x</libxslt:document>\n"
          "</xsl:template>\n</xsl:stylesheet>\n");
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(std::filesystem::exists(saxon));
  EXPECT_FALSE(std::filesystem::exists(xalan));
  EXPECT_FALSE(std::filesystem::exists(libxslt));
  // saxon:output and xalan:write are refused; libxslt:document is not even registered.
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-012")) << all_messages(r.diagnostics);
  EXPECT_TRUE(has_errors(r.diagnostics)) << all_messages(r.diagnostics);
}

void expect_import_refused(const Tree& tree, const std::string& href, std::string_view what) {
  for (const std::string_view element : {"import", "include"}) {
    CompileResult r = tree.compile_sheet(
        sheet("<xsl:" + std::string(element) + " href=\"" + href + "\"/>\n" + std::string(kPlain)));
    EXPECT_FALSE(r.ok()) << what << " via xsl:" << element;
    EXPECT_TRUE(has_code(r.diagnostics, "XSLT-004")) << what << "\n" << all_messages(r.diagnostics);
    // The refusal points at the xsl:import / xsl:include element.
    if (!r.diagnostics.empty()) {
      EXPECT_EQ(r.diagnostics.front().diagnostic.line, 6u) << all_messages(r.diagnostics);
    }
    const std::string messages = all_messages(r.diagnostics);
    EXPECT_EQ(messages.find("root:"), std::string::npos) << messages;
  }
}

TEST_F(XsltTest, ImportsOutsideTheAllowedFoldersAreRefused) {
  // A readable file outside the roots, with XSLT in it, so only the folder rule refuses it.
  const std::filesystem::path outside = tree_.write("elsewhere/evil.xsl", sheet(kPlain));
  expect_import_refused(tree_, "../../../../../../../../etc/passwd", "a .. escape to /etc/passwd");
  expect_import_refused(tree_, "../elsewhere/evil.xsl", "a .. escape to a stylesheet");
  expect_import_refused(tree_, outside.string(), "an absolute path elsewhere");
  expect_import_refused(tree_, "/etc/passwd", "an absolute system file");
  expect_import_refused(tree_, "file://" + outside.string(), "a file: URL elsewhere");
  expect_import_refused(tree_, "http://127.0.0.1:9/evil.xsl", "an http URL");
  expect_import_refused(tree_, "ftp://127.0.0.1:9/evil.xsl", "an ftp URL");
  expect_import_refused(tree_, "missing.xsl", "a missing file");
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, SymbolicLinksOutOfTheFoldersAreRefused) {
  const std::filesystem::path outside = tree_.write("elsewhere/evil.xsl", sheet(kPlain));
  std::filesystem::create_symlink(outside, tree_.profile() / "link.xsl");
  std::filesystem::create_directory_symlink(tree_.root() / "elsewhere", tree_.profile() / "dir");
  expect_import_refused(tree_, "link.xsl", "a symbolic link to a file outside");
  expect_import_refused(tree_, "dir/evil.xsl",
                        "a path through a symbolic link to a folder outside");
}

TEST_F(XsltTest, MainStylesheetMustLieInsideARoot) {
  const std::filesystem::path outside = tree_.write("elsewhere/main.xsl", sheet(kPlain));
  CompileResult r = compile(outside, tree_.roots());
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-004")) << all_messages(r.diagnostics);
  CompileResult text =
      compile_text(sheet(kPlain), tree_.root() / "elsewhere" / "up.xsl", tree_.roots());
  EXPECT_FALSE(text.ok());
  EXPECT_TRUE(has_code(text.diagnostics, "XSLT-004")) << all_messages(text.diagnostics);
}

TEST_F(XsltTest, StylesheetsWithADtdAreRefused) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE xsl:stylesheet [<!ENTITY e SYSTEM "
      "\"file:///etc/passwd\">]>\n"
      "<xsl:stylesheet version=\"1.0\" xmlns:xsl=\"http://www.w3.org/1999/XSL/Transform\">\n"
      "<xsl:template match=\"/\">&e;</xsl:template>\n</xsl:stylesheet>\n";
  CompileResult r = tree_.compile_sheet(text);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(has_code(r.diagnostics, "XSLT-006")) << all_messages(r.diagnostics);
  EXPECT_EQ(all_messages(r.diagnostics).find("root:"), std::string::npos);
}

TEST_F(XsltTest, InputsWithADtdAreRefused) {
  auto compiled = compile_ok(
      tree_, sheet(R"x(<xsl:template match="/"><xsl:value-of select="."/></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job;
  // External entity (file disclosure) and nested entities (billion laughs).
  const std::string external =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE chunk [<!ENTITY e SYSTEM "
      "\"file:///etc/passwd\">]>\n<chunk>&e;</chunk>";
  std::string laughs = "<?xml version=\"1.0\"?>\n<!DOCTYPE chunk [<!ENTITY a0 \"lol\">";
  for (int n = 1; n < 10; ++n) {
    laughs += "<!ENTITY a" + std::to_string(n) + " \"";
    for (int k = 0; k < 10; ++k) laughs += "&a" + std::to_string(n - 1) + ";";
    laughs += "\">";
  }
  laughs += "]>\n<chunk>&a9;</chunk>";
  for (const std::string& input : {external, laughs}) {
    TransformResult r = transform(*compiled, input, job);
    EXPECT_FALSE(r.ok);
    // libxml2 itself stops the entity loop while parsing (XSLT-010); otherwise the DTD is refused.
    EXPECT_TRUE(has_code(r.diagnostics, "XSLT-006") || has_code(r.diagnostics, "XSLT-010"))
        << all_messages(r.diagnostics);
    EXPECT_EQ(r.output.find("root:"), std::string::npos);
    EXPECT_LT(r.output.size(), 1000u);
  }
  expect_next_job_works(tree_);
}

}  // namespace
}  // namespace ncpost::xslt::test
