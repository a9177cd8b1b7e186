// CLOSED_POCKET and OPEN_POCKET: the shared reader, the rectangular and circular pockets'
// region, and the round pocket with a half-ball floor (pocket.hpp).

#include <cmath>

#include "milling_read.hpp"
#include "pocket.hpp"
#include "profile_read.hpp"
#include "region.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

bool read_pocket_basics(Reader& reader, PocketKind kind, PocketBasics& basics) {
  Report& report = reader.report();
  const Instance& f = reader.feature();
  const Subject pocket = reader.subject(f);
  const Instance& op = reader.operation();
  basics.walls_only = reader.is(&op, "side_milling");
  if (!reader.is(&op, "bottom_and_side_milling") && !basics.walls_only)
    return report.not_implemented(reader.name(op) + " on " + pocket.name() +
                                  " (pockets take bottom-and-side or side milling)");
  if (reader.has_items(f, "its_boss"))
    return report.not_implemented(pocket.name() + " with bosses (islands)");
  if (const auto slope = reader.number(f, "slope"); slope && std::abs(*slope) > kEps)
    return report.not_implemented(pocket.name() + " with sloped walls");
  basics.bottom = reader.ref(f, "bottom_condition", "pocket_bottom_condition");
  if (basics.bottom == nullptr)
    return report.bad(pocket, pocket.name() + " has no bottom_condition");
  basics.through = reader.is(basics.bottom, "through_pocket_bottom_condition");
  basics.radiused =
      kind == PocketKind::Closed && reader.is(basics.bottom, "radiused_pocket_bottom_condition");
  if (!basics.through && !basics.radiused &&
      !reader.is(basics.bottom, "planar_pocket_bottom_condition"))
    return report.not_implemented(pocket.name() + " with " + reader.name(basics.bottom));
  if (kind == PocketKind::Closed) {
    basics.boundary = reader.ref(f, "feature_boundary", "closed_profile");
    if (basics.boundary == nullptr)
      return report.bad(pocket, pocket.name() + " has no feature_boundary");
    basics.general = reader.is(basics.boundary, "general_closed_profile") ||
                     reader.is(basics.boundary, "ngon_closed_profile");
    return true;
  }
  basics.boundary = reader.ref(f, "open_boundary", "open_profile");
  if (basics.boundary == nullptr)
    return report.bad(pocket, pocket.name() + " has no open_boundary");
  if (const Instance* wall = reader.ref(f, "wall_boundary", "open_profile"))
    report.note(reader.subject(*wall),
                reader.name(*wall) + " is for information only (ISO 14649-10): " + pocket.name() +
                    " is open along the straight line between the ends of " +
                    reader.name(basics.boundary));
  return true;
}

bool read_pocket_region(Reader& reader, const PocketBasics& basics, RegionSpec& spec) {
  const Instance& f = reader.feature();
  Region region;
  const auto corner = reader.toleranced(f, "orthogonal_radius");
  if (!read_closed_profile(reader, *basics.boundary, corner ? corner->size : 0, "pocket's",
                           region.shape))
    return false;
  region.through = basics.through;
  region.fillet = reader.toleranced(f, "planar_radius");
  region.walls_only = basics.walls_only;
  return read_region(reader, region, spec);
}

// A RADIUSED_POCKET_BOTTOM_CONDITION is a portion of a sphere over the whole floor (ISO
// 14649-10). A 2.5D path makes exactly one such pocket: a round pocket whose floor is the lower
// half of a ball of the pocket's own radius, centred on its axis, which a ball end mill of that
// radius makes going straight down the axis. Any other sphere needs 3D surface finishing
// (STEPNC-101); a tool that is not that ball is STEPNC-102.
bool read_radiused_pocket(Reader& reader, const PocketBasics& basics, RadiusedPocketSpec& spec) {
  Report& report = reader.report();
  const Instance& f = reader.feature();
  const Instance& bottom = *basics.bottom;
  const Instance& boundary = *basics.boundary;
  const auto pocket = [&] { return reader.name(f); };
  if (!reader.is(&boundary, "circular_closed_profile"))
    return report.not_implemented(
        pocket() + " with " + reader.name(bottom) + " bounded by " + reader.name(boundary) +
        " (a round pocket whose floor is the half ball of its radius is)");
  Shape shape;
  if (!read_closed_profile(reader, boundary, 0, "pocket's", shape)) return false;
  const auto radius = reader.toleranced(bottom, "floor_radius");
  const auto centre = reader.point(bottom, "floor_radius_center");
  if (!radius || !centre || !(radius->size > 0))
    return report.bad(reader.subject(bottom),
                      reader.name(bottom) + " needs a floor_radius_center and a positive radius");
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  constexpr double kSame = 1e-3;
  const Vec3 axis = shape.frame.origin;
  if (std::hypot(centre->x - axis.x, centre->y - axis.y) > kSame ||
      std::abs(radius->size - shape.half_length) > kSame)
    return report.not_implemented(pocket() + " with " + reader.name(bottom) +
                                  ", a sphere of radius " + fmt(radius->size) + " about (" +
                                  fmt(centre->x) + ", " + fmt(centre->y) + ", " + fmt(centre->z) +
                                  ") that is not the half ball of the pocket's radius " +
                                  fmt(shape.half_length) + " on its axis (3D surface finishing)");
  if (std::abs(centre->z - radius->size + *depth) > kSame)
    return report.bad(reader.subject(bottom),
                      reader.name(bottom) + " puts the lowest point of the floor at z " +
                          fmt(centre->z - radius->size) + ", but the depth plane of " + pocket() +
                          " is at z " + fmt(-*depth));
  const bool ball =
      reader.is(tool->body, "ball_endmill") || std::abs(tool->corner_radius - tool->radius) <= kEps;
  if (!ball || tool->radius > radius->size + radius->upper + kEps ||
      tool->radius + radius->lower + kEps < radius->size)
    return report.unfit(tool->subject, tool->subject.name() + " (radius " + fmt(tool->radius) +
                                           (ball ? ", a ball end" : ", not a ball end") +
                                           ") cannot make " + reader.name(bottom) + " of " +
                                           pocket() + ": that needs a ball end mill of radius " +
                                           fmt(radius->size));
  if (operation.allowance_side > kEps)
    return report.unfit(tool->subject, tool->subject.name() + " fills " + pocket() + ", so " +
                                           operation.subject.name() +
                                           " cannot leave its allowance_side " +
                                           fmt(operation.allowance_side));
  if (operation.approach && !reader.is(operation.approach, "plunge_toolaxis"))
    return report.unfit(operation.approach, operation.approach.name() + ": " +
                                                tool->subject.name() + " fills " + pocket() +
                                                ", no room to enter but along the axis");
  const double finish = *depth - operation.allowance_bottom;
  if (!(finish > 0))
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves the whole depth of " + pocket());
  auto levels = depth_levels(reader, operation, finish);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  spec.axis = axis;
  spec.levels = std::move(*levels);
  spec.retract_plane = operation.retract_plane;
  return true;
}

}  // namespace ncpost::stepnc::features
