// The post job shared by `ncpost post` and ncpostd: the same text as the renderer alone, the
// error marker after a failure that comes once output has started, cancellation, and the same
// of all with the renderer on a thread of its own.

#include "ncpost/pipeline/post.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

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
    std::vector<diag::FileDiagnostic> d;
    auto p = store.load(id, d);
    EXPECT_TRUE(p) << (d.empty() ? "" : diag::format(d[0]));
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
  // Posts "executables" with linuxcnc and cancels from the output callback at the first text:
  // the result is cancelled, the text is a prefix of the whole program followed by the marker.
  static void expect_cut_mid_stream(PostOptions options) {
    const auto p = builtin("linuxcnc");
    ASSERT_TRUE(p);
    const auto loaded = load_case("executables");
    std::atomic<bool> cancel{false};
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
    EXPECT_FALSE(result.ok);
    const std::string_view tail = "(ERROR: the job was cancelled - the program is incomplete)\n";
    ASSERT_GE(text.size(), tail.size());
    EXPECT_EQ(text.substr(text.size() - tail.size()), tail);
    const std::string whole = run(loaded, *p).text;
    EXPECT_LT(text.size() - tail.size(), whole.size());
    EXPECT_EQ(whole.compare(0, text.size() - tail.size(), text, 0, text.size() - tail.size()), 0);
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

// The motion marks of the JSON post (each call rendered on its own): the same text as the
// streamed post for every profile whose stylesheet does not look ahead within a transform, one
// mark per motion of the trace, in order, each inside the text, most with text of their own.
TEST_F(PostJobTest, MotionMarksKeepTheTextAndFollowTheMotions) {
  std::size_t profiles = 0;
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "stylesheets")) {
    const std::string id = entry.path().filename().string();
    // The Klartext templates (common/heidenhain-tnc640.xsl, both TNC 640 profiles) look ahead.
    if (!fs::exists(entry.path() / "profile.json") || id.rfind("heidenhain-tnc640", 0) == 0)
      continue;
    const auto p = builtin(id);
    if (!p || p->profile.mode == profile::Mode::Raw) continue;
    ++profiles;
    for (const char* name : {"curves", "executables", "placement-rotated-setup"}) {
      SCOPED_TRACE(id + " " + name);
      const auto loaded = load_case(name);
      std::vector<MotionMark> motions;
      std::vector<WorkingstepMark> workingsteps;
      PostOptions options;
      options.motion_marks = &motions;
      options.workingstep_marks = &workingsteps;
      const Posted marked = run(loaded, *p, options);
      const Posted plain = run(loaded, *p);
      ASSERT_TRUE(plain.result.ok);
      EXPECT_EQ(marked.text, plain.text);
      const std::string trace = test::read_file(test::source_dir() / "tests" / "golden" / "trace" /
                                                "cases" / (std::string(name) + ".trace"));
      std::size_t expected = 0;
      for (const char* call : {" STRAIGHT_TRAVERSE(", " STRAIGHT_FEED(", " ARC_FEED(",
                               " ARC_FEED_3D(", " NURBS_FEED(", "_CYCLE("})
        for (auto at = trace.find(call); at != std::string::npos; at = trace.find(call, at + 1))
          ++expected;
      ASSERT_EQ(motions.size(), expected);
      std::size_t previous = 0;
      std::size_t with_text = 0;
      for (const MotionMark& m : motions) {
        EXPECT_LE(previous, m.begin);
        EXPECT_LE(m.begin, m.end);
        EXPECT_LE(m.end, marked.text.size());
        if (m.end > m.begin) ++with_text;
        previous = m.end;
      }
      EXPECT_GT(with_text, expected / 2);
      EXPECT_FALSE(workingsteps.empty());
    }
  }
  EXPECT_GE(profiles, 8u);
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
  EXPECT_TRUE(diag::has_errors(posted.result.diagnostics));
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
  expect_cut_mid_stream(PostOptions{});
}

// A large program is rendered on a second thread (PostOptions::render_thread_min_instances).
// Forced here for small programs, with batches of a few calls so that the bounded queue fills
// and the interpreter waits: text, diagnostics and flags are those of one thread, for programs
// that succeed, that fail part-way, and for every built-in profile that posts ex1E.
TEST_F(PostJobTest, RenderThreadGivesTheSameResult) {
  std::vector<std::pair<std::string, LoadedModel>> programs;
  for (const char* name : {"curves", "errors", "executables"})
    programs.emplace_back(name, load_case(name));
  if (const auto corpus = test::corpus_dir()) {
    static const express::SchemaRegistry registry;
    programs.emplace_back(
        "ex1E", load(test::read_file(*corpus / "p21" / "nist_toolkit_ex1E.stp"), registry));
  } else if (test::corpus_required()) {
    FAIL() << "NCPOST_REQUIRE_CORPUS is set and the corpus is missing";
  }
  std::size_t compared = 0;
  for (const char* id : {"linuxcnc", "fanuc-0i", "heidenhain-tnc640"}) {
    const auto p = builtin(id);
    ASSERT_TRUE(p);
    for (const auto& [name, loaded] : programs) {
      PostOptions one;
      one.render_thread_min_instances = 0;
      PostOptions two;
      two.render_thread_min_instances = 1;
      two.render_thread_batch = 3;
      const Posted a = run(loaded, *p, one);
      const Posted b = run(loaded, *p, two);
      EXPECT_EQ(a.text, b.text) << id << " " << name;
      EXPECT_EQ(a.result.ok, b.result.ok) << id << " " << name;
      EXPECT_EQ(a.result.started, b.result.started) << id << " " << name;
      EXPECT_EQ(a.result.calls, b.result.calls) << id << " " << name;
      ASSERT_EQ(a.result.diagnostics.size(), b.result.diagnostics.size()) << id << " " << name;
      for (std::size_t i = 0; i < a.result.diagnostics.size(); ++i)
        EXPECT_EQ(diag::format(a.result.diagnostics[i]), diag::format(b.result.diagnostics[i]));
      ++compared;
    }
  }
  EXPECT_GE(compared, 9u);
}

// Cancelled from the output callback, which then runs on the render thread: the interpreter
// stops, the queued calls are dropped, and the text ends with the marker.
TEST_F(PostJobTest, RenderThreadCancelledMidStreamEndsWithTheMarker) {
  PostOptions options;
  options.render_thread_min_instances = 1;
  options.render_thread_batch = 2;
  expect_cut_mid_stream(options);
}

// A stylesheet that would run for hours (2^40 template calls, each writing text) with the
// job's cancel flag set from another thread, as the server does at --job-timeout or when the
// client leaves: the transform itself stops, so the post ends cancelled with no error of the
// stylesheet's (before, it ran on until max_steps stopped it with XSLT-021 seconds later).
// Canonical mode on one thread and with the render thread, and raw mode.
TEST_F(PostJobTest, CancelStopsAStylesheetThatRunsOnAndOn) {
  const auto linuxcnc = builtin("linuxcnc");
  ASSERT_TRUE(linuxcnc);
  const std::filesystem::path roots[] = {linuxcnc->directory};
  const auto busy = xslt::compile_text(
      R"x(<xsl:stylesheet version="1.0" xmlns:xsl="http://www.w3.org/1999/XSL/Transform">
<xsl:output method="text"/>
<xsl:template match="/"><xsl:call-template name="busy"/></xsl:template>
<xsl:template name="busy"><xsl:param name="d" select="40"/>
  <xsl:if test="$d &gt; 0">
    <xsl:value-of select="$d"/>
    <xsl:call-template name="busy"><xsl:with-param name="d" select="$d - 1"/></xsl:call-template>
    <xsl:call-template name="busy"><xsl:with-param name="d" select="$d - 1"/></xsl:call-template>
  </xsl:if>
</xsl:template>
</xsl:stylesheet>
)x",
      linuxcnc->directory / "busy.xsl", roots);
  ASSERT_TRUE(busy.ok()) << (busy.diagnostics.empty() ? "" : diag::format(busy.diagnostics[0]));
  profile::LoadedProfile canonical = *linuxcnc;
  canonical.stylesheet = busy.stylesheet;
  profile::LoadedProfile raw = canonical;
  raw.profile.mode = profile::Mode::Raw;
  const auto loaded = load_case("curves");
  struct Case {
    const char* name;
    const profile::LoadedProfile* profile;
    std::size_t render_thread_min_instances;
  };
  for (const Case& c : {Case{"one_thread", &canonical, 0}, Case{"render_thread", &canonical, 1},
                        Case{"raw", &raw, 0}}) {
    std::atomic<bool> cancel{false};
    PostOptions options;
    options.cancel = &cancel;
    options.render_thread_min_instances = c.render_thread_min_instances;
    std::thread canceller([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      cancel.store(true);
    });
    const auto began = std::chrono::steady_clock::now();
    const Posted posted = run(loaded, *c.profile, options);
    const auto took = std::chrono::steady_clock::now() - began;
    canceller.join();
    EXPECT_TRUE(posted.result.cancelled) << c.name;
    EXPECT_FALSE(posted.result.ok) << c.name;
    // On one thread `render` is the time in transforms: one had begun when the flag was set
    // (the program interprets in milliseconds), so it is the transform that stopped.
    if (c.render_thread_min_instances == 0) {
      EXPECT_GT(posted.result.render, std::chrono::milliseconds(100)) << c.name;
    }
    for (const auto& d : posted.result.diagnostics)
      EXPECT_NE(d.diagnostic.severity, diag::Severity::Error) << c.name << ": " << diag::format(d);
    RecordProperty(
        std::string("stopped_after_ms_") + c.name,
        std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(took).count()));
  }
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
