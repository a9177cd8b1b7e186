// Controller code from the built-in profiles (linuxcnc, fanuc-0i, haas-ngc, mitsubishi-m80,
// hnc-21, siemens-840d, heidenhain-tnc640, okuma-osp, kuka-krl, abb-rapid): golden files in
// tests/golden/post/<profile>/<case>.nc for NIST's ex1E (from the corpus) and the project's own
// trace cases. NCPOST_UPDATE_GOLDEN=1 rewrites them.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vector>

#include "corpus.hpp"
#include "golden.hpp"
#include "ncpost/cls/reader.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::render {
namespace {

namespace fs = std::filesystem;

std::string post(const fs::path& file, const std::string& profile_id) {
  xslt::initialise();
  static const express::SchemaRegistry registry;
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<diag::FileDiagnostic> diagnostics;
  const auto profile = store.load(profile_id, diagnostics);
  EXPECT_TRUE(profile) << (diagnostics.empty() ? "" : diag::format(diagnostics[0]));
  if (!profile) return {};
  auto loaded = pipeline::load(test::read_file(file), registry);
  EXPECT_TRUE(loaded.ok()) << file;
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  std::string text;
  Renderer renderer(
      *profile, [&](std::string_view piece) { text += piece; }, {}, file.filename().string());
  const auto result = stepnc::interpret(loaded.model, attributes, renderer, {});
  renderer.finish();
  EXPECT_TRUE(result.ok());
  EXPECT_FALSE(renderer.failed());
  for (const auto& d : renderer.diagnostics()) ADD_FAILURE() << diag::format(d);
  return text;
}

using test::expect_golden;

const char* const kProfiles[] = {"linuxcnc", "fanuc-0i",     "haas-ngc",          "mitsubishi-m80",
                                 "hnc-21",   "siemens-840d", "heidenhain-tnc640", "okuma-osp",
                                 "kuka-krl", "abb-rapid"};

TEST(GoldenPost, TraceCases) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  for (const char* profile_id : kProfiles)
    for (const char* name : {"curves", "placement-rotated-setup", "executables"}) {
      SCOPED_TRACE(std::string(profile_id) + " " + name);
      expect_golden(post(cases / (std::string(name) + ".stp"), profile_id),
                    test::source_dir() / "tests" / "golden" / "post" / profile_id /
                        (std::string(name) + ".nc"));
    }
}

// The five-axis profiles (profile.json kinematics, docs/kinematics.md): the trace cases and
// the five-axis case with its tool-axis curve.
const char* const kFiveAxisProfiles[] = {"linuxcnc-5ax", "fanuc-30i-5ax", "siemens-840d-5ax",
                                         "heidenhain-tnc640-5ax"};

TEST(GoldenPost, FiveAxisProfiles) {
  const fs::path cases = test::source_dir() / "tests" / "golden" / "trace" / "cases";
  for (const char* profile_id : kFiveAxisProfiles)
    for (const char* name : {"curves", "placement-rotated-setup", "executables", "five-axis"}) {
      SCOPED_TRACE(std::string(profile_id) + " " + name);
      expect_golden(post(cases / (std::string(name) + ".stp"), profile_id),
                    test::source_dir() / "tests" / "golden" / "post" / profile_id /
                        (std::string(name) + ".nc"));
    }
}

TEST(GoldenPost, NistEx1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::vector<const char*> all(std::begin(kProfiles), std::end(kProfiles));
  all.insert(all.end(), std::begin(kFiveAxisProfiles), std::end(kFiveAxisProfiles));
  for (const char* profile_id : all) {
    SCOPED_TRACE(profile_id);
    expect_golden(
        post(corpus / "p21" / "nist_toolkit_ex1E.stp", profile_id),
        test::source_dir() / "tests" / "golden" / "post" / profile_id / "nist_toolkit_ex1E.nc");
  }
}

// A CL file posted with `profile_id` (no checks: the built-in profiles have none).
std::string post_cl(const fs::path& file, const std::string& profile_id) {
  xslt::initialise();
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<diag::FileDiagnostic> diagnostics;
  const auto profile = store.load(profile_id, diagnostics);
  EXPECT_TRUE(profile) << (diagnostics.empty() ? "" : diag::format(diagnostics[0]));
  if (!profile) return {};
  std::string text;
  Renderer renderer(
      *profile, [&](std::string_view piece) { text += piece; }, {}, file.filename().string());
  const auto result = cls::read(test::read_file(file), renderer);
  renderer.finish();
  EXPECT_TRUE(result.ok()) << file;
  EXPECT_FALSE(renderer.failed());
  // Warnings are part of five-axis posting (KIN-005: a rotary axis turning far in one feed).
  for (const auto& d : renderer.diagnostics())
    if (d.diagnostic.severity == diag::Severity::Error) ADD_FAILURE() << diag::format(d);
  return text;
}

// Every CL file of the corpus posted for LinuxCNC (tests/interop runs the same posts through
// rs274, motion for motion): tests/golden/post/linuxcnc/cls-<file>.ngc.
TEST(GoldenPost, ClCorpus) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(corpus / "cls")) {
    if (!entry.is_regular_file()) continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++files;
    expect_golden(post_cl(entry.path(), "linuxcnc"),
                  test::source_dir() / "tests" / "golden" / "post" / "linuxcnc" /
                      ("cls-" + entry.path().filename().string() + ".ngc"));
  }
  EXPECT_GE(files, 4u);
}

// The own five-axis CL program (tool axes on GOTO/) through every five-axis profile.
TEST(GoldenPost, ClFiveAxis) {
  const fs::path file = test::source_dir() / "tests" / "golden" / "cls" / "cases" / "five-axis.cls";
  for (const char* profile_id : kFiveAxisProfiles) {
    SCOPED_TRACE(profile_id);
    expect_golden(post_cl(file, profile_id), test::source_dir() / "tests" / "golden" / "post" /
                                                 profile_id / "cls-five-axis.nc");
  }
}

// hnc-21 carries the XSLT paper's set-up (90 degrees about Z, Z shifted by -14.7 mm): program
// (x, y, z) is machine (y, -x, z - 14.7). By hand: curves.stp's G1 to (10, 0, 0) is machine
// (0, -10, -14.7); its rapid to (0, 0, 50) is (0, 0, 35.3).
TEST(GoldenPost, HncSetupTransform) {
  const fs::path curves =
      test::source_dir() / "tests" / "golden" / "trace" / "cases" / "curves.stp";
  const std::string text = post(curves, "hnc-21");
  EXPECT_NE(text.find(" G01 X0.0000 Y-10.0000 Z-14.7000\n"), std::string::npos) << text;
  EXPECT_NE(text.find(" G00 X0.0000 Y0.0000 Z35.3000\n"), std::string::npos) << text;
  EXPECT_EQ(text.rfind("%1234\n", 0), 0u) << text;
}

}  // namespace
}  // namespace ncpost::render
