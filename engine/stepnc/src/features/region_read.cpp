// Clearing a rounded-rectangle or circular region: the reader (region.hpp).

#include <algorithm>
#include <cmath>

#include "milling_read.hpp"
#include "region.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// The tool against the region: its corners, its width, the centre pass.
bool check_fit(Reader& reader, const Region& region, const Tool& tool, const Operation& operation) {
  Report& report = reader.report();
  const auto f = [&] { return reader.name(reader.feature()); };
  const Shape& shape = region.shape;
  const double inset = tool.radius + operation.allowance_side;
  if (region.corners_in_material && shape.kind == Shape::Kind::Rectangle &&
      shape.corner + kEps < inset) {
    const std::string what = tool.subject.name() + " radius " + fmt(tool.radius) + " + allowance " +
                             fmt(operation.allowance_side) + " of " + operation.subject.name() +
                             " > corner radius " + fmt(shape.corner) + " of " + f();
    if (!roughing(reader)) return report.unfit(tool.subject, what);
    // A right-angled corner: the tool's arc stops (inset - corner)(√2 - 1) short of the fillet.
    report.stock_left(tool.subject, what + ": the roughing pass leaves up to " +
                                        fmt((inset - shape.corner) * (std::sqrt(2.0) - 1)) +
                                        " mm more stock in its corners for the finishing pass");
  }
  const double room = std::max(0.0, shape.inradius() - inset);
  if (shape.inradius() - inset < -kEps)
    return report.unfit(tool.subject, tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                                          " + allowances does not fit " + f());
  if (region.centre_only && room > 1e-3)
    return report.unfit(tool.subject, tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                                          " + allowances is " + fmt(2 * room) + " narrower than " +
                                          f() + ", which " + operation.strategy.name() +
                                          " (center milling) cuts in one pass");
  return true;
}

// The strategy's pattern: contour-parallel (the default), or lines along one of the profile's
// sides, in the order stepover_direction asks.
bool read_pattern(Reader& reader, const Region& region, const Operation& operation,
                  RegionSpec& spec) {
  Report& report = reader.report();
  const Subject& strategy = operation.strategy;
  const auto f = [&] { return reader.name(reader.feature()); };
  if (!strategy || reader.is(strategy, "contour_parallel") ||
      (region.centre_only && reader.is(strategy, "center_milling")))
    return true;
  if (region.centre_only)
    return report.not_implemented(strategy.name() + " on " + f() +
                                  ", which only a centre pass can machine");
  using Pattern = RegionSpec::Pattern;
  if (reader.is(strategy, "bidirectional_milling")) {
    spec.pattern = Pattern::Lines;
  } else if (reader.is(strategy, "unidirectional_milling")) {
    spec.pattern = Pattern::Lines;
    spec.zigzag = false;
  } else if (reader.is(strategy, "bidirectional_contour")) {
    spec.pattern = Pattern::LinesThenRing;
  } else if (reader.is(strategy, "contour_bidirectional")) {
    spec.pattern = Pattern::RingThenLines;
  } else {
    return report.not_implemented(strategy.name() + " on " + f());
  }
  if (const auto dir = reader.direction(*strategy.instance, "feed_direction")) {
    const Vec3 fx = region.shape.frame.x;
    const Vec3 fy = region.shape.frame.y;
    if (std::abs(std::abs(dir->dot(fx)) - 1) < 1e-9)
      spec.along_x = true;
    else if (std::abs(std::abs(dir->dot(fy)) - 1) < 1e-9)
      spec.along_x = false;
    else
      return report.not_implemented(strategy.name() + " feed_direction oblique to the sides of " +
                                    f());
    // Left of the feed direction is where the next line goes for stepover_direction LEFT.
    const Vec3 feed_local{dir->dot(fx), dir->dot(fy), 0};
    const Vec3 left{-feed_local.y, feed_local.x, 0};
    spec.lines_up = (spec.along_x ? left.y : left.x) > 0;
  }
  if (reader.enumeration(*strategy.instance, "stepover_direction") == "RIGHT")
    spec.lines_up = !spec.lines_up;
  return true;
}

}  // namespace

bool read_region(Reader& reader, const Region& region, RegionSpec& spec) {
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  return read_region(reader, region, *depth, *tool, reader.read_operation(), spec);
}

bool read_region(Reader& reader, const Region& region, double depth, const Tool& tool,
                 const Operation& operation, RegionSpec& spec) {
  Report& report = reader.report();
  const Subject f = reader.subject(reader.feature());
  if (region.fillet && !check_fillet(reader, tool, operation, *region.fillet)) return false;
  if (!check_fit(reader, region, tool, operation) || !read_pattern(reader, region, operation, spec))
    return false;
  spec.ccw = rings_ccw(reader, operation, true);
  double overlap = 0;
  spec.stepover = stepover(reader, tool, operation, overlap);
  if (!check_overlap(reader, operation, overlap)) return false;
  if (region.shape.kind == Shape::Kind::Rectangle)
    spec.stepover = std::min(spec.stepover, kSharpCornerStep * tool.radius);
  spec.finish =
      depth - (region.through ? -reader.options().through_clearance : operation.allowance_bottom);
  if (!(spec.finish > 0))
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves the whole depth of " + f.name());
  auto levels = depth_levels(reader, operation, spec.finish);
  if (!levels || !check_edge(reader, tool, *levels)) return false;
  if (region.walls_only && spec.pattern != RegionSpec::Pattern::Rings)
    return report.not_implemented(operation.strategy.name() + " for " + operation.subject.name() +
                                  " on " + f.name());
  if (!read_entry(reader, operation, tool, spec.entry) ||
      !read_exit(reader, operation, spec.entry, spec.exit))
    return false;
  spec.shape = region.shape;
  spec.centre_only = region.centre_only;
  spec.walls_only = region.walls_only;
  spec.inset = tool.radius + operation.allowance_side;
  spec.levels = std::move(*levels);
  spec.retract_plane = operation.retract_plane;
  spec.tool = tool.subject;
  spec.feature = f;
  return true;
}

}  // namespace ncpost::stepnc::features
