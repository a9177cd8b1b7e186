// GENERAL_OUTSIDE_PROFILE: the readers (outside.hpp).

#include "milling_read.hpp"
#include "outside.hpp"
#include "profile_read.hpp"

namespace ncpost::stepnc::features {
namespace {

// The part is inside the ring: a contour-parallel strategy or none.
bool check_strategy(Reader& reader, const Operation& operation) {
  const Subject& strategy = operation.strategy;
  if (!strategy || reader.is(strategy, "contour_parallel")) return true;
  return reader.report().not_implemented(strategy.name() + " on " + reader.name(reader.feature()));
}

}  // namespace

bool read_outside_boundary(Reader& reader, OutsideBoundary& boundary) {
  const Instance& f = reader.feature();
  if (!reader.is(&reader.operation(), "side_milling"))
    return reader.report().not_implemented(
        reader.name(reader.operation()) + " on " + reader.name(f) +
        " (an outside profile takes side rough or finish milling)");
  boundary.boundary = reader.ref(f, "feature_boundary", "profile");
  if (boundary.boundary == nullptr)
    return reader.report().bad(reader.subject(f), reader.name(f) + " has no feature_boundary");
  boundary.general = reader.is(boundary.boundary, "general_closed_profile") ||
                     reader.is(boundary.boundary, "ngon_closed_profile");
  return true;
}

bool read_outside(Reader& reader, const OutsideBoundary& boundary, OutsideSpec& spec) {
  if (!read_closed_profile(reader, *boundary.boundary, 0, "profile's", spec.shape)) return false;
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  if (!check_strategy(reader, operation) || !check_air_plunges(reader, operation)) return false;
  // The part is inside the ring: going clockwise it is on the tool's right, which with a
  // clockwise spindle is climb milling.
  spec.ccw = rings_ccw(reader, operation, false, false);
  auto levels = depth_levels(reader, operation, *depth);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  spec.offset = tool->radius + operation.allowance_side;
  spec.tool_radius = tool->radius;
  spec.levels = std::move(*levels);
  spec.retract_plane = operation.retract_plane;
  return true;
}

bool read_general_outside(Reader& reader, const OutsideBoundary& boundary,
                          GeneralOutsideSpec& spec) {
  Report& report = reader.report();
  const Instance& f = reader.feature();
  const auto outline = read_closed_outline(reader, *boundary.boundary);
  if (!outline) return false;
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  if (!check_strategy(reader, operation)) return false;
  if (operation.approach && !reader.is(operation.approach, "plunge_strategy"))
    return report.not_implemented(operation.approach.name() + " as the approach of " +
                                  operation.subject.name());
  if (!corner_checks(reader, *outline, *tool, operation, 0, false)) return false;
  const auto part = polygon_of(reader, *boundary.boundary, *outline, true);
  if (!part) return false;
  const poly::Polygons polygons(reader.options().chord_tolerance);
  const auto grown =
      polygons.offset(poly::Areas{poly::Area{*part, {}}},
                      tool->radius + operation.allowance_side + region_margin(reader.options()));
  if (!grown || grown->size() != 1)
    return report.bad(reader.subject(f), reader.name(f) + ": its outline cannot be offset");
  if (!grown->front().holes.empty())
    return report.unfit(tool->subject, tool->subject.name() + " diameter " + fmt(2 * tool->radius) +
                                           " + allowance " + fmt(operation.allowance_side) +
                                           " of " + operation.subject.name() +
                                           " does not fit into a bay of " + reader.name(f) +
                                           " near " +
                                           at_text(grown->front().holes.front().front()));
  spec.ring = grown->front().outer;
  spec.ccw = rings_ccw(reader, operation, false);
  auto levels = depth_levels(reader, operation, *depth);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  spec.tool_radius = tool->radius;
  spec.levels = std::move(*levels);
  spec.retract_plane = operation.retract_plane;
  return true;
}

}  // namespace ncpost::stepnc::features
