// The render stage: chunked output equals whole-program output byte for byte, NURBS
// linearisation (de Boor), limit checks, cycle expansion and native cycles.

#include "ncpost/render/render.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "corpus.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::render {
namespace {

namespace fs = std::filesystem;

class RenderTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { xslt::initialise(); }
  static fs::path stylesheets() { return test::source_dir() / "stylesheets"; }
  static std::shared_ptr<const profile::LoadedProfile> builtin(const std::string& id) {
    static profile::ProfileStore store(stylesheets());
    std::vector<diag::FileDiagnostic> d;
    auto p = store.load(id, d);
    EXPECT_TRUE(p) << (d.empty() ? "" : diag::format(d[0]));
    return p;
  }
  static std::vector<canon::Call> program(const fs::path& file) {
    static const express::SchemaRegistry registry;
    auto loaded = pipeline::load(test::read_file(file), registry);
    EXPECT_TRUE(loaded.ok()) << file;
    const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
    canon::ProgramBuffer buffer;
    (void)stepnc::interpret(loaded.model, attributes, buffer, {});
    return std::move(buffer).take();
  }
};

canon::Entity entity(std::uint64_t id, std::string type, std::string name) {
  return canon::Entity{id, std::move(type), std::move(name)};
}

// A hand-made program with every cycle kind (the interpreter does not emit cycles yet).
std::vector<canon::Call> cycle_program() {
  using namespace canon;
  std::vector<Call> calls;
  calls.emplace_back(Begin{Scope::Project, entity(1, "PROJECT", "CYCLES")});
  calls.emplace_back(UseLengthUnits{Units::Millimetres});
  calls.emplace_back(Begin{Scope::Workingstep, entity(10, "MACHINING_WORKINGSTEP", "DRILL")});
  calls.emplace_back(SelectTool{5});
  calls.emplace_back(ChangeTool{5});
  calls.emplace_back(UseToolLengthOffset{50});
  calls.emplace_back(SetSpindleSpeed{1500});
  calls.emplace_back(StartSpindleClockwise{});
  calls.emplace_back(StraightTraverse{{0, 0, 50}});
  Cycle drill{CycleKind::Drill, 10, 20, 10, 2, -15, 200, 0};
  calls.emplace_back(drill);
  Cycle dwell = drill;
  dwell.dwell = 0.5;
  dwell.x = 30;
  calls.emplace_back(dwell);
  Cycle peck = drill;
  peck.kind = CycleKind::PeckDrill;
  peck.x = 40;
  peck.peck = 5;
  calls.emplace_back(peck);
  Cycle tap = drill;
  tap.kind = CycleKind::Tap;
  tap.x = 50;
  tap.pitch = 1.25;
  tap.spindle_speed = 160;
  tap.feed = 200;
  calls.emplace_back(tap);
  Cycle bore = drill;
  bore.kind = CycleKind::Bore;
  bore.x = 60;
  bore.safe_z = bore.r_z;  // G99
  calls.emplace_back(bore);
  calls.emplace_back(End{Scope::Workingstep, entity(10, "MACHINING_WORKINGSTEP", "DRILL")});
  calls.emplace_back(ProgramEnd{});
  calls.emplace_back(End{Scope::Project, entity(1, "PROJECT", "CYCLES")});
  return calls;
}

void expect_chunked_equals_whole(const profile::LoadedProfile& p,
                                 const std::vector<canon::Call>& calls) {
  std::vector<diag::FileDiagnostic> d1, d2, d3, d4, d5, d6;
  const std::string chunked = render_program(p, calls, d1);
  const std::string whole = render_program(p, calls, d2, RenderOptions{{}, true});
  // Tiny chunks: long workingsteps split and reopened (continued="true").
  const std::string tiny = render_program(p, calls, d3, RenderOptions{{3}, false});
  // Without batching (one transform per chunk), and with batches of a few chunks each (the
  // default batches these small programs into two transforms).
  const std::string unbatched = render_program(p, calls, d4, RenderOptions{{}, false, 0});
  const std::string tiny_unbatched = render_program(p, calls, d5, RenderOptions{{3}, false, 0});
  const std::string small_batches = render_program(p, calls, d6, RenderOptions{{3}, false, 600});
  EXPECT_FALSE(diag::has_errors(d1)) << (d1.empty() ? "" : diag::format(d1[0]));
  EXPECT_FALSE(chunked.empty());
  EXPECT_EQ(chunked, whole);
  EXPECT_EQ(chunked, tiny);
  EXPECT_EQ(chunked, unbatched);
  EXPECT_EQ(chunked, tiny_unbatched);
  EXPECT_EQ(chunked, small_batches);
}

TEST_F(RenderTest, ChunkedEqualsWholeProgram) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  // The five-axis profiles too: their kinematics state (previous angles, tool length) lives
  // in the renderer, not in the chunks. (Not the Heidenhain profiles: their TOOL CALL
  // looks a few calls ahead for the speed, which a tiny chunk can cut off.)
  for (const char* id :
       {"linuxcnc", "fanuc-0i", "linuxcnc-5ax", "fanuc-30i-5ax", "siemens-840d-5ax"}) {
    auto p = builtin(id);
    ASSERT_TRUE(p);
    for (const char* c :
         {"curves.stp", "placement-rotated-setup.stp", "executables.stp", "five-axis.stp"}) {
      SCOPED_TRACE(std::string(id) + " " + c);
      expect_chunked_equals_whole(*p, program(cases / c));
    }
    SCOPED_TRACE(std::string(id) + " cycles");
    expect_chunked_equals_whole(*p, cycle_program());
  }
}

TEST_F(RenderTest, ChunkedEqualsWholeProgramEx1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto calls = program(corpus / "p21" / "nist_toolkit_ex1E.stp");
  expect_chunked_equals_whole(*builtin("linuxcnc"), calls);
  expect_chunked_equals_whole(*builtin("fanuc-0i"), calls);
}

// The tree the renderer builds for its stylesheets equals the tree libxml2 parses from the
// same chunks' XML text, chunk by chunk and for the whole program as one chunk.
class TreeOf final : public canon::XmlEvents {
 public:
  explicit TreeOf(xslt::InputTree& tree) : tree_(tree) {}
  void start_element(std::string_view name) override { tree_.start_element(name); }
  void attribute(std::string_view name, std::string_view value) override {
    tree_.attribute(name, value);
  }
  void text(std::string_view characters) override { tree_.text(characters); }
  void end_element(std::string_view) override { tree_.end_element(); }

 private:
  xslt::InputTree& tree_;
};

void expect_tree_equals_parsed_text(const std::vector<canon::Call>& calls) {
  for (const std::size_t max_calls : {std::size_t{3}, canon::ChunkLimits{}.max_calls}) {
    canon::ChunkBuffer chunks;
    canon::Chunker chunker(chunks, canon::ChunkLimits{max_calls});
    for (const auto& c : calls) chunker.call(c);
    chunker.finish();
    std::vector<std::pair<std::string, std::string>> texts_and_trees;
    canon::XmlChunkWriter text_writer, tree_writer;
    xslt::InputTree tree;
    TreeOf events(tree);
    std::uint64_t seq = 0;
    for (const auto& chunk : chunks.chunks()) {
      const canon::ChunkView view{seq++, chunk};
      std::string text;
      text_writer.append_chunk(text, view);
      tree.clear();
      tree_writer.append_chunk(events, view);
      ASSERT_TRUE(tree.complete());
      texts_and_trees.emplace_back(xslt::describe_parsed(text), tree.describe());
    }
    ASSERT_FALSE(texts_and_trees.empty());
    for (const auto& [parsed, built] : texts_and_trees) {
      ASSERT_FALSE(parsed.empty());
      EXPECT_EQ(built, parsed);
    }
  }
}

TEST_F(RenderTest, InputTreeEqualsParsedXml) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  for (const char* c : {"curves.stp", "placement-rotated-setup.stp", "executables.stp"}) {
    SCOPED_TRACE(c);
    expect_tree_equals_parsed_text(program(cases / c));
  }
  expect_tree_equals_parsed_text(cycle_program());
  // Names and comments with everything XML must escape or replace, and an empty comment.
  auto calls = cycle_program();
  const std::string nasty = std::string("<&\"'\t\r\n") + '\x02' + "\xFF" + "\xE2\x82\xAC";
  calls.insert(calls.begin() + 3, canon::Comment{nasty});
  calls.insert(calls.begin() + 3, canon::Comment{""});
  calls.insert(calls.begin() + 3, canon::Message{nasty});
  calls.insert(calls.begin() + 2,
               canon::Begin{canon::Scope::Workplan, entity(7, "WORKPLAN", nasty)});
  expect_tree_equals_parsed_text(calls);
}

TEST_F(RenderTest, InputTreeEqualsParsedXmlEx1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  expect_tree_equals_parsed_text(program(corpus / "p21" / "nist_toolkit_ex1E.stp"));
}

TEST_F(RenderTest, FanucWritesNativeCycles) {
  std::vector<diag::FileDiagnostic> d;
  const std::string text = render_program(*builtin("fanuc-0i"), cycle_program(), d);
  EXPECT_NE(text.find("G98 G81 X10. Y20. Z-15. R2. F200."), std::string::npos) << text;
  EXPECT_NE(text.find("G98 G82 X30. Y20. Z-15. R2. P500 F200."), std::string::npos) << text;
  EXPECT_NE(text.find("G98 G83 X40. Y20. Z-15. R2. Q5. F200."), std::string::npos) << text;
  EXPECT_NE(text.find("G98 G84 X50."), std::string::npos) << text;
  EXPECT_NE(text.find("G99 G85 X60."), std::string::npos) << text;
  EXPECT_NE(text.find("O0001 (CYCLES)"), std::string::npos) << text;
  EXPECT_NE(text.find("M30"), std::string::npos) << text;
}

TEST_F(RenderTest, LinuxcncExpandsCycles) {
  std::vector<diag::FileDiagnostic> d;
  const std::string text = render_program(*builtin("linuxcnc"), cycle_program(), d);
  EXPECT_EQ(text.find("G81"), std::string::npos) << text;
  EXPECT_NE(text.find("G1 X10. Y20. Z-15."), std::string::npos) << text;
  EXPECT_NE(text.find("G4 P0.5"), std::string::npos) << text;
}

// A quarter circle as a rational quadratic: centre (25, 0), radius 5 (as in curves.stp).
canon::NurbsFeed quarter_circle() {
  canon::NurbsFeed n;
  n.degree = 2;
  n.points = {{20, 0, -4, 1}, {20, 5, -4, std::sqrt(0.5)}, {25, 5, -4, 1}};
  n.knots = {0, 0, 0, 1, 1, 1};
  return n;
}

TEST(Nurbs, DeBoorEvaluatesRationalCurveExactly) {
  const auto n = quarter_circle();
  for (int i = 0; i <= 20; ++i) {
    const auto p = nurbs_point(n, i / 20.0);
    EXPECT_NEAR(std::hypot(p.x - 25, p.y), 5.0, 1e-12) << i;
    EXPECT_DOUBLE_EQ(p.z, -4);
  }
  const auto start = nurbs_point(n, 0);
  const auto end = nurbs_point(n, 1);
  EXPECT_DOUBLE_EQ(start.x, 20);
  EXPECT_DOUBLE_EQ(start.y, 0);
  EXPECT_NEAR(end.x, 25, 1e-15);
  EXPECT_NEAR(end.y, 5, 1e-15);
  // Midpoint of the arc: 45 degrees.
  const auto mid = nurbs_point(n, 0.5);
  EXPECT_NEAR(mid.x, 25 - 5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(mid.y, 5 / std::sqrt(2.0), 1e-12);
}

TEST(Nurbs, DeBoorMatchesBezierForOneSpan) {
  canon::NurbsFeed n;
  n.degree = 3;
  n.points = {{0, 0, 0, 1}, {1, 2, 0, 1}, {3, 2, 1, 1}, {4, 0, 0, 1}};
  n.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  for (double t : {0.0, 0.25, 0.5, 0.8, 1.0}) {
    const double b0 = std::pow(1 - t, 3), b1 = 3 * t * std::pow(1 - t, 2), b2 = 3 * t * t * (1 - t),
                 b3 = t * t * t;
    const auto p = nurbs_point(n, t);
    EXPECT_NEAR(p.x, b1 * 1 + b2 * 3 + b3 * 4, 1e-12);
    EXPECT_NEAR(p.y, b1 * 2 + b2 * 2, 1e-12);
    EXPECT_NEAR(p.z, b2 * 1, 1e-12);
    (void)b0;
  }
}

TEST(Nurbs, LinearizeStaysWithinChordTolerance) {
  const auto n = quarter_circle();
  for (double tol : {0.1, 0.01, 0.001}) {
    const auto pts = linearize(n, tol);
    ASSERT_GE(pts.size(), 2u);
    EXPECT_EQ(pts.back().x, 25);
    EXPECT_EQ(pts.back().y, 5);
    // Chord sagitta of a circle: r (1 - cos(theta/2)) <= tol for every piece.
    canon::Point prev{20, 0, -4};
    for (const auto& p : pts) {
      const double chord = std::hypot(p.x - prev.x, p.y - prev.y);
      const double sagitta = 5 - std::sqrt(25 - chord * chord / 4);
      EXPECT_LE(sagitta, tol * 1.0001);
      prev = p;
    }
  }
  canon::NurbsFeed bad = n;
  bad.knots.pop_back();
  EXPECT_TRUE(linearize(bad, 0.01).empty());
}

// Found by the render fuzz target: a valid NURBS whose distances overflow (control points near
// 1e308) had a deviation that was never within tolerance, so each of its pieces was halved 24
// times, 2^24 points a piece, until the process ran out of memory. Such a curve, and one that
// needs more than kMaxNurbsPoints pieces, is now refused (RENDER-003) at once.
TEST(Nurbs, CurvesThatCannotBeFollowedAreRefusedNotHalvedWithoutEnd) {
  canon::NurbsFeed huge;
  huge.degree = 1;
  huge.points = {{0, 0, 0, 1}, {1e308, 1e308, 0, 1}};
  huge.knots = {0, 0, 1, 1};
  ASSERT_TRUE(canon::valid(huge));
  EXPECT_TRUE(linearize(huge, 0.01).empty());
  // A quarter circle of radius 5 needs some 2,000 pieces at 1e-6, some 500,000 at 1e-11.
  const auto fine = linearize(quarter_circle(), 1e-11);
  EXPECT_TRUE(fine.empty()) << fine.size() << " points";
  EXPECT_FALSE(linearize(quarter_circle(), 1e-6).empty());
  EXPECT_LE(linearize(quarter_circle(), 1e-6).size(), kMaxNurbsPoints);
}

// Three workingsteps: block numbers switched off, left as the profile has them, switched on.
std::vector<canon::Call> numbering_program(int feeds) {
  using namespace canon;
  std::vector<Call> calls;
  calls.emplace_back(Begin{Scope::Project, entity(1, "PROJECT", "OPTIONS")});
  calls.emplace_back(UseLengthUnits{Units::Millimetres});
  const Switch switches[] = {Switch::Off, Switch::Unset, Switch::On};
  for (int w = 0; w < 3; ++w) {
    OutputOptions options;
    options.block_numbers = switches[w];
    const Entity ws = entity(10 + w, "CL_OPERATION", "OP" + std::to_string(w));
    calls.emplace_back(Begin{Scope::Workingstep, ws, options});
    for (int n = 0; n < feeds; ++n)
      calls.emplace_back(StraightFeed{{double(10 * w + n), double(w), -1, {}, {}}});
    calls.emplace_back(End{Scope::Workingstep, ws});
  }
  calls.emplace_back(ProgramEnd{});
  calls.emplace_back(End{Scope::Project, entity(1, "PROJECT", "OPTIONS")});
  return calls;
}

// block_numbers on a workingstep overrides the profile's numbering for that workingstep's
// blocks only, with elements and with motion runs, batched or not, and the counter goes on.
TEST_F(RenderTest, BlockNumbersOptionPerWorkingstep) {
  for (const char* id : {"fanuc-0i", "linuxcnc", "siemens-840d", "hnc-21"}) {
    auto p = builtin(id);
    ASSERT_TRUE(p);
    const bool numbered = p->profile.block.numbered;
    const auto calls = numbering_program(4);
    std::vector<diag::FileDiagnostic> d;
    const std::string text = render_program(*p, calls, d);
    EXPECT_TRUE(d.empty()) << id << ": " << (d.empty() ? "" : diag::format(d[0]));
    // Each motion block of workingstep w (after its "OPw" comment) carries N exactly when its
    // option, or for the unset one the profile, says so.
    bool saw_off = false, saw_on = false;
    std::size_t start = 0;
    int w = -1;
    while (start < text.size()) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      const std::string line = text.substr(start, end - start);
      start = end + 1;
      if (line.find("OP0") != std::string::npos) w = 0;
      if (line.find("OP1") != std::string::npos) w = 1;
      if (line.find("OP2") != std::string::npos) w = 2;
      const bool motion =
          line.find("G1 ") != std::string::npos || line.find("G01 ") != std::string::npos;
      if (!motion || w < 0) continue;
      const bool has_n = line.rfind("N", 0) == 0;
      const bool want = w == 0 ? false : w == 2 ? true : numbered;
      EXPECT_EQ(has_n, want) << id << " workingstep " << w << ": " << line;
      saw_off |= w == 0;
      saw_on |= w == 2;
    }
    EXPECT_TRUE(saw_off && saw_on) << id << "\n" << text;
    expect_chunked_equals_whole(*p, calls);
  }
}

// A profile that cannot honour an option writes the workingstep without it and says so once.
TEST_F(RenderTest, OptionTheProfileCannotHonourIsAWarning) {
  auto p = builtin("heidenhain-tnc640");
  ASSERT_TRUE(p);
  const auto calls = numbering_program(2);
  std::vector<diag::FileDiagnostic> d;
  const std::string text = render_program(*p, calls, d);
  ASSERT_EQ(d.size(), 1u) << diag::format(d[1]);
  EXPECT_EQ(d[0].diagnostic.code, diag::Code::RenderOutputOption);
  EXPECT_EQ(d[0].diagnostic.severity, diag::Severity::Warning);
  EXPECT_NE(d[0].diagnostic.message.find("workingstep #10 'OP0' asks for block_numbers=off"),
            std::string::npos)
      << d[0].diagnostic.message;
  EXPECT_NE(d[0].diagnostic.message.find("'heidenhain-tnc640'"), std::string::npos);
  // The same text as without any option.
  auto plain = calls;
  for (auto& c : plain)
    if (auto* b = std::get_if<canon::Begin>(&c)) b->options = {};
  std::vector<diag::FileDiagnostic> none;
  EXPECT_EQ(text, render_program(*p, plain, none));
  EXPECT_TRUE(none.empty());
}

TEST_F(RenderTest, LimitViolationNamesTheWorkingstep) {
  auto base = builtin("linuxcnc");
  ASSERT_TRUE(base);
  profile::LoadedProfile p = *base;
  p.profile.limits.x = profile::Range{-5, 5};
  p.profile.limits.max_feed = 1000;
  p.profile.limits.max_spindle = 2000;
  p.profile.limits.tool_number = std::array<std::int64_t, 2>{1, 99};
  const auto calls =
      program(test::source_dir() / "tests" / "golden" / "trace" / "cases" / "curves.stp");
  std::vector<diag::FileDiagnostic> d;
  const std::string text = render_program(p, calls, d);
  EXPECT_FALSE(text.empty());  // warnings: the output is complete
  EXPECT_FALSE(diag::has_errors(d));
  bool travel = false, feed = false, spindle = false, tool = false;
  for (const auto& x : d) {
    EXPECT_EQ(x.diagnostic.code, diag::Code::RenderLimit);
    const auto& m = x.diagnostic.message;
    travel |= m.find("travel X10.0000") != std::string::npos &&
              m.find("workingstep #10") != std::string::npos &&
              m.find("STRAIGHT_FEED(10.0000") != std::string::npos;
    feed |= m.find("feed 1200.0000") != std::string::npos;
    spindle |= m.find("spindle speed 3000.0000") != std::string::npos;
    tool |= m.find("tool number 901") != std::string::npos;
  }
  EXPECT_TRUE(travel && feed && spindle && tool);

  // severity: error stops the output at the first chunk that would contain the violation.
  p.profile.limits.severity = diag::Severity::Error;
  std::vector<diag::FileDiagnostic> e;
  const std::string partial = render_program(p, calls, e);
  EXPECT_TRUE(diag::has_errors(e));
  EXPECT_EQ(partial.find("G1 X10."), std::string::npos);
}

// A five-axis program on linuxcnc-5ax (C/A fork head) whose tool leans 60 degrees to +X,
// then to -X, `flips` times: from C90 A60 the other side is C90 A-60 (A turns 120) or C-90
// A60 (C turns 180), so every feed after the first turns an axis by more than 90 degrees.
std::vector<canon::Call> flipping_program(int flips, canon::Direction last) {
  using namespace canon;
  const double s = std::sin(std::numbers::pi / 3), c = std::cos(std::numbers::pi / 3);
  std::vector<Call> calls;
  calls.emplace_back(Begin{Scope::Project, entity(1, "PROJECT", "FLIPS")});
  calls.emplace_back(UseLengthUnits{Units::Millimetres});
  calls.emplace_back(Begin{Scope::Workingstep, entity(10, "MACHINING_WORKINGSTEP", "WS")});
  calls.emplace_back(UseToolLengthOffset{50});
  calls.emplace_back(StraightTraverse{{0, 0, 50}});
  calls.emplace_back(SetFeedRate{500});
  for (int i = 0; i < flips; ++i)
    calls.emplace_back(
        StraightFeed{{double(i), 0, 10, std::nullopt, Direction{i % 2 == 0 ? s : -s, 0, c}}});
  calls.emplace_back(StraightFeed{{99, 0, 10, std::nullopt, last}});
  calls.emplace_back(StraightTraverse{{99, 0, 50}});
  calls.emplace_back(End{Scope::Workingstep, entity(10, "MACHINING_WORKINGSTEP", "WS")});
  calls.emplace_back(ProgramEnd{});
  calls.emplace_back(End{Scope::Project, entity(1, "PROJECT", "FLIPS")});
  return calls;
}

std::size_t count_code(const std::vector<diag::FileDiagnostic>& d, diag::Code code) {
  return static_cast<std::size_t>(
      std::count_if(d.begin(), d.end(), [&](const auto& x) { return x.diagnostic.code == code; }));
}

// KIN-005 (a large rotary motion) is a warning per motion, at most
// RenderOptions::max_kinematics_warnings of them per program; the output is complete.
TEST_F(RenderTest, KinematicsWarningsAreCapped) {
  const auto p = builtin("linuxcnc-5ax");
  ASSERT_TRUE(p);
  const auto calls = flipping_program(10, {0, 0, 1});
  std::vector<diag::FileDiagnostic> all;
  const std::string text = render_program(*p, calls, all);
  EXPECT_FALSE(diag::has_errors(all));
  EXPECT_EQ(count_code(all, diag::Code::KinLargeRotation), 9u);
  EXPECT_NE(text.find("M2"), std::string::npos) << text;
  for (const auto& x : all)
    EXPECT_NE(x.diagnostic.message.find("STRAIGHT_FEED("), std::string::npos)
        << x.diagnostic.message;  // each names its motion

  RenderOptions capped;
  capped.max_kinematics_warnings = 3;
  std::vector<diag::FileDiagnostic> few;
  EXPECT_EQ(render_program(*p, calls, few, capped), text);
  EXPECT_EQ(count_code(few, diag::Code::KinLargeRotation), 3u);
}

// A tool axis the machine cannot reach (pointing up: A would be 180, beyond +-110) is KIN-001:
// an error that names the motion, and the output stops before it.
TEST_F(RenderTest, UnreachableToolAxisStopsThePost) {
  const auto p = builtin("linuxcnc-5ax");
  ASSERT_TRUE(p);
  std::vector<diag::FileDiagnostic> d;
  const std::string text = render_program(*p, flipping_program(2, {0, 0, -1}), d);
  EXPECT_TRUE(diag::has_errors(d));
  ASSERT_EQ(count_code(d, diag::Code::KinUnreachable), 1u);
  const auto& e = *std::find_if(d.begin(), d.end(), [](const auto& x) {
    return x.diagnostic.code == diag::Code::KinUnreachable;
  });
  EXPECT_NE(e.diagnostic.message.find("STRAIGHT_FEED(99.0000"), std::string::npos)
      << e.diagnostic.message;
  EXPECT_EQ(text.find("X99."), std::string::npos) << text;
  EXPECT_EQ(text.find("M2"), std::string::npos) << text;
}

// A failure inside a batch of chunks: the batch is rendered again chunk by chunk, so the text
// before the failing chunk and the diagnostics are those of rendering without batching.
TEST_F(RenderTest, FailureInABatchEndsWhereUnbatchedDoes) {
  using namespace canon;
  std::vector<Call> calls;
  calls.emplace_back(Begin{Scope::Project, entity(1, "PROJECT", "BATCH")});
  calls.emplace_back(UseLengthUnits{Units::Millimetres});
  for (std::uint64_t ws = 10; ws < 16; ++ws) {
    calls.emplace_back(Begin{Scope::Workingstep, entity(ws, "MACHINING_WORKINGSTEP", "WS")});
    calls.emplace_back(StraightTraverse{{0, 0, 10}});
    calls.emplace_back(StraightFeed{{static_cast<double>(ws), 0, 0}});
    if (ws == 13)  // in a tilted plane: no G2/G3 form, the stylesheet stops
      calls.emplace_back(ArcFeed{{1, 1, 0}, {0.5, 0.5, 0}, {0.6, 0, 0.8}, 1});
    calls.emplace_back(End{Scope::Workingstep, entity(ws, "MACHINING_WORKINGSTEP", "WS")});
  }
  calls.emplace_back(ProgramEnd{});
  calls.emplace_back(End{Scope::Project, entity(1, "PROJECT", "BATCH")});
  auto p = builtin("linuxcnc");
  ASSERT_TRUE(p);
  std::vector<diag::FileDiagnostic> batched_d, unbatched_d;
  const std::string batched = render_program(*p, calls, batched_d);
  const std::string unbatched = render_program(*p, calls, unbatched_d, RenderOptions{{}, false, 0});
  EXPECT_TRUE(diag::has_errors(batched_d));
  EXPECT_NE(batched.find("G1 X12."), std::string::npos) << batched;
  EXPECT_EQ(batched.find("G1 X13."), std::string::npos) << batched;
  EXPECT_EQ(batched, unbatched);
  ASSERT_EQ(batched_d.size(), unbatched_d.size());
  for (std::size_t i = 0; i < batched_d.size(); ++i)
    EXPECT_EQ(diag::format(batched_d[i]), diag::format(unbatched_d[i]));

  // An error found before the transform (a limit) ends the output where it did too.
  profile::LoadedProfile limited = *p;
  limited.profile.limits.x = profile::Range{-1, 12.5};
  limited.profile.limits.severity = diag::Severity::Error;
  calls.erase(std::remove_if(calls.begin(), calls.end(),
                             [](const Call& c) { return std::holds_alternative<ArcFeed>(c); }),
              calls.end());
  std::vector<diag::FileDiagnostic> e1, e2;
  const std::string batched_limit = render_program(limited, calls, e1);
  const std::string unbatched_limit =
      render_program(limited, calls, e2, RenderOptions{{}, false, 0});
  EXPECT_TRUE(diag::has_errors(e1));
  EXPECT_NE(batched_limit.find("G1 X12."), std::string::npos) << batched_limit;
  EXPECT_EQ(batched_limit, unbatched_limit);
}

// Motion runs (render.motion_runs) change how motions reach the stylesheet, never the text.
void expect_runs_change_nothing(const profile::LoadedProfile& with_runs,
                                const std::vector<canon::Call>& calls) {
  ASSERT_TRUE(with_runs.profile.motion_runs.any()) << with_runs.profile.id;
  profile::LoadedProfile without = with_runs;
  without.profile.motion_runs = {};
  for (const RenderOptions& options :
       {RenderOptions{}, RenderOptions{{3}, false, 0}, RenderOptions{{}, true}}) {
    std::vector<diag::FileDiagnostic> d1, d2;
    const std::string runs = render_program(with_runs, calls, d1, options);
    const std::string elements = render_program(without, calls, d2, options);
    EXPECT_FALSE(runs.empty());
    EXPECT_EQ(runs, elements);
    ASSERT_EQ(d1.size(), d2.size());
    for (std::size_t i = 0; i < d1.size(); ++i) EXPECT_EQ(diag::format(d1[i]), diag::format(d2[i]));
  }
}

TEST_F(RenderTest, MotionRunsWriteWhatTheElementTemplatesWrite) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  for (const char* id : {"linuxcnc", "fanuc-0i", "haas-ngc", "mitsubishi-m80", "okuma-osp",
                         "siemens-840d", "linuxcnc-5ax", "fanuc-30i-5ax", "siemens-840d-5ax"}) {
    auto p = builtin(id);
    ASSERT_TRUE(p);
    for (const char* c :
         {"curves.stp", "placement-rotated-setup.stp", "executables.stp", "five-axis.stp"}) {
      SCOPED_TRACE(std::string(id) + " " + c);
      expect_runs_change_nothing(*p, program(cases / c));
    }
    SCOPED_TRACE(std::string(id) + " cycles");
    expect_runs_change_nothing(*p, cycle_program());
  }
}

TEST_F(RenderTest, MotionRunsWriteWhatTheElementTemplatesWriteEx1AndEx1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  for (const char* file : {"nist_toolkit_ex1.stp", "nist_toolkit_ex1E.stp"}) {
    const auto calls = program(corpus / "p21" / file);
    for (const char* id : {"linuxcnc", "fanuc-0i", "siemens-840d"}) {
      SCOPED_TRACE(std::string(id) + " " + file);
      expect_runs_change_nothing(*builtin(id), calls);
    }
  }
}

// A profile that asks for runs with a stylesheet that has no template for them would lose
// motions silently (XSLT's built-in rule writes nothing for an empty element): it is an error.
TEST_F(RenderTest, RunsLeftUnrenderedAreAnError) {
  auto base = builtin("linuxcnc");
  ASSERT_TRUE(base);
  const fs::path dir = base->directory;
  const std::vector<fs::path> roots{dir, dir.parent_path() / "common"};
  // No template (an empty one over the common one), and one that renders each run twice.
  const char* const templates[] = {R"x(<xsl:template match="motions"/>)x",
                                   R"x(<xsl:template match="motions">
            <xsl:value-of select="ext:motion-run('G0', 'G1', 'G2', 'G3', 'ijk')"/>
            <xsl:value-of select="ext:motion-run('G0', 'G1', 'G2', 'G3', 'ijk')"/>
          </xsl:template>)x"};
  for (const char* motions_template : templates) {
    SCOPED_TRACE(motions_template);
    const std::string text = std::string(R"(<xsl:stylesheet version="1.0"
        xmlns:xsl="http://www.w3.org/1999/XSL/Transform" xmlns:ext="urn:ncpost:ext"
        exclude-result-prefixes="ext">
      <xsl:import href="../common/ncpost-common.xsl"/>
      <xsl:output method="text"/>)") +
                             motions_template + "</xsl:stylesheet>";
    auto compiled = xslt::compile_text(text, dir / "post.xsl", roots);
    ASSERT_TRUE(compiled.ok()) << (compiled.diagnostics.empty()
                                       ? ""
                                       : diag::format(compiled.diagnostics[0]));
    profile::LoadedProfile p = *base;
    p.stylesheet = compiled.stylesheet;
    std::vector<diag::FileDiagnostic> d;
    (void)render_program(p, cycle_program(), d);
    EXPECT_TRUE(diag::has_errors(d));
    const bool named = std::any_of(d.begin(), d.end(), [](const diag::FileDiagnostic& f) {
      return f.diagnostic.code == diag::Code::RenderRunNotRendered ||
             f.diagnostic.message.find("rendered before") != std::string::npos;
    });
    EXPECT_TRUE(named);
  }
}

TEST_F(RenderTest, CrLfLineEndings) {
  auto base = builtin("linuxcnc");
  profile::LoadedProfile p = *base;
  p.profile.line_ending = "\r\n";
  std::vector<diag::FileDiagnostic> d;
  const std::string text = render_program(p, cycle_program(), d);
  EXPECT_EQ(text.substr(0, 3), "%\r\n");
  EXPECT_EQ(text.find("\n", 0), text.find("\r\n", 0) + 1);
}

}  // namespace
}  // namespace ncpost::render
