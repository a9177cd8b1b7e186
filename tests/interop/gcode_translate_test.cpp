// Translation between controllers (issue 19): a FANUC program read into the canonical program,
// posted again with a profile and read back with that profile's dialect, keeps its geometry
// within 0.001 mm — FANUC → canonical → FANUC, and FANUC → Sinumerik → canonical. Sources: the
// fanuc-0i post of NIST's ex1E (corpus) and the project's macro B programs
// (tests/golden/gcode/fanuc-0i: loops, IF/GOTO, G65 with arguments, indirect variables, spaced
// expressions, M98 repeats).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "corpus.hpp"
#include "motions.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "ncpost/render/render.hpp"

namespace ncpost::interop {
namespace {

namespace fs = std::filesystem;

std::shared_ptr<const gcode::Dialect> dialect(const std::string& id) {
  const auto r = gcode::load_dialect(
      test::read_file(test::source_dir() / "stylesheets" / id / "dialect.json"));
  EXPECT_TRUE(r.dialect) << id;
  return r.dialect;
}

std::vector<canon::Call> read_text(const std::string& text, const std::string& id,
                                   const std::string& name) {
  const auto d = dialect(id);
  canon::ProgramBuffer buffer;
  if (!d) return {};
  gcode::ReadOptions options;
  options.program_name = name;
  const auto r = gcode::read(text, *d, buffer, options);
  for (const auto& x : r.diagnostics)
    EXPECT_NE(x.diagnostic.severity, diag::Severity::Error) << diag::format(x);
  return std::move(buffer).take();
}

// source (FANUC) → canonical → `to` profile → read with `to`'s dialect → canonical: the motions
// of both canonical programs must agree.
void translate(const std::string& source, const std::string& name, const std::string& to) {
  SCOPED_TRACE(name + " to " + to);
  const auto first = read_text(source, "fanuc-0i", name);
  ASSERT_FALSE(first.empty());
  const auto profile = load_profile(to);
  ASSERT_TRUE(profile);
  std::vector<diag::FileDiagnostic> diagnostics;
  const std::string text = render::render_program(*profile, first, diagnostics);
  for (const auto& d : diagnostics)
    EXPECT_NE(d.diagnostic.severity, diag::Severity::Error) << diag::format(d);
  const auto second = read_text(text, to, name + profile->profile.extension);
  const ReadBackOptions o = read_back_options(to, profile->profile);
  const auto a = normalised(motions_of(first, o.ours));
  const auto b = normalised(motions_of(second, o.theirs));
  const Outcome outcome = expect_same_motions(a, b, to + " read back");
  EXPECT_GT(outcome.compared, 3u);
  std::printf("[ translate] %s fanuc-0i -> %s -> canonical: %zu motions, max deviation %.6f\n",
              name.c_str(), to.c_str(), outcome.compared, outcome.max_deviation);
}

std::vector<fs::path> macro_programs() {
  std::vector<fs::path> out;
  for (const auto& e :
       fs::directory_iterator(test::source_dir() / "tests" / "golden" / "gcode" / "fanuc-0i"))
    if (e.path().extension() == ".nc" && e.path().stem() != "alarm") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

void translate_all(const std::string& to) {
  for (const fs::path& p : macro_programs())
    translate(test::read_file(p), p.filename().string(), to);
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Posted posted = post_file(corpus / "p21" / "nist_toolkit_ex1E.stp", "fanuc-0i");
  ASSERT_FALSE(posted.text.empty());
  translate(posted.text, "ex1E.nc", to);
}

TEST(GcodeTranslate, FanucToFanuc) {
  translate_all("fanuc-0i");
}
TEST(GcodeTranslate, FanucToSinumerik) {
  translate_all("siemens-840d");
}

}  // namespace
}  // namespace ncpost::interop
