// One compiled stylesheet shared by many threads, each job with its own transform context and
// state; errors of one job never appear in another.

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "support.hpp"

namespace ncpost::xslt::test {
namespace {

constexpr int kThreads = 4;
constexpr int kJobs = 100;

// Block numbers, modal words, formatting and a result tree fragment per job: everything that
// has per-job state or allocates.
constexpr std::string_view kBody = R"x(<xsl:template match="/">
  <xsl:for-each select="//STRAIGHT_FEED | //STRAIGHT_TRAVERSE">
    <xsl:variable name="words"><w><xsl:value-of select="ext:modal('g', name())"/></w></xsl:variable>
    <xsl:value-of select="concat('N', ext:block(), ' ', exsl:node-set($words)/w, ' X', ext:format(@x, 'length'),
                                 ' Y', ext:format(@y, 'length'), ' Z', ext:format(@z, 'length'))"/>
    <xsl:text>&#10;</xsl:text>
  </xsl:for-each>
</xsl:template>)x";

constexpr std::string_view kExpected =
    "N10 STRAIGHT_TRAVERSE X0. Y0. Z10.\n"
    "N20 STRAIGHT_FEED X91.9 Y-13.5 Z2.5\n"
    "N30  X10. Y2. Z3.\n";

TEST_F(XsltTest, OneStylesheetFourThreadsIdenticalOutputs) {
  const std::shared_ptr<const CompiledStylesheet> compiled = compile_ok(tree_, sheet(kBody));
  ASSERT_TRUE(compiled);
  std::atomic<int> good{0};
  std::atomic<int> bad{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int n = 0; n < kJobs; ++n) {
        JobState job;
        TransformResult r =
            transform(*compiled, kChunk, job, {}, "chunk-" + std::to_string(t) + ".xml");
        if (r.ok && r.output == kExpected && r.diagnostics.empty()) {
          ++good;
        } else {
          ++bad;
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(good.load(), kThreads * kJobs);
  EXPECT_EQ(bad.load(), 0);
}

// Failing jobs (refused reads, endless recursion, malformed input, xsl:message) run beside
// good ones; each job sees its own diagnostics only.
TEST_F(XsltTest, ErrorsStayWithTheirJob) {
  const auto good_sheet = compile_ok(tree_, sheet(kBody));
  const auto reader = compile_ok(
      tree_,
      sheet(
          R"x(<xsl:template match="/"><xsl:message>hello</xsl:message><xsl:value-of select="document('/etc/passwd')"/></xsl:template>)x"));
  const auto recursion = compile_ok(
      tree_,
      sheet(R"x(<xsl:template match="/"><xsl:apply-templates select="."/></xsl:template>)x"));
  ASSERT_TRUE(good_sheet && reader && recursion);
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int n = 0; n < kJobs; ++n) {
        JobState job;
        switch ((t + n) % 4) {
          case 0: {
            TransformResult r = transform(*good_sheet, kChunk, job);
            if (!r.ok || r.output != kExpected || !r.diagnostics.empty()) ++wrong;
            break;
          }
          case 1: {
            TransformResult r = transform(*reader, kChunk, job);
            if (r.ok || r.diagnostics.size() != 2 ||
                r.diagnostics[0].diagnostic.code_id() != "XSLT-013" ||
                r.diagnostics[1].diagnostic.code_id() != "XSLT-012") {
              ++wrong;
            }
            break;
          }
          case 2: {
            TransformResult r = transform(*recursion, kChunk, job);
            if (r.ok || r.diagnostics.size() != 1 ||
                r.diagnostics[0].diagnostic.code_id() != "XSLT-020")
              ++wrong;
            break;
          }
          default: {
            TransformResult r = transform(*good_sheet, "<chunk><oops></chunk>", job);
            if (r.ok || r.diagnostics.empty() ||
                r.diagnostics[0].diagnostic.code_id() != "XSLT-010")
              ++wrong;
            for (const FileDiagnostic& d : r.diagnostics) {
              if (d.diagnostic.code_id() != "XSLT-010") ++wrong;
            }
            break;
          }
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST_F(XsltTest, CompilesInParallelWithTheirOwnRoots) {
  // Each thread compiles from its own tree; imports refused in one do not leak into another.
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      Tree tree;
      tree.write("common/lib.xsl",
                 sheet("<xsl:template name=\"lib\">" + std::to_string(t) + "</xsl:template>"));
      for (int n = 0; n < 25; ++n) {
        const bool evil = (t + n) % 2 == 0;
        CompileResult r = tree.compile_sheet(
            sheet(std::string(evil ? "<xsl:import href=\"/etc/passwd\"/>"
                                   : "<xsl:import href=\"../common/lib.xsl\"/>") +
                  "<xsl:template match=\"/\"><xsl:call-template name=\"lib\"/></xsl:template>"));
        if (evil) {
          if (r.ok() || r.diagnostics.size() != 1 ||
              r.diagnostics[0].diagnostic.code_id() != "XSLT-004")
            ++wrong;
        } else {
          JobState job;
          if (!r.ok() || !r.diagnostics.empty() ||
              transform(*r.stylesheet, "<a/>", job).output != std::to_string(t)) {
            ++wrong;
          }
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST_F(XsltTest, TheStylesheetOutlivesItsCompileResult) {
  std::shared_ptr<const CompiledStylesheet> kept;
  {
    CompileResult r = tree_.compile_sheet(sheet(kBody));
    ASSERT_TRUE(r.ok());
    kept = r.stylesheet;
  }
  std::thread worker([kept] {
    JobState job;
    EXPECT_EQ(transform(*kept, kChunk, job).output, kExpected);
  });
  worker.join();
}

}  // namespace
}  // namespace ncpost::xslt::test
