// A ROUND_HOLE with a SPHERICAL_HOLE_BOTTOM milled: the reader (holes.hpp). In the hole's
// half section (distance from the axis, height), the tool's corner circle (radius c, the ball's
// whole radius for a ball end mill) has its centre at the flat's edge, f = r - c from the axis.
// The tool's lower surface is the flat disc of radius f swept by a ball of radius c, so it stays
// inside the sphere (radius R' = R - allowance_bottom, centre O) exactly when the disc stays
// inside the sphere of radius rho = R' - c: (axis distance + f)² + (height - O)² <= rho². A
// full circle with the disc's edge on that sphere touches the bottom along one circle; going
// down, the last has the axis at the hole's and leaves rho - sqrt(rho² - f²) at the centre.

#include <algorithm>
#include <cmath>

#include "holes.hpp"
#include "milling_read.hpp"
#include "reader.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// The sphere's geometry for one tool and operation, in the hole's coordinates.
struct SphereOffset {
  double centre = 0;  // O's height
  double rho = 0;     // the sphere the corner circle's centre keeps within
  double wall = 0;    // the farthest the corner circle's centre goes from the axis
  double flat = 0;    // f
  double corner = 0;  // c
  // The axis distance of the full circle whose tip is at height z.
  [[nodiscard]] double axis_at(double z) const {
    const double dz = z + corner - centre;
    const double s = dz >= 0 ? wall : std::min(wall, std::sqrt(std::max(0.0, rho * rho - dz * dz)));
    return std::max(0.0, s - flat);
  }
};

// The approach, retract, stepover and sense of the rings when no cylinder is cleared first
// (read_region does that for the core otherwise).
bool read_without_core(Reader& reader, const Tool& tool, const Operation& operation,
                       double hole_radius, RegionSpec& core) {
  if (tool.radius + operation.allowance_side > hole_radius + kEps)
    return reader.report().unfit(tool.subject,
                                 tool.subject.name() + " diameter " + fmt(2 * tool.radius) +
                                     " + allowances does not fit " + reader.name(reader.feature()));
  double overlap = 0;
  core.stepover = stepover(reader, tool, operation, overlap);
  if (!check_overlap(reader, operation, overlap)) return false;
  core.ccw = rings_ccw(reader, operation, true);
  if (!read_entry(reader, operation, tool, core.entry) ||
      !read_exit(reader, operation, core.entry, core.exit))
    return false;
  core.shape = Shape::circle(hole_radius);
  core.inset = tool.radius + operation.allowance_side;
  core.retract_plane = operation.retract_plane;
  core.tool = tool.subject;
  core.feature = reader.subject(reader.feature());
  return true;
}

}  // namespace

bool spherical_bottom(Reader& reader) {
  const auto bottom = reader.get(reader.feature(), "bottom_condition");
  return bottom && bottom->is_reference() &&
         reader.is(reader.model().find(bottom->id()), "spherical_hole_bottom");
}

bool read_milled_sphere(Reader& reader, MilledSphereSpec& spec) {
  Report& report = reader.report();
  const Instance& hole = reader.feature();
  const Instance& op = reader.operation();
  const auto h = [&] { return reader.name(hole); };
  const auto diameter = reader.toleranced(hole, "diameter");
  const Instance* bottom = reader.ref(hole, "bottom_condition", "hole_bottom_condition");
  if (!diameter || !(diameter->size > 0) || bottom == nullptr)
    return report.bad(reader.subject(hole),
                      h() + " needs a positive diameter and a bottom_condition");
  if (reader.is(&op, "side_milling"))
    return report.not_implemented(reader.name(op) + " on " + h() + " with " + reader.name(bottom) +
                                  " (side milling cuts the wall alone; the sphere is the "
                                  "bottom-and-side milling's)");
  const double hole_radius = diameter->size / 2;
  const auto sphere = reader.toleranced(*bottom, "radius");
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const std::string shape = [&] {
    return reader.name(bottom) + " of radius " + fmt(sphere ? sphere->size : 0) + " in " + h() +
           " (diameter " + fmt(diameter->size) + ", depth " + fmt(*depth) + ")";
  }();
  if (!sphere || !(sphere->size + sphere->upper + kEps >= hole_radius))
    return report.bad(reader.subject(*bottom),
                      shape + ": the sphere needs a radius of at least the hole's, " +
                          fmt(hole_radius) + ", to close its bottom");
  const double R = std::max(sphere->size, hole_radius);
  const double cap = R - std::sqrt(std::max(0.0, R * R - hole_radius * hole_radius));
  if (cap > *depth + kEps)
    return report.bad(reader.subject(*bottom),
                      shape + ": the sphere meets the wall " + fmt(cap) +
                          " above its lowest point, higher than the hole's top");
  const Operation operation = reader.read_operation();
  const double corner = std::clamp(tool->corner_radius, 0.0, tool->radius);
  const bool ball = reader.is(tool->body, "ball_endmill") || corner >= tool->radius - kEps;
  SphereOffset g;
  g.corner = ball ? tool->radius : corner;
  g.flat = tool->radius - g.corner;
  if (!(g.corner > kEps))
    return report.unfit(tool->subject,
                        tool->subject.name() + " is a flat end mill, which cannot form " + shape +
                            ": its edge leaves steps on the sphere (a ball end mill, or a bull "
                            "nose whose flat is small enough, does)");
  const double inner = R - operation.allowance_bottom;
  if (tool->radius > inner + kEps)
    return report.unfit(
        tool->subject,
        tool->subject.name() + " radius " + fmt(tool->radius) + " is larger than the sphere's " +
            (operation.allowance_bottom > 0
                 ? fmt(inner) + " (its radius " + fmt(R) + " less allowance_bottom " +
                       fmt(operation.allowance_bottom) + ")"
                 : fmt(R)) +
            ": it cannot form " + shape);
  g.rho = inner - g.corner;
  g.centre = -*depth + R;
  const double tolerance = reader.options().profile_tolerance;
  const double mound = g.rho - std::sqrt(std::max(0.0, g.rho * g.rho - g.flat * g.flat));
  if (mound > tolerance + kEps)
    return report.unfit(
        tool->subject, tool->subject.name() + " (radius " + fmt(tool->radius) + ", corner radius " +
                           fmt(g.corner) + ") cannot form " + shape + ": its flat leaves " +
                           fmt(mound) + " at the centre of the sphere, more than the tolerance " +
                           fmt(tolerance));
  g.wall = std::min(hole_radius - operation.allowance_side - g.corner, g.rho);
  // The cylinder, down to where the sphere starts (its allowance above that).
  const double cylinder = *depth - cap;
  spec.has_core = cylinder - operation.allowance_bottom > tolerance;
  Region region;
  region.shape = Shape::circle(hole_radius);
  if (spec.has_core ? !read_region(reader, region, cylinder, *tool, operation, spec.core)
                    : !read_without_core(reader, *tool, operation, hole_radius, spec.core))
    return false;
  const double top = spec.has_core ? spec.core.levels.back() : 0;
  const double lowest = g.centre - std::sqrt(g.rho * g.rho - g.flat * g.flat) - g.corner;
  auto steps = depth_levels(reader, operation, top - lowest);
  if (!steps) return false;
  std::vector<double> heights;
  for (const double dz : *steps) heights.push_back(top + dz);
  if (!check_edge(reader, *tool, *steps)) return false;
  // Clearing levels down to where the disc gets narrower than the tool's radius: below, the
  // circles' tools cover the axis, and each takes off what lies above the next.
  for (const double z : heights)
    if (g.axis_at(z) >= tool->radius) spec.levels.push_back({g.axis_at(z), z});
  // The rings: down the wall from the core's last level to where the offset sphere starts,
  // then along its meridian, each step leaving a cusp of at most the tolerance.
  const double max_moves = static_cast<double>(reader.options().max_moves);
  const double c = g.corner;
  const double wall_step = 2 * std::sqrt(std::max(0.0, 2 * c * tolerance - tolerance * tolerance));
  const double from = top + c;  // the corner circle's centre at the core's last level
  const double to = g.centre - std::sqrt(std::max(0.0, g.rho * g.rho - g.wall * g.wall));
  const double polar_top = std::asin(std::clamp(g.wall / g.rho, 0.0, 1.0));
  const double polar_end = std::asin(std::clamp(g.flat / g.rho, 0.0, 1.0));
  const double dphi = scallop_step(g.rho, c, tolerance);
  const double wall_n = from > to ? std::ceil((from - to) / wall_step - 1e-9) : 0;
  const double arc_n = std::ceil((polar_top - polar_end) / dphi - 1e-9);
  if (!(wall_step > 0) || !(dphi > 0) ||
      wall_n + arc_n + static_cast<double>(spec.levels.size()) > max_moves / 4)
    return report.limit_reached(reader.options().max_moves);
  const auto walls = static_cast<std::size_t>(wall_n);
  for (std::size_t k = 1; k <= walls; ++k)
    spec.rings.push_back(
        {g.wall - g.flat,
         from - (from - to) * static_cast<double>(k) / static_cast<double>(walls) - c});
  const auto arcs = static_cast<std::size_t>(std::max(0.0, arc_n));
  for (std::size_t j = walls > 0 ? 1 : 0; j <= arcs; ++j) {
    const double phi = arcs == 0 ? polar_end
                                 : polar_top - (polar_top - polar_end) * static_cast<double>(j) /
                                                   static_cast<double>(arcs);
    spec.rings.push_back(
        {std::max(0.0, g.rho * std::sin(phi) - g.flat), g.centre - g.rho * std::cos(phi) - c});
  }
  return true;
}

}  // namespace ncpost::stepnc::features
