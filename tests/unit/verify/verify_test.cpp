// The path verifier (engine/verify): its geometry, each check made to fail by perturbing a good
// program's canonical calls, drilling cycles against a ROUND_HOLE, and NIST's ex1E.

#include "ncpost/verify/verify.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../../../engine/verify/src/region.hpp"
#include "corpus.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/pipeline/load.hpp"

namespace ncpost::verify {
namespace {

namespace fs = std::filesystem;
using detail::Grid;
using detail::Region;
using detail::Vec2;

// ---- geometry ----------------------------------------------------------------------------

TEST(VerifyRegion, RectangleSignedDistance) {
  const Region r = Region::rectangle({50, 40}, {1, 0}, 40, 30, 0);
  EXPECT_NEAR(r.signed_distance({50, 40}), 15, 1e-9);
  EXPECT_NEAR(r.signed_distance({69, 40}), 1, 1e-9);
  EXPECT_NEAR(r.signed_distance({72, 40}), -2, 1e-9);
  EXPECT_NEAR(r.signed_distance({73, 59}), -5, 1e-9);  // 3-4-5 off the corner (70, 55)
}

TEST(VerifyRegion, RoundedCornersAndRotation) {
  // Corner radius 6: the corner point lies sqrt(2)*6 - 6 outside the arc.
  const Region r = Region::rectangle({0, 0}, {1, 0}, 40, 30, 6);
  EXPECT_NEAR(r.signed_distance({20, 15}), -(std::sqrt(2.0) * 6 - 6), 1e-9);
  EXPECT_NEAR(r.signed_distance({14, 9}), 6, 1e-9);
  // Rotated by 90 degrees: length runs along y.
  const Region q = Region::rectangle({0, 0}, {0, 1}, 40, 30, 0);
  EXPECT_NEAR(q.signed_distance({0, 19}), 1, 1e-9);
  EXPECT_NEAR(q.signed_distance({14, 0}), 1, 1e-9);
}

TEST(VerifyRegion, Circle) {
  const Region c = Region::circle({20, 20}, 5);
  EXPECT_NEAR(c.signed_distance({20, 20}), 5, 1e-9);
  EXPECT_NEAR(c.signed_distance({28, 20}), -3, 1e-9);
}

TEST(VerifyRegion, DistanceTransformMatchesBruteForce) {
  Grid g;
  g.step = 1;
  g.nx = 23;
  g.ny = 17;
  std::vector<unsigned char> seed(g.cells(), 0);
  const std::pair<int, int> seeds[] = {{3, 4}, {20, 2}, {11, 15}};
  for (auto [i, j] : seeds) seed[g.index(i, j)] = 1;
  const auto d = detail::distance_to_seeds(g, seed);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      double best = 1e300;
      for (auto [si, sj] : seeds) best = std::min(best, std::hypot(i - si, j - sj));
      EXPECT_NEAR(d[g.index(i, j)], best, 1e-5) << i << "," << j;
    }
}

// ---- programs ----------------------------------------------------------------------------

const express::SchemaRegistry& registry() {
  static const express::SchemaRegistry r;
  return r;
}

struct Program {
  pipeline::LoadedModel loaded;
  std::unique_ptr<stepnc::AttributeReader> attributes;
  std::vector<canon::Call> calls;
};

Program load(const fs::path& file) {
  Program p;
  p.loaded = pipeline::load(test::read_file(file), registry());
  EXPECT_TRUE(p.loaded.ok()) << file;
  p.attributes = std::make_unique<stepnc::AttributeReader>(p.loaded.model, *p.loaded.schema);
  canon::ProgramBuffer buffer;
  const auto r = stepnc::interpret(p.loaded.model, *p.attributes, buffer);
  EXPECT_TRUE(r.ok()) << file;
  p.calls = buffer.calls();
  return p;
}

fs::path cases() {
  return test::source_dir() / "tests/golden/verify/cases";
}

std::vector<const Finding*> findings(const VerifyResult& r, diag::Code code) {
  std::vector<const Finding*> out;
  for (const auto& f : r.findings)
    if (f.diagnostic.code == code) out.push_back(&f);
  return out;
}

std::string dump(const VerifyResult& r) {
  return format_text(r, "case") + format_json(r, "case");
}

// The calls of one workingstep, by name: [first, last) indices into the program.
std::pair<std::size_t, std::size_t> workingstep(const std::vector<canon::Call>& calls,
                                                const std::string& name) {
  std::size_t first = 0;
  for (std::size_t k = 0; k < calls.size(); ++k) {
    if (const auto* b = std::get_if<canon::Begin>(&calls[k]);
        b && b->scope == canon::Scope::Workingstep && b->entity.name == name)
      first = k;
    if (const auto* e = std::get_if<canon::End>(&calls[k]);
        e && e->scope == canon::Scope::Workingstep && e->entity.name == name)
      return {first, k};
  }
  ADD_FAILURE() << "no workingstep " << name;
  return {0, 0};
}

// The stock as a viewer draws it: the BLOCK's corners in machine coordinates, through the
// setup's origin (here moved by (10, 20, 5) in a copy of the case).
TEST(Verify, StockBoxesAreTheBlockInMachineCoordinates) {
  const Program p = load(cases() / "good.stp");
  const auto boxes = stock_boxes(p.loaded.model, *p.attributes);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].workpiece, 900u);
  EXPECT_EQ(boxes[0].name, "PART");
  EXPECT_EQ(boxes[0].setup, 8u);
  ASSERT_EQ(boxes[0].corners.size(), 8u);
  // BLOCK('STOCK', corner at (0, 0, -30), 100 x 80 x 32): corner k adds x, y, z by its bits.
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_DOUBLE_EQ(boxes[0].corners[k].x, (k & 1) ? 100 : 0) << k;
    EXPECT_DOUBLE_EQ(boxes[0].corners[k].y, (k & 2) ? 80 : 0) << k;
    EXPECT_DOUBLE_EQ(boxes[0].corners[k].z, (k & 4) ? 2 : -30) << k;
  }

  std::string text = test::read_file(cases() / "good.stp");
  const std::string setup = "#8=SETUP('SETUP1',#923,";
  ASSERT_NE(text.find(setup), std::string::npos);
  text.replace(text.find(setup), setup.size(), "#8=SETUP('SETUP1',#999,");
  text.replace(text.find("#900="), 0,
               "#998=CARTESIAN_POINT('',(10.,20.,5.));\n#999=AXIS2_PLACEMENT_3D('',#998,$,$);\n");
  const auto moved = pipeline::load(text, registry());
  ASSERT_TRUE(moved.ok());
  const stepnc::AttributeReader attributes(moved.model, *moved.schema);
  const auto shifted = stock_boxes(moved.model, attributes);
  ASSERT_EQ(shifted.size(), 1u);
  for (std::size_t k = 0; k < 8; ++k) {
    EXPECT_DOUBLE_EQ(shifted[0].corners[k].x, boxes[0].corners[k].x + 10) << k;
    EXPECT_DOUBLE_EQ(shifted[0].corners[k].y, boxes[0].corners[k].y + 20) << k;
    EXPECT_DOUBLE_EQ(shifted[0].corners[k].z, boxes[0].corners[k].z + 5) << k;
  }
}

TEST(Verify, GoodProgramPasses) {
  const Program p = load(cases() / "good.stp");
  const VerifyResult r = verify_calls(p.loaded.model, *p.attributes, p.calls);
  EXPECT_TRUE(r.ok()) << dump(r);
  ASSERT_EQ(r.features.size(), 3u);
  for (const auto& f : r.features) {
    EXPECT_TRUE(f.checked) << f.name;
    EXPECT_TRUE(f.depth_reached) << f.name;
    EXPECT_TRUE(f.coverage_checked) << f.name;
    EXPECT_EQ(f.uncovered_fraction, 0) << f.name;
    EXPECT_GT(f.reachable_area, 0) << f.name;
  }
  // The pocket: 40 x 30 with 6 mm corners, all reachable by an r 5 tool, within a few cells.
  const double area = 40 * 30 - (4 - 3.14159265) * 36;
  EXPECT_NEAR(r.features[1].reachable_area, area, 0.03 * area);
  EXPECT_NEAR(r.features[1].target_z, -10, 1e-9);
}

// Moving one finishing feed of the pocket 0.5 mm towards +x makes it gouge the wall by 0.5 mm
// there, and nowhere else.
TEST(Verify, ShiftedFeedGougesTheWall) {
  Program p = load(cases() / "good.stp");
  const auto [first, last] = workingstep(p.calls, "WS POCKET");
  bool shifted = false;
  for (std::size_t k = last; k > first && !shifted; --k) {
    auto* f = std::get_if<canon::StraightFeed>(&p.calls[k]);
    // (65, 40 + 9) → (65.5, 49): the +x side of the outer ring, 5 mm from the wall at x 70.
    if (f && std::abs(f->to.x - 65) < 1e-9 && std::abs(f->to.y - 49) < 1e-9 &&
        std::abs(f->to.z + 10) < 1e-9) {
      f->to.x += 0.5;
      shifted = true;
    }
  }
  ASSERT_TRUE(shifted);
  const VerifyResult r = verify_calls(p.loaded.model, *p.attributes, p.calls);
  EXPECT_FALSE(r.ok());
  const auto g = findings(r, diag::Code::VerifyGouge);
  ASSERT_EQ(g.size(), 1u) << dump(r);
  ASSERT_TRUE(g[0]->position);
  EXPECT_NEAR(g[0]->position->x, 65.5, 1e-6);
  EXPECT_NEAR(g[0]->position->y, 49, 1e-6);
  EXPECT_NE(g[0]->diagnostic.message.find("by 0.5000 mm"), std::string::npos) << dump(r);
  EXPECT_EQ(g[0]->workingstep_name, "WS POCKET");
}

// Dropping the two inner rings leaves the middle of the floor unswept.
TEST(Verify, MissingRingsLeaveFloorUncovered) {
  Program p = load(cases() / "good.stp");
  const auto [first, last] = workingstep(p.calls, "WS POCKET");
  // The inner rings are the feeds at z -10 with |x - 50| <= 11 after the ramp; lift them out
  // of the floor (z 0) instead of deleting them, so the path stays connected.
  std::size_t lifted = 0;
  for (std::size_t k = first; k < last; ++k) {
    auto* f = std::get_if<canon::StraightFeed>(&p.calls[k]);
    if (f && std::abs(f->to.z + 10) < 1e-9 && std::abs(f->to.x - 50) <= 11 + 1e-9 &&
        std::abs(f->to.y - 40) <= 6 + 1e-9) {
      f->to.z = -5;
      ++lifted;
    }
  }
  ASSERT_GT(lifted, 8u);
  const VerifyResult r = verify_calls(p.loaded.model, *p.attributes, p.calls);
  const auto c = findings(r, diag::Code::VerifyCoverage);
  ASSERT_EQ(c.size(), 1u) << dump(r);
  EXPECT_GT(r.features[1].uncovered_fraction, 0.05);
  ASSERT_TRUE(c[0]->position);
  EXPECT_NEAR(c[0]->position->x, 50, 6);
  EXPECT_NEAR(c[0]->position->y, 40, 6);
}

// A drilling cycle in the hole: right, off the axis, too shallow.
TEST(Verify, DrillingCycles) {
  Program p = load(cases() / "good.stp");
  const auto [first, last] = workingstep(p.calls, "WS DRILL");
  // Replace the drill's feeds and rapids by one DRILL_CYCLE.
  std::vector<canon::Call> calls(p.calls.begin(), p.calls.begin() + static_cast<long>(first) + 1);
  std::size_t k = first + 1;
  for (; k < last; ++k)
    if (canon::is_motion(p.calls[k]))
      break;
    else
      calls.push_back(p.calls[k]);
  const std::size_t tail = calls.size();
  const auto run = [&](double x, double bottom) {
    std::vector<canon::Call> c(calls.begin(), calls.begin() + static_cast<long>(tail));
    canon::Cycle cycle;
    cycle.kind = canon::CycleKind::Drill;
    cycle.x = x;
    cycle.y = 20;
    cycle.safe_z = 20;
    cycle.r_z = 2;
    cycle.bottom_z = bottom;
    cycle.feed = 300;
    c.push_back(cycle);
    c.insert(c.end(), p.calls.begin() + static_cast<long>(last), p.calls.end());
    return verify_calls(p.loaded.model, *p.attributes, c);
  };
  const VerifyResult good = run(20, -15);
  EXPECT_TRUE(good.ok()) << dump(good);
  const VerifyResult off = run(21, -15);
  ASSERT_EQ(findings(off, diag::Code::VerifyCycle).size(), 1u) << dump(off);
  EXPECT_NE(findings(off, diag::Code::VerifyCycle)[0]->diagnostic.message.find("1.0000 mm off"),
            std::string::npos);
  const VerifyResult shallow = run(20, -12);
  EXPECT_EQ(findings(shallow, diag::Code::VerifyCycle).size(), 1u) << dump(shallow);
  EXPECT_EQ(findings(shallow, diag::Code::VerifyDepth).size(), 1u) << dump(shallow);
}

// The tolerance is what decides: a 0.005 mm gouge passes at 0.01 and fails at 0.001.
TEST(Verify, ToleranceDecides) {
  Program p = load(cases() / "good.stp");
  const auto [first, last] = workingstep(p.calls, "WS POCKET");
  for (std::size_t k = first; k < last; ++k)
    if (auto* f = std::get_if<canon::StraightFeed>(&p.calls[k]);
        f && std::abs(f->to.x - 65) < 1e-9 && std::abs(f->to.y - 49) < 1e-9)
      f->to.x += 0.005;
  VerifyOptions loose;
  loose.tolerance = 0.01;
  EXPECT_TRUE(
      findings(verify_calls(p.loaded.model, *p.attributes, p.calls, loose), diag::Code::VerifyGouge)
          .empty());
  VerifyOptions tight;
  tight.tolerance = 0.001;
  EXPECT_EQ(
      findings(verify_calls(p.loaded.model, *p.attributes, p.calls, tight), diag::Code::VerifyGouge)
          .size(),
      1u);
}

// NIST's explicit toolpaths for ISO 14649-11 example 1 (docs/verify.md discusses them).
TEST(VerifyCorpus, NistExample1E) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  const Program p = load(corpus / "p21/nist_toolkit_ex1E.stp");
  const VerifyResult r = verify_calls(p.loaded.model, *p.attributes, p.calls);
  EXPECT_TRUE(r.ok()) << dump(r);
  ASSERT_EQ(r.features.size(), 3u) << dump(r);
  for (const auto& f : r.features) {
    EXPECT_TRUE(f.checked) << f.name;
    EXPECT_TRUE(f.depth_reached) << f.name;
    EXPECT_EQ(f.uncovered_fraction, 0) << f.name;
  }
  // The pocket's roughing levels move between levels at rapid inside the cleared pocket: below
  // the security plane over the part, but in air.
  EXPECT_GT(r.rapids_below_secplane_in_air, 0u);
}

// Issue 5's acceptance: ex1 has no toolpaths; the feature toolpath generator makes them, and
// they must verify. Fails while the interpreter cannot generate them (STEPNC-010).
TEST(VerifyCorpus, NistExample1Generated) {
  NCPOST_REQUIRE_CORPUS_OR_SKIP(corpus);
  pipeline::LoadedModel loaded =
      pipeline::load(test::read_file(corpus / "p21/nist_toolkit_ex1.stp"), registry());
  ASSERT_TRUE(loaded.ok());
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  const VerifyResult r = verify(loaded.model, attributes);
  EXPECT_TRUE(r.ok()) << dump(r);
  ASSERT_EQ(r.features.size(), 3u) << dump(r);
  for (const auto& f : r.features) EXPECT_TRUE(f.checked && f.depth_reached) << f.name;
}

}  // namespace
}  // namespace ncpost::verify
