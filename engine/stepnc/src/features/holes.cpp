// ROUND_HOLE with the drilling-type operations → canonical cycles (drill, peck, tap, bore,
// ream), or explicit motions where the operation asks for what no cycle expresses (changing
// feed or speed within the hole, a first peck unlike the others, a dwell between pecks).

#include <cmath>
#include <numbers>

#include "context.hpp"

namespace ncpost::stepnc::features::legacy {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

// The part of a pointed tool below its full diameter. NIST's ex1 gives a 20 mm twist drill a
// tool_tip_half_angle of 31°: read as the angle between the cutting edge and the plane normal
// to the axis (a standard 118° point), as NIST's interpreter does.
// A value of 90° or more cannot be a half angle in either reading; it is taken as the whole
// point angle (the project's bracket example gives its drill 118).
double tip_length(const Tool& tool) {
  if (!tool.tip_half_angle || !(*tool.tip_half_angle > 0) || !(*tool.tip_half_angle < 180))
    return 0;
  const double a = *tool.tip_half_angle * std::numbers::pi / 180.0;
  return *tool.tip_half_angle < 90 ? tool.radius * std::tan(a) : tool.radius / std::tan(a / 2);
}

double point_angle(double tip_half_angle) {
  return tip_half_angle < 90 ? 180 - 2 * tip_half_angle : tip_half_angle;
}

namespace {

struct Strategy {
  double cut_start = 1, feed_start = 1, depth_start = 0;
  double cut_end = 1, feed_end = 1, depth_end = 0;
  [[nodiscard]] bool any() const {
    return (depth_start > 0 && (cut_start != 1 || feed_start != 1)) ||
           (depth_end > 0 && (cut_end != 1 || feed_end != 1));
  }
};

}  // namespace

bool generate_hole(Context& ctx) {
  const Instance& f = ctx.feature();
  const Instance& op = ctx.op();
  if (!ctx.is(&op, "drilling_type_operation"))
    return ctx.not_implemented(ctx.d(op) + " on " + ctx.d(f) +
                               " (round holes take the drilling-type operations)");
  enum class Kind { Drill, Peck, Ream, Bore, Tap } kind = Kind::Drill;
  if (ctx.is(&op, "multistep_drilling"))
    kind = Kind::Peck;
  else if (ctx.is(&op, "drilling_operation"))  // drilling, center drilling, counter sinking
    kind = Kind::Drill;
  else if (ctx.is(&op, "reaming"))
    kind = Kind::Ream;
  else if (ctx.is(&op, "boring"))
    kind = Kind::Bore;
  else if (ctx.is(&op, "tapping"))
    kind = Kind::Tap;
  else
    return ctx.not_implemented(ctx.d(op) + " on " + ctx.d(f));
  if (ctx.set(f, "change_in_diameter")) return ctx.not_implemented(ctx.d(f) + " with a taper");
  const auto diameter = ctx.toleranced(f, "diameter");
  const Instance* bottom = ctx.ref(f, "bottom_condition", "hole_bottom_condition");
  if (!diameter || bottom == nullptr)
    return ctx.bad(f, ctx.d(f) + " needs a diameter and a bottom_condition");
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  if (!ctx.req.feed || !(*ctx.req.feed > 0))
    return ctx.bad(op, ctx.d(op) + " has no feed rate in its technology");

  // Size: a drill may be smaller than the hole (a reamer or boring bar finishes it); a reamer
  // or a tap is the hole's size.
  const double tool_d = 2 * tool->radius;
  if (tool_d > diameter->size + diameter->upper + kEps)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " diameter " + fmt(tool_d) +
                                          " > diameter " + fmt(diameter->size) + " + " +
                                          fmt(diameter->upper) + " of " + ctx.d(f));
  if ((kind == Kind::Ream || kind == Kind::Tap) && tool_d + diameter->lower + kEps < diameter->size)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " diameter " + fmt(tool_d) +
                                          " < diameter " + fmt(diameter->size) + " - " +
                                          fmt(diameter->lower) + " of " + ctx.d(f) + " for " +
                                          ctx.d(op));

  // Depth of the tool tip.
  const bool pointed = kind == Kind::Drill || kind == Kind::Peck;
  const double tip = pointed ? tip_length(*tool) : 0;
  double bottom_z = -*depth;
  const auto cutting_depth = ctx.number(op, "cutting_depth");
  if (cutting_depth) {
    if (!(*cutting_depth > 0) || *cutting_depth > *depth + tip + ctx.opt.through_clearance + kEps)
      return ctx.bad(op, ctx.d(op) + " cutting_depth " + fmt(*cutting_depth) +
                             " is not within the depth of " + ctx.d(f));
    bottom_z = -*cutting_depth;
  } else if (ctx.is(bottom, "through_bottom_condition")) {
    bottom_z = -(*depth + tip + ctx.opt.through_clearance);
  } else if (ctx.is(bottom, "conical_hole_bottom")) {
    // The depth plane ends the cylinder; the drill's own point makes the cone below it.
    const auto angle = ctx.number(*bottom, "tip_angle");
    if (pointed && angle && tool->tip_half_angle &&
        std::abs(point_angle(*tool->tip_half_angle) - *angle) > 0.5)
      return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " point angle " +
                                            fmt(point_angle(*tool->tip_half_angle)) +
                                            " differs from tip_angle " + fmt(*angle) + " of " +
                                            ctx.d(*bottom) + " of " + ctx.d(f));
    bottom_z = -(*depth + tip);
  } else if (ctx.is(bottom, "blind_bottom_condition")) {
    // Flat, flat with radius, spherical: the tip stops at the depth plane, never below it.
    if (pointed && tip > 0)
      ctx.note(f, ctx.d(*tool->instance) + "'s point leaves a cone in the " +
                      std::string(ctx.m.type_name(*bottom)) + " of " + ctx.d(f) +
                      "; another operation has to finish the bottom");
  } else {
    return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(*bottom));
  }
  if (tool->edge_length && *tool->edge_length + kEps < -bottom_z)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " cutting edge length " +
                                          fmt(*tool->edge_length) + " is shorter than the " +
                                          fmt(-bottom_z) + " that " + ctx.d(op) + " goes into " +
                                          ctx.d(f));

  const double r_z = ctx.number(op, "retract_plane").value_or(ctx.opt.clearance);
  if (!(r_z > 0)) return ctx.bad(op, ctx.d(op) + " retract_plane must be above the hole");
  const double feed = *ctx.req.feed;
  const double dwell = ctx.number(op, "dwell_time_bottom").value_or(0);
  if (dwell < 0) return ctx.bad(op, ctx.d(op) + " dwell_time_bottom is negative");
  const auto retract_ratio = ctx.number(op, "feed_on_retract");

  Strategy s;
  if (const Instance* st = ctx.ref(op, "its_machining_strategy", "drilling_type_strategy")) {
    s.cut_start = ctx.number(*st, "reduced_cut_at_start").value_or(1);
    s.feed_start = ctx.number(*st, "reduced_feed_at_start").value_or(1);
    s.depth_start = ctx.number(*st, "depth_of_start").value_or(0);
    s.cut_end = ctx.number(*st, "reduced_cut_at_end").value_or(1);
    s.feed_end = ctx.number(*st, "reduced_feed_at_end").value_or(1);
    s.depth_end = ctx.number(*st, "depth_of_end").value_or(0);
    for (const double ratio : {s.cut_start, s.feed_start, s.cut_end, s.feed_end})
      if (!(ratio > 0)) return ctx.bad(*st, ctx.d(*st) + " has a ratio that is not positive");
  }

  Move cycle{Move::Kind::Cycle, {0, 0, r_z}};
  cycle.bottom = bottom_z;
  cycle.feed = feed;
  cycle.dwell = dwell;
  std::optional<double> first_peck;
  double peck_dwell = 0;
  switch (kind) {
    case Kind::Drill:
      cycle.cycle = Move::CycleKind::Drill;
      break;
    case Kind::Peck: {
      cycle.cycle = Move::CycleKind::Peck;
      const auto first = ctx.number(op, "first_depth");
      const auto step = ctx.number(op, "depth_of_step");
      const auto back = ctx.number(op, "retract_distance");
      if (!first || !step || !back || !(*first > 0) || !(*step > 0) || *back < 0)
        return ctx.bad(op, ctx.d(op) +
                               " needs a positive first_depth and depth_of_step and a "
                               "retract_distance >= 0");
      if (static_cast<double>(ctx.opt.max_moves) * *step < -bottom_z) return ctx.limit_reached();
      cycle.peck = *step;
      cycle.peck_retract = *back;
      peck_dwell = ctx.number(op, "dwell_time_step").value_or(0);
      if (std::abs(*first - *step) > kEps) first_peck = *first;
      break;
    }
    case Kind::Ream:
    case Kind::Bore: {
      const bool stop = ctx.boolean(op, "spindle_stop_at_bottom").value_or(false);
      cycle.cycle = stop || kind == Kind::Bore ? Move::CycleKind::Bore : Move::CycleKind::Ream;
      cycle.spindle_stop = stop;
      if (ctx.set(op, "depth_of_testcut") || ctx.set(op, "waiting_position"))
        return ctx.not_implemented(ctx.d(op) + " with a test cut or waiting position");
      break;
    }
    case Kind::Tap: {
      cycle.cycle = Move::CycleKind::Tap;
      // Rigid tapping: the technology's feed and speed are pitch × speed and speed.
      if (!ctx.req.spindle || *ctx.req.spindle == 0)
        return ctx.bad(op, ctx.d(op) + " has no spindle speed, so the thread pitch is unknown");
      cycle.rpm = std::abs(*ctx.req.spindle) * 60.0;
      cycle.pitch = feed / cycle.rpm;
      cycle.left_hand = tool->left_hand;
      // The cycle reverses the spindle to come out; going in it must turn with the thread
      // (NIST's sign: negative is clockwise, a right-hand tap's direction).
      if ((*ctx.req.spindle > 0) != tool->left_hand)
        return ctx.unfit(*tool->instance,
                         ctx.d(*tool->instance) + " is a " + (tool->left_hand ? "left" : "right") +
                             "-hand tap, but the spindle of " + ctx.d(op) + " turns " +
                             (*ctx.req.spindle > 0 ? "counter-clockwise" : "clockwise") + " in " +
                             ctx.d(f));
      break;
    }
  }

  if (!s.any() && !first_peck && peck_dwell == 0 && !retract_ratio) {
    ctx.add(cycle);
    return true;
  }
  if (kind == Kind::Tap || kind == Kind::Bore || kind == Kind::Ream)
    return ctx.not_implemented(ctx.d(op) + " with a drilling strategy or feed_on_retract");

  // Explicit motions: what the cycle cannot say.
  ctx.rapid({0, 0, r_z});
  const double base_spindle = ctx.req.spindle.value_or(0);
  const auto set_feed = [&](double v) { ctx.add({Move::Kind::FeedRate, {}, {}, 1, v}); };
  const auto set_spindle = [&](double v) { ctx.add({Move::Kind::Spindle, {}, {}, 1, v}); };
  const double z_start = std::max(bottom_z, -s.depth_start);
  const double z_end = std::min(0.0, bottom_z + s.depth_end);
  // Feed and speed at a height: reduced near the top and near the bottom.
  const auto zone = [&](double z) { return z > z_start + kEps ? 0 : z > z_end + kEps ? 1 : 2; };
  int current = -1;
  const auto feed_to = [&](double from, double to) {
    // Split at the zone borders so each piece runs at its zone's feed and speed.
    for (const double border : {z_start, z_end}) {
      if (border < from - kEps && border > to + kEps) {
        const int z = zone(from - kEps);
        if (z != current) {
          set_feed(feed * (z == 0 ? s.feed_start : z == 2 ? s.feed_end : 1));
          if (base_spindle != 0)
            set_spindle(base_spindle * (z == 0 ? s.cut_start : z == 2 ? s.cut_end : 1));
          current = z;
        }
        ctx.feed({0, 0, border});
        from = border;
      }
    }
    const int z = zone(from - kEps);
    if (z != current) {
      set_feed(feed * (z == 0 ? s.feed_start : z == 2 ? s.feed_end : 1));
      if (base_spindle != 0)
        set_spindle(base_spindle * (z == 0 ? s.cut_start : z == 2 ? s.cut_end : 1));
      current = z;
    }
    ctx.feed({0, 0, to});
  };
  if (kind == Kind::Drill) {
    feed_to(r_z, bottom_z);
  } else {
    double at = r_z;
    double target = std::max(bottom_z, -first_peck.value_or(cycle.peck));
    for (;;) {
      feed_to(at, target);
      if (target <= bottom_z + kEps) break;
      if (peck_dwell > 0) ctx.add({Move::Kind::Dwell, {}, {}, 1, peck_dwell});
      at = target + cycle.peck_retract;
      if (cycle.peck_retract > 0)
        ctx.rapid({0, 0, at});
      else
        ctx.rapid({0, 0, at = r_z});
      target = std::max(bottom_z, target - cycle.peck);
      if (ctx.too_many()) return ctx.limit_reached();
    }
  }
  if (dwell > 0) ctx.add({Move::Kind::Dwell, {}, {}, 1, dwell});
  set_feed(feed);
  if (base_spindle != 0) set_spindle(base_spindle);
  if (retract_ratio && *retract_ratio > 0) {
    set_feed(feed * *retract_ratio);
    ctx.feed({0, 0, r_z});
    set_feed(feed);
  } else {
    ctx.rapid({0, 0, r_z});
  }
  return true;
}

}  // namespace ncpost::stepnc::features::legacy
