// Toolpaths generated from features (docs/features.md): golden traces of the project's own
// feature programs (cases/, written by make_cases.py), NIST's ex1 compared with the explicit
// toolpaths NIST wrote for the same part (ex1E), and the wrong-tool diagnostics.
// NCPOST_UPDATE_GOLDEN=1 rewrites the golden files; review the diff.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <set>

#include "corpus.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::stepnc {
namespace {

namespace fs = std::filesystem;

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

struct Generated {
  std::vector<canon::Call> calls;
  std::vector<diag::Diagnostic> diagnostics;
  std::string text(const std::string& name) const {
    std::string out = canon::trace(calls);
    for (const auto& d : diagnostics) out += diag::format(d, name) + "\n";
    return out;
  }
  std::size_t count(std::string_view code) const {
    return static_cast<std::size_t>(
        std::count_if(diagnostics.begin(), diagnostics.end(),
                      [&](const auto& d) { return d.code_id() == code; }));
  }
};

Generated run(const fs::path& file) {
  pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
  EXPECT_TRUE(loaded.ok()) << file;
  Generated out;
  out.diagnostics = loaded.diagnostics;
  const AttributeReader attributes(loaded.model, *loaded.schema);
  canon::ProgramBuffer buffer;
  auto result = interpret(loaded.model, attributes, buffer, {});
  out.calls = std::move(buffer).take();
  out.diagnostics.insert(out.diagnostics.end(), result.diagnostics.begin(),
                         result.diagnostics.end());
  return out;
}

fs::path cases() {
  return test::source_dir() / "tests/golden/features/cases";
}

// What a workingstep did, measured from its canonical calls: cutting moves (feeds and arcs)
// only, so the approach and retract rapids do not count.
struct Summary {
  std::string name;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, z0 = 1e300, z1 = -1e300;
  std::set<double> levels;  // z of horizontal cutting moves, rounded to 1 µm
  std::vector<double> xs;   // x of cutting moves parallel to y (face passes)
  std::size_t cycles = 0;
  std::size_t cuts = 0;
  void add(double x, double y, double z) {
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    z0 = std::min(z0, z), z1 = std::max(z1, z);
  }
};

// The independent verifier (engine/verify, no code shared with the generator) on what the
// generator made. A pointed drill (or a reamer stopped by a fillet) cannot make a spherical or
// flat-with-radius bottom by itself: those cases must leave uncovered floor (VERIFY-004), and
// nothing else.
void expect_verified(const fs::path& file, const std::vector<canon::Call>& calls) {
  const pipeline::LoadedModel loaded = pipeline::load(test::read_file(file), registry());
  const AttributeReader attributes(loaded.model, *loaded.schema);
  const verify::VerifyResult result = verify::verify_calls(loaded.model, attributes, calls);
  const bool pointed =
      file.stem() == "holes-pointed-bottoms" || file.stem() == "hole-bottoms-blind";
  std::size_t uncovered = 0;
  for (const auto& f : result.findings) {
    if (f.diagnostic.severity != diag::Severity::Error) continue;
    if (pointed && f.diagnostic.code_id() == "VERIFY-004") {
      ++uncovered;
      continue;
    }
    ADD_FAILURE() << file.filename() << ": " << diag::format(f.diagnostic, file.string());
  }
  if (pointed) {
    EXPECT_GT(uncovered, 0u) << "the verifier should see the cone a drill leaves";
  }
  EXPECT_FALSE(result.features.empty()) << file.filename();
  // Every feature a case machines is one the verifier can measure (else "passed" says little).
  for (const auto& f : result.features)
    EXPECT_TRUE(f.checked) << file.filename() << " " << f.name << ": " << f.not_checked_reason;
}

// Workingsteps grouped by a name prefix: ex1E splits one ex1 workingstep into several
// ("WS ROUGH POCKET1 A", "... B", ...) with rapid movements in between.
std::map<std::string, Summary> summarise(const std::vector<canon::Call>& calls) {
  std::map<std::string, Summary> out;
  Summary* current = nullptr;
  canon::Point at{};
  const auto round = [](double v) { return std::round(v * 1000) / 1000; };
  for (const canon::Call& c : calls) {
    if (const auto* b = std::get_if<canon::Begin>(&c); b && b->scope == canon::Scope::Workingstep) {
      std::string key = b->entity.name;
      if (key.size() > 2 && key[key.size() - 2] == ' ' && std::isupper(key.back()))
        key.resize(key.size() - 2);
      current = b->entity.type == "MACHINING_WORKINGSTEP" && key.rfind("WS ", 0) == 0 ? &out[key]
                                                                                      : nullptr;
    } else if (const auto* t = std::get_if<canon::StraightTraverse>(&c)) {
      at = {t->to.x, t->to.y, t->to.z};
    } else if (const auto* f = std::get_if<canon::StraightFeed>(&c)) {
      if (current) {
        current->add(f->to.x, f->to.y, f->to.z);
        ++current->cuts;
        if (std::abs(f->to.z - at.z) < 1e-9 &&
            (std::abs(f->to.x - at.x) > 1e-9 || std::abs(f->to.y - at.y) > 1e-9))
          current->levels.insert(round(f->to.z));
        if (std::abs(f->to.x - at.x) < 1e-9 && std::abs(f->to.y - at.y) > 50)
          current->xs.push_back(round(f->to.x));
      }
      at = {f->to.x, f->to.y, f->to.z};
    } else if (const auto* a = std::get_if<canon::ArcFeed>(&c)) {
      if (current) {
        current->add(a->end.x, a->end.y, a->end.z);
        ++current->cuts;
      }
      at = {a->end.x, a->end.y, a->end.z};
    } else if (const auto* cy = std::get_if<canon::Cycle>(&c)) {
      if (current) {
        ++current->cycles;
        current->add(cy->x, cy->y, cy->bottom_z);
      }
    }
  }
  return out;
}

// ---- NIST ex1: machined, and compared with NIST's own explicit paths (ex1E) ----

TEST(FeaturesCorpus, NistExample1IsMachined) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Generated r = run(corpus / "p21/nist_toolkit_ex1.stp");
  for (const auto& d : r.diagnostics)
    EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, "ex1");
  const std::string trace = canon::trace(r.calls);
  // Drill #20: strategy #46 reduces feed to 0.5 × 1800 and speed to 0.75 × 960 rpm for the first
  // 2 mm, then 0.75 × 1800 and 0.5 × 960 for the last 8; the through hole (30 deep, #64) is left
  // by the 6.0086 point (10 × tan 31°) and the 1 mm through clearance: -37.0086.
  EXPECT_NE(trace.find(" SET_FEED_RATE(900.0000)\n"), std::string::npos);
  EXPECT_NE(trace.find(" STRAIGHT_FEED(20.0000, 60.0000, -2.0000)\n"), std::string::npos);
  EXPECT_NE(trace.find(" STRAIGHT_FEED(20.0000, 60.0000, -29.0086)\n"), std::string::npos);
  EXPECT_NE(trace.find(" STRAIGHT_FEED(20.0000, 60.0000, -37.0086)\n"), std::string::npos);
  // Reaming #21 stops the spindle at the bottom (spindle_stop_at_bottom .T.): a G86-like bore
  // from the retract plane 10 above the hole to 30 + 1 below it, feed 0.03 m/s.
  EXPECT_NE(trace.find(" BORE_CYCLE(20.0000, 60.0000, 30.0000, 10.0000, -31.0000, 1800.0000, "
                       "0.0000, SPINDLE_STOP)\n"),
            std::string::npos);
  const fs::path golden = test::source_dir() / "tests/golden/features/nist_toolkit_ex1.trace";
  const std::string text = r.text("nist_toolkit_ex1.stp");
  if (const char* u = std::getenv("NCPOST_UPDATE_GOLDEN"); u && std::string(u) == "1")
    std::ofstream(golden, std::ios::binary) << text;
  else
    EXPECT_EQ(text, test::read_file(golden));
}

TEST(FeaturesCorpus, NistExample1AgreesWithEx1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const auto ours = summarise(run(corpus / "p21/nist_toolkit_ex1.stp").calls);
  const auto nist = summarise(run(corpus / "p21/nist_toolkit_ex1E.stp").calls);
  // Planar face: the same six passes 17.1 apart (overlap 0.05 of 18 mm), the same two levels
  // (axial depth 2.5 of a 5 mm face), the same overtravel.
  for (const char* ws : {"WS FINISH PLANAR FACE1", "WS ROUGH POCKET1", "WS FINISH POCKET1"}) {
    ASSERT_TRUE(ours.count(ws)) << ws;
    ASSERT_TRUE(nist.count(ws)) << ws;
    const Summary& a = ours.at(ws);
    const Summary& b = nist.at(ws);
    EXPECT_EQ(a.levels, b.levels) << ws;
    EXPECT_NEAR(a.x0, b.x0, 1e-6) << ws;
    EXPECT_NEAR(a.x1, b.x1, 1e-6) << ws;
    EXPECT_NEAR(a.y0, b.y0, 1e-6) << ws;
    EXPECT_NEAR(a.y1, b.y1, 1e-6) << ws;
  }
  std::vector<double> xs = ours.at("WS FINISH PLANAR FACE1").xs;
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  ASSERT_EQ(xs.size(), 12u);  // two levels of six passes
  xs.resize(6);
  EXPECT_EQ(xs, (std::vector<double>{91.9, 74.8, 57.7, 40.6, 23.5, 6.4}));
  // Rough pocket: levels 5.9 apart down to 30 - 0.5 (allowance_bottom), rings 5 apart.
  EXPECT_EQ(ours.at("WS ROUGH POCKET1").levels,
            (std::set<double>{-5.9, -11.8, -17.7, -23.6, -29.5}));
  EXPECT_EQ(ours.at("WS FINISH POCKET1").levels.size(), 15u);
  // Holes: one drilled path (explicit: the strategy changes feed and speed), one cycle.
  EXPECT_EQ(ours.at("WS REAM HOLE1").cycles, 1u);
  EXPECT_NEAR(ours.at("WS DRILL HOLE1").z0, -37.0086, 1e-4);
  EXPECT_NEAR(nist.at("WS DRILL HOLE1").z0, -37.1378, 1e-4);
}

// ---- The project's own feature programs ----

class FeatureGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(FeatureGolden, MatchesItsTraceFile) {
  const Generated r = run(cases() / (GetParam() + ".stp"));
  const std::string text = r.text(GetParam() + ".stp");
  const fs::path golden = cases() / (GetParam() + ".trace");
  if (const char* u = std::getenv("NCPOST_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    std::ofstream(golden, std::ios::binary) << text;
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden;
  EXPECT_EQ(text, test::read_file(golden)) << "differs from " << golden;
  // These are wrong on purpose; the others must interpret without an error.
  if (GetParam() != "wrong-tools" && GetParam() != "unsupported" && GetParam() != "hostile" &&
      GetParam() != "wrong-tools-general" && GetParam() != "hostile-general" &&
      GetParam() != "wrong-tools-shapes" && GetParam() != "hostile-shapes" &&
      GetParam() != "retract-refused" && GetParam() != "geometry-refused" &&
      GetParam() != "slot-section-refused" && GetParam() != "hole-bottoms-refused" &&
      GetParam() != "hole-milled-sphere-refused") {
    for (const auto& d : r.diagnostics)
      EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, GetParam());
    expect_verified(cases() / (GetParam() + ".stp"), r.calls);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, FeatureGolden,
    ::testing::Values(
        "face-unidirectional", "face-bidirectional-right", "pocket-rect-helix",
        "pocket-circle-ramp", "pocket-rect-zigzag", "pocket-toolaxis-fillet", "pocket-raster",
        "pocket-side-finish", "outside-profile", "holes-cycles", "holes-pointed-bottoms",
        "holes-strategy", "slots", "wrong-tools", "unsupported", "hostile", "pocket-polyline-l",
        "pocket-composite", "pocket-star", "pocket-ngon", "open-pocket", "outside-general",
        "pocket-radiused-bottom", "wrong-tools-general", "hostile-general", "slot-vee",
        "slot-partial-circular", "slot-ends-mixed", "slot-woodruff", "slot-circular", "step",
        "thread-drilling", "pocket-retract", "wrong-tools-shapes", "hostile-shapes",
        "retract-refused", "slot-placed-travel", "pocket-placed-profile", "hole-milled",
        "hole-bottoms-taper", "pocket-rough-corners", "geometry-refused", "geometry-combined",
        "slot-general-section", "slot-section-refused", "hole-bottoms-blind",
        "hole-bottoms-refused", "hole-milled-sphere", "hole-milled-sphere-refused"),
    [](const auto& param_info) {
      std::string n = param_info.param;
      for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

// ---- Numbers checked by hand from the cases' own data ----

TEST(FeaturesOwn, RectanglePocketRingsAndHelix) {
  // Pocket 60 × 40 at (50, 40), corner 6, tool 10, allowance 0.5: the outer ring is 10.5 - 5.5
  // = 24.5 × 14.5 half sizes around (50, 40) → x 25.5..74.5, y 25.5..54.5, corners 6 - 5.5 =
  // 0.5. Depth 12 - 0.3 in levels of at most 5: three of 3.9. Helix radius 3 at 5°: 2π·3·tan 5°
  // = 1.649 per turn, so 5.9 (from 2 above the top) takes four turns.
  const Generated r = run(cases() / "pocket-rect-helix.stp");
  const auto s = summarise(r.calls);
  ASSERT_TRUE(r.count("STEPNC-101") == 0 && r.count("STEPNC-102") == 0);
  const std::string trace = canon::trace(r.calls);
  EXPECT_NE(trace.find("STRAIGHT_FEED(74.5000, 40.0000, -3.9000)"), std::string::npos);
  EXPECT_NE(trace.find("STRAIGHT_FEED(26.0000, 54.5000, -3.9000)"), std::string::npos);
  EXPECT_NE(trace.find("-11.7000)"), std::string::npos);
  EXPECT_NE(trace.find("ARC_FEED(43.0000, 40.0000, 40.0000, 40.0000, 4, -3.9000)"),
            std::string::npos);
  // Climb with a clockwise spindle in a pocket: counter-clockwise rings (positive turns).
  EXPECT_NE(trace.find("ARC_FEED(74.0000, 54.5000, 74.0000, 54.0000, 1, -3.9000)"),
            std::string::npos)
      << trace;
}

TEST(FeaturesOwn, CircularPocketRings) {
  // Ø50, tool Ø12, radial step ≤ 5: room 25 - 6 = 19 → four rings 4.75 apart, full circles.
  const Generated r = run(cases() / "pocket-circle-ramp.stp");
  const std::string trace = canon::trace(r.calls);
  for (const char* ring : {"ARC_FEED(4.7500, 0.0000, 0.0000, 0.0000, -1, -4.0000)",
                           "ARC_FEED(19.0000, 0.0000, 0.0000, 0.0000, -1, -8.0000)"})
    EXPECT_NE(trace.find(ring), std::string::npos) << ring << "\n" << trace;
}

TEST(FeaturesOwn, HoleCycles) {
  const Generated r = run(cases() / "holes-cycles.stp");
  const std::string trace = canon::trace(r.calls);
  // Center drill to cutting_depth 3, retract plane 3 above the hole.
  EXPECT_NE(trace.find("DRILL_CYCLE(10.0000, 10.0000, 50.0000, 3.0000, -3.0000, 300.0000, 0.0000)"),
            std::string::npos)
      << trace;
  // Through drill Ø8: 15 + 4·tan 31° (2.4034) + 1; dwell 0.5.
  EXPECT_NE(
      trace.find("DRILL_CYCLE(10.0000, 10.0000, 50.0000, 3.0000, -18.4034, 600.0000, 0.5000)"),
      std::string::npos);
  // Equal pecks of 4 with 1 back-off (G73), flat bottom 20 deep: the point stops at the plane.
  EXPECT_NE(trace.find("PECK_DRILL_CYCLE(30.0000, 10.0000, 50.0000, 3.0000, -20.0000, 600.0000, "
                       "0.0000, 4.0000, 1.0000"),
            std::string::npos);
  // M10 × 1.5 at 500 rpm: feed 750.
  EXPECT_NE(trace.find("TAP_CYCLE(30.0000, 10.0000, 50.0000, 3.0000, -20.0000, 750.0000, 0.0000, "
                       "1.5000, 500.0000, RIGHT_HAND)"),
            std::string::npos);
  EXPECT_NE(trace.find("LEFT_HAND)"), std::string::npos);
  EXPECT_NE(trace.find("REAM_CYCLE(30.0000, 10.0000"), std::string::npos);
  EXPECT_NE(trace.find("BORE_CYCLE(30.0000, 10.0000, 50.0000, 3.0000, -20.0000, 300.0000, 0.0000, "
                       "SPINDLE_STOP)"),
            std::string::npos);
  EXPECT_EQ(r.count("STEPNC-016"), 1u);  // pointed drill in the flat bottom (reamed after)
  EXPECT_EQ(run(cases() / "holes-pointed-bottoms.stp").count("STEPNC-016"), 2u);
}

TEST(FeaturesOwn, UnsupportedIsNamedNotGuessed) {
  const Generated r = run(cases() / "unsupported.stp");
  EXPECT_EQ(r.count("STEPNC-101"), 8u) << r.text("unsupported");
  for (const auto& d : r.diagnostics) {
    if (d.code_id() == "STEPNC-101") {
      EXPECT_NE(d.message.find("MACHINING_WORKINGSTEP)"), std::string::npos);
    }
  }
  for (const auto& c : r.calls)
    EXPECT_FALSE(std::holds_alternative<canon::StraightFeed>(c) ||
                 std::holds_alternative<canon::ArcFeed>(c));
}

TEST(FeaturesOwn, HostileNumbersAreRefusedNotAllocated) {
  const auto start = std::chrono::steady_clock::now();
  const Generated r = run(cases() / "hostile.stp");
  EXPECT_EQ(r.count("STEPNC-103"), 3u) << r.text("hostile");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

// Every wrong tool for the new shapes is refused with one diagnostic that names the tool and
// the feature (STEPNC-102), or says that the combination is not implemented (STEPNC-101, the
// woodruff keyseat cutter), and nothing moves.
TEST(FeaturesOwn, WrongToolsForShapesNameToolAndFeature) {
  const Generated r = run(cases() / "wrong-tools-shapes.stp");
  EXPECT_EQ(r.count("STEPNC-102"), 11u) << r.text("wrong-tools-shapes");
  EXPECT_EQ(r.count("STEPNC-101"), 1u) << r.text("wrong-tools-shapes");
  for (const auto& d : r.diagnostics) {
    if (d.code_id() != "STEPNC-102") continue;
    EXPECT_NE(d.message.find("(MILLING_CUTTING_TOOL)"), std::string::npos) << d.message;
    const bool names_feature = d.message.find("(SLOT)") != std::string::npos ||
                               d.message.find("(STEP)") != std::string::npos ||
                               d.message.find("(DEFINED_THREAD)") != std::string::npos;
    EXPECT_TRUE(names_feature) << d.message;
  }
  for (const auto& c : r.calls)
    EXPECT_FALSE(std::holds_alternative<canon::StraightFeed>(c) ||
                 std::holds_alternative<canon::ArcFeed>(c));
}

// Zero, negative and huge sizes, angles of 180 degrees and more, a tool of radius 0: each a
// clean STEPNC-101/103 for its workingstep, quickly, with no motion.
TEST(FeaturesOwn, HostileShapesAreRefusedCleanly) {
  const auto start = std::chrono::steady_clock::now();
  const Generated r = run(cases() / "hostile-shapes.stp");
  EXPECT_EQ(r.count("STEPNC-103"), 14u) << r.text("hostile-shapes");
  EXPECT_EQ(r.count("STEPNC-101"), 1u) << r.text("hostile-shapes");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  for (const auto& c : r.calls)
    EXPECT_FALSE(std::holds_alternative<canon::StraightFeed>(c) ||
                 std::holds_alternative<canon::ArcFeed>(c));
}

TEST(FeaturesOwn, OutsideProfileRing) {
  // Box 60 × 40 at the origin, Ø12 tool, allowance 0.5: the ring is 6.5 outside, x ±36.5, y
  // ±26.5, corners rounded by 6.5 about the box's corners; climb with a clockwise spindle goes
  // clockwise round the part; lead-in 6 + 2 beyond the ring, at x 44.5.
  const Generated r = run(cases() / "outside-profile.stp");
  const std::string trace = canon::trace(r.calls);
  EXPECT_NE(trace.find("STRAIGHT_FEED(44.5000, 0.0000, -4.0000)"), std::string::npos) << trace;
  EXPECT_NE(trace.find("ARC_FEED(30.0000, -26.5000, 30.0000, -20.0000, -1, -4.0000)"),
            std::string::npos);
  // Finish: no allowance, ring 6 outside: the arc ends at (30, -26).
  EXPECT_NE(trace.find("ARC_FEED(30.0000, -26.0000, 30.0000, -20.0000, -1, -8.0000)"),
            std::string::npos);
}

TEST(FeaturesOwn, Slots) {
  // Radiused slot 40 long, 16 wide, 6 deep in levels of 3, tool Ø10: a stadium 56 × 16 about
  // (20, 0). At inset 5 the room is 3, one step: the centre line x 0..40, then one ring of half
  // sizes 23 × 3 with end radius 3 (x -3..43), counter-clockwise.
  const Generated r = run(cases() / "slots.stp");
  const std::string trace = canon::trace(r.calls);
  EXPECT_NE(trace.find("STRAIGHT_FEED(40.0000, 0.0000, -3.0000)"), std::string::npos) << trace;
  EXPECT_NE(trace.find("ARC_FEED(40.0000, 3.0000, 40.0000, 0.0000, 1, -3.0000)"),
            std::string::npos);
  // Ball Ø8 in the rounded-U slot of width 8 along (0.6, 0.8): one centre line per level,
  // from (0, 150) to (18, 174).
  EXPECT_NE(trace.find("STRAIGHT_FEED(18.0000, 174.0000, -4.0000)"), std::string::npos);
  for (const auto& d : r.diagnostics) EXPECT_NE(d.severity, diag::Severity::Error) << d.message;
}

// pocket-polyline-l.stp with its L outline (#120) replaced by `points` (new instances from
// #1000000 on), each "x,y". `interpret_time` gets the time of the interpretation alone.
Generated run_with_outline(const std::vector<std::string>& points,
                           std::chrono::steady_clock::duration* interpret_time = nullptr) {
  std::string text = test::read_file(cases() / "pocket-polyline-l.stp");
  std::string list;
  std::string instances;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const std::string id = "#" + std::to_string(1000000 + k);
    instances += id + "=CARTESIAN_POINT('',(" + points[k] + ",0.));\n";
    list += id + ",";
  }
  list += "#1000000";
  const std::size_t at = text.find("#120=POLYLINE('',(");
  const std::size_t end = text.find(";", at);
  text.replace(at, end - at, "#120=POLYLINE('',(" + list + "))");
  text.insert(text.find("ENDSEC;", text.find("DATA;")), instances);
  static const express::SchemaRegistry registry;
  pipeline::LoadedModel loaded = pipeline::load(text, registry);
  Generated out;
  out.diagnostics = loaded.diagnostics;
  if (!loaded.ok()) return out;
  const AttributeReader attributes(loaded.model, *loaded.schema);
  canon::ProgramBuffer buffer;
  const auto start = std::chrono::steady_clock::now();
  auto result = interpret(loaded.model, attributes, buffer, {});
  if (interpret_time != nullptr) *interpret_time = std::chrono::steady_clock::now() - start;
  out.calls = std::move(buffer).take();
  out.diagnostics.insert(out.diagnostics.end(), result.diagnostics.begin(),
                         result.diagnostics.end());
  return out;
}

std::size_t cutting_moves(const Generated& g) {
  return static_cast<std::size_t>(std::count_if(g.calls.begin(), g.calls.end(), [](const auto& c) {
    return std::holds_alternative<canon::StraightFeed>(c) ||
           std::holds_alternative<canon::ArcFeed>(c);
  }));
}

TEST(FeaturesOwn, AMillionVertexOutlineIsRefusedQuickly) {
  // A circle of a million vertices: more than FeatureOptions::max_profile_elements (100,000),
  // refused before its points are read. (Under AddressSanitizer 200,000, still over the limit:
  // reading a million instances there takes minutes, and the refusal is the same.)
#if defined(__SANITIZE_ADDRESS__)
  constexpr int kVertices = 200000;
#else
  constexpr int kVertices = 1000000;
#endif
  std::vector<std::string> points;
  for (int k = 0; k < kVertices; ++k) {
    const double t = 2 * std::numbers::pi * k / kVertices;
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6f,%.6f", 30 + 25 * std::cos(t), 25 + 25 * std::sin(t));
    points.emplace_back(buffer);
  }
  std::chrono::steady_clock::duration took{};
  const Generated r = run_with_outline(points, &took);
  EXPECT_LT(took, std::chrono::seconds(5));
  EXPECT_EQ(r.count("STEPNC-103"), 3u) << r.text("million");  // one per workingstep
  EXPECT_EQ(cutting_moves(r), 0u);
  bool named = false;
  for (const auto& d : r.diagnostics)
    named = named ||
            d.message.find("more than FeatureOptions::max_profile_elements") != std::string::npos;
  EXPECT_TRUE(named);
}

TEST(FeaturesOwn, NonFiniteCoordinatesAreACleanError) {
  // 1E400 is no double: the reader or the generator refuses it, and nothing is machined.
  const Generated r = run_with_outline({"0.,0.", "60.,0.", "1.E400,25.", "0.,50."});
  bool error = false;
  for (const auto& d : r.diagnostics) error = error || d.severity == diag::Severity::Error;
  EXPECT_TRUE(error) << r.text("inf");
  EXPECT_EQ(cutting_moves(r), 0u);
}

TEST(FeaturesOwn, GeneralOutlinesKeepTheirDistances) {
  // L pocket at (10, 10), Ø10 tool, allowance 0.5 then 0 (orthogonal_radius 6): no feed end
  // below the top comes nearer the L's sides than the radius, less 5 µm (5 ×
  // FeatureOptions::chord_tolerance), and all are inside the L.
  const Generated r = run(cases() / "pocket-polyline-l.stp");
  const double corners[6][2] = {{0, 0}, {60, 0}, {60, 25}, {25, 25}, {25, 50}, {0, 50}};
  std::size_t checked = 0;
  for (const auto& c : r.calls) {
    const auto* f = std::get_if<canon::StraightFeed>(&c);
    if (f == nullptr || f->to.z > -1e-9) continue;
    const double x = f->to.x - 10;
    const double y = f->to.y - 10;
    EXPECT_TRUE(x > 0 && y > 0 && (x < 25 || y < 25) && x < 60 && y < 50) << x << " " << y;
    double d = 1e300;
    for (int k = 0; k < 6; ++k) {
      const double ax = corners[k][0], ay = corners[k][1];
      const double bx = corners[(k + 1) % 6][0], by = corners[(k + 1) % 6][1];
      const double dx = bx - ax, dy = by - ay;
      const double t = std::clamp(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      d = std::min(d, std::hypot(ax + t * dx - x, ay + t * dy - y));
    }
    EXPECT_GT(d, 5 - 0.005) << x << " " << y;
    ++checked;
  }
  EXPECT_GT(checked, 50u);
}

TEST(FeaturesOwn, WrongToolsNameBothInstances) {
  const Generated r = run(cases() / "wrong-tools.stp");
  std::vector<std::string> unfit;
  for (const auto& d : r.diagnostics)
    if (d.code_id() == "STEPNC-102") unfit.push_back(d.message);
  ASSERT_EQ(unfit.size(), 10u) << r.text("wrong-tools");
  EXPECT_EQ(r.count("STEPNC-103"), 0u);
  // Every message names a tool (or strategy/approach) and the feature.
  for (const auto& m : unfit) {
    EXPECT_NE(m.find("#"), std::string::npos);
    EXPECT_NE(m.find("_POCKET)"), m.find("ROUND_HOLE)")) << m;
  }
  // The roughing pass whose tool (R10 + 0.5) is larger than the corner radius 8 is generated
  // with a warning (issue 17): (10.5 - 8)(√2 - 1) = 1.0355 more stock in the corners.
  ASSERT_EQ(r.count("STEPNC-120"), 1u);
  for (const auto& d : r.diagnostics) {
    if (d.code_id() != "STEPNC-120") continue;
    EXPECT_EQ(d.severity, diag::Severity::Warning);
    EXPECT_NE(d.message.find("radius 10 + allowance 0.5 of"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("> corner radius 8 of"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("leaves up to 1.0355 mm more stock"), std::string::npos) << d.message;
  }
  // Nothing is generated for the refused workingsteps: no motion between their markers.
  bool inside = false;
  std::size_t motions = 0;
  for (const auto& c : r.calls) {
    if (const auto* b = std::get_if<canon::Begin>(&c))
      inside = b->scope == canon::Scope::Workingstep && b->entity.name != "CORNER TOO SMALL";
    if (std::holds_alternative<canon::End>(c)) inside = false;
    if (inside && canon::is_motion(c) && !std::holds_alternative<canon::StraightTraverse>(c))
      ++motions;
  }
  EXPECT_EQ(motions, 0u);
}

// ---- Geometry other systems write (issue 17, parts 4 and 5) ----

// The end points of the cutting moves (feeds, arcs; cycles at their bottom) of each workingstep,
// by its name.
std::map<std::string, std::vector<canon::Point>> cuts_by_workingstep(
    const std::vector<canon::Call>& calls) {
  std::map<std::string, std::vector<canon::Point>> out;
  std::vector<canon::Point>* current = nullptr;
  for (const canon::Call& c : calls) {
    if (const auto* b = std::get_if<canon::Begin>(&c); b && b->scope == canon::Scope::Workingstep)
      current = &out[b->entity.name];
    else if (const auto* f = std::get_if<canon::StraightFeed>(&c); f && current)
      current->push_back({f->to.x, f->to.y, f->to.z});
    else if (const auto* a = std::get_if<canon::ArcFeed>(&c); a && current)
      current->push_back({a->end.x, a->end.y, a->end.z});
    else if (const auto* cy = std::get_if<canon::Cycle>(&c); cy && current)
      current->push_back({cy->x, cy->y, cy->bottom_z});
  }
  return out;
}

// The U slot's course of travel starts at (20, 10) of its own placement, turned 30 degrees, and
// runs 40 along that placement's x: with width 16 and an R5 tool the tool centres stay within 3
// of the centre line and 3 past its ends (radiused ends), and reach both.
TEST(FeaturesOwn, SlotAlongAPlacedCourseOfTravel) {
  const Generated r = run(cases() / "slot-placed-travel.stp");
  ASSERT_EQ(r.count("STEPNC-101") + r.count("STEPNC-102") + r.count("STEPNC-103"), 0u);
  const auto cuts = cuts_by_workingstep(r.calls);
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  double s_min = 1e9, s_max = -1e9, t_max = 0;
  for (const canon::Point& p : cuts.at("U SLOT")) {
    const double along = (p.x - 20) * c + (p.y - 10) * s;
    const double across = -(p.x - 20) * s + (p.y - 10) * c;
    s_min = std::min(s_min, along), s_max = std::max(s_max, along);
    t_max = std::max(t_max, std::abs(across));
  }
  EXPECT_NEAR(s_min, -3, 1e-3);
  EXPECT_NEAR(s_max, 43, 1e-3);
  EXPECT_NEAR(t_max, 3, 1e-3);
  // The vee slot's path is placed at (0, 60) turned 90 degrees: its centre line is x = 0,
  // y from 60 to 100.
  for (const canon::Point& p : cuts.at("VEE SLOT")) {
    EXPECT_NEAR(p.x, 0, 1e-9);
    EXPECT_GE(p.y, 60 - 1e-9);
    EXPECT_LE(p.y, 100 + 1e-9);
  }
}

// Milled holes: Ø30 with an R5 tool is finished at 15 - 5 = 10 from the axis (circles about it,
// never beyond); the through hole Ø24 goes 10 + 1 (through_clearance) deep.
TEST(FeaturesOwn, MilledHolesAreCirclesAboutTheAxis) {
  const Generated r = run(cases() / "hole-milled.stp");
  ASSERT_EQ(r.count("STEPNC-101") + r.count("STEPNC-102") + r.count("STEPNC-103"), 0u);
  std::size_t arcs = 0;
  for (const canon::Call& c : r.calls) arcs += std::holds_alternative<canon::ArcFeed>(c) ? 1 : 0;
  EXPECT_GT(arcs, 10u);
  const auto cuts = cuts_by_workingstep(r.calls);
  double outer = 0, deepest = 0;
  for (const canon::Point& p : cuts.at("HOLE FINISH")) {
    outer = std::max(outer, std::hypot(p.x, p.y));
    deepest = std::min(deepest, p.z);
  }
  EXPECT_NEAR(outer, 10, 1e-3);
  EXPECT_NEAR(deepest, -12, 1e-9);
  double through = 0;
  for (const canon::Point& p : cuts.at("THROUGH HOLE")) through = std::min(through, p.z);
  EXPECT_NEAR(through, -11, 1e-9);
}

// A cutting depth of 14.8 into the conical bottom (118 degrees, Ø10, depth 12: the cone's point
// is 5 / tan 59° = 3.0043 below) is accepted; 15.5 is refused with the limit 15.0043.
TEST(FeaturesOwn, CuttingDepthIntoAConeAndTapers) {
  const Generated ok = run(cases() / "hole-bottoms-taper.stp");
  for (const auto& d : ok.diagnostics)
    EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, "hole-bottoms-taper");
  EXPECT_EQ(ok.count("STEPNC-016"), 2u);  // one note per taper
  const auto cuts = cuts_by_workingstep(ok.calls);
  ASSERT_EQ(cuts.at("DRILL INTO CONE").size(), 1u);
  EXPECT_NEAR(cuts.at("DRILL INTO CONE")[0].z, -14.8, 1e-9);
  const Generated refused = run(cases() / "geometry-refused.stp");
  EXPECT_EQ(refused.count("STEPNC-101"), 3u);  // undercut, tilted path, region
  EXPECT_EQ(refused.count("STEPNC-102"), 1u);
  EXPECT_EQ(refused.count("STEPNC-103"), 1u);
  const std::string text = refused.text("geometry-refused");
  for (const char* named :
       {"(DIAMETER_TAPER) (diameter 30 at the top, 36 at the depth), which widens downwards",
        "at most 15.0043", "a drill makes a cylinder no wider than 8",
        "(LINEAR_PATH) placed out of the slot's plane", "(REGION_SURFACE_LIST) (#",
        "(BEZIER_SURFACE)), free-form region milling"})
    EXPECT_NE(text.find(named), std::string::npos) << named;
}

// A case that must interpret without an error.
Generated run_without_errors(const std::string& name) {
  Generated r = run(cases() / (name + ".stp"));
  for (const auto& d : r.diagnostics)
    EXPECT_NE(d.severity, diag::Severity::Error) << diag::format(d, name);
  return r;
}

// Each of `named` appears in the diagnostics' text.
void expect_named(const std::string& text, std::initializer_list<const char*> named) {
  for (const char* n : named) EXPECT_NE(text.find(n), std::string::npos) << n;
}

// General slot sections: the stepped polyline (floor 5 deep from -4 to 4, shoulders 2 deep
// from ±4 to ±9) cut by a flat end mill of radius 3 in levels of 2.5: its passes reach both
// floors exactly and never the walls; the B-spline groove's lowest pass is on its depth plane
// (its lowest point, 5.875 below the top) less the chord of the grid. Each refusal names its
// instance and why.
TEST(FeaturesOwn, GeneralSlotSections) {
  const Generated r = run_without_errors("slot-general-section");
  const auto cuts = cuts_by_workingstep(r.calls);
  double deepest = 0;
  for (const auto& p : cuts.at("STEPPED SLOT")) {
    deepest = std::min(deepest, p.z);
    // The slot runs along +x from (40, 60): across it is y - 60.
    const double across = std::abs(p.y - 60);
    if (p.z < -2 - 1e-9) {
      EXPECT_LE(across, 4 - 3 + 1e-6) << p.x << " " << p.y << " " << p.z;
    }
    EXPECT_LE(across, 9 - 3 + 1e-6);
  }
  EXPECT_NEAR(deepest, -5, 1e-9);
  double groove = 0;
  for (const auto& p : cuts.at("SPLINE GROOVE")) groove = std::min(groove, p.z);
  EXPECT_NEAR(groove, -5.875, 0.005);
  EXPECT_GE(groove, -5.875 - 1e-9);
  const Generated refused = run(cases() / "slot-section-refused.stp");
  EXPECT_EQ(refused.count("STEPNC-101"), 3u);  // dovetail, lopsided radiused, along an arc
  EXPECT_EQ(refused.count("STEPNC-102"), 1u);  // ball too large
  EXPECT_EQ(refused.count("STEPNC-103"), 2u);  // short walls, negative allowance
  EXPECT_EQ(refused.count("STEPNC-011"), 1u);  // a Bezier curve of 5 points and degree 3
  expect_named(refused.text("slot-section-refused"),
               {"(POLYLINE) turns back across the slot at x -5, y 0 (an undercut",
                "(BEZIER_CURVE) is not symmetric about the course of travel",
                "(radius 8, corner radius 8) cannot reach the section #", "(QUASI_UNIFORM_CURVE)",
                "ends 1.25 below the top at x -8", "leaves a negative allowance (-0.5 on the sides",
                "5 control points do not make a curve of degree 3",
                "(PARTIAL_CIRCULAR_PATH) (a general section is generated along a linear path or a "
                "complete circle)"});
}

// Drilling depths against blind bottoms: an 8 mm drill's point (118 degrees) reaches the lowest
// point of a spherical bottom of radius 5 and of a flat-with-radius floor (corner 1) in Ø10
// holes: its cone stays clear of the sphere and of the fillet. Beyond, each is refused with the
// limit: 12 below a flat floor, 12 - 5 = 7 for a Ø10 reamer, whose rim meets the sphere 5 above
// its tip, 12 for the drill over the fillet.
TEST(FeaturesOwn, CuttingDepthsAgainstBlindBottoms) {
  run_without_errors("hole-bottoms-blind");
  const Generated refused = run(cases() / "hole-bottoms-refused.stp");
  EXPECT_EQ(refused.count("STEPNC-103"), 3u);
  expect_named(refused.text("hole-bottoms-refused"),
               {"cutting_depth 12.5 is not within", "(FLAT_HOLE_BOTTOM)", "at most 12)",
                "cutting_depth 12 is not within", "(SPHERICAL_HOLE_BOTTOM) of radius 5",
                "meets it 5 above its tip", "at most 7)", "cutting_depth 12.3 is not within",
                "(FLAT_WITH_RADIUS_HOLE_BOTTOM) with the corner radius 1"});
}

// A Ø30 hole whose bottom is a sphere of radius 20 (its lowest point at the depth 16, its centre
// 4 above the top): every tool position of the ball of radius 5 keeps the ball's centre within
// 20 - allowance - 5 of the sphere's centre and within 15 - allowance - 5 of the axis; the finish
// reaches the bottom at the axis; the half ball of radius 12 is finished by a bull nose (flat
// 0.1: 0.0006 left at its centre, within the tolerance). The refusals name the tool and sizes.
TEST(FeaturesOwn, MilledSphericalBottoms) {
  const Generated r = run(cases() / "hole-milled-sphere.stp");
  ASSERT_EQ(r.count("STEPNC-101") + r.count("STEPNC-102") + r.count("STEPNC-103"), 0u);
  const auto cuts = cuts_by_workingstep(r.calls);
  for (const auto& [ws, allowance] :
       std::vector<std::pair<std::string, double>>{{"SPHERE ROUGH", 0.3}, {"SPHERE FINISH", 0}}) {
    double deepest = 0, worst = -1;
    for (const canon::Point& p : cuts.at(ws)) {
      deepest = std::min(deepest, p.z);
      const double rho = std::hypot(p.x, p.y);
      EXPECT_LE(rho, 15 - allowance - 5 + 1e-6) << ws;
      const double centre = p.z + 5;  // the ball's centre
      worst = std::max(worst, std::hypot(rho, centre - 4) - (20 - allowance - 5));
    }
    EXPECT_LE(worst, 1e-6) << ws;
    EXPECT_NEAR(deepest, -16 + allowance, 1e-6) << ws;
  }
  double half = 0;
  for (const canon::Point& p : cuts.at("HALF BALL")) half = std::min(half, p.z);
  EXPECT_NEAR(half, -12, 0.005);
  EXPECT_GT(half, -12);
  const Generated refused = run(cases() / "hole-milled-sphere-refused.stp");
  EXPECT_EQ(refused.count("STEPNC-102"), 3u);
  EXPECT_EQ(refused.count("STEPNC-103"), 1u);
  EXPECT_EQ(refused.count("STEPNC-101"), 1u);  // side milling: the wall alone
  expect_named(refused.text("hole-milled-sphere-refused"),
               {"is a flat end mill, which cannot form", "(SPHERICAL_HOLE_BOTTOM) of radius 15",
                "radius 15 is larger than the sphere's 14.5 (its radius 15 less allowance_bottom "
                "0.5)",
                "(radius 5, corner radius 1) cannot form", "its flat leaves 0.5836 at the centre",
                "the sphere needs a radius of at least the hole's, 15"});
}

}  // namespace
}  // namespace ncpost::stepnc
