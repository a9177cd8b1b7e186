// Pockets with general profiles: the readers (general.hpp). Each builds the region the tool
// centre may use and the floor it must reach, and checks the tool against them before anything
// else of the operation is read, as the generator always has.

#include <algorithm>
#include <cmath>

#include "general.hpp"
#include "milling_read.hpp"
#include "pocket.hpp"
#include "profile_read.hpp"

namespace ncpost::stepnc::features {
namespace {

using poly::Area;
using poly::Areas;
using poly::P;
using poly::Ring;

// What a general pocket (closed or open) hands to the reading of its machining.
struct PocketRegion {
  GeneralRegion region;
  Areas floor;  // what the tool must reach (the floor inset by the side allowance)
  bool through = false;
  std::optional<Toleranced> fillet;  // planar_radius
};

// The closed pocket's outline less its corner fillets, shrunk by the tool's radius + allowance
// (and the margin): the tool centres; shrunk by the allowance only: the floor.
std::optional<PocketRegion> closed_region(Reader& reader, const Instance& boundary,
                                          const Outline& outline, const Tool& tool,
                                          const Operation& operation, double rho) {
  const auto ring = polygon_of(reader, boundary, outline, false);
  if (!ring) return std::nullopt;
  const FeatureOptions& options = reader.options();
  const poly::Polygons polygons(options.chord_tolerance);
  const double d = tool.radius + operation.allowance_side;
  const double margin = region_margin(options);
  const auto fillets = fillet_material(reader, outline, rho, d);
  if (!fillets) return std::nullopt;
  const auto pocket = polygons.difference(Areas{Area{*ring, {}}}, *fillets);
  // Roughing leaves the corners tighter than the tool to the finishing pass (STEPNC-120,
  // corner_checks): the floor it must reach has fillets of the tool's radius + allowance there.
  const bool rough = roughing(reader) && d > rho;
  const auto rough_fillets = rough ? fillet_material(reader, outline, d, d) : fillets;
  if (!rough_fillets) return std::nullopt;
  const auto reached = rough ? polygons.difference(Areas{Area{*ring, {}}}, *rough_fillets) : pocket;
  const auto centres = pocket ? polygons.offset(*pocket, -(d + margin)) : std::nullopt;
  const auto floor = reached ? polygons.offset(*reached, -(operation.allowance_side + 2 * margin +
                                                           options.corner_tolerance))
                             : std::nullopt;
  if (!centres || !floor) {
    reader.report().bad(reader.subject(reader.feature()),
                        reader.name(reader.feature()) + ": its outline cannot be offset");
    return std::nullopt;
  }
  PocketRegion out;
  out.region = {*centres, *pocket, Areas{Area{*ring, {}}}, rho, d + margin};
  out.floor = *floor;
  return out;
}

// The open pocket: the walls closed by the straight open side, counter-clockwise; its regions.
// Beyond the open side the tool may run out by R + clearance: the centre region reaches that
// far past it, and keeps d from the walls, which go on along the open side's line past its ends
// (the part's face there, whose material the tool must not cut either).
std::optional<PocketRegion> open_region(Reader& reader, const Instance& boundary, Outline& walls,
                                        const Tool& tool, const Operation& operation) {
  Report& report = reader.report();
  const FeatureOptions& options = reader.options();
  const Instance& f = reader.feature();
  const auto closed_polygon = [&]() -> std::optional<Ring> {
    return tessellate(walls, options.chord_tolerance, false, options.max_polygon_points);
  };
  auto ring = closed_polygon();
  if (ring && poly::area(*ring) < 0) {
    reverse(walls);
    ring = closed_polygon();
  }
  const Subject named = reader.subject(boundary);
  if (!ring) {
    report.bad(named, named.name() + " needs too many polygon points");
    return std::nullopt;
  }
  if (!poly::simple(*ring)) {
    report.bad(named, named.name() + " and its open side cross or enclose no area");
    return std::nullopt;
  }
  const P a = walls.elements.back().end;  // the open side runs from a to b
  const P b = walls.elements.front().start;
  if ((b - a).length() < 1e-3) {
    report.bad(named, named.name() + " is closed: " + reader.name(f) + " has no open side");
    return std::nullopt;
  }
  const auto corner = reader.toleranced(f, "orthogonal_radius");
  const double rho = corner ? corner->size : 0;
  if (!corner_checks(reader, walls, tool, operation, rho, true)) return std::nullopt;
  const double d = tool.radius + operation.allowance_side;
  const double m = region_margin(options);
  const poly::Polygons polygons(options.chord_tolerance);
  const P along = (b - a) * (1 / (b - a).length());
  const P out{along.y, -along.x};
  const double run = tool.radius + options.clearance;
  const double reach = run + d;
  const Ring beyond{a - along * reach, b + along * reach, b + along * reach + out * run,
                    a - along * reach + out * run};
  auto walls_chain = tessellate(walls, options.chord_tolerance, false, options.max_polygon_points);
  if (!walls_chain) {
    report.bad(named, named.name() + " needs too many polygon points");
    return std::nullopt;
  }
  walls_chain->insert(walls_chain->begin(), b + along * (reach + d + 1));
  walls_chain->push_back(a - along * (reach + d + 1));
  const auto fillet_areas = fillet_material(reader, walls, rho, d);
  if (!fillet_areas) return std::nullopt;
  const Areas& fillets = *fillet_areas;
  const auto united = polygons.unite(Areas{Area{*ring, {}}}, Areas{Area{beyond, {}}});
  const auto open = united ? polygons.difference(*united, fillets) : std::nullopt;
  const auto band = polygons.sweep({}, {*walls_chain}, d + m + options.chord_tolerance);
  const auto fillet_band = polygons.offset(fillets, d + m + options.chord_tolerance);
  const auto keep_off = band && fillet_band ? polygons.unite(*band, *fillet_band) : std::nullopt;
  const auto centres = open && keep_off ? polygons.difference(*open, *keep_off) : std::nullopt;
  const auto inset =
      open ? polygons.offset(*open, -(operation.allowance_side + 2 * m + options.corner_tolerance))
           : std::nullopt;
  const auto floor = inset ? polygons.intersection(*inset, Areas{Area{*ring, {}}}) : std::nullopt;
  if (!centres || !floor) {
    report.bad(reader.subject(f), reader.name(f) + ": its outline cannot be offset");
    return std::nullopt;
  }
  PocketRegion region;
  region.region = {*centres, *centres, *centres, 0, 0};
  region.floor = *floor;
  return region;
}

// Everything of the floor within the tool radius of the centre region: nothing narrower than
// the tool (a neck between two walls) may be left.
bool check_reach(Reader& reader, const Tool& tool, const Operation& operation,
                 const PocketRegion& region) {
  Report& report = reader.report();
  const auto f = [&] { return reader.name(reader.feature()); };
  // Checks only: within a fifth of the corner tolerance, erring towards "not reached".
  const double e = reader.options().corner_tolerance / 5;
  const poly::Polygons polygons(e);
  if (region.region.centres.empty())
    return report.unfit(tool.subject, tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                                          " + allowances does not fit " + f());
  const auto reach = polygons.offset(poly::simplified(region.region.centres, e), tool.radius - e);
  const auto missed = reach ? polygons.difference(region.floor, *reach) : std::nullopt;
  const auto missed_much =
      missed ? polygons.offset(*missed, -reader.options().chord_tolerance) : std::nullopt;
  if (!missed_much)
    return report.bad(reader.subject(reader.feature()), f() + ": its outline cannot be offset");
  if (!missed_much->empty())
    return report.unfit(tool.subject, tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                                          " + allowance " + fmt(operation.allowance_side) + " of " +
                                          operation.subject.name() + " does not reach all of " +
                                          f() + ": a part near " +
                                          at_text(missed_much->front().outer.front()) +
                                          " is narrower than the tool");
  return true;
}

// The strategy's pattern: rings, or lines along its feed direction then (or after) the rings.
bool read_pattern(Reader& reader, const Operation& operation, GeneralPocketSpec& spec) {
  Report& report = reader.report();
  const Subject& strategy = operation.strategy;
  if (!strategy || reader.is(strategy, "contour_parallel")) return true;
  const auto f = [&] { return reader.name(reader.feature()); };
  if (reader.is(strategy, "bidirectional_milling") ||
      reader.is(strategy, "bidirectional_contour")) {
    spec.pattern = GeneralPocketSpec::Pattern::LinesThenRing;
  } else if (reader.is(strategy, "unidirectional_milling")) {
    spec.pattern = GeneralPocketSpec::Pattern::LinesThenRing;
    spec.zigzag = false;
  } else if (reader.is(strategy, "contour_bidirectional")) {
    spec.pattern = GeneralPocketSpec::Pattern::RingThenLines;
  } else {
    return report.not_implemented(strategy.name() + " on " + f());
  }
  if (spec.walls_only)
    return report.not_implemented(strategy.name() + " for " + operation.subject.name() + " on " +
                                  f());
  if (const auto dir = reader.direction(*strategy.instance, "feed_direction")) {
    if (std::abs(dir->z) > 1e-9)
      return report.bad(strategy, strategy.name() + " feed_direction is not in the pocket");
    spec.feed = P{dir->x, dir->y} * (1 / std::hypot(dir->x, dir->y));
  }
  // Lines follow each other to the left of the feed direction, or to the right when asked.
  spec.left = reader.enumeration(*strategy.instance, "stepover_direction") != "RIGHT";
  return true;
}

// What the operation asks of the region: pattern, stepover, levels, approach and retract.
bool read_machining(Reader& reader, const Tool& tool, const Operation& operation,
                    PocketRegion& region, double depth, GeneralPocketSpec& spec) {
  if (!check_reach(reader, tool, operation, region)) return false;
  spec.walls_only = reader.is(&reader.operation(), "side_milling");
  if (!read_pattern(reader, operation, spec)) return false;
  spec.ccw = rings_ccw(reader, operation, true);
  double overlap = 0;
  spec.stepover = stepover(reader, tool, operation, overlap);
  if (!check_overlap(reader, operation, overlap)) return false;
  spec.stepover = std::min(spec.stepover, kSharpCornerStep * tool.radius);
  if (region.fillet && !check_fillet(reader, tool, operation, *region.fillet)) return false;
  const double finish =
      depth - (region.through ? -reader.options().through_clearance : operation.allowance_bottom);
  if (!(finish > 0))
    return reader.report().bad(
        operation.subject,
        operation.subject.name() + " leaves the whole depth of " + reader.name(reader.feature()));
  auto levels = depth_levels(reader, operation, finish);
  if (!levels || !check_edge(reader, tool, *levels)) return false;
  if (!read_entry(reader, operation, tool, spec.entry) ||
      !read_exit(reader, operation, spec.entry, spec.exit))
    return false;
  spec.levels = std::move(*levels);
  spec.region = std::move(region.region);
  spec.retract_plane = operation.retract_plane;
  spec.tool = tool.subject;
  spec.tool_radius = tool.radius;
  spec.operation = operation.subject;
  spec.feature = reader.subject(reader.feature());
  return true;
}

}  // namespace

bool read_general_pocket(Reader& reader, const PocketBasics& basics, GeneralPocketSpec& spec) {
  const Instance& f = reader.feature();
  const auto fillet = reader.toleranced(f, "planar_radius");
  const auto outline = read_closed_outline(reader, *basics.boundary);
  if (!outline) return false;
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  const auto corner = reader.toleranced(f, "orthogonal_radius");
  const double rho = corner ? corner->size : 0;
  if (!corner_checks(reader, *outline, *tool, operation, rho, true)) return false;
  auto region = closed_region(reader, *basics.boundary, *outline, *tool, operation, rho);
  if (!region) return false;
  region->through = basics.through;
  region->fillet = fillet;
  return read_machining(reader, *tool, operation, *region, *depth, spec);
}

bool read_open_pocket(Reader& reader, const PocketBasics& basics, GeneralPocketSpec& spec) {
  auto walls = read_open_outline(reader, *basics.boundary);
  if (!walls) return false;
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  auto region = open_region(reader, *basics.boundary, *walls, *tool, operation);
  if (!region) return false;
  region->through = basics.through;
  region->fillet = reader.toleranced(reader.feature(), "planar_radius");
  return read_machining(reader, *tool, operation, *region, *depth, spec);
}

}  // namespace ncpost::stepnc::features
