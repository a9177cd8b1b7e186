#pragma once
// Shared by the canon tests: a sample program that uses every call, and libxml2 helpers
// (well-formedness, RELAX NG validation against engine/canon/canon.rng).

#include <libxml/parser.h>
#include <libxml/relaxng.h>

#include <string>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "xml_check.hpp"

namespace ncpost::canon::test {

inline Entity entity(std::uint64_t id, std::string type, std::string name) {
  return Entity{id, std::move(type), std::move(name)};
}

// Every kind of call at least once, in a plausible program order: start (set-up), two
// workingsteps with NC functions between them, end.
inline std::vector<Call> sample_program() {
  const Entity project = entity(1, "PROJECT", "bracket & <co>");
  const Entity setup = entity(5, "SETUP", "setup \"1\"");
  const Entity plan = entity(3, "WORKPLAN", "main");
  const Entity ws1 = entity(10, "MACHINING_WORKINGSTEP", "WS FINISH PLANAR FACE1");
  const Entity ws2 = entity(20, "MACHINING_WORKINGSTEP", "WS DRILL");
  Cycle drill{.kind = CycleKind::Drill,
              .x = 10,
              .y = 20,
              .safe_z = 50,
              .r_z = 2,
              .bottom_z = -10,
              .feed = 100};
  Cycle peck = drill;
  peck.kind = CycleKind::PeckDrill, peck.peck = 3, peck.peck_clearance = 0.5;
  Cycle tap = drill;
  tap.kind = CycleKind::Tap, tap.pitch = 1.25, tap.spindle_speed = 400, tap.feed = 500;
  tap.left_hand = true;
  Cycle bore = drill;
  bore.kind = CycleKind::Bore, bore.spindle_stop = true, bore.dwell = 0.5;
  Cycle ream = drill;
  ream.kind = CycleKind::Ream, ream.tool_axis = Direction{0, 0, 1};
  NurbsFeed nurbs{.degree = 2,
                  .points = {{0, 0, 0, 1}, {1, 2, 0, 0.5}, {3, 0, 0, 1}},
                  .knots = {0, 0, 0, 1, 1, 1}};
  return {
      Begin{Scope::Project, project},
      UseLengthUnits{Units::Millimetres},
      SetOriginOffsets{{0, 0, -14.7}, {}},
      SetFeedReference{FeedReference::Workpiece},
      SelectPlane{Plane::Xy},
      Begin{Scope::Setup, setup},
      Begin{Scope::Workplan, plan},
      Begin{Scope::Workingstep, ws1},
      SelectTool{1},
      ChangeTool{1},
      UseToolLengthOffset{12.5},
      SetSpindleSpeed{1000},
      StartSpindleClockwise{},
      FloodOn{},
      SetFeedRate{200},
      StraightTraverse{{0, 0, 5, {}, {}}},
      StraightFeed{{91.9, -13.5, 2.5, Rotary{0, 30, -0.0}, Direction{0, 0.5, 0.8660254037844386}}},
      ArcFeed{{20, 0, 2.5, {}, {}}, {15, 0, 2.5}, {0, 0, 1}, -1},
      NurbsFeed{nurbs},
      Dwell{1.5},
      Comment{"tab\there \"quoted\" <&> \x01 done"},
      Message{"change insert"},
      End{Scope::Workingstep, ws1},
      Comment{"NC function between workingsteps"},
      OptionalProgramStop{},
      Begin{Scope::Workingstep, ws2},
      Cycle{drill},
      Cycle{peck},
      Cycle{tap},
      Cycle{bore},
      Cycle{ream},
      MistOn{},
      MistOff{},
      FloodOff{},
      StopSpindleTurning{},
      StartSpindleCounterclockwise{},
      SpindleRetract{},
      ProgramStop{},
      End{Scope::Workingstep, ws2},
      End{Scope::Workplan, plan},
      End{Scope::Setup, setup},
      ProgramEnd{},
      End{Scope::Project, project},
  };
}

using ncpost::test::well_formed;

inline std::string rng_path() {
  return std::string(NCPOST_SOURCE_DIR) + "/engine/canon/canon.rng";
}

// Empty when `xml` is well-formed and valid against canon.rng; otherwise what went wrong.
inline std::string rng_errors(const std::string& xml) {
  return ncpost::test::rng_errors(xml, rng_path());
}

}  // namespace ncpost::canon::test
