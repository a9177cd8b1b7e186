// Posts ex1E and the trace cases with the linuxcnc profile, runs LinuxCNC's `rs274 -g` on the
// result and compares its canonical motions with our own canonical program of the same input:
// same count and order of STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED, end points, arc
// centres and turns, and the feed rate in force, within 0.001 mm. README.md explains what is
// filtered. Skips when /usr/bin/rs274 is missing, unless NCPOST_REQUIRE_RS274=1.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "corpus.hpp"
#include "ncpost/canon/cycle.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRs274 = "/usr/bin/rs274";
constexpr double kTolerance = 0.001;

// One motion, in rs274's terms: kind, six numbers (x y z, or the arc's first_end second_end
// first_axis second_axis rotation axis_end_point) and the feed rate in force.
struct Motion {
  std::string kind;
  std::vector<double> values;
  double feed = 0;
};

std::string describe(const Motion& m) {
  std::ostringstream s;
  s << m.kind << "(";
  for (std::size_t i = 0; i < m.values.size(); ++i) s << (i ? ", " : "") << m.values[i];
  s << ") F" << m.feed;
  return s.str();
}

// Our canonical program, after what the renderer does before the stylesheet for this profile
// (cycles expanded, NURBS linearised with the profile's chord tolerance).
class Motions final : public canon::Sink {
 public:
  explicit Motions(const profile::Profile& p) : profile_(p) {}
  void call(const canon::Call& call) override {
    if (const auto* f = std::get_if<canon::SetFeedRate>(&call)) feed_ = f->rate;
    if (const auto* t = std::get_if<canon::StraightTraverse>(&call))
      motions.push_back({"STRAIGHT_TRAVERSE", {t->to.x, t->to.y, t->to.z}, feed_});
    if (const auto* t = std::get_if<canon::StraightFeed>(&call))
      motions.push_back({"STRAIGHT_FEED", {t->to.x, t->to.y, t->to.z}, feed_});
    if (const auto* a = std::get_if<canon::ArcFeed>(&call)) {
      const auto p = canon::plane_arc(*a);
      ASSERT_TRUE(p) << "tilted arc";
      motions.push_back({"ARC_FEED",
                         {p->first_end, p->second_end, p->first_axis, p->second_axis,
                          double(p->rotation), p->axis_end_point},
                         feed_});
    }
    if (const auto* n = std::get_if<canon::NurbsFeed>(&call))
      for (const auto& q : render::linearize(*n, profile_.chord_tolerance))
        motions.push_back({"STRAIGHT_FEED", {q.x, q.y, q.z}, feed_});
    if (const auto* c = std::get_if<canon::Cycle>(&call)) (void)canon::expand_cycle(*c, *this);
  }
  std::vector<Motion> motions;

 private:
  const profile::Profile& profile_;
  double feed_ = 0;
};

// rs274's lines: "   30 N..... STRAIGHT_TRAVERSE(91.9000, -13.5000, 30.0000, 0.0000, 0.0000,
// 0.0000)".
std::vector<Motion> parse_rs274(const std::string& text) {
  static const std::regex line(R"(^\s*\d+\s+N(?:\.\.\.\.\.|\d+)\s+([A-Z_0-9]+)\((.*)\)\s*$)");
  std::vector<Motion> out;
  double feed = 0;
  std::istringstream in(text);
  std::string s;
  while (std::getline(in, s)) {
    std::smatch m;
    if (!std::regex_match(s, m, line)) continue;
    const std::string name = m[1];
    std::vector<double> args;
    std::string arg;
    std::istringstream a(m[2]);
    while (std::getline(a, arg, ',')) args.push_back(std::strtod(arg.c_str(), nullptr));
    if (name == "SET_FEED_RATE" && !args.empty()) feed = args[0];
    if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") {
      args.resize(3);  // x, y, z; a, b, c are 0 in a 3-axis program
      out.push_back({name, args, feed});
    } else if (name == "ARC_FEED") {
      args.resize(6);  // first_end, second_end, first_axis, second_axis, rotation, axis_end_point
      out.push_back({name, args, feed});
    }
  }
  return out;
}

std::string read_all(const fs::path& p) {
  return test::read_file(p);
}

struct Outcome {
  std::size_t compared = 0;
  double max_deviation = 0;
};

Outcome compare_with_rs274(const fs::path& input, const std::string& case_name,
                           const std::string& profile_id) {
  xslt::initialise();
  static const express::SchemaRegistry registry;
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<xslt::FileDiagnostic> diagnostics;
  const auto profile = store.load(profile_id, diagnostics);
  EXPECT_TRUE(profile);
  if (!profile) return {};

  // Ours: the canonical program, and the posted text.
  auto loaded = pipeline::load(test::read_file(input), registry);
  EXPECT_TRUE(loaded.ok());
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  canon::ProgramBuffer buffer;
  (void)stepnc::interpret(loaded.model, attributes, buffer, {});
  Motions ours(profile->profile);
  std::set<int> tools;
  for (const auto& c : buffer.calls()) {
    ours.call(c);
    if (const auto* t = std::get_if<canon::ChangeTool>(&c); t && t->slot > 0) tools.insert(t->slot);
    if (const auto* t = std::get_if<canon::SelectTool>(&c); t && t->slot > 0) tools.insert(t->slot);
  }
  std::vector<xslt::FileDiagnostic> render_diagnostics;
  std::string ngc = render::render_program(*profile, buffer.calls(), render_diagnostics);
  if (profile_id != "linuxcnc") {
    // FANUC's "O0001 (name)" is a subroutine label to LinuxCNC: the one line dropped.
    std::string kept;
    std::istringstream lines(ngc);
    for (std::string l; std::getline(lines, l);)
      if (l.empty() || l[0] != 'O') kept += l + "\n";
    ngc = kept;
  }
  EXPECT_FALSE(xslt::has_errors(render_diagnostics));

  // A work folder with the program and a tool table of the tools it uses. Tool lengths are 0,
  // so rs274's positions are the programmed ones (our canonical program does not apply them).
  const fs::path dir = fs::temp_directory_path() / ("ncpost-interop-" + std::to_string(::getpid()) +
                                                    "-" + profile_id + "-" + case_name);
  fs::create_directories(dir);
  std::ofstream(dir / "program.ngc", std::ios::binary) << ngc;
  {
    std::ofstream table(dir / "tools.tbl");
    for (int t : tools) table << "T" << t << " P" << t << " Z0 D10 ;\n";
  }
  // rs274 runs in the work folder (it may write rs274ngc.var there).
  const std::string command =
      "cd '" + dir.string() + "' && " + std::string(kRs274) + " -g -t '" +
      (dir / "tools.tbl").string() + "' '" + (dir / "program.ngc").string() + "' '" +
      (dir / "canon.txt").string() + "' > '" + (dir / "rs274.log").string() + "' 2>&1 < /dev/null";
  // Another rs274 running at the same time (another test) can disturb the shared tool table:
  // one retry.
  int rc = std::system(command.c_str());
  if (rc != 0 || read_all(dir / "canon.txt").find("PROGRAM_END()") == std::string::npos)
    rc = std::system(command.c_str());
  EXPECT_EQ(rc, 0) << read_all(dir / "rs274.log");
  const std::string canon_text = read_all(dir / "canon.txt");
  EXPECT_NE(canon_text.find("PROGRAM_END()"), std::string::npos) << "rs274 stopped early:\n"
                                                                 << read_all(dir / "rs274.log");
  const auto theirs = parse_rs274(canon_text);

  Outcome outcome;
  EXPECT_EQ(ours.motions.size(), theirs.size());
  const std::size_t n = std::min(ours.motions.size(), theirs.size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = ours.motions[i];
    const auto& b = theirs[i];
    if (a.kind != b.kind || a.values.size() != b.values.size()) {
      ADD_FAILURE() << "motion " << i << ": ours " << describe(a) << ", rs274 " << describe(b);
      break;
    }
    double dev = std::abs(a.feed - b.feed);
    if (a.kind != "STRAIGHT_TRAVERSE")
      EXPECT_LE(dev, kTolerance) << "feed of motion " << i << ": " << describe(a) << " vs "
                                 << describe(b);
    else
      dev = 0;
    for (std::size_t k = 0; k < a.values.size(); ++k)
      dev = std::max(dev, std::abs(a.values[k] - b.values[k]));
    EXPECT_LE(dev, kTolerance) << "motion " << i << ": ours " << describe(a) << ", rs274 "
                               << describe(b);
    outcome.max_deviation = std::max(outcome.max_deviation, dev);
  }
  outcome.compared = n;
  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
  return outcome;
}

bool rs274_available() {
  if (fs::exists(kRs274)) return true;
  return false;
}

#define NCPOST_REQUIRE_RS274_OR_SKIP()                                         \
  if (!rs274_available()) {                                                    \
    const char* req = std::getenv("NCPOST_REQUIRE_RS274");                     \
    if (req && std::string(req) == "1")                                        \
      FAIL() << "NCPOST_REQUIRE_RS274=1 but /usr/bin/rs274 is missing";        \
    GTEST_SKIP() << "/usr/bin/rs274 not found (install linuxcnc-uspace); set " \
                    "NCPOST_REQUIRE_RS274=1 to fail";                          \
  }

// One test per profile, with all cases: LinuxCNC 2.9 keeps the loaded tool table in shared
// memory, so two rs274 processes at once (ctest -j) see each other's tools (hence also the
// ctest RESOURCE_LOCK).
void check_profile(const std::string& profile_id) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  for (const char* name : {"curves", "placement-rotated-setup", "executables"}) {
    SCOPED_TRACE(name);
    const auto o = compare_with_rs274(cases / (std::string(name) + ".stp"), name, profile_id);
    EXPECT_GT(o.compared, 0u);
    std::printf("[ rs274    ] %s %s: %zu motions compared, max deviation %.6f\n",
                profile_id.c_str(), name, o.compared, o.max_deviation);
  }
}

void check_ex1e(const fs::path& corpus, const std::string& profile_id) {
  const auto o = compare_with_rs274(corpus / "p21" / "nist_toolkit_ex1E.stp", "ex1E", profile_id);
  EXPECT_GT(o.compared, 400u);
  std::printf("[ rs274    ] %s ex1E: %zu motions compared, max deviation %.6f\n",
              profile_id.c_str(), o.compared, o.max_deviation);
}

TEST(Rs274Interop, LinuxcncProfile) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_profile("linuxcnc");
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  check_ex1e(corpus, "linuxcnc");
}

// FANUC and LinuxCNC share the syntax of these programs (N words, R arcs, leading-zero-less
// numbers, M30) except the O line.
TEST(Rs274Interop, FanucProfile) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_profile("fanuc-0i");
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  check_ex1e(corpus, "fanuc-0i");
}

// Haas NGC: FANUC syntax without N words; its G4 P is in seconds (dwells are not compared).
TEST(Rs274Interop, HaasNgcProfile) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_profile("haas-ngc");
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  check_ex1e(corpus, "haas-ngc");
}

}  // namespace
}  // namespace ncpost::interop
