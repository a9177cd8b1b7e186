// The post job shared by `ncpost post` and ncpostd: the same text as the renderer alone, the
// error marker after a failure that comes once output has started, and cancellation.

#include "ncpost/pipeline/post.hpp"

#include <gtest/gtest.h>

#include "corpus.hpp"
#include "ncpost/express/registry.hpp"

namespace ncpost::pipeline {
namespace {

namespace fs = std::filesystem;

class PostJobTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { xslt::initialise(); }
  static std::shared_ptr<const profile::LoadedProfile> builtin(const std::string& id) {
    static profile::ProfileStore store(test::source_dir() / "stylesheets");
    std::vector<xslt::FileDiagnostic> d;
    auto p = store.load(id, d);
    EXPECT_TRUE(p) << (d.empty() ? "" : xslt::format(d[0]));
    return p;
  }
  static LoadedModel load_case(const std::string& name) {
    static const express::SchemaRegistry registry;
    auto loaded = load(test::read_file(test::source_dir() / "tests" / "golden" / "trace" / "cases" /
                                       (name + ".stp")),
                       registry);
    EXPECT_TRUE(loaded.ok()) << name;
    return loaded;
  }
  struct Posted {
    std::string text;
    PostResult result;
  };
  static Posted run(const LoadedModel& loaded, const profile::LoadedProfile& p,
                    const PostOptions& options = {}) {
    Posted out;
    out.result = post(
        loaded, p, [&](std::string_view piece) { out.text += piece; }, options);
    return out;
  }
};

TEST_F(PostJobTest, SameTextAsTheGoldenPost) {
  const auto p = builtin("linuxcnc");
  ASSERT_TRUE(p);
  const auto loaded = load_case("curves");
  PostOptions options;
  options.input_name = "curves.stp";
  const Posted posted = run(loaded, *p, options);
  EXPECT_TRUE(posted.result.ok);
  EXPECT_TRUE(posted.result.started);
  EXPECT_FALSE(posted.result.cancelled);
  EXPECT_GT(posted.result.calls, 10u);
  EXPECT_EQ(posted.text, test::read_file(test::source_dir() / "tests" / "golden" / "post" /
                                         "linuxcnc" / "curves.nc"));
}

// errors.stp fails part-way: what went out must end with the marker, never with M2/M30.
TEST_F(PostJobTest, FailureAfterOutputEndsWithTheMarker) {
  const auto p = builtin("linuxcnc");
  ASSERT_TRUE(p);
  const Posted posted = run(load_case("errors"), *p);
  EXPECT_FALSE(posted.result.ok);
  ASSERT_TRUE(posted.result.started);
  const std::string_view tail = "- the program is incomplete)\n";
  ASSERT_GE(posted.text.size(), tail.size());
  EXPECT_EQ(posted.text.substr(posted.text.size() - tail.size()), tail) << posted.text;
  EXPECT_NE(posted.text.rfind("(ERROR: STEPNC-"), std::string::npos) << posted.text;
  EXPECT_EQ(posted.text.find("M2\n"), std::string::npos);
  EXPECT_TRUE(xslt::has_errors(posted.result.diagnostics));
}

TEST_F(PostJobTest, CancelledBeforeTheFirstExecutable) {
  const auto p = builtin("linuxcnc");
  ASSERT_TRUE(p);
  std::atomic<bool> cancel{true};
  PostOptions options;
  options.cancel = &cancel;
  const Posted posted = run(load_case("curves"), *p, options);
  EXPECT_TRUE(posted.result.cancelled);
  EXPECT_FALSE(posted.result.ok);
  EXPECT_EQ(posted.text.find("M2"), std::string::npos) << posted.text;
  if (posted.result.started) {
    EXPECT_NE(posted.text.find("(ERROR: the job was cancelled - the program is incomplete)"),
              std::string::npos)
        << posted.text;
  }
}

// Cancelled from the output callback, that is after text went out (what the server does when
// the client goes away mid-stream).
TEST_F(PostJobTest, CancelledMidStreamEndsWithTheMarker) {
  const auto p = builtin("linuxcnc");
  ASSERT_TRUE(p);
  const auto loaded = load_case("executables");
  std::atomic<bool> cancel{false};
  PostOptions options;
  options.cancel = &cancel;
  // One transform per chunk, so that text comes out before the program's end (batched, this
  // small program is one piece at its end, after which there is nothing left to cancel).
  options.render.batch_bytes = 0;
  std::string text;
  const PostResult result = post(
      loaded, *p,
      [&](std::string_view piece) {
        text += piece;
        cancel = true;
      },
      options);
  EXPECT_TRUE(result.cancelled);
  EXPECT_TRUE(result.started);
  const std::string_view tail = "(ERROR: the job was cancelled - the program is incomplete)\n";
  ASSERT_GE(text.size(), tail.size());
  EXPECT_EQ(text.substr(text.size() - tail.size()), tail);
  const std::string whole = run(loaded, *p).text;
  EXPECT_LT(text.size() - tail.size(), whole.size());
  EXPECT_EQ(whole.compare(0, text.size() - tail.size(), text, 0, text.size() - tail.size()), 0);
}

TEST(ErrorMarker, UsesTheProfileSyntaxAndSanitisesTheMessage) {
  profile::Profile p;
  p.error_marker = "; ERROR {message} - incomplete";
  p.line_ending = "\r\n";
  EXPECT_EQ(error_marker(p, "STEPNC-010 #12 (tool)\nbad 'x'"),
            "; ERROR STEPNC-010 #12  tool  bad  x  - incomplete\r\n");
  EXPECT_EQ(error_marker(profile::Profile{}, "X"), "(ERROR: X - the program is incomplete)\n");
}

}  // namespace
}  // namespace ncpost::pipeline
