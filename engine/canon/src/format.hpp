#pragma once
// Small formatting helpers shared by the trace and the XML writer (internal to the stage).

#include <charconv>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "ncpost/canon/call.hpp"

namespace ncpost::canon::detail {

template <class Integer>
void append_integer(std::string& out, Integer value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer,
             static_cast<std::size_t>(result.ptr - buffer));  // not (first, last): replace()
}

// A cycle's arguments by name, in canon.rng's order, for the writers that name them (the XML
// form and the JSON trace): p.number(name, double) for numbers, p.text(name, text) for the
// tap's hand and the bore's spindle stop ("true"/"false"; the JSON writer makes it a boolean
// through p.flag when it has one).
template <class Printer>
void cycle_arguments(Printer& p, const Cycle& c) {
  p.number("x", c.x), p.number("y", c.y);
  p.number("safe_z", c.safe_z), p.number("r_z", c.r_z), p.number("bottom_z", c.bottom_z);
  p.number("feed", c.feed), p.number("dwell", c.dwell);
  switch (c.kind) {
    case CycleKind::PeckDrill:
      p.number("peck", c.peck), p.number("peck_retract", c.peck_retract);
      p.number("peck_clearance", c.peck_clearance);
      break;
    case CycleKind::Tap:
      p.number("pitch", c.pitch), p.number("spindle_speed", c.spindle_speed);
      p.text("hand", c.left_hand ? "left" : "right");
      break;
    case CycleKind::Bore:
      p.flag("spindle_stop", c.spindle_stop);
      break;
    case CycleKind::Drill:
    case CycleKind::Ream:
      break;
  }
}

// NURBS control points as the trace and the JSON trace list them: `open` x `separator` y
// `separator` z `separator` weight `close`, the points joined by `separator`; then the knots
// (append_values). `number` appends one number in the writer's own form.
template <class Number>
void append_control_points(std::string& out, std::span<const ControlPoint> points, Number number,
                           std::string_view separator, char open, char close) {
  for (std::size_t n = 0; n < points.size(); ++n) {
    if (n > 0) out += separator;
    out += open;
    for (const double v : {points[n].x, points[n].y, points[n].z}) number(out, v), out += separator;
    number(out, points[n].weight);
    out += close;
  }
}
template <class Number>
void append_values(std::string& out, std::span<const double> values, Number number,
                   std::string_view separator) {
  for (std::size_t n = 0; n < values.size(); ++n) {
    if (n > 0) out += separator;
    number(out, values[n]);
  }
}

}  // namespace ncpost::canon::detail
