// STEP (ISO 14649-10): a floor at the depth plane between the step's open boundary and its
// wall. The schema gives a step no width attribute; it has two boundaries:
// - open_boundary, a LINEAR_PATH: the edge where the step is open (the part ends there), from
//   its placement (the feature's origin when unset) along its direction for its distance;
// - wall_boundary, a VEE_PROFILE: the wall's profile; its placement's origin is the vertex of
//   the vee (ISO 10303-214: the profile's placement lies at the connection of its two sides),
//   the foot of the wall. Its first side is the floor (tilt_angle 0: along the profile's x
//   axis), profile_angle the angle from the floor up to the wall, profile_radius the fillet
//   between them.
// The width is the distance between the two. A step without a wall_boundary, or whose vee has
// no placement, has no width: STEPNC-103 says so. The step is open at the two ends of its
// open boundary too (it runs out of the part there): passes run R + clearance past them and
// past the open boundary, as faces do.

#include <algorithm>
#include <cmath>

#include "milling.hpp"

namespace ncpost::stepnc::features::legacy {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

bool generate_step(Context& ctx) {
  const Instance& f = ctx.feature();
  const bool side = ctx.is(&ctx.op(), "side_milling");
  if (!ctx.is(&ctx.op(), "bottom_and_side_milling") && !side)
    return ctx.not_implemented(ctx.d(ctx.op()) + " on " + ctx.d(f) +
                               " (steps take bottom-and-side or side milling)");
  if (const auto bosses = ctx.g.get(f, "its_boss"); bosses && bosses->is_list() && bosses->count())
    return ctx.not_implemented(ctx.d(f) + " with bosses");
  const Instance* open = ctx.ref(f, "open_boundary", "linear_path");
  if (open == nullptr) return ctx.bad(f, ctx.d(f) + " has no open_boundary");
  const auto length = ctx.toleranced(*open, "distance");
  auto along = ctx.direction(*open, "its_direction");
  if (!length || !along || !(length->size > 0))
    return ctx.bad(*open, ctx.d(*open) + " needs a positive distance and a direction");
  if (!ctx.size_ok(*open, length->size, "distance")) return false;
  Vec3 origin{};
  if (ctx.set(*open, "placement")) {
    const auto frame = ctx.g.placement(ctx.g.get(*open, "placement"));
    if (!frame) return false;
    if (std::abs(frame->z.z - 1) > 1e-9 || std::abs(frame->origin.z) > kEps)
      return ctx.not_implemented(ctx.d(*open) + " placed out of " + ctx.d(f) + "'s top plane");
    origin = frame->origin;
    along = frame->direction(*along);
  }
  if (std::abs(along->z) > kEps)
    return ctx.bad(*open, ctx.d(*open) + " does not run in " + ctx.d(f) + "'s top plane");
  const Vec3 dir = *along * (1.0 / along->length());
  const Vec3 left = Vec3{0, 0, 1}.cross(dir);

  const auto depth = ctx.depth();
  if (!depth) return false;
  const Instance* wall = ctx.ref(f, "wall_boundary", "vee_profile");
  if (wall == nullptr || !ctx.set(*wall, "placement"))
    return ctx.bad(
        f, ctx.d(f) + " has no width: " +
               (wall == nullptr ? std::string("it has no wall_boundary")
                                : "its wall_boundary " + ctx.d(*wall) + " has no placement") +
               ", and the schema locates a step's wall only by the placement of its "
               "wall_boundary's vee (the foot of the wall)");
  const auto foot = ctx.g.placement(ctx.g.get(*wall, "placement"));
  if (!foot) return false;
  if (std::abs(foot->origin.z) > kEps && std::abs(foot->origin.z + *depth) > 1e-6)
    return ctx.bad(*wall, ctx.d(*wall) + " places the foot of the wall at z " +
                              fmt(foot->origin.z) + ", neither on " + ctx.d(f) +
                              "'s floor nor at its top");
  const double width_signed = (foot->origin - origin).dot(left);
  const double width = std::abs(width_signed);
  if (!ctx.size_ok(f, width, "width (open boundary to wall)")) return false;
  if (!(width > 1e-6))
    return ctx.bad(f, ctx.d(f) + "'s wall (the vertex of " + ctx.d(*wall) +
                          ") stands on its open boundary: the step has no width");
  const auto angle = ctx.number(*wall, "profile_angle");
  const auto tilt = ctx.number(*wall, "tilt_angle");
  const auto fillet = ctx.toleranced(*wall, "profile_radius");
  if (!angle || !tilt) return ctx.bad(*wall, ctx.d(*wall) + " needs a profile_angle and tilt");
  if (std::abs(*tilt) > 1e-6)
    return ctx.not_implemented(ctx.d(f) + " whose " + ctx.d(*wall) +
                               " is tilted (its first side, the floor, is not along its x axis)");
  if (std::abs(*angle - 90) > 1e-6)
    return ctx.not_implemented(ctx.d(f) + " with a wall at " + fmt(*angle) +
                               " degrees to the floor (" + ctx.d(*wall) + "; vertical walls are)");

  const auto tool = ctx.tool();
  if (!tool) return false;
  const OperationData o = ctx.operation();
  // The fillet at the foot of the wall is the tool's corner radius (as a pocket's floor radius).
  const double rho = fillet ? fillet->size : 0;
  const double upper = fillet ? fillet->upper : 0;
  const double lower = fillet ? fillet->lower : 0;
  if (tool->corner_radius > rho + upper + o.allowance_bottom + kEps)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " edge radius " +
                                          fmt(tool->corner_radius) + " > the wall's radius " +
                                          fmt(rho) + " + allowance " + fmt(o.allowance_bottom) +
                                          " of " + ctx.d(f));
  if (tool->corner_radius + lower + kEps < rho)
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " edge radius " +
                                          fmt(tool->corner_radius) + " < the wall's radius " +
                                          fmt(rho) + " of " + ctx.d(f) +
                                          ": the tool would cut the fillet away");

  // Strategy: passes parallel to the wall, from the open boundary to the wall.
  bool one_way = true;
  if (o.strategy != nullptr) {
    if (ctx.is(o.strategy, "bidirectional_milling")) {
      one_way = false;
    } else if (!ctx.is(o.strategy, "unidirectional_milling") &&
               !ctx.is(o.strategy, "contour_parallel")) {
      return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f));
    }
    if (const auto feed = ctx.direction(*o.strategy, "feed_direction");
        feed && std::abs(std::abs(feed->dot(dir)) - 1) > 1e-9)
      return ctx.not_implemented(ctx.d(*o.strategy) + " feed_direction across the wall of " +
                                 ctx.d(f) + " (passes run along the wall)");
    if (ctx.set(*o.strategy, "stepover_direction"))
      ctx.note(*o.strategy, ctx.d(*o.strategy) + ": the passes over " + ctx.d(f) +
                                " go from its open boundary towards its wall, whichever the "
                                "stepover_direction");
  }
  for (const auto& [strategy, role] :
       {std::pair{o.approach, "approach"}, std::pair{o.retract, "retract"}}) {
    if (strategy == nullptr) continue;
    if (!ctx.is(strategy, "plunge_strategy"))
      return ctx.not_implemented(ctx.d(*strategy) + " as the " + role + " of " + ctx.d(ctx.op()));
    if (!ctx.is(strategy, "plunge_toolaxis"))
      ctx.note(*strategy, ctx.d(*strategy) + ": every pass over " + ctx.d(f) +
                              " starts and ends outside the material, so the tool moves along "
                              "its axis there");
  }

  double overlap = 0;
  const double step = stepover(ctx, *tool, o, overlap);
  if (!check_overlap(ctx, o, overlap)) return false;
  const double finish = *depth - o.allowance_bottom;
  if (!(finish > 0))
    return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
  const auto z_levels = depth_levels(ctx, o, finish);
  if (!z_levels || !check_edge(ctx, *tool, *z_levels)) return false;

  // Across (t, from the open boundary towards the wall): the last pass R + allowance off the
  // wall, the first with the tool reaching the overlap past the open boundary, evenly between.
  const double r = tool->radius;
  const double t_wall = width - r - o.allowance_side;
  const double t_first = std::min(t_wall, r - overlap * 2 * r);
  if ((t_wall - t_first) / step > static_cast<double>(ctx.opt.max_moves) ||
      (t_wall - t_first) / step * static_cast<double>(z_levels->size()) >
          static_cast<double>(ctx.opt.max_moves))
    return ctx.limit_reached();
  std::vector<double> across;
  const auto n = static_cast<std::size_t>(std::ceil((t_wall - t_first) / step - 1e-9));
  for (std::size_t k = 0; k <= n; ++k)
    across.push_back(n == 0 ? t_wall
                            : t_first + (t_wall - t_first) * static_cast<double>(k) /
                                            static_cast<double>(n));
  if (side) across.erase(across.begin(), across.end() - 1);

  // Climb milling with the material on the tool's right: with a clockwise spindle, the wall
  // side (the uncut material) must be on the right of the pass.
  const bool spindle_cw = !ctx.req.spindle || *ctx.req.spindle <= 0;
  const std::string_view cutmode =
      o.strategy ? ctx.enumeration(*o.strategy, "cutmode") : std::string_view();
  const bool climb = cutmode != "CONVENTIONAL";
  const double wall_side = width_signed > 0 ? 1 : -1;  // the wall is to the left of +dir when > 0
  // Moving along +dir the wall is on the left when wall_side > 0.
  const bool material_right_forward = wall_side < 0;
  const bool forward = (climb == spindle_cw) == material_right_forward;

  const double run = r + ctx.opt.clearance;
  const double s0 = -run;
  const double s1 = length->size + run;
  const auto at = [&](double s, double t, double z) {
    return origin + dir * s + left * (t * wall_side) + Vec3{0, 0, z};
  };
  const double clear = ctx.opt.clearance;
  const double retract = o.retract_plane.value_or(clear);
  bool first = true;
  for (const double z : *z_levels) {
    for (std::size_t k = 0; k < across.size(); ++k) {
      const bool fwd = one_way ? forward : (k % 2 == 0) == forward;
      const double from = fwd ? s0 : s1;
      const double to = fwd ? s1 : s0;
      if (first) {
        ctx.rapid(at(from, across[k], std::max(retract, clear)));
        if (retract > clear) ctx.rapid(at(from, across[k], clear));
        ctx.feed(at(from, across[k], z));
        first = false;
      } else if (k == 0 || one_way) {
        // Up, over (outside the part) and down at feed, as faces do between levels.
        const Vec3 here = ctx.path.moves.back().to;
        ctx.rapid({here.x, here.y, clear});
        ctx.rapid(at(from, across[k], clear));
        ctx.feed(at(from, across[k], z));
      } else {
        ctx.feed(at(from, across[k], z));  // step over beyond the open end
      }
      ctx.feed(at(to, across[k], z));
    }
    if (ctx.too_many()) return ctx.limit_reached();
  }
  const Vec3 end = ctx.path.moves.back().to;
  ctx.rapid({end.x, end.y, std::max(retract, clear)});
  return true;
}

}  // namespace ncpost::stepnc::features::legacy
