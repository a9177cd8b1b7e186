// STEP: the reader (step.hpp).

#include <cmath>

#include "milling_read.hpp"
#include "reader.hpp"
#include "step.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// The open boundary: where it starts, its direction and length in the step's top plane.
bool read_open_boundary(Reader& reader, StepSpec& spec) {
  Report& report = reader.report();
  const Instance& step = reader.feature();
  const Instance* open = reader.ref(step, "open_boundary", "linear_path");
  if (open == nullptr)
    return report.bad(reader.subject(step), reader.name(step) + " has no open_boundary");
  const auto length = reader.toleranced(*open, "distance");
  auto along = reader.direction(*open, "its_direction");
  if (!length || !along || !(length->size > 0))
    return report.bad(reader.subject(*open),
                      reader.name(*open) + " needs a positive distance and a direction");
  if (!reader.size_ok(*open, length->size, "distance")) return false;
  Vec3 origin{};
  if (reader.set(*open, "placement")) {
    const auto frame = reader.placement(*open, "placement");
    if (!frame) return false;
    if (std::abs(frame->z.z - 1) > 1e-9 || std::abs(frame->origin.z) > kEps)
      return report.not_implemented(reader.name(*open) + " placed out of " + reader.name(step) +
                                    "'s top plane");
    origin = frame->origin;
    along = frame->direction(*along);
  }
  if (std::abs(along->z) > kEps)
    return report.bad(reader.subject(*open), reader.name(*open) + " does not run in " +
                                                 reader.name(step) + "'s top plane");
  spec.origin = origin;
  spec.along = *along * (1.0 / along->length());
  spec.length = length->size;
  return true;
}

// The wall: where its foot is (so the width), its angle to the floor and its fillet.
bool read_wall(Reader& reader, double depth, StepSpec& spec, std::optional<Toleranced>& fillet) {
  Report& report = reader.report();
  const Instance& step = reader.feature();
  const Subject named = reader.subject(step);
  const Instance* wall = reader.ref(step, "wall_boundary", "vee_profile");
  if (wall == nullptr || !reader.set(*wall, "placement"))
    return report.bad(
        named,
        named.name() + " has no width: " +
            (wall == nullptr ? std::string("it has no wall_boundary")
                             : "its wall_boundary " + reader.name(*wall) + " has no placement") +
            ", and the schema locates a step's wall only by the placement of its "
            "wall_boundary's vee (the foot of the wall)");
  const auto foot = reader.placement(*wall, "placement");
  if (!foot) return false;
  if (std::abs(foot->origin.z) > kEps && std::abs(foot->origin.z + depth) > 1e-6)
    return report.bad(reader.subject(*wall), reader.name(*wall) +
                                                 " places the foot of the wall at z " +
                                                 fmt(foot->origin.z) + ", neither on " +
                                                 named.name() + "'s floor nor at its top");
  const Vec3 left = Vec3{0, 0, 1}.cross(spec.along);
  spec.width = (foot->origin - spec.origin).dot(left);
  const double width = std::abs(spec.width);
  if (!reader.size_ok(step, width, "width (open boundary to wall)")) return false;
  if (!(width > 1e-6))
    return report.bad(named, named.name() + "'s wall (the vertex of " + reader.name(*wall) +
                                 ") stands on its open boundary: the step has no width");
  const auto angle = reader.number(*wall, "profile_angle");
  const auto tilt = reader.number(*wall, "tilt_angle");
  fillet = reader.toleranced(*wall, "profile_radius");
  if (!angle || !tilt)
    return report.bad(reader.subject(*wall),
                      reader.name(*wall) + " needs a profile_angle and tilt");
  if (std::abs(*tilt) > 1e-6)
    return report.not_implemented(
        named.name() + " whose " + reader.name(*wall) +
        " is tilted (its first side, the floor, is not along its x axis)");
  if (std::abs(*angle - 90) > 1e-6)
    return report.not_implemented(named.name() + " with a wall at " + fmt(*angle) +
                                  " degrees to the floor (" + reader.name(*wall) +
                                  "; vertical walls are)");
  return true;
}

// The fillet at the foot of the wall is the tool's corner radius (as a pocket's floor radius).
bool check_fillet(Reader& reader, const Tool& tool, const Operation& operation,
                  const std::optional<Toleranced>& fillet) {
  const auto step = [&] { return reader.name(reader.feature()); };
  const double rho = fillet ? fillet->size : 0;
  const double upper = fillet ? fillet->upper : 0;
  const double lower = fillet ? fillet->lower : 0;
  if (tool.corner_radius > rho + upper + operation.allowance_bottom + kEps)
    return reader.report().unfit(tool.subject,
                                 tool.subject.name() + " edge radius " + fmt(tool.corner_radius) +
                                     " > the wall's radius " + fmt(rho) + " + allowance " +
                                     fmt(operation.allowance_bottom) + " of " + step());
  if (tool.corner_radius + lower + kEps < rho)
    return reader.report().unfit(tool.subject, tool.subject.name() + " edge radius " +
                                                   fmt(tool.corner_radius) +
                                                   " < the wall's radius " + fmt(rho) + " of " +
                                                   step() + ": the tool would cut the fillet away");
  return true;
}

// Passes parallel to the wall, from the open boundary to the wall: back and forth or one way.
bool read_strategy(Reader& reader, const Operation& operation, StepSpec& spec) {
  Report& report = reader.report();
  const Subject& strategy = operation.strategy;
  const auto step = [&] { return reader.name(reader.feature()); };
  if (strategy) {
    const Instance& instance = *strategy.instance;
    if (reader.is(strategy, "bidirectional_milling")) {
      spec.one_way = false;
    } else if (!reader.is(strategy, "unidirectional_milling") &&
               !reader.is(strategy, "contour_parallel")) {
      return report.not_implemented(strategy.name() + " on " + step());
    }
    if (const auto feed = reader.direction(instance, "feed_direction");
        feed && std::abs(std::abs(feed->dot(spec.along)) - 1) > 1e-9)
      return report.not_implemented(strategy.name() + " feed_direction across the wall of " +
                                    step() + " (passes run along the wall)");
    if (reader.set(instance, "stepover_direction"))
      report.note(strategy, strategy.name() + ": the passes over " + step() +
                                " go from its open boundary towards its wall, whichever the "
                                "stepover_direction");
  }
  return check_air_plunges(reader, operation, [&](bool) {
    return ": every pass over " + step() +
           " starts and ends outside the material, so the tool moves along its axis there";
  });
}

// Climb milling with the material on the tool's right: with a clockwise spindle, the wall side
// (the uncut material) must be on the right of the pass.
bool passes_forward(Reader& reader, const Operation& operation, double width) {
  const bool spindle_cw = !reader.spindle() || *reader.spindle() <= 0;
  const std::string_view cutmode = operation.strategy
                                       ? reader.enumeration(*operation.strategy.instance, "cutmode")
                                       : std::string_view();
  const bool climb = cutmode != "CONVENTIONAL";
  // Moving along +along the wall is on the left when the width is positive.
  const bool material_right_forward = width < 0;
  return (climb == spindle_cw) == material_right_forward;
}

}  // namespace

bool read_step(Reader& reader, StepSpec& spec) {
  Report& report = reader.report();
  const Subject step = reader.subject(reader.feature());
  const Instance& op = reader.operation();
  spec.walls_only = reader.is(&op, "side_milling");
  if (!reader.is(&op, "bottom_and_side_milling") && !spec.walls_only)
    return report.not_implemented(reader.name(op) + " on " + step.name() +
                                  " (steps take bottom-and-side or side milling)");
  if (reader.has_items(reader.feature(), "its_boss"))
    return report.not_implemented(step.name() + " with bosses");
  if (!read_open_boundary(reader, spec)) return false;
  const auto depth = reader.read_depth();
  if (!depth) return false;
  std::optional<Toleranced> fillet;
  if (!read_wall(reader, *depth, spec, fillet)) return false;
  const auto tool = reader.read_tool();
  if (!tool) return false;
  const Operation operation = reader.read_operation();
  if (!check_fillet(reader, *tool, operation, fillet) || !read_strategy(reader, operation, spec))
    return false;
  spec.stepover = stepover(reader, *tool, operation, spec.overlap);
  if (!check_overlap(reader, operation, spec.overlap)) return false;
  const double finish = *depth - operation.allowance_bottom;
  if (!(finish > 0))
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves the whole depth of " + step.name());
  auto levels = depth_levels(reader, operation, finish);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  spec.levels = std::move(*levels);
  spec.tool_radius = tool->radius;
  spec.allowance_side = operation.allowance_side;
  spec.retract_plane = operation.retract_plane;
  spec.forward = passes_forward(reader, operation, spec.width);
  return true;
}

}  // namespace ncpost::stepnc::features
