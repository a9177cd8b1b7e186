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
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "corpus.hpp"
#include "motions.hpp"
#include "ncpost/render/render.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRs274 = "/usr/bin/rs274";

// rs274's lines: "   30 N..... STRAIGHT_TRAVERSE(91.9000, -13.5000, 30.0000, 0.0000, 0.0000,
// 0.0000)", read into canonical calls: feeds, planes, motions with their rotary axes A B C,
// and the tool length offset, with the length `tool_lengths` gives the tool in the spindle
// (the tool table rs274 reads has zero lengths: its positions are the programmed ones).
std::vector<canon::Call> parse_rs274(const std::string& text,
                                     const std::map<int, double>& tool_lengths) {
  static const std::regex line(R"(^\s*\d+\s+N(?:\.\.\.\.\.|\d+)\s+([A-Z_0-9]+)\((.*)\)\s*$)");
  std::vector<canon::Call> out;
  canon::Plane plane = canon::Plane::Xy;
  int selected = 0, tool = 0;
  std::istringstream in(text);
  std::string s;
  while (std::getline(in, s)) {
    std::smatch m;
    if (!std::regex_match(s, m, line)) continue;
    const std::string name = m[1];
    const std::string arguments = m[2];
    std::vector<double> args;
    std::string arg;
    std::istringstream a(arguments);
    while (std::getline(a, arg, ',')) args.push_back(std::strtod(arg.c_str(), nullptr));
    const auto rotary = [&](std::size_t first) {
      return canon::Rotary{args[first], args[first + 1], args[first + 2]};
    };
    if (name == "SET_FEED_RATE" && !args.empty()) out.emplace_back(canon::SetFeedRate{args[0]});
    if (name == "SELECT_PLANE")
      plane = arguments.find("YZ") != std::string::npos   ? canon::Plane::Yz
              : arguments.find("XZ") != std::string::npos ? canon::Plane::Xz
                                                          : canon::Plane::Xy;
    // SELECT_TOOL names the tool; CHANGE_TOOL prints its index in the tool table.
    if (name == "SELECT_TOOL" && !args.empty()) selected = static_cast<int>(args[0]);
    if (name == "CHANGE_TOOL") tool = selected;
    if (name == "USE_TOOL_LENGTH_OFFSET") {
      const auto length = tool_lengths.find(tool);
      out.emplace_back(
          canon::UseToolLengthOffset{length != tool_lengths.end() ? length->second : 0.0});
    }
    if ((name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") && args.size() >= 6) {
      const canon::Pose to{args[0], args[1], args[2], rotary(3), std::nullopt};
      if (name == "STRAIGHT_TRAVERSE")
        out.emplace_back(canon::StraightTraverse{to});
      else
        out.emplace_back(canon::StraightFeed{to});
    } else if (name == "ARC_FEED" && args.size() >= 9) {
      // first_end, second_end, first_axis, second_axis, rotation, axis_end_point, a, b, c
      canon::ArcFeed arc = canon::arc_from_plane(
          {plane, args[0], args[1], args[2], args[3], static_cast<int>(args[4]), args[5]});
      arc.end.rotary = rotary(6);
      out.emplace_back(arc);
    }
  }
  return out;
}

// The tool table of a program: each tool with the length its USE_TOOL_LENGTH_OFFSET gives it.
std::map<int, double> tool_lengths(const std::vector<canon::Call>& calls) {
  std::map<int, double> lengths;
  int tool = 0;
  for (const auto& c : calls) {
    if (const auto* t = std::get_if<canon::ChangeTool>(&c)) tool = t->slot;
    if (const auto* l = std::get_if<canon::UseToolLengthOffset>(&c); l && l->length != 0)
      lengths[tool] = l->length;
  }
  return lengths;
}

std::string read_all(const fs::path& p) {
  return test::read_file(p);
}

// rs274 prints angles with 4 decimals: a tool axis read back from them is off by up to about
// 1.3e-6 (the dialect checker reads the post's own 6 decimals within 1e-6).
constexpr double kRs274AxisTolerance = 2e-6;

Outcome compare_with_rs274(const Posted& posted, const std::string& case_name,
                           const std::string& profile_id) {
  if (!posted.profile) return {};
  const auto ours = motions_of(posted.calls, options_for(posted.profile->profile));
  std::set<int> tools;
  for (const auto& c : posted.calls) {
    if (const auto* t = std::get_if<canon::ChangeTool>(&c); t && t->slot > 0) tools.insert(t->slot);
    if (const auto* t = std::get_if<canon::SelectTool>(&c); t && t->slot > 0) tools.insert(t->slot);
  }
  std::string ngc = posted.text;
  if (profile_id.rfind("linuxcnc", 0) != 0) {
    // FANUC's "O0001 (name)" is a subroutine label to LinuxCNC: the one line dropped.
    std::string kept;
    std::istringstream lines(ngc);
    for (std::string l; std::getline(lines, l);)
      if (l.empty() || l[0] != 'O') kept += l + "\n";
    ngc = kept;
  }

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
  MotionOptions read = options_for(posted.profile->profile);
  read.posted = true;  // five-axis: machine positions, turned back by the forward kinematics
  const auto theirs = motions_of(parse_rs274(canon_text, tool_lengths(posted.calls)), read);

  const Outcome outcome = expect_same_motions(ours, theirs, "rs274", kRs274AxisTolerance);
  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
  return outcome;
}

Outcome compare_with_rs274(const fs::path& input, const std::string& case_name,
                           const std::string& profile_id) {
  return compare_with_rs274(post_file(input, profile_id), case_name, profile_id);
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

// Programs whose paths the feature generator makes (tests/golden/features/cases): thread
// drilling's multi-turn helices (G2/G3 with P), helical ramps round a ring groove, helical
// retracts out of a pocket.
TEST(Rs274Interop, LinuxcncGeneratedFeatures) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  const fs::path cases = test::source_dir() / "tests" / "golden" / "features" / "cases";
  for (const char* name : {"thread-drilling", "slot-circular", "pocket-retract"}) {
    SCOPED_TRACE(name);
    const auto o = compare_with_rs274(cases / (std::string(name) + ".stp"), name, "linuxcnc");
    EXPECT_GT(o.compared, 0u);
    std::printf("[ rs274    ] linuxcnc %s: %zu motions compared, max deviation %.6f\n", name,
                o.compared, o.max_deviation);
  }
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

// A five-axis fork head (C carrying A) without tool-centre-point control: the post moves X Y Z
// for the pivot and the tool length. rs274 reads A and C like any axis; its motions, turned
// back by the tests' forward kinematics with the tool table's lengths, are the program's tips
// and tool axes. Three-axis programs on the same machine stay as they were.
TEST(Rs274Interop, LinuxcncFiveAxisProfile) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_profile("linuxcnc-5ax");
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  const auto step_nc = compare_with_rs274(cases / "five-axis.stp", "five-axis", "linuxcnc-5ax");
  EXPECT_GT(step_nc.compared, 10u);
  std::printf(
      "[ rs274    ] linuxcnc-5ax five-axis.stp: %zu motions, max deviation %.6f, tool axes %.2e\n",
      step_nc.compared, step_nc.max_deviation, step_nc.max_axis_deviation);
  Posted hand;
  std::vector<diag::FileDiagnostic> diagnostics;
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  hand.profile = store.load("linuxcnc-5ax", diagnostics);
  ASSERT_TRUE(hand.profile);
  hand.calls = five_axis_program();
  hand.text = render::render_program(*hand.profile, hand.calls, diagnostics);
  ASSERT_FALSE(diag::has_errors(diagnostics));
  const auto o = compare_with_rs274(hand, "five-axis-program", "linuxcnc-5ax");
  EXPECT_GT(o.compared, 15u);
  std::printf(
      "[ rs274    ] linuxcnc-5ax five-axis program: %zu motions, max deviation %.6f, tool axes "
      "%.2e\n",
      o.compared, o.max_deviation, o.max_axis_deviation);
}

}  // namespace
}  // namespace ncpost::interop
