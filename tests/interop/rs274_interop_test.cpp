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
#include "motions.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRs274 = "/usr/bin/rs274";

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

Outcome compare_with_rs274(const fs::path& input, const std::string& case_name,
                           const std::string& profile_id, bool tolerant = false) {
  // Ours: the canonical program, and the posted text.
  const Posted posted = post_file(input, profile_id, tolerant);
  if (!posted.profile) return {};
  const auto ours = motions_of(posted.calls, options_for(posted.profile->profile));
  std::set<int> tools;
  for (const auto& c : posted.calls) {
    if (const auto* t = std::get_if<canon::ChangeTool>(&c); t && t->slot > 0) tools.insert(t->slot);
    if (const auto* t = std::get_if<canon::SelectTool>(&c); t && t->slot > 0) tools.insert(t->slot);
  }
  std::string ngc = posted.text;
  if (profile_id != "linuxcnc") {
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
  const auto theirs = parse_rs274(canon_text);

  const Outcome outcome = expect_same_motions(ours, theirs, "rs274");
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

// Programs written the way other systems write them (tests/golden/tolerant/cases), posted as
// a job without --strict posts them.
TEST(Rs274Interop, LinuxcncTolerantCases) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  const fs::path cases = test::source_dir() / "tests" / "golden" / "tolerant" / "cases";
  for (const char* name : {"omitted-unread", "abstract-tool", "combined"}) {
    SCOPED_TRACE(name);
    const auto o = compare_with_rs274(cases / (std::string(name) + ".stp"), name, "linuxcnc", true);
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

}  // namespace
}  // namespace ncpost::interop
