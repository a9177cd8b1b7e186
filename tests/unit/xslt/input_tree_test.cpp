// InputTree: a document built in memory equals the one libxml2 parses from the same XML text,
// transforms over it give the same output, and the cases where libxslt would free input nodes
// (xsl:strip-space) or the tree is incomplete are handled without touching the arena.

#include "ncpost/xslt/input_tree.hpp"

#include <gtest/gtest.h>

#include "support.hpp"

namespace ncpost::xslt::test {
namespace {

// kChunk (support.hpp) event by event, as canon::XmlChunkWriter would give it.
void build_chunk(InputTree& t) {
  t.start_element("chunk");
  t.attribute("seq", "1");
  t.text("\n  ");
  t.start_element("workingstep");
  t.attribute("id", "10");
  t.attribute("type", "MACHINING_WORKINGSTEP");
  t.attribute("name", "WS FINISH PLANAR FACE1");
  t.text("\n    ");
  t.start_element("SET_FEED_RATE");
  t.attribute("rate", "500");
  t.end_element();
  t.text("\n    ");
  t.start_element("STRAIGHT_TRAVERSE");
  t.attribute("x", "0"), t.attribute("y", "0"), t.attribute("z", "10");
  t.end_element();
  t.text("\n    ");
  t.start_element("STRAIGHT_FEED");
  t.attribute("x", "91.9"), t.attribute("y", "-13.5"), t.attribute("z", "2.5");
  t.end_element();
  t.text("\n    ");
  t.start_element("STRAIGHT_FEED");
  t.attribute("x", "10"), t.attribute("y", "2"), t.attribute("z", "3");
  t.end_element();
  t.text("\n    ");
  t.start_element("ARC_FEED");
  for (auto [n, v] : {std::pair{"x", "20"},
                      {"y", "2"},
                      {"z", "3"},
                      {"cx", "15"},
                      {"cy", "2"},
                      {"cz", "3"},
                      {"ni", "0"},
                      {"nj", "0"},
                      {"nk", "1"},
                      {"turns", "-1"},
                      {"plane", "xy"},
                      {"first_end", "20"},
                      {"second_end", "2"},
                      {"first_axis", "15"},
                      {"second_axis", "2"},
                      {"rotation", "-1"},
                      {"axis_end_point", "3"}})
    t.attribute(n, v);
  t.end_element();
  t.text("\n    ");
  t.start_element("COMMENT");
  t.text("finish (face)");
  t.end_element();
  t.text("\n  ");
  t.end_element();
  t.text("\n");
  t.end_element();
  t.text("\n");
}

// kChunk with its ARC_FEED on one line: the events above cannot say that the text wraps.
std::string chunk_on_single_lines() {
  std::string text(kChunk);
  const std::string wrap = "\n" + std::string(14, ' ');
  for (auto at = text.find(wrap); at != std::string::npos; at = text.find(wrap))
    text.replace(at, wrap.size(), " ");
  return text;
}

TEST(InputTree, EqualsTheParsedText) {
  InputTree tree;
  build_chunk(tree);
  ASSERT_TRUE(tree.complete());
  const std::string text = chunk_on_single_lines();
  const std::string parsed = describe_parsed(text);
  ASSERT_FALSE(parsed.empty()) << text;
  EXPECT_EQ(tree.describe(), parsed);
  EXPECT_EQ(describe_parsed(tree.to_xml()), parsed);
}

TEST(InputTree, CharactersAreWhatAParserReadsBack) {
  // Markup, quotes, tab/CR/LF in attributes and content, control characters, malformed UTF-8,
  // U+FFFF, an empty attribute and an empty element: each as the escaper writes it.
  const std::string nasty = std::string("a<b>&c\"d'\te\rf\ng") + '\x01' + "\xC3\x28" +
                            "\xEF\xBF\xBF" + "\xE2\x82\xAC" + "]]>";
  InputTree tree;
  tree.start_element("chunk");
  tree.attribute("name", nasty);
  tree.attribute("empty", "");
  tree.text("\n");
  tree.start_element("COMMENT");
  tree.text(nasty);
  tree.end_element();
  tree.text("\n");
  tree.start_element("COMMENT");
  tree.end_element();
  tree.text("\n");
  tree.end_element();
  ASSERT_TRUE(tree.complete());
  const std::string text = tree.to_xml();
  const std::string parsed = describe_parsed(text);
  ASSERT_FALSE(parsed.empty()) << text;
  EXPECT_EQ(tree.describe(), parsed) << text;
  EXPECT_NE(parsed.find("\xEF\xBF\xBD"), std::string::npos);  // U+FFFD stands in
  EXPECT_NE(parsed.find("\xE2\x82\xAC"), std::string::npos);  // valid UTF-8 is kept
}

TEST(InputTree, IncompleteOrMalformedTreesAreNotComplete) {
  InputTree tree;
  EXPECT_FALSE(tree.complete());  // no root
  tree.start_element("a");
  EXPECT_FALSE(tree.complete());  // unclosed
  tree.end_element();
  EXPECT_TRUE(tree.complete());
  tree.start_element("b");  // a second root
  tree.end_element();
  EXPECT_FALSE(tree.complete());
  tree.clear();
  tree.end_element();  // an end without a start
  EXPECT_FALSE(tree.complete());
  tree.clear();
  tree.start_element("a");
  tree.text("x");
  tree.attribute("late", "1");  // after content
  tree.end_element();
  EXPECT_FALSE(tree.complete());
}

TEST_F(XsltTest, TransformOfATreeEqualsTransformOfItsText) {
  auto compiled = compile_ok(tree_, sheet(R"x(
<xsl:template match="/"><xsl:apply-templates select="chunk/workingstep/*"/></xsl:template>
<xsl:template match="*"><xsl:value-of select="concat(name(), ' ', count(@*), ' ',
    count(preceding-sibling::node()), ' ', ext:format(sum(@x), 'length'), '|', string(.))"/>
  <xsl:text>&#10;</xsl:text></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  InputTree tree;
  // Reused: the second document is built in the memory of the first.
  for (int round = 0; round < 2; ++round) {
    tree.clear();
    build_chunk(tree);
    JobState a, b;
    TransformResult from_tree = transform(*compiled, tree, a);
    TransformResult from_text = transform(*compiled, tree.to_xml(), b);
    ASSERT_TRUE(from_tree.ok) << all_messages(from_tree.diagnostics);
    ASSERT_TRUE(from_text.ok) << all_messages(from_text.diagnostics);
    EXPECT_EQ(from_tree.output, from_text.output);
    EXPECT_NE(from_tree.output.find("STRAIGHT_FEED 3 5 91.9|"), std::string::npos)
        << from_tree.output;
  }
}

// libxslt frees the whitespace nodes of the input a strip-space stylesheet removes; a tree in
// an arena must never reach that, so such stylesheets get the tree as text (AddressSanitizer
// would report the free otherwise).
TEST_F(XsltTest, StripSpaceStylesheetsGetTheTextForm) {
  for (const char* rule :
       {R"(<xsl:strip-space elements="*"/>)", R"(<xsl:strip-space elements="workingstep chunk"/>)",
        R"(<xsl:preserve-space elements="COMMENT"/>)"}) {
    SCOPED_TRACE(rule);
    auto compiled = compile_ok(tree_, sheet(std::string(rule) + R"x(
<xsl:template match="/"><xsl:value-of select="count(//text())"/></xsl:template>)x"));
    ASSERT_TRUE(compiled);
    InputTree tree;
    build_chunk(tree);
    JobState a, b;
    TransformResult from_tree = transform(*compiled, tree, a);
    TransformResult from_text = transform(*compiled, tree.to_xml(), b);
    ASSERT_TRUE(from_tree.ok) << all_messages(from_tree.diagnostics);
    EXPECT_EQ(from_tree.output, from_text.output);
    // The tree itself is untouched: it still equals its text.
    EXPECT_EQ(tree.describe(), describe_parsed(tree.to_xml()));
  }
}

TEST_F(XsltTest, AnIncompleteTreeIsAJobError) {
  auto compiled = compile_ok(tree_, sheet(R"(<xsl:template match="/">x</xsl:template>)"));
  ASSERT_TRUE(compiled);
  InputTree tree;
  tree.start_element("chunk");  // never closed
  JobState job;
  TransformResult r = transform(*compiled, tree, job);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].diagnostic.code, diag::Code::XsltInputXml)
      << all_messages(r.diagnostics);
}

}  // namespace
}  // namespace ncpost::xslt::test
