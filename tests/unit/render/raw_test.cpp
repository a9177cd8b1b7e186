// Raw mode (profile "mode": "raw", engine/render/raw.hpp): the p28-raw-demo profile reads the
// whole late-bound P28 document of NIST's ex1E. Golden output through pipeline::post (the path
// `ncpost post` takes), the same text from P28 input, and a geometry check: every G0/G1 the
// demo writes must be one of our canonical motions of the same workingstep, in order, within
// 0.001 mm.

#include "ncpost/render/raw.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "corpus.hpp"
#include "golden.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/pipeline/post.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::render {
namespace {

namespace fs = std::filesystem;

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

std::shared_ptr<const profile::LoadedProfile> demo_profile() {
  xslt::initialise();
  static profile::ProfileStore store(test::source_dir() / "stylesheets");
  std::vector<diag::FileDiagnostic> diagnostics;
  auto p = store.load("p28-raw-demo", diagnostics);
  EXPECT_TRUE(p) << (diagnostics.empty() ? "" : diag::format(diagnostics[0]));
  return p;
}

struct Posted {
  std::string text;
  pipeline::PostResult result;
};

Posted post_bytes(std::string bytes, const profile::LoadedProfile& profile) {
  Posted posted;
  auto loaded = pipeline::load(std::move(bytes), registry());
  EXPECT_TRUE(loaded.ok());
  if (!loaded.ok()) return posted;
  pipeline::PostOptions options;
  options.input_name = "ex1E";
  posted.result = pipeline::post(
      loaded, profile, [&](std::string_view piece) { posted.text += piece; }, options);
  return posted;
}

struct Point3 {
  double x, y, z;
};

// Workingstep id → the end points of its straight motions, in order.
using ByWorkingstep = std::map<std::uint64_t, std::vector<Point3>>;
// Workingstep id → where the tool stands when it begins.
using Starts = std::map<std::uint64_t, Point3>;

ByWorkingstep canonical_motions(const std::string& bytes, Starts& starts) {
  ByWorkingstep out;
  Point3 at{NAN, NAN, NAN};
  auto loaded = pipeline::load(bytes, registry());
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  canon::ProgramBuffer buffer;
  EXPECT_TRUE(stepnc::interpret(loaded.model, attributes, buffer, {}).ok());
  std::uint64_t ws = 0;
  for (const auto& call : buffer.calls()) {
    if (const auto* b = std::get_if<canon::Begin>(&call);
        b && b->scope == canon::Scope::Workingstep) {
      ws = b->entity.id;
      starts[ws] = at;
    }
    if (const auto* t = std::get_if<canon::StraightTraverse>(&call)) {
      at = {t->to.x, t->to.y, t->to.z};
      out[ws].push_back(at);
    }
    if (const auto* f = std::get_if<canon::StraightFeed>(&call)) {
      at = {f->to.x, f->to.y, f->to.z};
      out[ws].push_back(at);
    }
  }
  return out;
}

// The demo's G0/G1 points per workingstep ("(WS #id ...)"), and the workingsteps in which it
// skipped a toolpath.
struct DemoMotions {
  ByWorkingstep points;
  std::vector<std::uint64_t> skipped;
};

double word(const std::string& line, char letter) {
  const auto at = line.find(std::string(" ") + letter);
  return at == std::string::npos ? NAN : std::stod(line.substr(at + 2));
}

DemoMotions demo_motions(const std::string& text) {
  DemoMotions out;
  std::istringstream in(text);
  std::string line;
  std::uint64_t ws = 0;
  while (std::getline(in, line)) {
    if (line.rfind("(WS #", 0) == 0) ws = std::stoull(line.substr(5));
    if (line.rfind("(SKIPPED", 0) == 0) out.skipped.push_back(ws);
    const auto g = line.find(" G0 X");
    const auto g1 = line.find(" G1 X");
    if (g != std::string::npos || g1 != std::string::npos)
      out.points[ws].push_back({word(line, 'X'), word(line, 'Y'), word(line, 'Z')});
  }
  return out;
}

// Every demo point of a fully covered workingstep must match the next canonical motion end
// within 0.001 mm, in order (the canonical program adds approach and retract moves the demo,
// which only writes the toolpaths, does not). A toolpath's first point may be where the tool
// already stands (the interpreter does not move there again). Returns the problems; counts
// matched points.
bool near(const Point3& a, const Point3& b) {
  return std::abs(a.x - b.x) <= 0.001 && std::abs(a.y - b.y) <= 0.001 &&
         std::abs(a.z - b.z) <= 0.001;
}

std::vector<std::string> compare(const DemoMotions& demo, const ByWorkingstep& ours,
                                 const Starts& starts, std::size_t& matched,
                                 std::size_t& workingsteps) {
  std::vector<std::string> problems;
  matched = workingsteps = 0;
  for (const auto& [ws, points] : demo.points) {
    if (std::find(demo.skipped.begin(), demo.skipped.end(), ws) != demo.skipped.end()) continue;
    const auto it = ours.find(ws);
    if (it == ours.end()) {
      problems.push_back("workingstep #" + std::to_string(ws) + " has no canonical motions");
      continue;
    }
    ++workingsteps;
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Point3& p = points[i];
      if (i == 0 && starts.count(ws) && near(starts.at(ws), p) &&
          !(k < it->second.size() && near(it->second[k], p))) {
        ++matched;
        continue;
      }
      while (k < it->second.size() && !near(it->second[k], p)) ++k;
      if (k == it->second.size()) {
        std::ostringstream s;
        s << "workingstep #" << ws << ": (" << p.x << ", " << p.y << ", " << p.z
          << ") is not one of our motions (in order)";
        problems.push_back(s.str());
        break;
      }
      ++k;
      ++matched;
    }
  }
  return problems;
}

using test::expect_golden;

TEST(RawMode, ProfileDeclaresRaw) {
  const auto profile = demo_profile();
  ASSERT_TRUE(profile);
  EXPECT_EQ(profile->profile.mode, profile::Mode::Raw);
}

TEST(RawMode, NistEx1EGoldenAndGeometry) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto profile = demo_profile();
  ASSERT_TRUE(profile);
  const std::string bytes = test::read_file(corpus / "p21" / "nist_toolkit_ex1E.stp");
  const Posted posted = post_bytes(bytes, *profile);
  EXPECT_TRUE(posted.result.ok);
  for (const auto& d : posted.result.diagnostics)
    EXPECT_NE(d.diagnostic.severity, diag::Severity::Error) << diag::format(d);
  EXPECT_EQ(posted.result.calls, 0u) << "raw mode does not interpret";
  expect_golden(posted.text, test::source_dir() / "tests" / "golden" / "post" / "p28-raw-demo" /
                                 "nist_toolkit_ex1E.ngc");

  Starts starts;
  const auto ours = canonical_motions(bytes, starts);
  const DemoMotions demo = demo_motions(posted.text);
  std::size_t matched = 0, workingsteps = 0;
  const auto problems = compare(demo, ours, starts, matched, workingsteps);
  for (const auto& p : problems) ADD_FAILURE() << p;
  // The demo must cover something real: ex1E's polyline toolpaths (22 workingsteps, 67 points).
  EXPECT_GE(workingsteps, 20u);
  EXPECT_GE(matched, 60u);

  // The checker can fail: one coordinate moved by 0.01 mm is reported.
  std::string perturbed = posted.text;
  const auto at = perturbed.find(" G1 X");
  ASSERT_NE(at, std::string::npos);
  const auto y = perturbed.find(" Y", at) + 2;
  const auto y_end = perturbed.find(' ', y);
  const double moved = std::stod(perturbed.substr(y, y_end - y)) + 0.01;
  perturbed.replace(y, y_end - y, std::to_string(moved));
  std::size_t m2 = 0, w2 = 0;
  EXPECT_FALSE(compare(demo_motions(perturbed), ours, starts, m2, w2).empty());
}

TEST(RawMode, P28InputGivesTheSameProgram) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto profile = demo_profile();
  ASSERT_TRUE(profile);
  const std::string bytes = test::read_file(corpus / "p21" / "nist_toolkit_ex1E.stp");
  auto loaded = pipeline::load(bytes, registry());
  ASSERT_TRUE(loaded.ok());
  std::vector<diag::FileDiagnostic> notes;
  const std::string xml = raw_document(loaded.model, loaded.schema, notes, "ex1E");
  ASSERT_NE(xml.find("late_binding"), std::string::npos);
  EXPECT_EQ(post_bytes(xml, *profile).text, post_bytes(bytes, *profile).text);
}

// A program without explicit toolpaths is outside the demo's scope: it stops with its message
// and writes nothing.
TEST(RawMode, OutOfScopeProgramStopsWithAMessage) {
  const auto profile = demo_profile();
  ASSERT_TRUE(profile);
  const std::string p21 =
      "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\n"
      "FILE_NAME('x','2024-01-01T00:00:00',(''),(''),'','','');\n"
      "FILE_SCHEMA(('MACHINING_SCHEMA'));\nENDSEC;\nDATA;\n"
      "#1=PROJECT('EMPTY',#2,(),$,$,$);\n#2=WORKPLAN('MAIN',(),$,$,$);\nENDSEC;\n"
      "END-ISO-10303-21;\n";
  auto loaded = pipeline::load(p21, registry(), false);
  ASSERT_TRUE(loaded.ok());
  std::string text;
  const auto result =
      pipeline::post(loaded, *profile, [&](std::string_view piece) { text += piece; });
  EXPECT_FALSE(result.ok);
  EXPECT_TRUE(text.empty()) << text;
  bool found = false;
  for (const auto& d : result.diagnostics)
    found = found || d.diagnostic.message.find("explicit toolpaths only") != std::string::npos;
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace ncpost::render
