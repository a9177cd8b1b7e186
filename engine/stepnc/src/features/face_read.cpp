// PLANAR_FACE: the reader (face.hpp).

#include <cmath>

#include "face.hpp"
#include "milling_read.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// The rectangle: course_of_travel (direction and length) and removal_boundary (its width).
bool read_rectangle(Reader& reader, FaceSpec& spec) {
  Report& report = reader.report();
  const Instance& face = reader.feature();
  const Subject named = reader.subject(face);
  if (reader.set(face, "face_boundary"))
    return report.not_implemented(named.name() + " with a face_boundary");
  if (reader.has_items(face, "its_boss"))
    return report.not_implemented(named.name() + " with bosses");
  const Instance* travel = reader.ref(face, "course_of_travel", "linear_path");
  const Instance* removal = reader.ref(face, "removal_boundary", "linear_profile");
  if (travel == nullptr || removal == nullptr)
    return report.bad(named, named.name() + " needs a course_of_travel and a removal_boundary");
  if (reader.set(*travel, "placement") || reader.set(*removal, "placement"))
    return report.not_implemented(named.name() +
                                  " with a placed course_of_travel or removal_boundary");
  const auto length = reader.toleranced(*travel, "distance");
  const auto along = reader.direction(*travel, "its_direction");
  const Instance* width_parameter = reader.ref(*removal, "profile_length", "numeric_parameter");
  const double width =
      width_parameter ? reader.number(*width_parameter, "its_parameter_value").value_or(0) : 0;
  if (!length || !along || !(length->size > 0) || !(width > 0) || std::abs(along->z) > kEps)
    return report.bad(named, named.name() +
                                 " needs a positive travel distance and profile length, and a "
                                 "course of travel in its plane");
  spec.travel = *along;
  spec.length = length->size;
  spec.width = width;
  return true;
}

// Bidirectional unless the strategy says otherwise; the feed direction along the travel unless
// it says otherwise.
bool read_strategy(Reader& reader, const Operation& operation, FaceSpec& spec) {
  Report& report = reader.report();
  const Subject& strategy = operation.strategy;
  std::optional<Vec3> feed;
  if (strategy) {
    const Instance& instance = *strategy.instance;
    if (reader.is(strategy, "bidirectional_milling")) {
      spec.left = reader.enumeration(instance, "stepover_direction") != "RIGHT";
      if (reader.set(instance, "its_stroke_connection_strategy") &&
          reader.enumeration(instance, "its_stroke_connection_strategy") != "STRAIGHTLINE")
        return report.not_implemented(strategy.name() +
                                      " with a stroke connection other than "
                                      "straightline");
    } else if (reader.is(strategy, "unidirectional_milling")) {
      spec.bidirectional = false;
      if (reader.set(instance, "cutmode"))
        report.note(strategy, strategy.name() +
                                  ": cutmode has no effect on a planar face, whose passes run "
                                  "past the material on both sides");
    } else {
      return report.not_implemented(strategy.name() + " on " + reader.name(reader.feature()) +
                                    " (planar faces take unidirectional or bidirectional milling)");
    }
    feed = reader.direction(instance, "feed_direction");
  }
  const auto face = [&] { return reader.name(reader.feature()); };
  const auto note = [&](bool approach) {
    return ": every pass of " + face() +
           (approach ? " starts outside the material, so the tool goes down along its axis there"
                     : " ends outside the material, so the tool leaves along its axis there");
  };
  if (!check_air_plunges(reader, operation, note)) return false;
  Vec3 u = feed.value_or(spec.travel);
  if (std::abs(u.z) > kEps)
    return report.bad(strategy, strategy.name() + " feed_direction is not in the face");
  u = u * (1.0 / u.length());
  const Vec3 p = spec.travel.cross({0, 0, 1});
  const bool parallel = std::abs(std::abs(u.dot(spec.travel)) - 1) < 1e-9;
  const bool across = std::abs(std::abs(u.dot(p)) - 1) < 1e-9;
  if (!parallel && !across)
    return report.not_implemented(strategy.name() +
                                  " feed_direction oblique to the course of "
                                  "travel of " +
                                  face());
  spec.feed = u;
  return true;
}

}  // namespace

bool read_face(Reader& reader, FaceSpec& spec) {
  Report& report = reader.report();
  const Subject face = reader.subject(reader.feature());
  if (!reader.is(&reader.operation(), "plane_milling"))
    return report.not_implemented(reader.name(reader.operation()) + " on " + face.name() +
                                  " (a planar face takes plane rough or finish milling)");
  if (!read_rectangle(reader, spec)) return false;
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  if (!read_strategy(reader, operation, spec)) return false;
  spec.stepover = stepover(reader, *tool, operation, spec.overlap);
  if (!check_overlap(reader, operation, spec.overlap)) return false;
  spec.tool_radius = tool->radius;
  const double finish = *depth - operation.allowance_bottom;
  if (!(finish > 0))
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves the whole depth of " + face.name());
  auto levels = depth_levels(reader, operation, finish);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  spec.levels = std::move(*levels);
  spec.retract_plane = operation.retract_plane;
  return true;
}

}  // namespace ncpost::stepnc::features
