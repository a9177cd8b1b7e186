// What the 2.5D milling readers share (milling_read.hpp).

#include "milling_read.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;
// With no overlap in the strategy: half the diameter between neighbouring passes.
constexpr double kDefaultOverlap = 0.5;

}  // namespace

double stepover(Reader& reader, const Tool& tool, const Operation& operation, double& overlap) {
  overlap = kDefaultOverlap;
  if (operation.strategy) {
    if (auto v = reader.number(*operation.strategy.instance, "overlap")) overlap = *v;
  }
  double step = 2 * tool.radius * (1 - overlap);
  if (operation.radial && *operation.radial > 0) step = std::min(step, *operation.radial);
  return step;
}

bool check_overlap(Reader& reader, const Operation& operation, double overlap) {
  if (overlap >= 0 && overlap < 1) return true;
  const Subject& at = operation.strategy ? operation.strategy : operation.subject;
  return reader.report().bad(
      at, at.name() + " overlap " + std::to_string(overlap) + " is not in [0, 1)");
}

bool check_edge(Reader& reader, const Tool& tool, const std::vector<double>& z) {
  double deepest = -z.front();
  for (std::size_t i = 1; i < z.size(); ++i) deepest = std::max(deepest, z[i - 1] - z[i]);
  if (!tool.edge_length || *tool.edge_length + kEps >= deepest) return true;
  return reader.report().unfit(tool.subject, tool.subject.name() + " cutting edge length " +
                                                 fmt(*tool.edge_length) + " is shorter than the " +
                                                 fmt(deepest) + " axial depth per level that " +
                                                 reader.name(reader.operation()) + " needs on " +
                                                 reader.name(reader.feature()));
}

bool check_fillet(Reader& reader, const Tool& tool, const Operation& operation,
                  const Toleranced& fillet) {
  const auto feature = [&] { return reader.name(reader.feature()); };
  if (tool.corner_radius > fillet.size + fillet.upper + operation.allowance_bottom + kEps)
    return reader.report().unfit(
        tool.subject, tool.subject.name() + " edge radius " + fmt(tool.corner_radius) +
                          " > planar (floor) radius " + fmt(fillet.size) + " + allowance " +
                          fmt(operation.allowance_bottom) + " of " + feature());
  if (tool.corner_radius + fillet.lower + kEps < fillet.size)
    return reader.report().unfit(
        tool.subject, tool.subject.name() + " edge radius " + fmt(tool.corner_radius) +
                          " < planar (floor) radius " + fmt(fillet.size) + " of " + feature() +
                          ": the tool would cut the fillet away");
  return true;
}

std::optional<std::vector<double>> depth_levels(Reader& reader, const Operation& operation,
                                                double depth) {
  bool multiple = true;
  if (operation.strategy)
    multiple = reader.boolean(*operation.strategy.instance, "allow_multiple_passes").value_or(true);
  if (!multiple && operation.axial && *operation.axial + kEps < depth) {
    reader.report().unfit(operation.strategy,
                          operation.strategy.name() + " forbids multiple passes, but " +
                              operation.subject.name() + " cuts at most " + fmt(*operation.axial) +
                              " deep and " + reader.name(reader.feature()) + " is " + fmt(depth) +
                              " deep");
    return std::nullopt;
  }
  if (multiple && operation.axial && *operation.axial > 0 &&
      depth / *operation.axial > static_cast<double>(reader.options().max_moves)) {
    reader.report().limit_reached(reader.options().max_moves);
    return std::nullopt;
  }
  return levels(depth, multiple ? operation.axial : std::nullopt);
}

bool read_plunge(Reader& reader, const Instance& strategy, std::string_view role, Entry& entry) {
  entry.strategy = reader.subject(strategy);
  if (reader.is(&strategy, "plunge_toolaxis")) {
    entry.kind = Entry::Kind::Plunge;
    return true;
  }
  if (reader.is(&strategy, "plunge_helix")) {
    entry.kind = Entry::Kind::Helix;
    entry.radius = reader.number(strategy, "radius").value_or(entry.radius);
    if (const auto angle = reader.number(strategy, "angle")) entry.angle = radians(*angle);
  } else if (reader.is(&strategy, "plunge_ramp") || reader.is(&strategy, "plunge_zigzag")) {
    entry.kind = Entry::Kind::Ramp;
    entry.angle = radians(reader.number(strategy, "angle").value_or(0));
    entry.width = reader.number(strategy, "width").value_or(0);
  } else {
    return reader.report().not_implemented(reader.name(strategy) + " as the " + std::string(role) +
                                           " " + reader.name(reader.feature()));
  }
  if (!(entry.angle > 0 && entry.angle < radians(90)))
    return reader.report().bad(entry.strategy,
                               entry.strategy.name() + " angle must be between 0 and 90 degrees");
  return true;
}

bool read_entry(Reader& reader, const Operation& operation, const Tool& tool, Entry& entry) {
  entry = Entry{};
  entry.radius = reader.options().default_helix_radius * tool.radius;
  entry.angle = radians(reader.options().default_helix_angle);
  if (!operation.approach) return true;
  entry.explicit_entry = true;
  return read_plunge(reader, *operation.approach.instance, "approach into", entry);
}

bool read_exit(Reader& reader, const Operation& operation, const Entry& entry, Entry& exit) {
  exit = Entry{};
  exit.kind = Entry::Kind::Plunge;
  exit.radius = entry.radius;
  exit.angle = entry.angle;
  return !operation.retract ||
         read_plunge(reader, *operation.retract.instance, "retract from", exit);
}

bool check_air_plunges(Reader& reader, const Operation& operation,
                       const std::function<std::string(bool approach)>& note) {
  for (const auto& [strategy, role, approach] :
       {std::tuple{&operation.approach, "approach", true},
        std::tuple{&operation.retract, "retract", false}}) {
    if (!*strategy) continue;
    if (!reader.is(*strategy, "plunge_strategy"))
      return reader.report().not_implemented(strategy->name() + " as the " + role + " of " +
                                             operation.subject.name());
    if (note && !reader.is(*strategy, "plunge_toolaxis"))
      reader.report().note(*strategy, strategy->name() + note(approach));
  }
  return true;
}

bool rings_ccw(Reader& reader, const Operation& operation, bool wall_outside, bool note_conflict) {
  const bool spindle_cw = !reader.spindle() || *reader.spindle() <= 0;  // NIST: negative = CW
  // A pocket's wall is outside the path: going counter-clockwise it is on the tool's right,
  // which with a clockwise spindle is climb milling. Round a part it is the other way.
  const bool climb_ccw = wall_outside ? spindle_cw : !spindle_cw;
  const Instance* strategy = operation.strategy.instance;
  const std::string_view cutmode =
      strategy ? reader.enumeration(*strategy, "cutmode") : std::string_view();
  const std::string_view rotation =
      strategy ? reader.enumeration(*strategy, "rotation_direction") : std::string_view();
  if (rotation.empty()) return cutmode == "CONVENTIONAL" ? !climb_ccw : climb_ccw;
  const bool ccw = rotation == "CCW";
  if (note_conflict && !cutmode.empty() && (cutmode == "CLIMB") != (ccw == climb_ccw))
    reader.report().note(operation.strategy, operation.strategy.name() + ": rotation_direction ." +
                                                 std::string(rotation) +
                                                 ". is followed; with this spindle it mills " +
                                                 (ccw == climb_ccw ? "climb" : "conventional") +
                                                 ", not ." + std::string(cutmode) + ".");
  return ccw;
}

bool roughing(Reader& reader) {
  const Instance* op = &reader.operation();
  return reader.is(op, "bottom_and_side_rough_milling") || reader.is(op, "side_rough_milling") ||
         reader.is(op, "plane_rough_milling");
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

}  // namespace ncpost::stepnc::features
