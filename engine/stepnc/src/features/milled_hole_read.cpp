// ROUND_HOLE milled rather than drilled: the reader (holes.hpp). The hole's circle is a region
// (region.hpp): the planner goes down by a helix (the default approach: helical interpolation)
// and cuts each level in full circles (circular interpolation), as for a circular pocket.

#include <algorithm>
#include <cmath>

#include "holes.hpp"
#include "reader.hpp"
#include "region.hpp"

namespace ncpost::stepnc::features {

std::optional<Taper> read_taper(Reader& reader, const Instance& hole, double diameter,
                                double depth) {
  const auto value = reader.get(hole, "change_in_diameter");
  if (!value || !value->is_reference()) return Taper{diameter / 2, diameter / 2, {}};
  const Instance* taper = reader.model().find(value->id());
  Taper out{diameter / 2, diameter / 2, reader.subject(taper)};
  const auto bad = [&](const std::string& why) {
    reader.report().bad(out.subject, out.subject.name() + " of " + reader.name(hole) + " " + why);
    return std::nullopt;
  };
  if (reader.is(taper, "diameter_taper")) {
    const auto final_diameter = reader.toleranced(*taper, "final_diameter");
    if (!final_diameter || !(final_diameter->size > 0))
      return bad("needs a positive final_diameter");
    out.bottom = final_diameter->size / 2;
  } else if (reader.is(taper, "angle_taper")) {
    // The angle between the wall and the hole's axis; positive: the hole narrows downwards.
    const auto angle = reader.number(*taper, "angle");
    if (!angle || !(std::abs(*angle) < 90)) return bad("needs an angle within (-90, 90) degrees");
    out.bottom = out.top - depth * std::tan(radians(*angle));
    if (!(out.bottom > 0)) return bad("closes the hole above its depth");
  } else {
    return bad("is neither a DIAMETER_TAPER nor an ANGLE_TAPER");
  }
  return out;
}

namespace {

// What both milled readers need first: the hole's diameter and its bottom condition, or the
// report that the hole lacks them (nullopt).
struct HoleOutline {
  double diameter;
  const Instance* bottom;
};

std::optional<HoleOutline> read_hole_outline(Reader& reader) {
  const Instance& hole = reader.feature();
  const auto diameter = reader.toleranced(hole, "diameter");
  const Instance* bottom = reader.ref(hole, "bottom_condition", "hole_bottom_condition");
  if (!diameter || !(diameter->size > 0) || bottom == nullptr) {
    (void)reader.report().bad(
        reader.subject(hole),
        reader.name(hole) + " needs a positive diameter and a bottom_condition");
    return std::nullopt;
  }
  return HoleOutline{diameter->size, bottom};
}

}  // namespace

bool read_milled_hole(Reader& reader, RegionSpec& spec) {
  Report& report = reader.report();
  const Instance& hole = reader.feature();
  const Instance& op = reader.operation();
  const auto outline = read_hole_outline(reader);
  if (!outline) return false;
  const Instance* bottom = outline->bottom;
  Region region;
  region.shape = Shape::circle(outline->diameter / 2);
  region.walls_only = reader.is(&op, "side_milling");
  if (reader.is(bottom, "through_bottom_condition")) {
    region.through = true;
  } else if (reader.is(bottom, "flat_with_radius_hole_bottom")) {
    region.fillet = reader.toleranced(*bottom, "corner_radius");
  } else if (!reader.is(bottom, "flat_hole_bottom")) {
    return report.not_implemented(
        reader.name(op) + " on " + reader.name(hole) + " with " + reader.name(bottom) +
        " (an end mill makes a flat, flat-with-radius, spherical or through bottom; a conical "
        "bottom is a drill's)");
  }
  return read_region(reader, region, spec);
}

bool read_milled_taper(Reader& reader, MilledTaperSpec& spec) {
  Report& report = reader.report();
  const Instance& hole = reader.feature();
  const Instance& op = reader.operation();
  const auto outline = read_hole_outline(reader);
  if (!outline) return false;
  const Instance* bottom = outline->bottom;
  const auto depth = reader.read_depth();
  if (!depth) return false;
  const auto taper = read_taper(reader, hole, outline->diameter, *depth);
  if (!taper) return false;
  const auto shape = [&] {
    return reader.name(hole) + " with " + taper->subject.name() + " (diameter " +
           fmt(2 * taper->top) + " at the top, " + fmt(2 * taper->bottom) + " at the depth)";
  };
  if (!(taper->bottom < taper->top))
    return report.not_implemented(reader.name(op) + " on " + shape() +
                                  ", which widens downwards (an undercut no tool reaches from "
                                  "above),");
  const bool through = reader.is(bottom, "through_bottom_condition");
  if (!through && !reader.is(bottom, "flat_hole_bottom"))
    return report.not_implemented(reader.name(op) + " on " + shape() + " and " +
                                  reader.name(bottom) +
                                  " (a milled taper has a flat or through "
                                  "bottom),");
  Region region;
  region.shape = Shape::circle(taper->bottom);
  region.through = through;
  region.walls_only = reader.is(&op, "side_milling");
  if (!read_region(reader, region, spec.core)) return false;
  spec.top = taper->top;
  spec.bottom = taper->bottom;
  spec.depth = *depth;
  // Steps of at most profile_tolerance across the cone: dz · slope <= tolerance.
  const double last = std::min(spec.core.finish, *depth);
  const double slope = (taper->top - taper->bottom) / *depth;
  const double n = std::ceil(last * slope / reader.options().profile_tolerance);
  if (!(n * 4 < static_cast<double>(reader.options().max_moves)))
    return reader.report().limit_reached(reader.options().max_moves);
  const auto count = static_cast<std::size_t>(std::max(1.0, n));
  for (std::size_t k = 1; k <= count; ++k)
    spec.levels.push_back(-last * static_cast<double>(k) / static_cast<double>(count));
  return true;
}

}  // namespace ncpost::stepnc::features
