// PLANAR_FACE (plane milling) and CLOSED_POCKET (bottom-and-side milling): equal depth levels,
// each machined by the strategy's pattern; see docs/features.md for every decision and the
// comparison with NIST's explicit toolpaths for the same part.

#include "milling.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpost::stepnc::features::legacy {
namespace {

constexpr double kEps = 1e-9;
constexpr double kTiny = 1e-9;
// With no overlap in the strategy: half the diameter between neighbouring passes.
constexpr double kDefaultOverlap = 0.5;

double helix_rise_per_turn(const Entry& e) {
  return 2 * std::numbers::pi * e.radius * std::tan(e.angle);
}

}  // namespace

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

double stepover(Context& ctx, const Tool& tool, const OperationData& o, double& overlap) {
  overlap = kDefaultOverlap;
  if (o.strategy != nullptr) {
    if (auto v = ctx.number(*o.strategy, "overlap")) overlap = *v;
  }
  double step = 2 * tool.radius * (1 - overlap);
  if (o.radial && *o.radial > 0) step = std::min(step, *o.radial);
  return step;
}

bool check_overlap(Context& ctx, const OperationData& o, double overlap) {
  if (overlap >= 0 && overlap < 1) return true;
  return ctx.bad(o.strategy ? *o.strategy : ctx.op(), ctx.d(o.strategy ? *o.strategy : ctx.op()) +
                                                          " overlap " + std::to_string(overlap) +
                                                          " is not in [0, 1)");
}

bool check_edge(Context& ctx, const Tool& tool, const std::vector<double>& z) {
  double deepest = -z.front();
  for (std::size_t i = 1; i < z.size(); ++i) deepest = std::max(deepest, z[i - 1] - z[i]);
  if (!tool.edge_length || *tool.edge_length + kEps >= deepest) return true;
  return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " cutting edge length " +
                                       fmt(*tool.edge_length) + " is shorter than the " +
                                       fmt(deepest) + " axial depth per level that " +
                                       ctx.d(ctx.op()) + " needs on " + ctx.d(ctx.feature()));
}

std::optional<std::vector<double>> depth_levels(Context& ctx, const OperationData& o,
                                                double depth) {
  bool multiple = true;
  if (o.strategy != nullptr)
    multiple = ctx.boolean(*o.strategy, "allow_multiple_passes").value_or(true);
  if (!multiple && o.axial && *o.axial + kEps < depth) {
    ctx.unfit(*o.strategy, ctx.d(*o.strategy) + " forbids multiple passes, but " + ctx.d(ctx.op()) +
                               " cuts at most " + fmt(*o.axial) + " deep and " +
                               ctx.d(ctx.feature()) + " is " + fmt(depth) + " deep");
    return std::nullopt;
  }
  if (multiple && o.axial && *o.axial > 0 &&
      depth / *o.axial > static_cast<double>(ctx.opt.max_moves)) {
    ctx.limit_reached();
    return std::nullopt;
  }
  return levels(depth, multiple ? o.axial : std::nullopt);
}

// ---- CLOSED_POCKET
// -------------------------------------------------------------------------------

bool read_plunge(Context& ctx, const Instance& strategy, std::string_view role, Entry& e) {
  if (ctx.is(&strategy, "plunge_toolaxis")) {
    e.kind = Entry::Kind::Plunge;
    return true;
  }
  if (ctx.is(&strategy, "plunge_helix")) {
    e.kind = Entry::Kind::Helix;
    e.radius = ctx.number(strategy, "radius").value_or(e.radius);
    if (const auto angle = ctx.number(strategy, "angle")) e.angle = radians(*angle);
  } else if (ctx.is(&strategy, "plunge_ramp") || ctx.is(&strategy, "plunge_zigzag")) {
    e.kind = Entry::Kind::Ramp;
    e.angle = radians(ctx.number(strategy, "angle").value_or(0));
    e.width = ctx.number(strategy, "width").value_or(0);
  } else {
    return ctx.not_implemented(ctx.d(strategy) + " as the " + std::string(role) + " " +
                               ctx.d(ctx.feature()));
  }
  if (!(e.angle > 0 && e.angle < radians(90)))
    return ctx.bad(strategy, ctx.d(strategy) + " angle must be between 0 and 90 degrees");
  return true;
}

void enter(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z) {
  switch (e.kind) {
    case Entry::Kind::Plunge:
      ctx.feed({p0.x, p0.y, to_z});
      return;
    case Entry::Kind::Helix: {
      // Whole turns about p0, so the helix ends where it began; its descent is at most `angle`.
      const double per_turn = helix_rise_per_turn(e);
      const int turns = std::max(1, static_cast<int>(std::ceil((from_z - to_z) / per_turn - 1e-9)));
      const Vec3 start = p0 + x * e.radius + Vec3{0, 0, to_z - p0.z};
      ctx.arc(start, {p0.x, p0.y, to_z}, ccw ? turns : -turns);
      ctx.feed({p0.x, p0.y, to_z});
      return;
    }
    case Entry::Kind::Ramp: {
      const double drop = ramp_length * std::tan(e.angle);
      double z = from_z;
      bool out = true;
      Vec3 here{p0.x, p0.y, from_z};
      p0.z = from_z;
      while (z > to_z + kEps) {
        const double share = std::min(1.0, (z - to_z) / drop);
        z = std::max(to_z, z - drop);
        const Vec3 target =
            out ? p0 + ramp_dir * (ramp_length * share) : here - ramp_dir * (ramp_length * share);
        here = {target.x, target.y, z};
        ctx.feed(here);
        out = !out;
        if (ctx.too_many()) return;
      }
      ctx.feed({p0.x, p0.y, to_z});  // back over the last leg at depth
      return;
    }
  }
}

bool check_fillet(Context& ctx, const Tool& tool, const OperationData& o,
                  const Toleranced& fillet) {
  const Instance& f = ctx.feature();
  // The floor fillet is the tool's corner radius.
  if (tool.corner_radius > fillet.size + fillet.upper + o.allowance_bottom + kEps)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " edge radius " +
                                         fmt(tool.corner_radius) + " > planar (floor) radius " +
                                         fmt(fillet.size) + " + allowance " +
                                         fmt(o.allowance_bottom) + " of " + ctx.d(f));
  if (tool.corner_radius + fillet.lower + kEps < fillet.size)
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " edge radius " +
                                         fmt(tool.corner_radius) + " < planar (floor) radius " +
                                         fmt(fillet.size) + " of " + ctx.d(f) +
                                         ": the tool would cut the fillet away");
  return true;
}

bool read_entry(Context& ctx, const OperationData& o, const Tool& tool, Entry& entry) {
  entry = Entry{};
  entry.radius = ctx.opt.default_helix_radius * tool.radius;
  entry.angle = radians(ctx.opt.default_helix_angle);
  if (o.approach == nullptr) return true;
  entry.explicit_entry = true;
  return read_plunge(ctx, *o.approach, "approach into", entry);
}

bool read_exit(Context& ctx, const OperationData& o, const Entry& entry, Entry& exit) {
  exit = Entry{};
  exit.kind = Entry::Kind::Plunge;
  exit.radius = entry.radius;
  exit.angle = entry.angle;
  return o.retract == nullptr || read_plunge(ctx, *o.retract, "retract from", exit);
}

bool entry_too_long(Context& ctx, const Entry& e, double ramp_length, double drop) {
  const auto limit = static_cast<double>(ctx.opt.max_moves);
  if (e.kind == Entry::Kind::Helix) return drop / helix_rise_per_turn(e) > limit;
  if (e.kind == Entry::Kind::Ramp) return drop / (ramp_length * std::tan(e.angle)) > limit;
  return false;
}

bool rings_ccw(Context& ctx, const OperationData& o, bool wall_outside) {
  const bool spindle_cw = !ctx.req.spindle || *ctx.req.spindle <= 0;  // NIST: negative = CW
  // A pocket's wall is outside the path: going counter-clockwise it is on the tool's right,
  // which with a clockwise spindle is climb milling. Round a part it is the other way.
  const bool climb_ccw = wall_outside ? spindle_cw : !spindle_cw;
  const std::string_view cutmode =
      o.strategy ? ctx.enumeration(*o.strategy, "cutmode") : std::string_view();
  const std::string_view rotation =
      o.strategy ? ctx.enumeration(*o.strategy, "rotation_direction") : std::string_view();
  if (rotation.empty()) return cutmode == "CONVENTIONAL" ? !climb_ccw : climb_ccw;
  const bool ccw = rotation == "CCW";
  if (!cutmode.empty() && (cutmode == "CLIMB") != (ccw == climb_ccw))
    ctx.note(*o.strategy, ctx.d(*o.strategy) + ": rotation_direction ." + std::string(rotation) +
                              ". is followed; with this spindle it mills " +
                              (ccw == climb_ccw ? "climb" : "conventional") + ", not ." +
                              std::string(cutmode) + ".");
  return ccw;
}

void leave(Context& ctx, const Entry& e, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z) {
  switch (e.kind) {
    case Entry::Kind::Plunge:
      ctx.feed({p0.x, p0.y, to_z});
      return;
    case Entry::Kind::Helix: {
      // Out to the helix and whole turns up about p0 (the approach's helix, run backwards).
      const double per_turn = helix_rise_per_turn(e);
      const int turns = std::max(1, static_cast<int>(std::ceil((to_z - from_z) / per_turn - 1e-9)));
      const Vec3 start{p0.x + x.x * e.radius, p0.y + x.y * e.radius, from_z};
      ctx.feed(start);
      ctx.arc({start.x, start.y, to_z}, {p0.x, p0.y, to_z}, ccw ? turns : -turns);
      return;
    }
    case Entry::Kind::Ramp: {
      // Back and forth along the ramp line, rising by at most the angle.
      const double rise = ramp_length * std::tan(e.angle);
      double z = from_z;
      bool out = true;
      Vec3 here{p0.x, p0.y, from_z};
      while (z < to_z - kEps) {
        const double share = std::min(1.0, (to_z - z) / rise);
        z = std::min(to_z, z + rise);
        const Vec3 target =
            out ? here + ramp_dir * (ramp_length * share) : here - ramp_dir * (ramp_length * share);
        here = {target.x, target.y, z};
        ctx.feed(here);
        out = !out;
        if (ctx.too_many()) return;
      }
      return;
    }
  }
}

namespace {

// A rectangular or circular closed profile as a Shape in the feature's coordinates: the
// boundary of pockets and outside profiles. `corner` is the rectangle's corner radius (0: sharp).
// False after reporting what is wrong or not implemented.
bool read_closed_profile(Context& ctx, const Instance& f, const Instance& boundary, double corner,
                         std::string_view plane_owner, Shape& shape) {
  if (ctx.is(&boundary, "rectangular_closed_profile")) {
    const auto w = ctx.toleranced(boundary, "profile_width");
    const auto l = ctx.toleranced(boundary, "profile_length");
    if (!w || !l || !(w->size > 0) || !(l->size > 0))
      return ctx.bad(boundary, ctx.d(boundary) + " needs a positive width and length");
    // Length along the profile's x axis, width along y: as NIST's ex1/ex1E pair places it.
    shape = Shape::rectangle(l->size / 2, w->size / 2, corner);
    if (shape.corner > std::min(shape.a, shape.b) + kEps)
      return ctx.bad(f, ctx.d(f) + " orthogonal_radius " + fmt(shape.corner) +
                            " is more than half the width of " + ctx.d(boundary));
  } else if (ctx.is(&boundary, "circular_closed_profile")) {
    const auto dia = ctx.toleranced(boundary, "diameter");
    if (!dia || !(dia->size > 0))
      return ctx.bad(boundary, ctx.d(boundary) + " needs a positive diameter");
    shape = Shape::circle(dia->size / 2);
  } else {
    return ctx.not_implemented(ctx.d(f) + " bounded by " + ctx.d(boundary));
  }
  if (ctx.set(boundary, "placement")) {
    const auto frame = ctx.g.placement(ctx.g.get(boundary, "placement"));
    if (!frame) return false;
    if (std::abs(frame->z.z - 1) > 1e-9 || std::abs(frame->origin.z) > kEps)
      return ctx.not_implemented(ctx.d(boundary) + " placed out of the " +
                                 std::string(plane_owner) + " plane");
    shape.frame = *frame;
  }
  return true;
}

// A RADIUSED_POCKET_BOTTOM_CONDITION is a portion of a sphere over the whole floor (ISO
// 14649-10). A 2.5D path makes exactly one such pocket: a round pocket whose floor is the lower
// half of a ball of the pocket's own radius, centred on its axis, which a ball end mill of that
// radius makes going straight down the axis. Any other sphere needs 3D surface finishing
// (STEPNC-101); a tool that is not that ball is STEPNC-102.
bool radiused_pocket(Context& ctx, const Instance& bottom, const Instance& boundary) {
  const Instance& f = ctx.feature();
  if (!ctx.is(&boundary, "circular_closed_profile"))
    return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(bottom) + " bounded by " +
                               ctx.d(boundary) +
                               " (a round pocket whose floor is the half ball of its radius is)");
  Shape shape;
  if (!read_closed_profile(ctx, f, boundary, 0, "pocket's", shape)) return false;
  const auto radius = ctx.toleranced(bottom, "floor_radius");
  const auto centre = ctx.g.point(ctx.g.get(bottom, "floor_radius_center"));
  if (!radius || !centre || !(radius->size > 0))
    return ctx.bad(bottom, ctx.d(bottom) + " needs a floor_radius_center and a positive radius");
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  constexpr double kSame = 1e-3;
  const Vec3 axis = shape.frame.origin;
  if (std::hypot(centre->x - axis.x, centre->y - axis.y) > kSame ||
      std::abs(radius->size - shape.a) > kSame)
    return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(bottom) + ", a sphere of radius " +
                               fmt(radius->size) + " about (" + fmt(centre->x) + ", " +
                               fmt(centre->y) + ", " + fmt(centre->z) +
                               ") that is not the half ball of the pocket's radius " +
                               fmt(shape.a) + " on its axis (3D surface finishing)");
  if (std::abs(centre->z - radius->size + *depth) > kSame)
    return ctx.bad(bottom, ctx.d(bottom) + " puts the lowest point of the floor at z " +
                               fmt(centre->z - radius->size) + ", but the depth plane of " +
                               ctx.d(f) + " is at z " + fmt(-*depth));
  const bool ball =
      ctx.is(tool->body, "ball_endmill") || std::abs(tool->corner_radius - tool->radius) <= kEps;
  if (!ball || tool->radius > radius->size + radius->upper + kEps ||
      tool->radius + radius->lower + kEps < radius->size)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " (radius " + fmt(tool->radius) +
                                          (ball ? ", a ball end" : ", not a ball end") +
                                          ") cannot make " + ctx.d(bottom) + " of " + ctx.d(f) +
                                          ": that needs a ball end mill of radius " +
                                          fmt(radius->size));
  if (o.allowance_side > kEps)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " fills " + ctx.d(f) + ", so " +
                                          ctx.d(ctx.op()) + " cannot leave its allowance_side " +
                                          fmt(o.allowance_side));
  if (o.approach != nullptr && !ctx.is(o.approach, "plunge_toolaxis"))
    return ctx.unfit(*o.approach, ctx.d(*o.approach) + ": " + ctx.d(*tool->instance) + " fills " +
                                      ctx.d(f) + ", no room to enter but along the axis");
  const double finish = *depth - o.allowance_bottom;
  if (!(finish > 0))
    return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
  const auto z_levels = depth_levels(ctx, o, finish);
  if (!z_levels || !check_edge(ctx, *tool, *z_levels)) return false;
  const double clear = ctx.opt.clearance;
  const double retract = o.retract_plane.value_or(clear);
  ctx.rapid({axis.x, axis.y, std::max(retract, clear)});
  if (retract > clear) ctx.rapid({axis.x, axis.y, clear});
  for (const double z : *z_levels) ctx.feed({axis.x, axis.y, z});
  ctx.rapid({axis.x, axis.y, std::max(retract, clear)});
  return true;
}

}  // namespace

bool generate_pocket(Context& ctx) {
  const Instance& f = ctx.feature();
  if (!ctx.is(&ctx.op(), "bottom_and_side_milling") && !ctx.is(&ctx.op(), "side_milling"))
    return ctx.not_implemented(ctx.d(ctx.op()) + " on " + ctx.d(f) +
                               " (pockets take bottom-and-side or side milling)");
  if (const auto bosses = ctx.g.get(f, "its_boss"); bosses && bosses->is_list() && bosses->count())
    return ctx.not_implemented(ctx.d(f) + " with bosses (islands)");
  if (const auto slope = ctx.number(f, "slope"); slope && std::abs(*slope) > kEps)
    return ctx.not_implemented(ctx.d(f) + " with sloped walls");
  const Instance* bottom = ctx.ref(f, "bottom_condition", "pocket_bottom_condition");
  if (bottom == nullptr) return ctx.bad(f, ctx.d(f) + " has no bottom_condition");
  const bool through = ctx.is(bottom, "through_pocket_bottom_condition");
  const bool radiused = ctx.is(bottom, "radiused_pocket_bottom_condition");
  if (!through && !radiused && !ctx.is(bottom, "planar_pocket_bottom_condition"))
    return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(*bottom));
  const Instance* boundary = ctx.ref(f, "feature_boundary", "closed_profile");
  if (boundary == nullptr) return ctx.bad(f, ctx.d(f) + " has no feature_boundary");
  if (radiused) return radiused_pocket(ctx, *bottom, *boundary);
  if (ctx.is(boundary, "general_closed_profile") || ctx.is(boundary, "ngon_closed_profile"))
    return general_pocket(ctx, *boundary, through, ctx.toleranced(f, "planar_radius"));

  // The profile, in the pocket's coordinates.
  Shape shape;
  const auto corner = ctx.toleranced(f, "orthogonal_radius");
  if (!read_closed_profile(ctx, f, *boundary, corner ? corner->size : 0, "pocket's", shape))
    return false;
  Region region;
  region.shape = shape;
  region.through = through;
  region.fillet = ctx.toleranced(f, "planar_radius");
  region.walls_only = ctx.is(&ctx.op(), "side_milling");
  return clear_region(ctx, region);
}

bool clear_region(Context& ctx, const Region& region) {
  const Instance& f = ctx.feature();
  const Shape& shape = region.shape;
  const bool through = region.through;
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  if (region.fillet && !check_fillet(ctx, *tool, o, *region.fillet)) return false;

  const double inset = tool->radius + o.allowance_side;
  if (region.corners_in_material && shape.kind == Shape::Kind::Rectangle &&
      shape.corner + kEps < inset)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " radius " + fmt(tool->radius) +
                                          " + allowance " + fmt(o.allowance_side) + " of " +
                                          ctx.d(ctx.op()) + " > corner radius " +
                                          fmt(shape.corner) + " of " + ctx.d(f));
  const double room = std::max(0.0, shape.inradius() - inset);
  if (shape.inradius() - inset < -kEps)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " diameter " +
                                          fmt(2 * tool->radius) + " + allowances does not fit " +
                                          ctx.d(f));
  if (region.centre_only && room > 1e-3)
    return ctx.unfit(*tool->instance,
                     ctx.d(*tool->instance) + " diameter " + fmt(2 * tool->radius) +
                         " + allowances is " + fmt(2 * room) + " narrower than " + ctx.d(f) +
                         ", which " + ctx.d(o.strategy) + " (center milling) cuts in one pass");

  // Strategy: contour-parallel (the default for pockets).
  bool ccw = false;
  // Pattern: contour-parallel rings (the default), or parallel lines, with a contour ring
  // before or after them for the combined strategies.
  enum class Pattern { Rings, Lines, LinesThenRing, RingThenLines } pattern = Pattern::Rings;
  bool zigzag = true;
  bool along_x = true;
  bool lines_up = true;  // lines from -y (-x) to +y (+x)
  if (o.strategy != nullptr && !ctx.is(o.strategy, "contour_parallel") &&
      !(region.centre_only && ctx.is(o.strategy, "center_milling"))) {
    if (region.centre_only)
      return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f) +
                                 ", which only a centre pass can machine");
    if (ctx.is(o.strategy, "bidirectional_milling")) {
      pattern = Pattern::Lines;
    } else if (ctx.is(o.strategy, "unidirectional_milling")) {
      pattern = Pattern::Lines;
      zigzag = false;
    } else if (ctx.is(o.strategy, "bidirectional_contour")) {
      pattern = Pattern::LinesThenRing;
    } else if (ctx.is(o.strategy, "contour_bidirectional")) {
      pattern = Pattern::RingThenLines;
    } else {
      return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f));
    }
    if (const auto dir = ctx.direction(*o.strategy, "feed_direction")) {
      const Vec3 fx = shape.frame.x;
      const Vec3 fy = shape.frame.y;
      if (std::abs(std::abs(dir->dot(fx)) - 1) < 1e-9)
        along_x = true;
      else if (std::abs(std::abs(dir->dot(fy)) - 1) < 1e-9)
        along_x = false;
      else
        return ctx.not_implemented(ctx.d(*o.strategy) + " feed_direction oblique to the sides of " +
                                   ctx.d(f));
      // Left of the feed direction is where the next line goes for stepover_direction LEFT.
      const Vec3 feed_local{dir->dot(fx), dir->dot(fy), 0};
      const Vec3 left{-feed_local.y, feed_local.x, 0};
      lines_up = (along_x ? left.y : left.x) > 0;
    }
    if (ctx.enumeration(*o.strategy, "stepover_direction") == "RIGHT") lines_up = !lines_up;
  }
  ccw = rings_ccw(ctx, o, true);
  double overlap = 0;
  double step = stepover(ctx, *tool, o, overlap);
  if (!check_overlap(ctx, o, overlap)) return false;
  if (shape.kind == Shape::Kind::Rectangle) step = std::min(step, kSharpCornerStep * tool->radius);

  const double finish = *depth - (through ? -ctx.opt.through_clearance : o.allowance_bottom);
  if (!(finish > 0))
    return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
  const auto z_levels = depth_levels(ctx, o, finish);
  if (!z_levels || !check_edge(ctx, *tool, *z_levels)) return false;

  // Counted before anything is built: a hostile stepover must not allocate its way out.
  if (room / step > static_cast<double>(ctx.opt.max_moves)) return ctx.limit_reached();
  Rings rings;
  std::vector<std::pair<Vec3, Vec3>> lines;
  if (pattern == Pattern::Rings) {
    rings = contour_rings(shape, inset, step);
    if (region.walls_only && !region.centre_only) {
      // The wall ring alone, entered from the centre across the pocket the bottom operation
      // cleared (or, if it did not, by a cut no deeper than the level).
      rings.line_length = 0;
      if (rings.loops.size() > 1) rings.loops.erase(rings.loops.begin(), rings.loops.end() - 1);
    }
  } else {
    if (region.walls_only)
      return ctx.not_implemented(ctx.d(*o.strategy) + " for " + ctx.d(ctx.op()) + " on " +
                                 ctx.d(f));
    if (2 * shape.inradius() / step > static_cast<double>(ctx.opt.max_moves))
      return ctx.limit_reached();
    lines = raster(shape, inset, step, along_x);
    if (!lines_up) std::reverse(lines.begin(), lines.end());
    // The entry is at the centre; the ring of the combined strategies is the outermost one.
    rings.start = {0, 0, 0};
    // One-way lines have no move along the wall between their ends, which leaves a cusp there,
    // and zigzag lines join their ends by chords, which cut across rounded corners (and circles)
    // of the region: the wall ring clears both, as in the combined strategy.
    bool rounded = shape.kind == Shape::Kind::Circle;
    for (int k = 0; k < 4; ++k) rounded = rounded || shape.corner_at(k) > inset + kEps;
    if (pattern == Pattern::Lines && (!zigzag || rounded)) pattern = Pattern::LinesThenRing;
    if (pattern != Pattern::Lines) {
      const Rings outer = contour_rings(shape, inset, step);
      if (!outer.loops.empty()) rings.loops.push_back(outer.loops.back());
    }
  }
  if ((rings.loops.size() + lines.size()) * z_levels->size() > ctx.opt.max_moves)
    return ctx.limit_reached();

  // Entry: the operation's approach, else a helix as NIST's ex1E.
  Entry entry;
  if (!read_entry(ctx, o, *tool, entry)) return false;
  const bool explicit_entry = entry.explicit_entry;
  Entry exit;
  if (!read_exit(ctx, o, entry, exit)) return false;
  const Vec3 p0 = rings.start;
  Vec3 ramp_dir = rings.axis;
  double ramp_length = std::max(rings.line_length, room);
  if (entry.kind == Entry::Kind::Helix) {
    if (entry.radius > room + kEps) {
      if (explicit_entry)
        return ctx.unfit(*o.approach, ctx.d(*o.approach) + " radius " + fmt(entry.radius) +
                                          " leaves no room for " + ctx.d(*tool->instance) + " in " +
                                          ctx.d(f) + " (at most " + fmt(room) + ")");
      entry.radius = room;
    }
    if (entry.radius < 1e-3) {
      if (explicit_entry)
        return ctx.unfit(*o.approach, ctx.d(*o.approach) + ": " + ctx.d(*tool->instance) +
                                          " fills " + ctx.d(f) + ", no room for a helix");
      entry.kind = Entry::Kind::Plunge;
      ctx.note(f, ctx.d(*tool->instance) + " fills " + ctx.d(f) +
                      " across; it enters along its axis, as there is no room for a helix");
    }
  } else if (entry.kind == Entry::Kind::Ramp) {
    if (entry.width > 0) ramp_length = std::min(ramp_length, entry.width);
    if (ramp_length < 1e-3)
      return ctx.unfit(*o.approach, ctx.d(*o.approach) + ": no room for a ramp of " +
                                        ctx.d(*tool->instance) + " in " + ctx.d(f));
  }
  // The retract needs the same room as an approach of its kind.
  double exit_length = std::max(rings.line_length, room);
  if (exit.kind == Entry::Kind::Helix && (exit.radius > room + kEps || exit.radius < 1e-3))
    return ctx.unfit(*o.retract, ctx.d(*o.retract) + " radius " + fmt(exit.radius) +
                                     " does not fit " + ctx.d(*tool->instance) + " in " + ctx.d(f) +
                                     " (room " + fmt(room) + ")");
  if (exit.kind == Entry::Kind::Ramp) {
    if (exit.width > 0) exit_length = std::min(exit_length, exit.width);
    if (exit_length < 1e-3)
      return ctx.unfit(*o.retract, ctx.d(*o.retract) + ": no room for a ramp of " +
                                       ctx.d(*tool->instance) + " in " + ctx.d(f));
  }

  const double clear = ctx.opt.clearance;
  const double retract = o.retract_plane.value_or(clear);
  if (entry_too_long(ctx, entry, ramp_length, clear + finish) ||
      entry_too_long(ctx, exit, exit_length, clear + finish))
    return ctx.limit_reached();
  const Vec3 p0f = shape.frame.point(p0);
  const Vec3 x_axis = shape.frame.x;
  const Vec3 entry_start = entry.kind == Entry::Kind::Helix ? p0f + x_axis * entry.radius : p0f;
  ctx.rapid({entry_start.x, entry_start.y, std::max(retract, clear)});
  if (retract > clear) ctx.rapid({entry_start.x, entry_start.y, clear});
  double from_z = clear;
  for (const double zz : *z_levels) {
    if (from_z < clear) ctx.feed({entry_start.x, entry_start.y, from_z});
    enter(ctx, entry, p0f, x_axis, shape.frame.direction(ramp_dir), ramp_length, ccw, from_z, zz);
    if (pattern == Pattern::Rings || pattern == Pattern::RingThenLines)
      play_rings(ctx, rings, shape.frame, ccw, zz);
    if (pattern != Pattern::Rings) {
      const auto at = [&](Vec3 p) { return shape.frame.point({p.x, p.y, zz}); };
      // Back above the feature's top: between two lines the material near the wall is not yet
      // cut at every height, so a rapid lower down could run into it.
      const double lift = clear;
      for (std::size_t k = 0; k < lines.size(); ++k) {
        const bool reverse = zigzag && k % 2 == 1;
        const Vec3 a = at(reverse ? lines[k].second : lines[k].first);
        const Vec3 b = at(reverse ? lines[k].first : lines[k].second);
        if (!zigzag && k > 0) {
          // One way only: up, back at rapid, down at feed.
          const Vec3 here = ctx.path.moves.back().to;
          ctx.rapid({here.x, here.y, lift});
          ctx.rapid({a.x, a.y, lift});
        }
        ctx.feed(a);
        ctx.feed(b);
      }
      if (pattern == Pattern::LinesThenRing) {
        Rings ring = rings;
        ring.line_length = 0;
        play_rings(ctx, ring, shape.frame, ccw, zz);
      }
    }
    if (ctx.too_many()) return ctx.limit_reached();
    from_z = zz;
  }
  if (exit.kind != Entry::Kind::Plunge) {
    // Back across the cleared floor to where the approach came down, and up the same way.
    ctx.feed({p0f.x, p0f.y, from_z});
    leave(ctx, exit, p0f, x_axis, shape.frame.direction(ramp_dir), exit_length, ccw, from_z, clear);
  }
  const Vec3 end = ctx.path.moves.back().to;
  if (end.z < std::max(retract, clear) - kEps) ctx.rapid({end.x, end.y, std::max(retract, clear)});
  return true;
}

// ---- GENERAL_OUTSIDE_PROFILE -------------------------------------------------------------------

bool generate_outside_profile(Context& ctx) {
  const Instance& f = ctx.feature();
  if (!ctx.is(&ctx.op(), "side_milling"))
    return ctx.not_implemented(ctx.d(ctx.op()) + " on " + ctx.d(f) +
                               " (an outside profile takes side rough or finish milling)");
  const Instance* boundary = ctx.ref(f, "feature_boundary", "profile");
  if (boundary == nullptr) return ctx.bad(f, ctx.d(f) + " has no feature_boundary");
  if (ctx.is(boundary, "general_closed_profile") || ctx.is(boundary, "ngon_closed_profile"))
    return general_outside_profile(ctx, *boundary);
  Shape shape;
  if (!read_closed_profile(ctx, f, *boundary, 0, "profile's", shape)) return false;
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  if (o.strategy != nullptr && !ctx.is(o.strategy, "contour_parallel"))
    return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f));
  if (o.approach != nullptr && !ctx.is(o.approach, "plunge_strategy"))
    return ctx.not_implemented(ctx.d(*o.approach) + " as the approach of " + ctx.d(ctx.op()));
  if (o.retract != nullptr && !ctx.is(o.retract, "plunge_strategy"))
    return ctx.not_implemented(ctx.d(*o.retract) + " as the retract of " + ctx.d(ctx.op()));
  // The part is inside the ring: going clockwise it is on the tool's right, which with a
  // clockwise spindle is climb milling.
  const bool spindle_cw = !ctx.req.spindle || *ctx.req.spindle <= 0;
  const std::string_view cutmode =
      o.strategy ? ctx.enumeration(*o.strategy, "cutmode") : std::string_view();
  const std::string_view rotation =
      o.strategy ? ctx.enumeration(*o.strategy, "rotation_direction") : std::string_view();
  bool ccw = !rotation.empty() ? rotation == "CCW"
                               : (cutmode == "CONVENTIONAL" ? spindle_cw : !spindle_cw);
  const auto z_levels = depth_levels(ctx, o, *depth);
  if (!z_levels || !check_edge(ctx, *tool, *z_levels)) return false;
  const Loop ring = outside_ring(shape, tool->radius + o.allowance_side);
  const double clear = ctx.opt.clearance;
  const double retract = o.retract_plane.value_or(clear);
  // Each level starts and ends at a lead-in point clear of the ring, outside the part.
  const Vec3 lead_local = ring.start + Vec3{tool->radius + clear, 0, 0};
  const auto at = [&](Vec3 p, double z) { return shape.frame.point({p.x, p.y, z}); };
  ctx.rapid(at(lead_local, std::max(retract, clear)));
  if (retract > clear) ctx.rapid(at(lead_local, clear));
  for (const double zz : *z_levels) {
    ctx.feed(at(lead_local, zz));
    ctx.feed(at(ring.start, zz));
    if (ccw) {
      for (const Span& s : ring.spans) {
        if (s.arc)
          ctx.arc(at(s.to, zz), at(s.centre, zz), 1);
        else
          ctx.feed(at(s.to, zz));
      }
    } else {
      for (std::size_t i = ring.spans.size(); i-- > 0;) {
        const Vec3 to = i == 0 ? ring.start : ring.spans[i - 1].to;
        if (ring.spans[i].arc)
          ctx.arc(at(to, zz), at(ring.spans[i].centre, zz), -1);
        else
          ctx.feed(at(to, zz));
      }
    }
    ctx.feed(at(lead_local, zz));
    if (ctx.too_many()) return ctx.limit_reached();
  }
  ctx.rapid(at(lead_local, std::max(retract, clear)));
  return true;
}

void play_rings(Context& ctx, const Rings& rings, const detail::Frame& frame, bool ccw, double z) {
  const auto at = [&](Vec3 p) { return frame.point({p.x, p.y, z}); };
  if (rings.line_length > kTiny) ctx.feed(at(rings.start + rings.axis * rings.line_length));
  for (const Loop& loop : rings.loops) {
    ctx.feed(at(loop.start));
    if (ccw) {
      for (const Span& s : loop.spans) {
        if (s.arc)
          ctx.arc(at(s.to), at(s.centre), 1);
        else
          ctx.feed(at(s.to));
      }
    } else {
      // Backwards: span i runs from the end of span i-1 (the start for the first) to its end.
      for (std::size_t i = loop.spans.size(); i-- > 0;) {
        const Vec3 to = i == 0 ? loop.start : loop.spans[i - 1].to;
        const Span& s = loop.spans[i];
        if (s.arc)
          ctx.arc(at(to), at(s.centre), -1);
        else
          ctx.feed(at(to));
      }
    }
  }
}

}  // namespace ncpost::stepnc::features::legacy
