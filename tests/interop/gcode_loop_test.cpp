// Closing the loop (issue 19): for every G-code profile, the program a post writes, read back
// with the dialect.json of the same profile folder, gives back the canonical motions it was
// posted from — within the profile's number format (kTolerance, 0.001). Inputs: NIST's ex1E
// (corpus), the golden trace cases and the hand-made cycle program. Our dialect readers are so
// a second, independent check of the stylesheets (and the stylesheets of the readers).
//
// Motions are compared as the dialect checkers compare them (dialect_check_test.cpp): the
// profile's set-up and arc splitting applied to the posted-from program, both sides
// normalised. No external program.

#include <gtest/gtest.h>

#include <cstdio>

#include "corpus.hpp"
#include "motions.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "ncpost/render/render.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

std::shared_ptr<const gcode::Dialect> dialect_of(const profile::LoadedProfile& p) {
  const auto r = gcode::load_dialect(test::read_file(p.directory / "dialect.json"));
  EXPECT_TRUE(r.dialect) << p.profile.id << ": "
                         << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  return r.dialect;
}

// read(post(x)) against x: the number of motions compared.
std::size_t loop(const std::string& id, const profile::LoadedProfile& p,
                 const std::vector<canon::Call>& calls, const std::string& text,
                 const std::string& label) {
  SCOPED_TRACE(id + " " + label);
  const auto dialect = dialect_of(p);
  if (!dialect) return 0;
  const ReadBackOptions o = read_back_options(id, p.profile);
  Motions back(o.theirs);
  gcode::ReadOptions options;
  options.program_name = label + p.profile.extension;
  const gcode::ReadResult r = gcode::read(text, *dialect, back, options);
  for (const auto& d : r.diagnostics)
    EXPECT_NE(d.diagnostic.severity, diag::Severity::Error) << diag::format(d);
  const auto ours = normalised(motions_of(calls, o.ours));
  const auto theirs = normalised(back.motions);
  const Outcome outcome = expect_same_motions(ours, theirs, id + " read back by engine/gcode");
  std::printf("[ loop     ] %s %s: %zu motions, max deviation %.6f\n", id.c_str(), label.c_str(),
              outcome.compared, outcome.max_deviation);
  return outcome.compared;
}

void check_profile(const std::string& id) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  for (const char* name : {"curves", "placement-rotated-setup", "executables"}) {
    const Posted posted = post_file(cases / (std::string(name) + ".stp"), id);
    if (!posted.profile) continue;
    EXPECT_GT(loop(id, *posted.profile, posted.calls, posted.text, name), 2u);
  }
  if (const auto p = load_profile(id)) {
    const auto calls = cycles_program();
    std::vector<diag::FileDiagnostic> diagnostics;
    const std::string text = render::render_program(*p, calls, diagnostics);
    EXPECT_FALSE(diag::has_errors(diagnostics));
    EXPECT_GT(loop(id, *p, calls, text, "cycles"), 7u);
  }
  const auto corpus = test::corpus_dir();
  if (!corpus) {
    if (test::corpus_required()) ADD_FAILURE() << "NCPOST_REQUIRE_CORPUS=1 but no corpus";
    std::printf("[ loop     ] %s ex1E: skipped (no corpus)\n", id.c_str());
    return;
  }
  const Posted posted = post_file(*corpus / "p21" / "nist_toolkit_ex1E.stp", id);
  if (posted.profile) {
    EXPECT_GT(loop(id, *posted.profile, posted.calls, posted.text, "ex1E"), 400u);
  }
}

TEST(GcodeLoop, Linuxcnc) {
  check_profile("linuxcnc");
}
TEST(GcodeLoop, Fanuc0i) {
  check_profile("fanuc-0i");
}
TEST(GcodeLoop, Siemens840d) {
  check_profile("siemens-840d");
}
TEST(GcodeLoop, HaasNgc) {
  check_profile("haas-ngc");
}
TEST(GcodeLoop, MitsubishiM80) {
  check_profile("mitsubishi-m80");
}
TEST(GcodeLoop, OkumaOsp) {
  check_profile("okuma-osp");
}
TEST(GcodeLoop, Hnc21) {
  check_profile("hnc-21");
}
TEST(GcodeLoop, HeidenhainTnc640) {
  check_profile("heidenhain-tnc640");
}

}  // namespace
}  // namespace ncpost::interop
