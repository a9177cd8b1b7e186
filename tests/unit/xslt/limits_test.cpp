// Limits: endless recursion, exponential node sets and strings, XPath blow-ups, long runs.
// Each must end the job with its limit's diagnostic, quickly, and the next job must run.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "support.hpp"

namespace ncpost::xslt::test {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::string_view kPlain = R"x(<xsl:template match="/">fine</xsl:template>)x";

// Small limits so that the tests stay fast; each test widens the ones it does not probe.
Limits test_limits() {
  Limits l;
  l.max_memory = std::size_t{64} << 20;
  l.max_time = std::chrono::milliseconds(5000);
  l.max_steps = 500'000;
  l.max_xpath_ops = 2'000'000;
  return l;
}

struct Outcome {
  TransformResult result;
  double seconds;
};

Outcome run(const Tree& tree, std::string_view body, const Limits& limits,
            std::string_view xml = kChunk) {
  auto compiled = compile_ok(tree, sheet(body));
  if (!compiled) return {};
  JobState job({}, limits);
  const auto start = Clock::now();
  TransformResult r = transform(*compiled, xml, job);
  return {std::move(r), std::chrono::duration<double>(Clock::now() - start).count()};
}

void expect_limit(const Outcome& r, std::string_view code, double max_seconds = 3.0) {
  if (std::getenv("NCPOST_XSLT_SHOW") != nullptr) std::cout << all_messages(r.result.diagnostics);
  EXPECT_FALSE(r.result.ok);
  EXPECT_TRUE(r.result.output.empty());
  ASSERT_FALSE(r.result.diagnostics.empty());
  EXPECT_EQ(r.result.diagnostics.front().diagnostic.code_id(), code)
      << all_messages(r.result.diagnostics);
  EXPECT_LT(r.seconds, max_seconds);
}

void expect_next_job_works(const Tree& tree) {
  auto compiled = compile_ok(tree, sheet(kPlain));
  ASSERT_TRUE(compiled);
  JobState job;
  TransformResult r = transform(*compiled, kChunk, job);
  EXPECT_TRUE(r.ok) << all_messages(r.diagnostics);
  EXPECT_EQ(r.output, "fine");
}

TEST_F(XsltTest, EndlessNamedTemplateRecursion) {
  const Outcome r =
      run(tree_, R"x(<xsl:template match="/"><xsl:call-template name="again"/></xsl:template>
<xsl:template name="again"><xsl:param name="n" select="0"/>
  <xsl:call-template name="again"><xsl:with-param name="n" select="$n + 1"/></xsl:call-template>
</xsl:template>)x",
          Limits{});
  expect_limit(r, "XSLT-020");
  // The diagnostic points into the recursive template.
  EXPECT_GE(r.result.diagnostics.front().diagnostic.line, 7u) << all_messages(r.result.diagnostics);
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, EndlessApplyTemplatesRecursion) {
  expect_limit(
      run(tree_, R"x(<xsl:template match="/"><xsl:apply-templates select="."/></xsl:template>)x",
          Limits{}),
      "XSLT-020");
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, EndlessFunctionRecursion) {
  const Outcome r = run(
      tree_,
      R"x(<func:function name="my:f"><xsl:param name="n"/><func:result select="my:f($n + 1)"/></func:function>
<xsl:template match="/"><xsl:value-of select="my:f(1)"/></xsl:template>)x",
      Limits{});
  EXPECT_FALSE(r.result.ok);
  EXPECT_TRUE(has_code(r.result.diagnostics, "XSLT-020") ||
              has_code(r.result.diagnostics, "XSLT-023"))
      << all_messages(r.result.diagnostics);
  EXPECT_LT(r.seconds, 3.0);
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, VariableLimit) {
  Limits limits;
  limits.max_template_vars = 100;
  const Outcome r = run(
      tree_,
      R"x(<xsl:template match="/"><xsl:call-template name="deep"><xsl:with-param name="n" select="60"/></xsl:call-template></xsl:template>
<xsl:template name="deep"><xsl:param name="n"/>
  <xsl:variable name="a" select="1"/><xsl:variable name="b" select="2"/><xsl:variable name="c" select="3"/>
  <xsl:if test="$n > 0"><xsl:call-template name="deep"><xsl:with-param name="n" select="$n - 1"/></xsl:call-template></xsl:if>
  <xsl:value-of select="$a + $b + $c"/>
</xsl:template>)x",
      limits);
  expect_limit(r, "XSLT-021");
  expect_next_job_works(tree_);
}

// A node-set that doubles 60 times through result tree fragments: 2^60 nodes unless stopped.
// Copying a fragment costs one instruction and no XPath operation per node, so only the
// memory limit can catch it.
TEST_F(XsltTest, DoublingResultTreeFragmentsHitTheMemoryLimit) {
  Limits limits = test_limits();
  limits.max_steps = 0;
  limits.max_xpath_ops = 0;
  const Outcome r = run(tree_, R"x(<xsl:template match="/">
  <xsl:call-template name="double"><xsl:with-param name="n" select="60"/><xsl:with-param name="set" select="/*"/></xsl:call-template>
</xsl:template>
<xsl:template name="double"><xsl:param name="n"/><xsl:param name="set"/>
  <xsl:choose>
    <xsl:when test="$n = 0"><xsl:value-of select="count(exsl:node-set($set)//*)"/></xsl:when>
    <xsl:otherwise>
      <xsl:variable name="twice"><xsl:copy-of select="$set"/><xsl:copy-of select="$set"/></xsl:variable>
      <xsl:call-template name="double"><xsl:with-param name="n" select="$n - 1"/><xsl:with-param name="set" select="$twice"/></xsl:call-template>
    </xsl:otherwise>
  </xsl:choose>
</xsl:template>)x",
                        limits);
  expect_limit(r, "XSLT-024");
  // One limit diagnostic, no cascade of consequences.
  EXPECT_EQ(r.result.diagnostics.size(), 1u) << all_messages(r.result.diagnostics);
  expect_next_job_works(tree_);
}

// The same through node-sets (exsl:node-set(...)/*): the XPath operation or memory limit.
TEST_F(XsltTest, DoublingNodeSetsHitALimit) {
  const Outcome r = run(tree_, R"x(<xsl:template match="/">
  <xsl:call-template name="double"><xsl:with-param name="n" select="60"/><xsl:with-param name="set" select="//*"/></xsl:call-template>
</xsl:template>
<xsl:template name="double"><xsl:param name="n"/><xsl:param name="set"/>
  <xsl:choose>
    <xsl:when test="$n = 0"><xsl:value-of select="count($set)"/></xsl:when>
    <xsl:otherwise>
      <xsl:variable name="twice"><xsl:copy-of select="$set"/><xsl:copy-of select="$set"/></xsl:variable>
      <xsl:call-template name="double"><xsl:with-param name="n" select="$n - 1"/><xsl:with-param name="set" select="exsl:node-set($twice)/*"/></xsl:call-template>
    </xsl:otherwise>
  </xsl:choose>
</xsl:template>)x",
                        test_limits());
  EXPECT_FALSE(r.result.ok);
  EXPECT_TRUE(has_code(r.result.diagnostics, "XSLT-023") ||
              has_code(r.result.diagnostics, "XSLT-024"))
      << all_messages(r.result.diagnostics);
  EXPECT_LT(r.seconds, 3.0);
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, DoublingStringsHitTheMemoryLimit) {
  Limits limits = test_limits();
  limits.max_steps = 0;
  limits.max_xpath_ops = 0;
  const Outcome r = run(
      tree_,
      R"x(<xsl:template match="/"><xsl:call-template name="s"><xsl:with-param name="n" select="60"/><xsl:with-param name="s" select="'ab'"/></xsl:call-template></xsl:template>
<xsl:template name="s"><xsl:param name="n"/><xsl:param name="s"/>
  <xsl:choose>
    <xsl:when test="$n = 0"><xsl:value-of select="string-length($s)"/></xsl:when>
    <xsl:otherwise><xsl:call-template name="s"><xsl:with-param name="n" select="$n - 1"/><xsl:with-param name="s" select="concat($s, $s)"/></xsl:call-template></xsl:otherwise>
  </xsl:choose>
</xsl:template>)x",
      limits);
  expect_limit(r, "XSLT-024");
  expect_next_job_works(tree_);
}

// Nested //* predicates over a document of 2000 elements: n^3 = 8e9 steps of XPath.
TEST_F(XsltTest, NestedDescendantScansHitTheXPathLimit) {
  std::string xml = "<chunk>";
  for (int n = 0; n < 2000; ++n) xml += "<a/>";
  xml += "</chunk>";
  const Outcome r = run(
      tree_,
      R"x(<xsl:template match="/"><xsl:value-of select="count(//*[count(//*[count(//* | //*/..) > 0]) > 0])"/></xsl:template>)x",
      test_limits(), xml);
  expect_limit(r, "XSLT-023");
  EXPECT_EQ(r.result.diagnostics.front().diagnostic.line, 6u) << all_messages(r.result.diagnostics);
  expect_next_job_works(tree_);
}

// 2^40 template calls at a depth of 40: only the instruction count stops it.
constexpr std::string_view kBinaryTree =
    R"x(<xsl:template match="/"><xsl:call-template name="t"><xsl:with-param name="n" select="40"/></xsl:call-template></xsl:template>
<xsl:template name="t"><xsl:param name="n"/>
  <xsl:if test="$n > 0">
    <xsl:call-template name="t"><xsl:with-param name="n" select="$n - 1"/></xsl:call-template>
    <xsl:call-template name="t"><xsl:with-param name="n" select="$n - 1"/></xsl:call-template>
  </xsl:if>
</xsl:template>)x";

TEST_F(XsltTest, ExponentialCallTreeHitsTheStepLimit) {
  Limits limits = test_limits();
  limits.max_xpath_ops = 0;
  expect_limit(run(tree_, kBinaryTree, limits), "XSLT-022");
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, ExponentialCallTreeHitsTheXPathLimitToo) {
  Limits limits = test_limits();
  limits.max_steps = 0;
  expect_limit(run(tree_, kBinaryTree, limits), "XSLT-023");
  expect_next_job_works(tree_);
}

// A long run that allocates as it goes (building fragments), with every count unlimited:
// only the clock stops it.
TEST_F(XsltTest, LongRunHitsTheTimeLimit) {
  Limits limits;
  limits.max_steps = 0;
  limits.max_xpath_ops = 0;
  limits.max_memory = 0;
  limits.max_time = std::chrono::milliseconds(300);
  const Outcome r = run(
      tree_,
      R"x(<xsl:template match="/"><xsl:call-template name="t"><xsl:with-param name="n" select="40"/></xsl:call-template></xsl:template>
<xsl:template name="t"><xsl:param name="n"/>
  <xsl:if test="$n > 0">
    <xsl:variable name="f"><x><xsl:value-of select="$n"/></x></xsl:variable>
    <xsl:call-template name="t"><xsl:with-param name="n" select="$n - 1 + count(exsl:node-set($f)/x) - 1"/></xsl:call-template>
    <xsl:call-template name="t"><xsl:with-param name="n" select="$n - 1"/></xsl:call-template>
  </xsl:if>
</xsl:template>)x",
      limits);
  expect_limit(r, "XSLT-025", 2.0);
  EXPECT_GT(r.seconds, 0.25);
  expect_next_job_works(tree_);
}

// The same endless run with only a distant clock: the job's cancel flag, set from another
// thread (as the server does at --job-timeout or when the client leaves), stops it. It ends
// cancelled, with no error of its own and no text; the clock would have needed a minute.
TEST_F(XsltTest, ACancelledJobStopsItsTransform) {
  Limits limits;
  limits.max_steps = 0;
  limits.max_xpath_ops = 0;
  limits.max_memory = 0;
  limits.max_time = std::chrono::milliseconds(60'000);
  auto compiled = compile_ok(
      tree_,
      sheet(
          R"x(<xsl:template match="/"><xsl:call-template name="t"><xsl:with-param name="n" select="40"/></xsl:call-template></xsl:template>
<xsl:template name="t"><xsl:param name="n"/>
  <xsl:if test="$n > 0">
    <xsl:value-of select="$n"/>
    <xsl:call-template name="t"><xsl:with-param name="n" select="$n - 1"/></xsl:call-template>
    <xsl:call-template name="t"><xsl:with-param name="n" select="$n - 1"/></xsl:call-template>
  </xsl:if>
</xsl:template>)x"));
  ASSERT_TRUE(compiled);
  std::atomic<bool> cancel{false};
  JobState job({}, limits);
  job.set_cancel(&cancel);
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancel.store(true);
  });
  const auto start = Clock::now();
  const TransformResult r = transform(*compiled, kChunk, job);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  canceller.join();
  EXPECT_TRUE(r.cancelled) << all_messages(r.diagnostics);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.output.empty());
  EXPECT_FALSE(diag::has_errors(r.diagnostics)) << all_messages(r.diagnostics);
  EXPECT_LT(seconds, 30.0);
  RecordProperty("stopped_after_ms", std::to_string(static_cast<int>(seconds * 1000)));
  // Already cancelled: nothing runs. The same job state, the flag cleared: it runs again.
  const TransformResult again = transform(*compiled, kChunk, job);
  EXPECT_TRUE(again.cancelled);
  cancel.store(false);
  auto plain = compile_ok(tree_, sheet(kPlain));
  ASSERT_TRUE(plain);
  const TransformResult fine = transform(*plain, kChunk, job);
  EXPECT_TRUE(fine.ok) << all_messages(fine.diagnostics);
  EXPECT_FALSE(fine.cancelled);
  EXPECT_EQ(fine.output, "fine");
}

TEST_F(XsltTest, AnInputLargerThanTheMemoryLimitIsNotTransformed) {
  std::string xml = "<chunk>";
  for (int n = 0; n < 20000; ++n) xml += "<STRAIGHT_FEED x=\"1\" y=\"2\" z=\"3\"/>";
  xml += "</chunk>";
  Limits limits;
  limits.max_memory = std::size_t{1} << 20;
  auto compiled = compile_ok(
      tree_,
      sheet(R"x(<xsl:template match="/"><xsl:message>started</xsl:message></xsl:template>)x"));
  ASSERT_TRUE(compiled);
  JobState job({}, limits);
  TransformResult r = transform(*compiled, xml, job, {}, "big.xml");
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.diagnostics.size(), 1u)
      << all_messages(r.diagnostics);  // no "started": it did not run
  EXPECT_EQ(r.diagnostics[0].diagnostic.code_id(), "XSLT-024");
  EXPECT_EQ(r.diagnostics[0].file, "big.xml");
  expect_next_job_works(tree_);
}

TEST_F(XsltTest, DefaultLimitsStopAnXPathBlowUpQuickly) {
  // The shipped defaults, not the test's small ones, end an n^3 scan in about a second.
  std::string xml = "<chunk>";
  for (int n = 0; n < 2000; ++n) xml += "<a/>";
  xml += "</chunk>";
  const Outcome r = run(
      tree_,
      R"x(<xsl:template match="/"><xsl:value-of select="count(//*[count(//*[count(//*) > 0]) > 0])"/></xsl:template>)x",
      Limits{}, xml);
  expect_limit(r, "XSLT-023", 8.0);
}

}  // namespace
}  // namespace ncpost::xslt::test
