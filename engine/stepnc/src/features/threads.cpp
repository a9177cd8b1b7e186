// THREAD_DRILLING (ISO 14649-11): one tool drills the core hole and mills the thread. With
// helical_movement_on_forward .F. it drills to depth along its axis and mills the thread on
// the way back: out to the thread at the bottom of the thread, a helix up to the top with the
// thread's pitch, back to the axis. (With .T. the tool mills its way in along the helix, into
// solid material; that needs the tool's drilling and threading diameters, which ISO 14649-111
// does not give: not generated.)
//
// The operation has no pitch and no thread diameter: they are the THREAD feature's (ISO 14649-10),
// which the workingstep machines and which names its hole (applied_shape):
// - major_diameter: the helix keeps the tool's edge on it;
// - number_of_threads: threads per length unit, its_parameter_unit saying which (per mm or per
//   inch), so the pitch is 1 / n mm or 25.4 / n mm;
// - thread_hand: RIGHT or LEFT, the hand of the helix;
// - the THREAD's depth plane: how far down the thread runs (at most the hole's depth);
// - the hole (a ROUND_HOLE on the same axis): its diameter is the tool's drilling diameter, its
//   depth and bottom the drilling depth, as for a drill (holes.cpp).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "context.hpp"

namespace ncpost::stepnc::features::legacy {
namespace {

constexpr double kEps = 1e-9;

std::string upper_no_space(std::string_view text) {
  std::string out;
  for (const char c : text)
    if (!std::isspace(static_cast<unsigned char>(c)))
      out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

bool generate_thread_drilling(Context& ctx) {
  const Instance& f = ctx.feature();
  const Instance& op = ctx.op();
  if (ctx.boolean(op, "helical_movement_on_forward").value_or(false))
    return ctx.not_implemented(ctx.d(op) +
                               " with helical_movement_on_forward .T. (milling the "
                               "hole and the thread on the way in) on " +
                               ctx.d(f));
  if (!ctx.is(&f, "thread"))
    return ctx.bad(f, ctx.d(op) + " on " + ctx.d(f) +
                          ": a thread drilling needs a THREAD feature, which gives the pitch, "
                          "the major diameter and the hand (and names its hole)");
  if (!ctx.boolean(f, "inner_or_outer_thread").value_or(false))
    return ctx.bad(f, ctx.d(f) + " is an outer thread (inner_or_outer_thread .F.), which " +
                          ctx.d(op) + " cannot make");

  // The hole the thread is cut in.
  const Instance* hole = nullptr;
  if (const auto shapes = ctx.g.get(f, "applied_shape"); shapes && shapes->is_list()) {
    const auto items = ctx.m.items(*shapes);
    if (items.size() == 1)
      hole = ctx.g.instance(items[0], "machining_feature", &f, "applied_shape");
  }
  if (hole == nullptr || !ctx.is(hole, "round_hole"))
    return ctx.not_implemented(ctx.d(op) + " on " + ctx.d(f) +
                               " whose applied_shape is not one ROUND_HOLE");
  const auto thread_frame = ctx.g.placement(ctx.g.get(f, "feature_placement"));
  const auto hole_frame = ctx.g.placement(ctx.g.get(*hole, "feature_placement"));
  if (!thread_frame || !hole_frame) return false;
  if ((thread_frame->origin - hole_frame->origin).length() > 1e-6 ||
      (thread_frame->z - hole_frame->z).length() > 1e-9)
    return ctx.bad(f, ctx.d(f) + " is not placed on the axis and top of its hole " + ctx.d(*hole));

  // Thread data.
  const auto major = ctx.number(f, "major_diameter");
  const Instance* count = ctx.ref(f, "number_of_threads", "numeric_parameter");
  const Instance* hand = ctx.ref(f, "thread_hand", "descriptive_parameter");
  const auto threads = count ? ctx.number(*count, "its_parameter_value") : std::nullopt;
  if (!major || !(*major > 0) || !threads || !(*threads > 0) || hand == nullptr)
    return ctx.bad(f, ctx.d(f) +
                          " needs a positive major_diameter and number_of_threads, and a "
                          "thread_hand");
  if (!ctx.size_ok(f, *major, "major_diameter")) return false;
  std::string unit;
  if (const auto u = ctx.g.get(*count, "its_parameter_unit");
      u && u->kind() == p21::ValueKind::String)
    unit = upper_no_space(ctx.m.as_string(*u));
  double pitch = 0;
  if (unit == "1/MM" || unit == "/MM" || unit == "PERMM" || unit == "THREADSPERMM")
    pitch = 1 / *threads;
  else if (unit == "1/IN" || unit == "/IN" || unit == "1/INCH" || unit == "PERINCH" ||
           unit == "TPI" || unit == "THREADSPERINCH")
    pitch = 25.4 / *threads;
  else
    return ctx.bad(*count, ctx.d(*count) + " gives the number of threads per '" + unit +
                               "': per mm (1/MM) or per inch (1/IN, TPI) are understood, so the "
                               "pitch of " +
                               ctx.d(f) + " is unknown");
  std::string hand_text;
  if (const auto h = ctx.g.get(*hand, "descriptive_string");
      h && h->kind() == p21::ValueKind::String)
    hand_text = upper_no_space(ctx.m.as_string(*h));
  bool right = true;
  if (hand_text.rfind("RIGHT", 0) == 0 || hand_text == "RH" || hand_text == "R")
    right = true;
  else if (hand_text.rfind("LEFT", 0) == 0 || hand_text == "LH" || hand_text == "L")
    right = false;
  else
    return ctx.bad(*hand,
                   ctx.d(*hand) + " thread_hand '" + hand_text + "' is neither RIGHT nor LEFT");

  // The hole, in the same frame.
  const auto hole_d = ctx.toleranced(*hole, "diameter");
  const Instance* bottom = ctx.ref(*hole, "bottom_condition", "hole_bottom_condition");
  if (!hole_d || !(hole_d->size > 0) || bottom == nullptr)
    return ctx.bad(*hole, ctx.d(*hole) + " needs a diameter and a bottom_condition");
  if (ctx.set(*hole, "change_in_diameter"))
    return ctx.not_implemented(ctx.d(op) + " in the tapered " + ctx.d(*hole));
  if (!(*major > hole_d->size))
    return ctx.bad(f, ctx.d(f) + " major_diameter " + fmt(*major) + " is not larger than " +
                          ctx.d(*hole) + "'s diameter " + fmt(hole_d->size));
  const auto thread_depth = ctx.depth();  // the THREAD's own depth plane
  const Instance* hole_plane = ctx.ref(*hole, "depth", "elementary_surface");
  const auto hole_plane_frame =
      hole_plane ? ctx.g.placement(ctx.g.get(*hole_plane, "position")) : std::nullopt;
  if (!thread_depth || !hole_plane_frame) {
    if (hole_plane == nullptr) ctx.bad(*hole, ctx.d(*hole) + " has no depth plane");
    return false;
  }
  const double hole_depth = -hole_plane_frame->origin.z;
  if (!(hole_depth > 0) || std::abs(hole_plane_frame->z.z - 1) > 1e-9)
    return ctx.bad(*hole_plane,
                   ctx.d(*hole_plane) + " is not a depth plane below the top of " + ctx.d(*hole));
  const bool through = ctx.is(bottom, "through_bottom_condition");
  if (*thread_depth > hole_depth + kEps && !through)
    return ctx.bad(f, ctx.d(f) + " runs " + fmt(*thread_depth) + " deep, deeper than its hole " +
                          ctx.d(*hole) + " (" + fmt(hole_depth) + ")");

  // The tool: a thread drill-mill, whose drilling diameter is the hole's.
  const auto tool = ctx.tool();
  if (!tool) return false;
  if (!ctx.is(tool->body, "milling_threading_tool") && !ctx.is(tool->body, "thread_mill"))
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " is not a threading tool; " +
                                          ctx.d(op) + " on " + ctx.d(f) +
                                          " needs a thread drill-mill");
  const double tool_d = 2 * tool->radius;
  if (tool_d > hole_d->size + hole_d->upper + kEps || tool_d + hole_d->lower + kEps < hole_d->size)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " diameter " + fmt(tool_d) +
                                          " is not the diameter " + fmt(hole_d->size) + " of " +
                                          ctx.d(*hole) + " that " + ctx.d(op) + " drills for " +
                                          ctx.d(f));
  const double tip = tip_length(*tool);
  double bottom_z = -hole_depth;
  if (through) {
    bottom_z = -(hole_depth + tip + ctx.opt.through_clearance);
  } else if (ctx.is(bottom, "conical_hole_bottom")) {
    const auto angle = ctx.number(*bottom, "tip_angle");
    if (angle && tool->tip_half_angle &&
        std::abs(point_angle(*tool->tip_half_angle) - *angle) > 0.5)
      return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " point angle " +
                                            fmt(point_angle(*tool->tip_half_angle)) +
                                            " differs from tip_angle " + fmt(*angle) + " of " +
                                            ctx.d(*bottom) + " of " + ctx.d(*hole));
    bottom_z = -(hole_depth + tip);
  } else if (ctx.is(bottom, "blind_bottom_condition")) {
    if (tip > 0)
      ctx.note(*hole, ctx.d(*tool->instance) + "'s point leaves a cone in the " +
                          std::string(ctx.m.type_name(*bottom)) + " of " + ctx.d(*hole) +
                          "; another operation has to finish the bottom");
  } else {
    return ctx.not_implemented(ctx.d(op) + " in " + ctx.d(*hole) + " with " + ctx.d(*bottom));
  }
  if (tool->edge_length && *tool->edge_length + kEps < -bottom_z)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " cutting edge length " +
                                          fmt(*tool->edge_length) + " is shorter than the " +
                                          fmt(-bottom_z) + " that " + ctx.d(op) + " goes into " +
                                          ctx.d(*hole));
  if (!ctx.req.feed || !(*ctx.req.feed > 0))
    return ctx.bad(op, ctx.d(op) + " has no feed rate in its technology");
  const double r_z = ctx.number(op, "retract_plane").value_or(ctx.opt.clearance);
  if (!(r_z > 0)) return ctx.bad(op, ctx.d(op) + " retract_plane must be above the hole");
  const double dwell = ctx.number(op, "dwell_time_bottom").value_or(0);
  if (dwell < 0) return ctx.bad(op, ctx.d(op) + " dwell_time_bottom is negative");
  if (ctx.set(op, "its_machining_strategy") || ctx.set(op, "feed_on_retract"))
    return ctx.not_implemented(ctx.d(op) + " with a drilling strategy or feed_on_retract");

  // The helix keeps the tool's edge on the major diameter, and rises the thread's length:
  // counter-clockwise (seen from above) for a right-hand thread, whole and part turns.
  const double offset = *major / 2 - tool->radius;
  const double length = *thread_depth;
  const double turns = length / pitch;
  if (turns > static_cast<double>(ctx.opt.max_moves)) return ctx.limit_reached();
  const double whole = std::floor(turns + 1e-9);
  const double rest = turns - whole;
  const double end_angle = 2 * std::numbers::pi * rest * (right ? 1 : -1);
  int n = static_cast<int>(whole);
  if (rest > 1e-9) n += 1;
  n = std::max(n, 1);

  ctx.rapid({0, 0, r_z});
  ctx.feed({0, 0, bottom_z});
  if (dwell > 0) ctx.add({Move::Kind::Dwell, {}, {}, 1, dwell});
  if (bottom_z < -length - kEps) ctx.feed({0, 0, -length});
  ctx.feed({offset, 0, -length});
  ctx.arc({offset * std::cos(end_angle), offset * std::sin(end_angle), 0}, {0, 0, 0},
          right ? n : -n);
  ctx.feed({0, 0, 0});
  ctx.rapid({0, 0, r_z});
  return true;
}

}  // namespace ncpost::stepnc::features::legacy
