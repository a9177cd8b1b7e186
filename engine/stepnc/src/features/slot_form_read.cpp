// SLOT made by a form tool along its course of travel: the reader (slot.hpp). What each profile
// asks of its tool (a cone of the vee's angle, a ball no larger than a round profile, an end
// mill of a square-U's width along a circle), the finishing passes across the profile, and what
// the ends allow.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "milling_read.hpp"
#include "reader.hpp"
#include "slot.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

double degrees(double radians) {
  return radians * 180 / std::numbers::pi;
}

// What the ends allow a form tool.
bool check_ends(Reader& reader, const SlotBasics& basics, const Tool& tool, double depth) {
  Report& report = reader.report();
  const SlotPath& path = basics.path;
  const auto f = [&] { return reader.name(reader.feature()); };
  const auto swept = [&] { return basics.swept.name(); };
  const auto travel = [&] { return basics.travel.name(); };
  for (const SlotEnd& e : basics.end) {
    if (path.kind == SlotPath::Kind::Circle) break;
    const auto end = [&] { return e.subject.name(); };
    if (e.kind == SlotEnd::Kind::Flat)
      return report.not_implemented(f() + " with " + swept() +
                                    (path.kind == SlotPath::Kind::Arc ? " along " + travel() : "") +
                                    " and the flat end " + end() +
                                    " (a form tool cannot make a flat end across the profile)");
    if (e.kind == SlotEnd::Kind::Open && path.kind == SlotPath::Kind::Arc)
      return report.not_implemented(f() + " along " + travel() + " with the open end " + end());
    if (e.kind != SlotEnd::Kind::Woodruff) continue;
    if (basics.section.kind == SlotSection::Kind::SquareU) {
      // The woodruff end is the swept profile turned about an axis across the slot: with a
      // square-U profile its corners with the walls are sharp at every height, which no tool
      // turning about a vertical axis leaves.
      if (reader.is(tool.body, "woodruff_keyseat_mill"))
        return report.not_implemented(f() + "'s woodruff end " + end() + " with " +
                                      tool.subject.name() +
                                      ", which cuts with its axis across the slot (the "
                                      "generator's tools turn about the feature's z axis)");
      return report.unfit(tool.subject,
                          tool.subject.name() + " cannot make the woodruff end " + end() + " of " +
                              f() +
                              ": the end meets the square-U walls in sharp corners at every "
                              "height, which a tool turning about the vertical leaves rounded");
    }
    if (basics.section.kind == SlotSection::Kind::Vee)
      return report.not_implemented(f() + " with " + swept() + " and the woodruff end " + end() +
                                    " (a cone cannot follow the turned vee)");
    if (path.kind != SlotPath::Kind::Line)
      return report.not_implemented(f() + " along " + travel() + " with the woodruff end " + end());
    if (e.woodruff.size + kEps < depth)
      return report.not_implemented(f() + "'s woodruff end " + end() + " of radius " +
                                    fmt(e.woodruff.size) + ", less than the " + fmt(depth) +
                                    " depth (its arc would turn under the top)");
  }
  return true;
}

// A tool turning about its axis makes a section of the slot exactly when its profile is the
// section's: a cone of the vee's angle, its tip on the final pass `tip` below the top.
bool vee_passes(Reader& reader, const Tool& tool, const Operation& operation, const SlotSection& s,
                double depth, std::vector<SlotPass>& passes) {
  Report& report = reader.report();
  const auto f = [&] { return reader.name(reader.feature()); };
  const auto named = [&] { return tool.subject.name(); };
  // A cone: a countersink, or a milling cutter with a point (its tool_tip_half_angle, read as
  // for drills: NIST's angle between the cutting edge and the plane normal to the axis below
  // 90 degrees, the whole point angle from 90 on).
  const bool cone_body = reader.is(tool.body, "countersink") ||
                         reader.is(tool.body, "milling_cutter") ||
                         reader.is(tool.body, "user_defined_tool");
  if (!cone_body || !tool.tip_half_angle || !(*tool.tip_half_angle > 0) ||
      !(*tool.tip_half_angle < 180))
    return report.unfit(tool.subject, named() + " has no cone of " + fmt(degrees(s.angle)) +
                                          " degrees to make " + f() +
                                          "'s vee (a countersink or a pointed cutter "
                                          "of the vee's angle is needed)");
  const double point =
      *tool.tip_half_angle < 90 ? 180 - 2 * *tool.tip_half_angle : *tool.tip_half_angle;
  if (std::abs(point - degrees(s.angle)) > kAngleMatch)
    return report.unfit(tool.subject, named() + " point angle " + fmt(point) +
                                          " differs from the profile_angle " +
                                          fmt(degrees(s.angle)) + " of " + f());
  const double rho = s.radius.size;
  const double c = tool.corner_radius;
  if (c > rho + s.radius.upper + kEps || c < rho - s.radius.lower - kEps)
    return report.unfit(tool.subject, named() + " tip radius " + fmt(c) +
                                          " is not the vee's profile_radius " + fmt(rho) + " of " +
                                          f() + " within its tolerance");
  const double half = s.angle / 2;
  const double sin_half = std::sin(half);
  // Lifted along the axis by `lift`, the cone stays a_s off the walls (normal to them) and a_b
  // off the bottom; a sharper tip than the vee's radius is lifted until it touches the bottom.
  const double lift = std::max(operation.allowance_bottom, operation.allowance_side / sin_half) +
                      std::max(0.0, (rho - c) * (1 / sin_half - 1));
  const double tip = depth - lift;
  if (!(tip > 0))
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves the whole depth of " + f());
  // The cone must reach the top of the walls: its width at the top of the slot is what the
  // tool's diameter has to cover.
  const double apex_below_tip = c / sin_half - c;
  const double needed = (tip + apex_below_tip) * std::tan(half);
  if (tool.radius + kEps < needed)
    return report.unfit(tool.subject, named() + " diameter " + fmt(2 * tool.radius) +
                                          " is narrower than the " + fmt(2 * needed) + " that " +
                                          f() + "'s vee is wide at its top");
  // The flank touches the walls over the whole depth: its length along the cone (the edge
  // length, whichever way it is measured, covers at least that height once projected).
  if (tool.edge_length && *tool.edge_length * std::cos(half) + kEps < tip)
    return report.unfit(tool.subject, named() + " cutting edge length " + fmt(*tool.edge_length) +
                                          " does not reach the " + fmt(tip) + " deep walls of " +
                                          f());
  passes.push_back({0, tip});
  return true;
}

bool ball_check(Reader& reader, const Tool& tool, const std::string& what) {
  const bool ball =
      reader.is(tool.body, "ball_endmill") || tool.corner_radius >= tool.radius - kEps;
  if (ball) return true;
  return reader.report().unfit(tool.subject, tool.subject.name() + " is not a ball end mill; " +
                                                 reader.name(reader.feature()) + ", " + what);
}

// A ball of the profile's radius along the centre, or a smaller ball stepped across the
// circle, each ball centre on the circle of radius R - allowance - r about the profile's
// centre, close enough for the cusps between them to stay within the profile tolerance.
bool partial_circle_passes(Reader& reader, const Tool& tool, const Operation& operation,
                           const SlotSection& s, double depth, std::vector<SlotPass>& passes,
                           bool& stepped) {
  Report& report = reader.report();
  const auto f = [&] { return reader.name(reader.feature()); };
  const double R = s.radius.size;
  // The arc, its lowest point on the depth plane, must reach the top of the slot: a shallower
  // arc would leave the slot's upper walls undefined.
  if (R * (1 - std::cos(s.sweep / 2)) + 1e-9 < depth)
    return report.bad(reader.subject(reader.feature()),
                      f() + " is " + fmt(depth) + " deep, but its partial circle (radius " +
                          fmt(R) + ", " + fmt(degrees(s.sweep)) + " degrees) ends " +
                          fmt(R * (1 - std::cos(s.sweep / 2))) + " above its bottom");
  if (!ball_check(reader, tool, "a partial-circular slot, takes a ball of at most its radius"))
    return false;
  const double r = tool.radius;
  if (r > R + s.radius.upper + kEps)
    return report.unfit(tool.subject, tool.subject.name() + " radius " + fmt(r) +
                                          " is larger than the radius " + fmt(R) + " of " + f() +
                                          "'s partial circle");
  const double allowance = std::max(operation.allowance_side, operation.allowance_bottom);
  if (allowance == 0 && r >= R - s.radius.lower - kEps) {
    stepped = false;
    passes.push_back({0, depth});
    return true;
  }
  const double rc = R - allowance - r;
  if (!(rc > 1e-6))
    return report.unfit(tool.subject, tool.subject.name() + " radius " + fmt(r) + " + allowance " +
                                          fmt(allowance) + " of " + operation.subject.name() +
                                          " leaves no room in the radius " + fmt(R) + " of " + f());
  stepped = true;
  const double centre = R - depth;  // the profile's centre above the top (>= 0)
  const double top = std::acos(std::clamp(centre / R, -1.0, 1.0));  // where it meets the top
  const double dpsi = scallop_step(rc, r, reader.options().profile_tolerance);
  if (!(dpsi > 1e-9) || top / dpsi > static_cast<double>(reader.options().max_moves))
    return report.limit_reached(reader.options().max_moves);
  const auto n = static_cast<std::size_t>(std::ceil(top / dpsi - 1e-9));
  for (std::size_t j = 0; j <= n; ++j) {
    const double psi = n == 0 ? 0 : top * static_cast<double>(j) / static_cast<double>(n);
    // Tip depth below the top: the ball centre is rc·cos ψ below the profile's centre.
    passes.push_back({rc * std::sin(psi), rc * std::cos(psi) + r - centre});
  }
  return true;
}

// A tool of the slot's width along its centre: a ball for a rounded-U, an end mill of the
// floor's corner radius for a square-U along a circle.
bool u_pass(Reader& reader, const SlotBasics& basics, const Tool& tool, const Operation& operation,
            double depth, FormSlotSpec& spec) {
  Report& report = reader.report();
  const SlotSection& section = basics.section;
  const auto f = [&] { return reader.name(reader.feature()); };
  const double inset = tool.radius + operation.allowance_side;
  if (section.kind == SlotSection::Kind::RoundedU) {
    if (!ball_check(reader, tool, "a rounded-U slot, takes a ball of its width")) return false;
    if (std::abs(section.half - inset) > 1e-3)
      return report.unfit(tool.subject, tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                                            " + allowances is not the width " +
                                            fmt(2 * section.half) + " of " + f() +
                                            ", which a ball cuts in one pass");
    spec.ball_radius = tool.radius;
  } else {
    if (section.half - inset < -kEps || section.half - inset > 1e-3)
      return report.unfit(tool.subject,
                          tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                              " + allowances is not the width " + fmt(2 * section.half) + " of " +
                              f() + " along " + basics.travel.name() +
                              " (only a tool of the slot's width, along its centre, is generated "
                              "there)");
    const double fillet = section.fillet ? section.fillet->size : 0;
    const double upper = section.fillet ? section.fillet->upper : 0;
    const double lower = section.fillet ? section.fillet->lower : 0;
    if (tool.corner_radius > fillet + upper + operation.allowance_bottom + kEps ||
        tool.corner_radius + lower + kEps < fillet)
      return report.unfit(tool.subject, tool.subject.name() + " edge radius " +
                                            fmt(tool.corner_radius) + " is not the floor radius " +
                                            fmt(fillet) + " of " + f());
  }
  const double tip = depth - operation.allowance_bottom;
  if (!(tip > 0))
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves the whole depth of " + f());
  spec.passes.push_back({0, tip});
  return true;
}

// The finishing passes across the profile, from the course of travel outwards.
bool read_passes(Reader& reader, const SlotBasics& basics, const Tool& tool,
                 const Operation& operation, double depth, FormSlotSpec& spec, bool& stepped) {
  const SlotSection& section = basics.section;
  switch (section.kind) {
    case SlotSection::Kind::Vee:
      return vee_passes(reader, tool, operation, section, depth, spec.passes);
    case SlotSection::Kind::PartialCircular: {
      double overlap = 0;
      const double step = stepover(reader, tool, operation, overlap);
      if (!check_overlap(reader, operation, overlap)) return false;
      if (!partial_circle_passes(reader, tool, operation, section, depth, spec.passes, stepped))
        return false;
      spec.stepover = step;
      spec.ball_radius = tool.radius;
      return true;
    }
    case SlotSection::Kind::RoundedU:
    case SlotSection::Kind::SquareU:
      return u_pass(reader, basics, tool, operation, depth, spec);
    case SlotSection::Kind::General:
      break;  // read_section_slot's
  }
  return false;
}

// Stepped passes only along straight slots without woodruff ends; a ball that fits each
// woodruff end; a ramp approach that allows the woodruff end's arc the tool comes down along.
bool check_woodruff(Reader& reader, const SlotBasics& basics, const Tool& tool,
                    const Operation& operation, bool stepped, const FormSlotSpec& spec) {
  Report& report = reader.report();
  const SlotPath& path = basics.path;
  const auto f = [&] { return reader.name(reader.feature()); };
  const bool woodruff =
      path.kind != SlotPath::Kind::Circle && (basics.end[0].kind == SlotEnd::Kind::Woodruff ||
                                              basics.end[1].kind == SlotEnd::Kind::Woodruff);
  if (stepped && (path.kind != SlotPath::Kind::Line || woodruff))
    return report.not_implemented(
        f() + " with " + basics.swept.name() + " cut by " + tool.subject.name() +
        ", smaller than its radius, " +
        (path.kind != SlotPath::Kind::Line ? "along " + basics.travel.name()
                                           : std::string("with a woodruff end")) +
        " (stepped passes are generated along straight slots with radiused or open ends)");
  // A woodruff end turns the profile about its axis: a ball larger than its radius (less the
  // allowance) does not fit in it.
  const double depth = spec.depth;
  for (const SlotEnd& e : basics.end) {
    if (e.kind != SlotEnd::Kind::Woodruff || path.kind == SlotPath::Kind::Circle) continue;
    const double allowance = depth - spec.passes.front().depth;
    if (spec.ball_radius + allowance > e.woodruff.size + e.woodruff.upper + kEps)
      return report.unfit(tool.subject, tool.subject.name() + " radius " + fmt(spec.ball_radius) +
                                            " + allowance " + fmt(allowance) + " > the radius " +
                                            fmt(e.woodruff.size) + " of the woodruff end " +
                                            e.subject.name() + " of " + f());
  }
  // Into a woodruff end the tool comes down along its arc, which is as steep as the end is at
  // the top of the slot: a ramp or zigzag approach must allow that.
  const Subject& approach = operation.approach;
  if (!approach || !(reader.is(approach, "plunge_ramp") || reader.is(approach, "plunge_zigzag")))
    return true;
  const double allowed = reader.number(*approach.instance, "angle").value_or(0);
  for (const SlotEnd& e : basics.end) {
    if (e.kind != SlotEnd::Kind::Woodruff) continue;
    const double r = spec.ball_radius;
    const double allowance = depth - spec.passes.front().depth;
    const double rho = e.woodruff.size - r - allowance;
    const double axis = -depth + e.woodruff.size;
    // The ball leaves the material where its tip reaches the top; the arc's slope there.
    const double steepest =
        rho > 1e-9 ? degrees(std::acos(std::clamp((axis - r) / rho, -1.0, 1.0))) : 90;
    if (std::min(steepest, 90.0) > allowed + 1e-9)
      return report.not_implemented(approach.name() + " at " + fmt(allowed) + " degrees into " +
                                    f() + ", whose woodruff end " + e.subject.name() +
                                    " the tool follows down at up to " +
                                    fmt(std::min(steepest, 90.0)) + " degrees");
  }
  return true;
}

// The approach and retract: along the tool axis, or a ramp along the course of travel; no room
// for a helix.
bool read_plunges(Reader& reader, const Tool& tool, const Operation& operation,
                  FormSlotSpec& spec) {
  spec.entry.kind = Entry::Kind::Plunge;
  spec.exit.kind = Entry::Kind::Plunge;
  for (const auto& [strategy, role, entry] :
       {std::tuple{&operation.approach, "approach into", &spec.entry},
        std::tuple{&operation.retract, "retract from", &spec.exit}}) {
    if (!*strategy) continue;
    if (!read_plunge(reader, *strategy->instance, role, *entry)) return false;
    if (entry->kind == Entry::Kind::Helix)
      return reader.report().unfit(*strategy,
                                   strategy->name() + ": " + tool.subject.name() + " machines " +
                                       reader.name(reader.feature()) +
                                       " along its course of travel; there is no room for a "
                                       "helix");
  }
  return true;
}

}  // namespace

bool read_form_slot(Reader& reader, const SlotBasics& basics, FormSlotSpec& spec) {
  Report& report = reader.report();
  const auto f = [&] { return reader.name(reader.feature()); };
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  const SlotPath& path = basics.path;
  if (reader.is(&reader.operation(), "side_milling"))
    return report.not_implemented(
        operation.subject.name() + " on " + f() + " with " + basics.swept.name() +
        (path.kind == SlotPath::Kind::Line ? std::string() : " along " + basics.travel.name()) +
        " (its walls are the form tool's, made by bottom-and-side milling)");
  if (operation.strategy && !reader.is(operation.strategy, "center_milling") &&
      !reader.is(operation.strategy, "contour_parallel"))
    return report.not_implemented(operation.strategy.name() + " on " + f() + ", which " +
                                  tool->subject.name() + " machines along its course of travel");
  if (!check_ends(reader, basics, *tool, *depth)) return false;
  spec.path = path;
  spec.end[0] = basics.end[0];
  spec.end[1] = basics.end[1];
  spec.depth = *depth;
  spec.tool_radius = tool->radius;
  spec.ccw = rings_ccw(reader, operation, true, false);
  bool stepped = false;
  if (!read_passes(reader, basics, *tool, operation, *depth, spec, stepped) ||
      !check_woodruff(reader, basics, *tool, operation, stepped, spec) ||
      !read_plunges(reader, *tool, operation, spec))
    return false;
  double deepest = 0;
  for (const SlotPass& p : spec.passes) deepest = std::max(deepest, p.depth);
  auto levels = depth_levels(reader, operation, deepest);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  spec.levels = std::move(*levels);
  spec.retract_plane = operation.retract_plane;
  spec.tool = tool->subject;
  spec.feature = reader.subject(reader.feature());
  return true;
}

}  // namespace ncpost::stepnc::features
