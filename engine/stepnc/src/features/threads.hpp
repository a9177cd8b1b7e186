#pragma once
// THREAD_DRILLING (ISO 14649-11): one tool drills the core hole and mills the thread. With
// helical_movement_on_forward .F. it drills to depth along its axis and mills the thread on the
// way back: out to the thread at the bottom of the thread, a helix up to the top with the
// thread's pitch, back to the axis. Coordinates are the hole's (docs/features.md).
//
// The operation has no pitch and no thread diameter: they are the THREAD feature's (ISO
// 14649-10), which the workingstep machines and which names its hole (applied_shape):
// major_diameter (the helix keeps the tool's edge on it), number_of_threads per length unit
// (its_parameter_unit: per mm or per inch), thread_hand, and the THREAD's depth plane (how far
// down the thread runs). The hole (a ROUND_HOLE on the same axis) gives the drilling diameter,
// depth and bottom, as for a drill (holes.hpp).

#include "draft.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;

struct ThreadSpec {
  double retract_z = 0;  // the R plane, above the top
  double bottom_z = 0;   // where the drill's tip stops
  double dwell = 0;      // seconds at the bottom
  double length = 0;     // of the thread, down from the top
  double pitch = 0;      // mm per turn
  bool right = true;     // right hand: counter-clockwise up, seen from above
  double offset = 0;     // of the tool's centre from the axis on the helix: major / 2 - R
};

// Diagnostics (and Reader::read_depth's, read_tool's, read_drill_bottom's):
// - STEPNC-101: helical_movement_on_forward .T.; a thread whose applied_shape is not one
//   ROUND_HOLE; a tapered hole; a drilling strategy or feed_on_retract.
// - STEPNC-102: a tool that is not a thread drill-mill, or not of the hole's diameter; its
//   cutting edge shorter than the depth.
// - STEPNC-103: a feature that is not a THREAD; an outer thread; a thread off its hole's axis or
//   top; no positive major diameter, number of threads or hand; a major diameter beyond the
//   length limit; an unknown unit of the number of threads or an unknown hand; a hole without
//   diameter, bottom condition or depth plane; a major diameter not larger than the hole; a
//   thread deeper than its blind hole; no feed rate; a retract plane not above the hole; a
//   negative dwell.
[[nodiscard]] bool read_thread_drilling(Reader& reader, ThreadSpec& spec);

// Diagnostics: STEPNC-103 more helix turns than the motion limit.
[[nodiscard]] bool plan_thread_drilling(const ThreadSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
