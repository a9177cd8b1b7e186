// ROUND_HOLE: the reader (holes.hpp).

#include <algorithm>
#include <cmath>

#include "holes.hpp"
#include "implicit.hpp"
#include "reader.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

enum class HoleKind { Drill, Peck, Ream, Bore, Tap };

// The operation's kind. Diagnostics: STEPNC-101 one the generator does not know.
std::optional<HoleKind> read_kind(Reader& reader) {
  const Instance& op = reader.operation();
  const auto on = [&] { return reader.name(op) + " on " + reader.name(reader.feature()); };
  if (!reader.is(&op, "drilling_type_operation")) {
    reader.report().not_implemented(on() + " (round holes take the drilling-type operations)");
    return std::nullopt;
  }
  if (reader.is(&op, "multistep_drilling")) return HoleKind::Peck;
  if (reader.is(&op, "drilling_operation")) return HoleKind::Drill;  // drilling, centre, sink
  if (reader.is(&op, "reaming")) return HoleKind::Ream;
  if (reader.is(&op, "boring")) return HoleKind::Bore;
  if (reader.is(&op, "tapping")) return HoleKind::Tap;
  reader.report().not_implemented(on());
  return std::nullopt;
}

// A drill may be smaller than the hole (a reamer or boring bar finishes it); a reamer or a tap
// is the hole's size.
bool check_size(Reader& reader, const Tool& tool, const Toleranced& diameter, HoleKind kind) {
  const auto hole = [&] { return reader.name(reader.feature()); };
  const double tool_d = 2 * tool.radius;
  if (tool_d > diameter.size + diameter.upper + kEps)
    return reader.report().unfit(tool.subject, tool.subject.name() + " diameter " + fmt(tool_d) +
                                                   " > diameter " + fmt(diameter.size) + " + " +
                                                   fmt(diameter.upper) + " of " + hole());
  if ((kind == HoleKind::Ream || kind == HoleKind::Tap) &&
      tool_d + diameter.lower + kEps < diameter.size)
    return reader.report().unfit(tool.subject, tool.subject.name() + " diameter " + fmt(tool_d) +
                                                   " < diameter " + fmt(diameter.size) + " - " +
                                                   fmt(diameter.lower) + " of " + hole() + " for " +
                                                   reader.name(reader.operation()));
  return true;
}

// DRILLING_TYPE_STRATEGY. Diagnostics: STEPNC-103 a ratio that is not positive.
bool read_zones(Reader& reader, DrillingZones& zones) {
  const Instance* strategy =
      reader.ref(reader.operation(), "its_machining_strategy", "drilling_type_strategy");
  if (strategy == nullptr) return true;
  zones.cut_start = reader.number(*strategy, "reduced_cut_at_start").value_or(1);
  zones.feed_start = reader.number(*strategy, "reduced_feed_at_start").value_or(1);
  zones.depth_start = reader.number(*strategy, "depth_of_start").value_or(0);
  zones.cut_end = reader.number(*strategy, "reduced_cut_at_end").value_or(1);
  zones.feed_end = reader.number(*strategy, "reduced_feed_at_end").value_or(1);
  zones.depth_end = reader.number(*strategy, "depth_of_end").value_or(0);
  for (const double ratio : {zones.cut_start, zones.feed_start, zones.cut_end, zones.feed_end})
    if (!(ratio > 0))
      return reader.report().bad(reader.subject(*strategy),
                                 reader.name(*strategy) + " has a ratio that is not positive");
  return true;
}

// Pecks of MULTISTEP_DRILLING.
bool read_pecks(Reader& reader, HoleSpec& spec) {
  const Instance& op = reader.operation();
  const auto first = reader.number(op, "first_depth");
  const auto step = reader.number(op, "depth_of_step");
  const auto back = reader.number(op, "retract_distance");
  if (!first || !step || !back || !(*first > 0) || !(*step > 0) || *back < 0)
    return reader.report().bad(reader.subject(op),
                               reader.name(op) +
                                   " needs a positive first_depth and depth_of_step and a "
                                   "retract_distance >= 0");
  if (static_cast<double>(reader.options().max_moves) * *step < -spec.bottom_z)
    return reader.report().limit_reached(reader.options().max_moves);
  spec.peck = *step;
  spec.peck_retract = *back;
  spec.peck_dwell = reader.number(op, "dwell_time_step").value_or(0);
  if (std::abs(*first - *step) > kEps) spec.first_peck = *first;
  return true;
}

// Rigid tapping: the technology's feed and speed are pitch × speed and speed.
bool read_tapping(Reader& reader, const Tool& tool, HoleSpec& spec) {
  const Instance& op = reader.operation();
  const auto spindle = reader.spindle();
  if (!spindle || *spindle == 0)
    return reader.report().bad(
        reader.subject(op),
        reader.name(op) + " has no spindle speed, so the thread pitch is unknown");
  spec.rpm = std::abs(*spindle) * 60.0;
  spec.pitch = spec.feed / spec.rpm;
  spec.left_hand = tool.left_hand;
  // The cycle reverses the spindle to come out; going in it must turn with the thread (NIST's
  // sign: negative is clockwise, a right-hand tap's direction).
  if ((*spindle > 0) != tool.left_hand)
    return reader.report().unfit(
        tool.subject, tool.subject.name() + " is a " + (tool.left_hand ? "left" : "right") +
                          "-hand tap, but the spindle of " + reader.name(op) + " turns " +
                          (*spindle > 0 ? "counter-clockwise" : "clockwise") + " in " +
                          reader.name(reader.feature()));
  return true;
}

// The cycle and what the operation's kind adds to it.
bool read_cycle(Reader& reader, HoleKind kind, const Tool& tool, HoleSpec& spec) {
  const Instance& op = reader.operation();
  switch (kind) {
    case HoleKind::Drill:
      spec.cycle = Move::CycleKind::Drill;
      return true;
    case HoleKind::Peck:
      spec.cycle = Move::CycleKind::Peck;
      return read_pecks(reader, spec);
    case HoleKind::Ream:
    case HoleKind::Bore: {
      const bool stop = reader.boolean(op, "spindle_stop_at_bottom").value_or(false);
      spec.cycle = stop || kind == HoleKind::Bore ? Move::CycleKind::Bore : Move::CycleKind::Ream;
      spec.spindle_stop = stop;
      if (reader.set(op, "depth_of_testcut") || reader.set(op, "waiting_position"))
        return reader.report().not_implemented(reader.name(op) +
                                               " with a test cut or waiting position");
      return true;
    }
    case HoleKind::Tap:
      spec.cycle = Move::CycleKind::Tap;
      return read_tapping(reader, tool, spec);
  }
  return false;
}

// How far above its tip a bottom of the hole rises higher than the tool's point, at most, over
// the tool's radius r: the bottom's height above the depth plane is `rise` (0 up to `flat`, then
// a circle of radius `bend` whose lowest point is at `flat`), the point's height above its tip
// k·s at s from the axis (a cone; k = 0 for a flat end). The largest of `rise(s) − k·s` is at
// s = r, where the circle's slope is k, or 0 (ISO 10303-42 circles, so exact).
double bottom_above_point(double flat, double bend, double r, double k) {
  const auto rise = [&](double x) {
    const double d = std::clamp(x - flat, 0.0, bend);
    return x <= flat ? 0.0 : bend - std::sqrt(std::max(0.0, bend * bend - d * d));
  };
  double worst = 0;
  for (const double x : {r, flat + k * bend / std::sqrt(1 + k * k)})
    if (x >= 0 && x <= r) worst = std::max(worst, rise(x) - k * x);
  return worst;
}

// How deep the tip may go in the hole, by its bottom: through, past the depth plane by the
// point and the clearance; a conical bottom, down to the cone's point (its height below the
// depth plane, R / tan(tip_angle / 2)) or the tool's point, whichever is lower. A blind flat,
// flat-with-radius or spherical bottom has its lowest point on the depth plane: the tip may
// reach it as long as the tool's point (or flat end) stays clear of the fillet or the sphere
// over the tool's radius, and no further (a point below a flat floor is the bottom's note,
// read_drill_bottom). `why` says which.
double deepest_tip(Reader& reader, const Instance& bottom, double depth, double radius,
                   const Tool& tool, double tip, std::string& why) {
  if (reader.is(&bottom, "conical_hole_bottom")) {
    const auto angle = reader.number(bottom, "tip_angle");
    const double cone =
        angle && *angle > 0 && *angle < 180 ? radius / std::tan(radians(*angle / 2)) : 0;
    why = "the point of its " + reader.name(bottom) + ", " + fmt(cone) + " below its depth " +
          fmt(depth);
    return depth + std::max(cone, tip);
  }
  if (reader.is(&bottom, "blind_bottom_condition")) {
    const double r = std::min(tool.radius, radius);
    const double k = r > 0 ? tip / tool.radius : 0;
    double above = 0;
    std::string shape;
    if (reader.is(&bottom, "spherical_hole_bottom")) {
      const double sphere = reader.toleranced(bottom, "radius").value_or(Toleranced{}).size;
      above = bottom_above_point(0, std::max(sphere, radius), r, k);
      shape = " of radius " + fmt(sphere);
    } else if (reader.is(&bottom, "flat_with_radius_hole_bottom")) {
      const double corner = std::clamp(
          reader.toleranced(bottom, "corner_radius").value_or(Toleranced{}).size, 0.0, radius);
      above = bottom_above_point(radius - corner, corner, r, k);
      shape = " with the corner radius " + fmt(corner);
    }
    why = "its " + reader.name(bottom) + shape + ", whose lowest point is its depth " + fmt(depth) +
          (above > 0 ? "; " + tool.subject.name() + " meets it " + fmt(above) + " above its tip"
                     : "");
    return depth - above;
  }
  why = "its depth " + fmt(depth);
  return depth + tip + reader.options().through_clearance;
}

// Where the tip stops: the operation's cutting_depth, else the bottom condition's.
std::optional<double> read_bottom(Reader& reader, const Instance& bottom, double depth,
                                  double radius, const Tool& tool, bool pointed) {
  const Instance& op = reader.operation();
  const auto cutting_depth = reader.number(op, "cutting_depth");
  if (!cutting_depth) {
    const auto z = read_drill_bottom(reader, reader.feature(), bottom, depth, tool, pointed, "");
    if (z) note_implicit_cutting_depth(reader, *z);
    return z;
  }
  const double tip = pointed ? tip_length(tool) : 0;
  std::string why;
  const double deepest = deepest_tip(reader, bottom, depth, radius, tool, tip, why);
  if (!(*cutting_depth > 0) || *cutting_depth > deepest + kEps) {
    reader.report().bad(reader.subject(op), reader.name(op) + " cutting_depth " +
                                                fmt(*cutting_depth) + " is not within " +
                                                reader.name(reader.feature()) + " (" + why +
                                                ": at most " + fmt(deepest) + ")");
    return std::nullopt;
  }
  return -*cutting_depth;
}

// A tapered hole: a drill (a cylinder) no wider than its narrowest diameter drills it, and the
// taper is left to another operation (a note); a wider one would cut into the taper.
bool check_taper(Reader& reader, const Tool& tool, const Toleranced& diameter, double depth,
                 const Taper& taper) {
  const Instance& hole = reader.feature();
  if (!taper.subject) return true;
  const std::string shape = reader.name(hole) + " with " + taper.subject.name() + " (diameter " +
                            fmt(2 * taper.top) + " at the top, " + fmt(2 * taper.bottom) +
                            " at its depth " + fmt(depth) + ")";
  if (2 * tool.radius > 2 * taper.smallest() + diameter.upper + kEps)
    return reader.report().unfit(tool.subject, tool.subject.name() + " diameter " +
                                                   fmt(2 * tool.radius) + " cuts into " + shape +
                                                   ": a drill makes a cylinder no wider than " +
                                                   fmt(2 * taper.smallest()) + " here");
  reader.report().note(taper.subject, reader.name(reader.operation()) + " drills a cylinder of " +
                                          tool.subject.name() + "'s diameter " +
                                          fmt(2 * tool.radius) + " in " + shape +
                                          "; another operation has to cut the taper");
  return true;
}

}  // namespace

std::optional<double> read_drill_bottom(Reader& reader, const Instance& hole,
                                        const Instance& bottom, double depth, const Tool& tool,
                                        bool pointed, std::string_view what_prefix) {
  const double tip = pointed ? tip_length(tool) : 0;
  if (reader.is(&bottom, "through_bottom_condition"))
    return -(depth + tip + reader.options().through_clearance);
  if (reader.is(&bottom, "conical_hole_bottom")) {
    // The depth plane ends the cylinder; the drill's own point makes the cone below it.
    const auto angle = reader.number(bottom, "tip_angle");
    if (pointed && angle && tool.tip_half_angle &&
        std::abs(point_angle(*tool.tip_half_angle) - *angle) > 0.5) {
      reader.report().unfit(tool.subject, tool.subject.name() + " point angle " +
                                              fmt(point_angle(*tool.tip_half_angle)) +
                                              " differs from tip_angle " + fmt(*angle) + " of " +
                                              reader.name(bottom) + " of " + reader.name(hole));
      return std::nullopt;
    }
    return -(depth + tip);
  }
  if (reader.is(&bottom, "blind_bottom_condition")) {
    // Flat, flat with radius, spherical: the tip stops at the depth plane, never below it.
    if (pointed && tip > 0)
      reader.report().note(reader.subject(hole),
                           tool.subject.name() + "'s point leaves a cone in the " +
                               std::string(reader.model().type_name(bottom)) + " of " +
                               reader.name(hole) + "; another operation has to finish the bottom");
    return -depth;
  }
  reader.report().not_implemented(std::string(what_prefix) + reader.name(hole) + " with " +
                                  reader.name(bottom));
  return std::nullopt;
}

bool check_drill_edge(Reader& reader, const Tool& tool, double bottom_z, const Instance& hole) {
  if (!tool.edge_length || *tool.edge_length + kEps >= -bottom_z) return true;
  return reader.report().unfit(
      tool.subject, tool.subject.name() + " cutting edge length " + fmt(*tool.edge_length) +
                        " is shorter than the " + fmt(-bottom_z) + " that " +
                        reader.name(reader.operation()) + " goes into " + reader.name(hole));
}

bool read_hole(Reader& reader, HoleSpec& spec) {
  Report& report = reader.report();
  const Instance& hole = reader.feature();
  const Instance& op = reader.operation();
  const auto kind = read_kind(reader);
  if (!kind) return false;
  const auto diameter = reader.toleranced(hole, "diameter");
  const Instance* bottom = reader.ref(hole, "bottom_condition", "hole_bottom_condition");
  if (!diameter || bottom == nullptr)
    return report.bad(reader.subject(hole),
                      reader.name(hole) + " needs a diameter and a bottom_condition");
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  if (!reader.feed() || !(*reader.feed() > 0))
    return report.bad(reader.subject(op), reader.name(op) + " has no feed rate in its technology");
  // A taper: the cone of a conical bottom has the taper's final diameter.
  const auto taper = read_taper(reader, hole, diameter->size, *depth);
  if (!taper || !check_size(reader, *tool, *diameter, *kind) ||
      !check_taper(reader, *tool, *diameter, *depth, *taper))
    return false;
  const bool pointed = *kind == HoleKind::Drill || *kind == HoleKind::Peck;
  const auto bottom_z = read_bottom(reader, *bottom, *depth, taper->bottom, *tool, pointed);
  if (!bottom_z || !check_drill_edge(reader, *tool, *bottom_z, hole)) return false;
  spec.bottom_z = *bottom_z;
  spec.retract_z = reader.number(op, "retract_plane").value_or(reader.options().clearance);
  if (!(spec.retract_z > 0))
    return report.bad(reader.subject(op),
                      reader.name(op) + " retract_plane must be above the hole");
  spec.feed = *reader.feed();
  spec.dwell = reader.number(op, "dwell_time_bottom").value_or(0);
  if (spec.dwell < 0)
    return report.bad(reader.subject(op), reader.name(op) + " dwell_time_bottom is negative");
  spec.feed_on_retract = reader.number(op, "feed_on_retract");
  spec.spindle = reader.spindle().value_or(0);
  if (!read_zones(reader, spec.zones) || !read_cycle(reader, *kind, *tool, spec)) return false;
  if (spec.needs_motions() &&
      (*kind == HoleKind::Tap || *kind == HoleKind::Bore || *kind == HoleKind::Ream))
    return report.not_implemented(reader.name(op) + " with a drilling strategy or feed_on_retract");
  return true;
}

}  // namespace ncpost::stepnc::features
