// Posts ex1E and the trace cases with the linuxcnc profile, runs LinuxCNC's `rs274 -g` on the
// result and compares its canonical motions with our own canonical program of the same input:
// same count and order of STRAIGHT_TRAVERSE / STRAIGHT_FEED / ARC_FEED, end points, arc
// centres and turns, and the feed rate in force, within 0.001 mm. README.md explains what is
// filtered. Skips when /usr/bin/rs274 is missing, unless NCPOST_REQUIRE_RS274=1.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "corpus.hpp"
#include "motions.hpp"
#include "ncpost/cls/reader.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

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

// rs274 prints angles with 4 decimals: a tool axis read back from them is off by up to about
// 1.3e-6 (the dialect checker reads the post's own 6 decimals within 1e-6).
constexpr double kRs274AxisTolerance = 2e-6;

// Ours (the canonical program `posted` was rendered from) against rs274's reading of the text.
Outcome compare_posted_with_rs274(const Posted& posted, const std::string& case_name,
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
  // Another rs274 running at the same time (another test) can disturb the shared tool table:
  // one retry.
  const std::vector<std::string> args{"-t", (dir / "tools.tbl").string()};
  Rs274Run run = run_rs274(dir, dir / "program.ngc", args);
  if (run.status != 0 || run.canon.find("PROGRAM_END()") == std::string::npos)
    run = run_rs274(dir, dir / "program.ngc", args);
  EXPECT_EQ(run.status, 0) << run.log;
  const std::string& canon_text = run.canon;
  EXPECT_NE(canon_text.find("PROGRAM_END()"), std::string::npos) << "rs274 stopped early:\n"
                                                                 << run.log;
  // rs274 prints millimetres whatever the program's unit: an inch program's are scaled back.
  const bool inches = std::any_of(posted.calls.begin(), posted.calls.end(), [](const auto& c) {
    const auto* u = std::get_if<canon::UseLengthUnits>(&c);
    return u && u->units == canon::Units::Inches;
  });
  MotionOptions read = options_for(posted.profile->profile);
  read.posted = true;  // five-axis: machine positions, turned back by the forward kinematics
  const auto theirs = motions_of(
      parse_rs274_calls(canon_text, tool_lengths(posted.calls), inches ? 1 / 25.4 : 1.0), read);

  const Outcome outcome = expect_same_motions(ours, theirs, "rs274", kRs274AxisTolerance);
  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
  return outcome;
}

Outcome compare_with_rs274(const fs::path& input, const std::string& case_name,
                           const std::string& profile_id) {
  return compare_posted_with_rs274(post_file(input, profile_id), case_name, profile_id);
}

// A CL file read by engine/cls and posted.
Outcome compare_cl_with_rs274(const fs::path& input, const std::string& case_name,
                              const std::string& profile_id) {
  canon::ProgramBuffer buffer;
  const auto read = cls::read(test::read_file(input), buffer);
  EXPECT_TRUE(read.ok()) << input;
  return compare_posted_with_rs274(post_calls(std::move(buffer).take(), profile_id), case_name,
                                   profile_id);
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
// retracts out of a pocket; slots along placed paths, pockets with placed profiles, milled and
// tapered holes, roughing into tight corners, slots with general sections, drilling depths
// against blind bottoms, milled spherical hole bottoms.
TEST(Rs274Interop, LinuxcncGeneratedFeatures) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  const fs::path cases = test::source_dir() / "tests" / "golden" / "features" / "cases";
  for (const char* name : {"thread-drilling", "slot-circular", "pocket-retract",
                           // geometry other systems write (issue 17)
                           "slot-placed-travel", "pocket-placed-profile", "hole-milled",
                           "hole-bottoms-taper", "pocket-rough-corners", "geometry-combined",
                           "slot-general-section", "hole-bottoms-blind", "hole-milled-sphere"}) {
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
  for (const char* name :
       {"omitted-unread", "abstract-tool", "combined", "tool-dimension", "combined-schema",
        "implicit-depths", "open-polyline", "units-rpm", "interop-all"}) {
    SCOPED_TRACE(name);
    const auto o = compare_posted_with_rs274(
        post_file(cases / (std::string(name) + ".stp"), "linuxcnc", true, true), name, "linuxcnc");
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

// AP238 AIM programs (issue 18): the project's own and the corpus's milling programs, posted
// through engine/ap238. Lines in three planes, full circles, multi-turn helices, dwells, tool
// changes.
void check_ap238(const std::string& profile_id) {
  std::size_t compared = 0;
  for (const fs::path& input : ap238_programs()) {
    SCOPED_TRACE(input.filename().string());
    const std::string name = input.stem().string();
    const auto o = compare_with_rs274(input, name, profile_id);
    EXPECT_GT(o.compared, 0u);
    compared += o.compared;
    std::printf("[ rs274    ] %s %s: %zu motions compared, max deviation %.6f\n",
                profile_id.c_str(), name.c_str(), o.compared, o.max_deviation);
  }
  EXPECT_GT(compared, 30u);
}

TEST(Rs274Interop, LinuxcncAp238Programs) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_ap238("linuxcnc");
}

TEST(Rs274Interop, FanucAp238Programs) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_ap238("fanuc-0i");
}

TEST(Rs274Interop, HaasNgcAp238Programs) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  check_ap238("haas-ngc");
}

// Cutter-location files (issue 20): every file of the corpus's cls/ folder and the project's own
// CL programs that a 3-axis machine can run, read by engine/cls and posted for LinuxCNC.
TEST(Rs274Interop, LinuxcncClFiles) {
  NCPOST_REQUIRE_RS274_OR_SKIP();
  const fs::path cases = test::source_dir() / "tests" / "golden" / "cls" / "cases";
  for (const char* name :
       {"arcs-planes", "apt-cycles", "feeds-spindle", "inch", "continuation", "five-axis"}) {
    SCOPED_TRACE(name);
    const auto o = compare_cl_with_rs274(cases / (std::string(name) + ".cls"), name, "linuxcnc");
    EXPECT_GT(o.compared, 0u);
    std::printf("[ rs274    ] linuxcnc %s.cls: %zu motions compared, max deviation %.6f\n", name,
                o.compared, o.max_deviation);
  }
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(corpus / "cls")) {
    SCOPED_TRACE(e.path().filename().string());
    const auto o = compare_cl_with_rs274(e.path(), e.path().stem().string(), "linuxcnc");
    EXPECT_GT(o.compared, 50u);
    std::printf("[ rs274    ] linuxcnc %s: %zu motions compared, max deviation %.6f\n",
                e.path().filename().string().c_str(), o.compared, o.max_deviation);
    ++files;
  }
  EXPECT_EQ(files, 4u);
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
  const auto o = compare_posted_with_rs274(post_calls(five_axis_program(), "linuxcnc-5ax"),
                                           "five-axis-program", "linuxcnc-5ax");
  EXPECT_GT(o.compared, 15u);
  std::printf(
      "[ rs274    ] linuxcnc-5ax five-axis program: %zu motions, max deviation %.6f, tool axes "
      "%.2e\n",
      o.compared, o.max_deviation, o.max_axis_deviation);
}

}  // namespace
}  // namespace ncpost::interop
