// SLOT (ISO 14649-10): a profile swept along a course of travel, closed by its end types.
//
// Square-U and rounded-U slots along a straight path with radiused, flat or open ends are
// rounded rectangles (one radius per corner), cleared like pockets (milling.cpp). Every other
// combination the generator makes is one or more passes of a form tool along the course of
// travel (slot_passes.cpp): a cone of the vee's angle, a ball of the partial circle's radius
// (or smaller balls stepped across it within FeatureOptions::profile_tolerance), a ball or an
// end mill of the slot's width along a circle or up a woodruff end. docs/features.md gives the
// reading of the standard behind each choice.

#include "slots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "milling.hpp"

namespace ncpost::stepnc::features::legacy {
namespace {

constexpr double kEps = 1e-9;
// A cone tool must have the vee's angle: at another angle it cuts the walls off by the depth
// times the difference (0.01° over 20 mm: 0.002 mm).
constexpr double kAngleMatch = 0.01;

double degrees(double radians) {
  return radians * 180 / std::numbers::pi;
}

bool read_path(Context& ctx, const Instance& f, const Instance& travel, SlotPath& path) {
  if (ctx.set(travel, "placement"))
    return ctx.not_implemented(ctx.d(f) + " with a placed course_of_travel " + ctx.d(travel));
  if (ctx.is(&travel, "linear_path")) {
    const auto length = ctx.toleranced(travel, "distance");
    const auto along = ctx.direction(travel, "its_direction");
    if (!length || !along || !(length->size > 0) || std::abs(along->z) > kEps)
      return ctx.bad(travel, ctx.d(travel) + " needs a positive distance in the slot's plane");
    if (!ctx.size_ok(travel, length->size, "distance")) return false;
    path.kind = SlotPath::Kind::Line;
    path.length = length->size;
    path.dir = *along * (1.0 / along->length());
    return true;
  }
  if (ctx.is(&travel, "circular_path")) {
    // The circle is centred on the placement; a partial one starts on its x axis and sweeps
    // counter-clockwise (clockwise for a negative sweep_angle).
    const auto radius = ctx.toleranced(travel, "radius");
    if (!radius || !(radius->size > 0))
      return ctx.bad(travel, ctx.d(travel) + " needs a positive radius");
    if (!ctx.size_ok(travel, radius->size, "radius")) return false;
    path.radius = radius->size;
    if (ctx.is(&travel, "complete_circular_path")) {
      path.kind = SlotPath::Kind::Circle;
      path.sweep = 2 * std::numbers::pi;
    } else {
      const auto sweep = ctx.number(travel, "sweep_angle");
      if (!sweep || !(std::abs(*sweep) > 1e-6) || !(std::abs(*sweep) < 360 - 1e-6))
        return ctx.bad(travel, ctx.d(travel) +
                                   " needs a sweep_angle strictly between -360 and 360 degrees "
                                   "and not 0 (a whole circle is a COMPLETE_CIRCULAR_PATH)");
      path.kind = SlotPath::Kind::Arc;
      path.sweep = radians(*sweep);
    }
    path.length = path.radius * std::abs(path.sweep);
    return true;
  }
  return ctx.not_implemented(ctx.d(f) + " along " + ctx.d(travel) +
                             " (linear and circular paths are)");
}

bool read_section(Context& ctx, const Instance& f, const Instance& swept, SlotSection& s) {
  if (ctx.set(swept, "placement"))
    return ctx.not_implemented(ctx.d(f) + " with a placed swept_shape " + ctx.d(swept));
  if (ctx.is(&swept, "square_u_profile")) {
    const auto w = ctx.toleranced(swept, "width");
    const auto r1 = ctx.toleranced(swept, "first_radius");
    const auto r2 = ctx.toleranced(swept, "second_radius");
    const auto a1 = ctx.number(swept, "first_angle");
    const auto a2 = ctx.number(swept, "second_angle");
    if (!w || !(w->size > 0)) return ctx.bad(swept, ctx.d(swept) + " needs a positive width");
    if (!ctx.size_ok(swept, w->size, "width")) return false;
    if ((a1 && std::abs(*a1 - 90) > 1e-6) || (a2 && std::abs(*a2 - 90) > 1e-6))
      return ctx.not_implemented(ctx.d(swept) + " with walls that are not vertical");
    if (r1 && r2 && std::abs(r1->size - r2->size) > kEps)
      return ctx.not_implemented(ctx.d(swept) + " with two different floor radii");
    s.kind = SlotSection::Kind::SquareU;
    s.half = w->size / 2;
    if (r1 && r1->size > 0) s.fillet = r1;
    return true;
  }
  if (ctx.is(&swept, "rounded_u_profile")) {
    const auto w = ctx.toleranced(swept, "width");
    if (!w || !(w->size > 0)) return ctx.bad(swept, ctx.d(swept) + " needs a positive width");
    if (!ctx.size_ok(swept, w->size, "width")) return false;
    s.kind = SlotSection::Kind::RoundedU;
    s.half = w->size / 2;
    s.radius = Toleranced{w->size / 2, w->upper / 2, w->lower / 2};
    return true;
  }
  if (ctx.is(&swept, "vee_profile")) {
    // ISO 10303-214 (whose vee_profile ISO 14649-10 uses): profile_angle is the angle between
    // the two sides, tilt_angle the angle between the first side and the profile's x axis
    // (across the slot). The vee is symmetric about the tool axis when the first side rises at
    // 90° - angle/2, which is the only vee a cone turning about that axis makes.
    const auto angle = ctx.number(swept, "profile_angle");
    const auto tilt = ctx.number(swept, "tilt_angle");
    const auto radius = ctx.toleranced(swept, "profile_radius");
    if (!angle || !(*angle > 0) || !(*angle < 180))
      return ctx.bad(swept, ctx.d(swept) + " profile_angle must be between 0 and 180 degrees");
    if (!tilt) return ctx.bad(swept, ctx.d(swept) + " has no tilt_angle");
    const double symmetric = 90 - *angle / 2;
    if (std::abs(*tilt - symmetric) > kAngleMatch)
      return ctx.not_implemented(
          ctx.d(f) + " with " + ctx.d(swept) + ", a vee tilted to one side (tilt_angle " +
          fmt(*tilt) + "; read as ISO 10303-214 does, the angle between its first side and its x " +
          "axis, a symmetric vee of " + fmt(*angle) + " degrees has " + fmt(symmetric) + ")");
    if (radius && radius->size < 0)
      return ctx.bad(swept, ctx.d(swept) + " profile_radius is negative");
    if (radius && !ctx.size_ok(swept, radius->size, "profile_radius")) return false;
    s.kind = SlotSection::Kind::Vee;
    s.angle = radians(*angle);
    s.radius = radius.value_or(Toleranced{});
    return true;
  }
  if (ctx.is(&swept, "partial_circular_profile")) {
    const auto radius = ctx.toleranced(swept, "radius");
    const auto sweep = ctx.number(swept, "sweep_angle");
    if (!radius || !(radius->size > 0))
      return ctx.bad(swept, ctx.d(swept) + " needs a positive radius");
    if (!ctx.size_ok(swept, radius->size, "radius")) return false;
    if (!sweep || !(*sweep > 0) || *sweep > 180 + 1e-9)
      return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(swept) +
                                 " whose sweep_angle is not in (0, 180] degrees (a wider arc "
                                 "undercuts its own top)");
    s.kind = SlotSection::Kind::PartialCircular;
    s.radius = *radius;
    s.sweep = radians(*sweep);
    return true;
  }
  return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(swept) +
                             " (square-U, rounded-U, vee and partial-circular slots are)");
}

bool read_ends(Context& ctx, const Instance& f, SlotEnd (&end)[2], std::size_t& count) {
  const auto list = ctx.g.get(f, "end_conditions");
  count = 0;
  if (!list || !list->is_list()) return true;
  const auto items = ctx.m.items(*list);
  if (items.size() > 2) return ctx.bad(f, ctx.d(f) + " has more than two end_conditions");
  count = items.size();
  for (std::size_t k = 0; k < items.size(); ++k) {
    const Instance* e = ctx.g.instance(items[k], "slot_end_type", &f, "end_conditions");
    if (e == nullptr) return false;
    SlotEnd& out = end[k];
    out.instance = e;
    if (ctx.is(e, "radiused_slot_end_type")) {
      out.kind = SlotEnd::Kind::Radiused;
    } else if (ctx.is(e, "open_slot_end_type")) {
      out.kind = SlotEnd::Kind::Open;
    } else if (ctx.is(e, "loop_slot_end_type")) {
      out.kind = SlotEnd::Kind::Loop;
    } else if (ctx.is(e, "flat_slot_end_type")) {
      out.kind = SlotEnd::Kind::Flat;
      const auto c1 = ctx.toleranced(*e, "corner_radius1");
      const auto c2 = ctx.toleranced(*e, "corner_radius2");
      out.right = c1 ? c1->size : 0;
      out.left = c2 ? c2->size : 0;
      if (out.right < 0 || out.left < 0)
        return ctx.bad(*e, ctx.d(*e) + " has a negative corner radius");
      if (!ctx.size_ok(*e, std::max(out.right, out.left), "corner radius")) return false;
    } else if (ctx.is(e, "woodruff_slot_end_type")) {
      out.kind = SlotEnd::Kind::Woodruff;
      const auto r = ctx.toleranced(*e, "radius");
      if (!r || !(r->size > 0)) return ctx.bad(*e, ctx.d(*e) + " needs a positive radius");
      if (!ctx.size_ok(*e, r->size, "radius")) return false;
      out.woodruff = *r;
    } else {
      return ctx.not_implemented(ctx.d(f) + " with end type " + ctx.d(*e));
    }
  }
  // One end type for a slot with two ends: both ends are of that type (ISO 14649-10 allows one
  // item only for a loop; a single other item is read leniently, as before).
  if (items.size() == 1) end[1] = end[0];
  return true;
}

// Which side of the spindle's turning a pass is climb milling: the wall outside a counter-
// clockwise ring is on the tool's right, which with a clockwise spindle is climb milling.
bool counter_clockwise(Context& ctx, const OperationData& o) {
  const bool spindle_cw = !ctx.req.spindle || *ctx.req.spindle <= 0;
  const std::string_view cutmode =
      o.strategy ? ctx.enumeration(*o.strategy, "cutmode") : std::string_view();
  const std::string_view rotation =
      o.strategy ? ctx.enumeration(*o.strategy, "rotation_direction") : std::string_view();
  if (!rotation.empty()) return rotation == "CCW";
  return cutmode == "CONVENTIONAL" ? !spindle_cw : spindle_cw;
}

// ---- Square-U and rounded-U slots along a straight path: a rounded rectangle -----------------

bool rectangle_slot(Context& ctx, const SlotPath& path, const SlotSection& section,
                    const SlotEnd (&end)[2]) {
  const auto tool = ctx.tool();
  if (!tool) return false;
  const OperationData o = ctx.operation();
  const double half = section.half;
  const double runout = tool->radius + ctx.opt.clearance;
  // Extent along the course of travel (s from its start) and the corners at each end: a
  // radiused end is a half circle about the end of the course of travel, a flat end a wall at
  // it (corner_radius1 on the right of the travel direction, corner_radius2 on the left), an
  // open end lets the tool run out of the slot.
  const auto reach = [&](const SlotEnd& e) {
    return e.kind == SlotEnd::Kind::Radiused ? half : e.kind == SlotEnd::Kind::Open ? runout : 0.0;
  };
  const auto corner = [&](const SlotEnd& e, bool left) {
    if (e.kind == SlotEnd::Kind::Radiused) return half;
    if (e.kind == SlotEnd::Kind::Open) return tool->radius + o.allowance_side;
    return std::min(left ? e.left : e.right, half);
  };
  const double s0 = -reach(end[0]);
  const double s1 = path.length + reach(end[1]);
  Region region;
  // Corners counter-clockwise from (+a, +b): the second end (+x) left, the first end (-x) left,
  // the first end right, the second end right.
  const std::array<double, 4> corners{corner(end[1], true), corner(end[0], true),
                                      corner(end[0], false), corner(end[1], false)};
  double in_material = half;
  bool any_in_material = false;
  for (int k = 0; k < 4; ++k) {
    const SlotEnd& e = end[k == 0 || k == 3 ? 1 : 0];
    if (e.kind == SlotEnd::Kind::Open) continue;
    any_in_material = true;
    in_material = std::min(in_material, corners[static_cast<std::size_t>(k)]);
  }
  region.shape = Shape::rectangle((s1 - s0) / 2, half, in_material);
  if (std::any_of(corners.begin(), corners.end(),
                  [&](double c) { return std::abs(c - corners[0]) > kEps; }))
    region.shape.corners = corners;
  else
    region.shape.corner = corners[0];
  region.corners_in_material = any_in_material;
  // The slot's frame: centred half way along its extent, x along the course of travel.
  region.shape.frame.origin = path.dir * ((s0 + s1) / 2);
  region.shape.frame.x = path.dir;
  region.shape.frame.y = Vec3{0, 0, 1}.cross(path.dir);
  if (section.kind == SlotSection::Kind::RoundedU) {
    // A full-round floor: only a ball of the slot's width, along the centre line.
    region.fillet = section.radius;
    region.centre_only = true;
  } else {
    region.fillet = section.fillet;
  }
  if (ctx.is(o.strategy, "center_milling")) region.centre_only = true;
  region.walls_only = ctx.is(&ctx.op(), "side_milling");
  return clear_region(ctx, region);
}

// ---- The form-tool slots: what each profile asks of its tool --------------------------------

// A tool turning about its axis makes a section of the slot exactly when its profile is the
// section's: `tip` is the depth of its tip (below the top, > 0) on the final pass, `offsets`
// the passes across the slot as (distance from the course of travel, tip depth).
bool vee_passes(Context& ctx, const Tool& tool, const OperationData& o, const SlotSection& s,
                double depth, std::vector<SlotPass>& passes) {
  const Instance& f = ctx.feature();
  // A cone: a countersink, or a milling cutter with a point (its tool_tip_half_angle, read as
  // for drills: NIST's angle between the cutting edge and the plane normal to the axis below
  // 90 degrees, the whole point angle from 90 on).
  const bool cone_body = ctx.is(tool.body, "countersink") || ctx.is(tool.body, "milling_cutter") ||
                         ctx.is(tool.body, "user_defined_tool");
  if (!cone_body || !tool.tip_half_angle || !(*tool.tip_half_angle > 0) ||
      !(*tool.tip_half_angle < 180))
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " has no cone of " +
                                         fmt(degrees(s.angle)) + " degrees to make " + ctx.d(f) +
                                         "'s vee (a countersink or a pointed cutter "
                                         "of the vee's angle is needed)");
  const double point =
      *tool.tip_half_angle < 90 ? 180 - 2 * *tool.tip_half_angle : *tool.tip_half_angle;
  if (std::abs(point - degrees(s.angle)) > kAngleMatch)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " point angle " + fmt(point) +
                                         " differs from the profile_angle " +
                                         fmt(degrees(s.angle)) + " of " + ctx.d(f));
  const double rho = s.radius.size;
  const double c = tool.corner_radius;
  if (c > rho + s.radius.upper + kEps || c < rho - s.radius.lower - kEps)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " tip radius " + fmt(c) +
                                         " is not the vee's profile_radius " + fmt(rho) + " of " +
                                         ctx.d(f) + " within its tolerance");
  const double half = s.angle / 2;
  const double sin_half = std::sin(half);
  // Lifted along the axis by `lift`, the cone stays a_s off the walls (normal to them) and a_b
  // off the bottom; a sharper tip than the vee's radius is lifted until it touches the bottom.
  const double lift = std::max(o.allowance_bottom, o.allowance_side / sin_half) +
                      std::max(0.0, (rho - c) * (1 / sin_half - 1));
  const double tip = depth - lift;
  if (!(tip > 0))
    return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
  // The cone must reach the top of the walls: its width at the top of the slot is what the
  // tool's diameter has to cover.
  const double apex_below_tip = c / sin_half - c;
  const double needed = (tip + apex_below_tip) * std::tan(half);
  if (tool.radius + kEps < needed)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " diameter " + fmt(2 * tool.radius) +
                                         " is narrower than the " + fmt(2 * needed) + " that " +
                                         ctx.d(f) + "'s vee is wide at its top");
  // The flank touches the walls over the whole depth: its length along the cone (the edge
  // length, whichever way it is measured, covers at least that height once projected).
  if (tool.edge_length && *tool.edge_length * std::cos(half) + kEps < tip)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " cutting edge length " +
                                         fmt(*tool.edge_length) + " does not reach the " +
                                         fmt(tip) + " deep walls of " + ctx.d(f));
  passes.push_back({0, tip});
  return true;
}

bool ball_check(Context& ctx, const Tool& tool, const std::string& what) {
  const bool ball = ctx.is(tool.body, "ball_endmill") || tool.corner_radius >= tool.radius - kEps;
  if (ball) return true;
  return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " is not a ball end mill; " +
                                       ctx.d(ctx.feature()) + ", " + what);
}

// The largest step (radians) between two ball centres on a circle of radius rc (a ball of
// radius r in a concave circle of radius rs = rc + r) that leaves a cusp of at most h.
double scallop_step(double rc, double r, double h) {
  const double rs = rc + r;
  const auto cusp = [&](double step) {
    const double s = rc * std::sin(step / 2);
    return rs - (rc * std::cos(step / 2) + std::sqrt(std::max(0.0, r * r - s * s)));
  };
  double lo = 0;
  double hi = std::numbers::pi / 2;
  if (cusp(hi) <= h) return hi;
  for (int i = 0; i < 60; ++i) {
    const double mid = (lo + hi) / 2;
    (cusp(mid) <= h ? lo : hi) = mid;
  }
  return lo;
}

bool partial_circle_passes(Context& ctx, const Tool& tool, const OperationData& o,
                           const SlotSection& s, double depth, std::vector<SlotPass>& passes,
                           bool& stepped) {
  const Instance& f = ctx.feature();
  const double R = s.radius.size;
  // The arc, its lowest point on the depth plane, must reach the top of the slot: a shallower
  // arc would leave the slot's upper walls undefined.
  if (R * (1 - std::cos(s.sweep / 2)) + 1e-9 < depth)
    return ctx.bad(f, ctx.d(f) + " is " + fmt(depth) + " deep, but its partial circle (radius " +
                          fmt(R) + ", " + fmt(degrees(s.sweep)) + " degrees) ends " +
                          fmt(R * (1 - std::cos(s.sweep / 2))) + " above its bottom");
  if (!ball_check(ctx, tool, "a partial-circular slot, takes a ball of at most its radius"))
    return false;
  const double r = tool.radius;
  if (r > R + s.radius.upper + kEps)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " radius " + fmt(r) +
                                         " is larger than the radius " + fmt(R) + " of " +
                                         ctx.d(f) + "'s partial circle");
  const double allowance = std::max(o.allowance_side, o.allowance_bottom);
  if (allowance == 0 && r >= R - s.radius.lower - kEps) {
    // A ball of the profile's radius: one pass along the centre, its tip on the bottom.
    stepped = false;
    passes.push_back({0, depth});
    return true;
  }
  // A smaller ball: passes across the circle, each ball centre on the circle of radius
  // R - allowance - r about the profile's centre, close enough for the cusps between them to
  // stay within the profile tolerance.
  const double rc = R - allowance - r;
  if (!(rc > 1e-6))
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " radius " + fmt(r) + " + allowance " +
                                         fmt(allowance) + " of " + ctx.d(ctx.op()) +
                                         " leaves no room in the radius " + fmt(R) + " of " +
                                         ctx.d(f));
  stepped = true;
  const double centre = R - depth;  // the profile's centre above the top (>= 0)
  const double top = std::acos(std::clamp(centre / R, -1.0, 1.0));  // where it meets the top
  const double dpsi = scallop_step(rc, r, ctx.opt.profile_tolerance);
  if (!(dpsi > 1e-9) || top / dpsi > static_cast<double>(ctx.opt.max_moves)) {
    ctx.limit_reached();
    return false;
  }
  const auto n = static_cast<std::size_t>(std::ceil(top / dpsi - 1e-9));
  for (std::size_t j = 0; j <= n; ++j) {
    const double psi = n == 0 ? 0 : top * static_cast<double>(j) / static_cast<double>(n);
    // Tip depth below the top: the ball centre is rc·cos ψ below the profile's centre.
    passes.push_back({rc * std::sin(psi), rc * std::cos(psi) + r - centre});
  }
  return true;
}

}  // namespace

bool generate_slot(Context& ctx) {
  const Instance& f = ctx.feature();
  if (!ctx.is(&ctx.op(), "bottom_and_side_milling") && !ctx.is(&ctx.op(), "side_milling"))
    return ctx.not_implemented(ctx.d(ctx.op()) + " on " + ctx.d(f) +
                               " (slots take bottom-and-side or side milling)");
  const Instance* travel = ctx.ref(f, "course_of_travel", "travel_path");
  const Instance* swept = ctx.ref(f, "swept_shape", "open_profile");
  if (travel == nullptr || swept == nullptr)
    return ctx.bad(f, ctx.d(f) + " needs a course_of_travel and a swept_shape");
  SlotPath path;
  SlotSection section;
  SlotEnd end[2];
  std::size_t end_count = 0;
  if (!read_path(ctx, f, *travel, path) || !read_section(ctx, f, *swept, section) ||
      !read_ends(ctx, f, end, end_count))
    return false;

  // Ends against the path (ISO 14649-10: a loop end closes a slot whose path closes, alone).
  const bool loop =
      end_count > 0 && (end[0].kind == SlotEnd::Kind::Loop || end[1].kind == SlotEnd::Kind::Loop);
  if (path.kind == SlotPath::Kind::Circle) {
    if (end_count > 0 && !(end_count == 1 && loop))
      return ctx.bad(f, ctx.d(f) + " runs along the closed " + ctx.d(*travel) +
                            ": its only end condition can be a LOOP_SLOT_END_TYPE");
  } else {
    if (loop)
      return ctx.bad(f, ctx.d(f) + " has a LOOP_SLOT_END_TYPE, but its course of travel " +
                            ctx.d(*travel) + " does not close");
    if (end_count == 0)
      return ctx.bad(f, ctx.d(f) + " has no end_conditions: the shape of its ends is unknown");
  }
  const auto has = [&](SlotEnd::Kind k) {
    return path.kind != SlotPath::Kind::Circle && (end[0].kind == k || end[1].kind == k);
  };
  const bool u_profile =
      section.kind == SlotSection::Kind::SquareU || section.kind == SlotSection::Kind::RoundedU;
  if (path.kind == SlotPath::Kind::Line && u_profile && !has(SlotEnd::Kind::Woodruff))
    return rectangle_slot(ctx, path, section, end);

  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  if (ctx.is(&ctx.op(), "side_milling"))
    return ctx.not_implemented(
        ctx.d(ctx.op()) + " on " + ctx.d(f) + " with " + ctx.d(*swept) +
        (path.kind == SlotPath::Kind::Line ? std::string() : " along " + ctx.d(*travel)) +
        " (its walls are the form tool's, made by bottom-and-side milling)");
  if (o.strategy != nullptr && !ctx.is(o.strategy, "center_milling") &&
      !ctx.is(o.strategy, "contour_parallel"))
    return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f) + ", which " +
                               ctx.d(*tool->instance) + " machines along its course of travel");

  // What the ends allow.
  for (const SlotEnd& e : end) {
    if (path.kind == SlotPath::Kind::Circle) break;
    if (e.kind == SlotEnd::Kind::Flat)
      return ctx.not_implemented(
          ctx.d(f) + " with " + ctx.d(*swept) +
          (path.kind == SlotPath::Kind::Arc ? " along " + ctx.d(*travel) : std::string()) +
          " and the flat end " + ctx.d(e.instance) +
          " (a form tool cannot make a flat end across the profile)");
    if (e.kind == SlotEnd::Kind::Open && path.kind == SlotPath::Kind::Arc)
      return ctx.not_implemented(ctx.d(f) + " along " + ctx.d(*travel) + " with the open end " +
                                 ctx.d(e.instance));
    if (e.kind == SlotEnd::Kind::Woodruff) {
      if (section.kind == SlotSection::Kind::SquareU) {
        // The woodruff end is the swept profile turned about an axis across the slot: with a
        // square-U profile its corners with the walls are sharp at every height, which no tool
        // turning about a vertical axis leaves.
        if (ctx.is(tool->body, "woodruff_keyseat_mill"))
          return ctx.not_implemented(ctx.d(f) + "'s woodruff end " + ctx.d(e.instance) + " with " +
                                     ctx.d(*tool->instance) +
                                     ", which cuts with its axis across the slot (the "
                                     "generator's tools turn about the feature's z axis)");
        return ctx.unfit(*tool->instance,
                         ctx.d(*tool->instance) + " cannot make the woodruff end " +
                             ctx.d(e.instance) + " of " + ctx.d(f) +
                             ": the end meets the square-U walls in sharp corners at every "
                             "height, which a tool turning about the vertical leaves rounded");
      }
      if (section.kind == SlotSection::Kind::Vee)
        return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(*swept) + " and the woodruff end " +
                                   ctx.d(e.instance) + " (a cone cannot follow the turned vee)");
      if (path.kind != SlotPath::Kind::Line)
        return ctx.not_implemented(ctx.d(f) + " along " + ctx.d(*travel) +
                                   " with the woodruff end " + ctx.d(e.instance));
      if (e.woodruff.size + kEps < *depth)
        return ctx.not_implemented(ctx.d(f) + "'s woodruff end " + ctx.d(e.instance) +
                                   " of radius " + fmt(e.woodruff.size) + ", less than the " +
                                   fmt(*depth) + " depth (its arc would turn under the top)");
    }
  }

  // The passes across the profile.
  SlotPlan plan;
  plan.path = path;
  plan.end[0] = end[0];
  plan.end[1] = end[1];
  plan.tool_radius = tool->radius;
  plan.ccw = counter_clockwise(ctx, o);
  bool stepped = false;
  switch (section.kind) {
    case SlotSection::Kind::Vee:
      if (!vee_passes(ctx, *tool, o, section, *depth, plan.passes)) return false;
      break;
    case SlotSection::Kind::PartialCircular: {
      double overlap = 0;
      const double step = stepover(ctx, *tool, o, overlap);
      if (!check_overlap(ctx, o, overlap)) return false;
      if (!partial_circle_passes(ctx, *tool, o, section, *depth, plan.passes, stepped))
        return false;
      plan.stepover = step;
      plan.ball_radius = tool->radius;
      break;
    }
    case SlotSection::Kind::RoundedU: {
      // A ball of the slot's width along its centre (as for the straight slot).
      if (!ball_check(ctx, *tool, "a rounded-U slot, takes a ball of its width")) return false;
      const double inset = tool->radius + o.allowance_side;
      if (std::abs(section.half - inset) > 1e-3)
        return ctx.unfit(*tool->instance,
                         ctx.d(*tool->instance) + " diameter " + fmt(2 * tool->radius) +
                             " + allowances is not the width " + fmt(2 * section.half) + " of " +
                             ctx.d(f) + ", which a ball cuts in one pass");
      const double tip = *depth - o.allowance_bottom;
      if (!(tip > 0))
        return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
      plan.passes.push_back({0, tip});
      plan.ball_radius = tool->radius;
      break;
    }
    case SlotSection::Kind::SquareU: {
      // Along a circle: an end mill of the slot's width along the centre (center milling).
      const double inset = tool->radius + o.allowance_side;
      if (section.half - inset < -kEps || section.half - inset > 1e-3)
        return ctx.unfit(*tool->instance,
                         ctx.d(*tool->instance) + " diameter " + fmt(2 * tool->radius) +
                             " + allowances is not the width " + fmt(2 * section.half) + " of " +
                             ctx.d(f) + " along " + ctx.d(*travel) +
                             " (only a tool of the slot's width, along its centre, is generated "
                             "there)");
      const double fillet = section.fillet ? section.fillet->size : 0;
      const double upper = section.fillet ? section.fillet->upper : 0;
      const double lower = section.fillet ? section.fillet->lower : 0;
      if (tool->corner_radius > fillet + upper + o.allowance_bottom + kEps ||
          tool->corner_radius + lower + kEps < fillet)
        return ctx.unfit(*tool->instance,
                         ctx.d(*tool->instance) + " edge radius " + fmt(tool->corner_radius) +
                             " is not the floor radius " + fmt(fillet) + " of " + ctx.d(f));
      const double tip = *depth - o.allowance_bottom;
      if (!(tip > 0))
        return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
      plan.passes.push_back({0, tip});
      break;
    }
  }
  if (stepped && (path.kind != SlotPath::Kind::Line || has(SlotEnd::Kind::Woodruff)))
    return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(*swept) + " cut by " +
                               ctx.d(*tool->instance) + ", smaller than its radius, " +
                               (path.kind != SlotPath::Kind::Line
                                    ? "along " + ctx.d(*travel)
                                    : std::string("with a woodruff end")) +
                               " (stepped passes are generated along straight slots with "
                               "radiused or open ends)");
  // A woodruff end turns the profile about its axis: a ball larger than its radius (less the
  // allowance) does not fit in it.
  for (const SlotEnd& e : end) {
    if (e.kind != SlotEnd::Kind::Woodruff || path.kind == SlotPath::Kind::Circle) continue;
    const double allowance = *depth - plan.passes.front().depth;
    if (plan.ball_radius + allowance > e.woodruff.size + e.woodruff.upper + kEps)
      return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " radius " +
                                            fmt(plan.ball_radius) + " + allowance " +
                                            fmt(allowance) + " > the radius " +
                                            fmt(e.woodruff.size) + " of the woodruff end " +
                                            ctx.d(e.instance) + " of " + ctx.d(f));
  }
  // Into a woodruff end the tool comes down along its arc, which is as steep as the end is at
  // the top of the slot: a ramp or zigzag approach must allow that.
  if (o.approach != nullptr &&
      (ctx.is(o.approach, "plunge_ramp") || ctx.is(o.approach, "plunge_zigzag"))) {
    const double allowed = ctx.number(*o.approach, "angle").value_or(0);
    for (const SlotEnd& e : end) {
      if (e.kind != SlotEnd::Kind::Woodruff) continue;
      const double r = plan.ball_radius;
      const double allowance = *depth - plan.passes.front().depth;
      const double rho = e.woodruff.size - r - allowance;
      const double axis = -*depth + e.woodruff.size;
      // The ball leaves the material where its tip reaches the top; the arc's slope there.
      const double steepest =
          rho > 1e-9 ? degrees(std::acos(std::clamp((axis - r) / rho, -1.0, 1.0))) : 90;
      if (std::min(steepest, 90.0) > allowed + 1e-9)
        return ctx.not_implemented(ctx.d(*o.approach) + " at " + fmt(allowed) + " degrees into " +
                                   ctx.d(f) + ", whose woodruff end " + ctx.d(e.instance) +
                                   " the tool follows down at up to " +
                                   fmt(std::min(steepest, 90.0)) + " degrees");
    }
  }
  return slot_passes(ctx, *tool, o, plan, *depth);
}

}  // namespace ncpost::stepnc::features::legacy
