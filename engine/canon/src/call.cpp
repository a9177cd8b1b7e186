#include "ncpost/canon/call.hpp"

#include <cmath>
#include <type_traits>

namespace ncpost::canon {
namespace {

// False for every T, but only once T is known: lets the last `else` reject a forgotten call.
template <class T>
[[maybe_unused]] constexpr bool is = false;

// Names of the calls that do not depend on their arguments.
template <class T>
constexpr std::string_view fixed_name() noexcept {
  if constexpr (std::is_same_v<T, UseLengthUnits>)
    return "USE_LENGTH_UNITS";
  else if constexpr (std::is_same_v<T, SetOriginOffsets>)
    return "SET_ORIGIN_OFFSETS";
  else if constexpr (std::is_same_v<T, SetFeedReference>)
    return "SET_FEED_REFERENCE";
  else if constexpr (std::is_same_v<T, SelectPlane>)
    return "SELECT_PLANE";
  else if constexpr (std::is_same_v<T, StraightTraverse>)
    return "STRAIGHT_TRAVERSE";
  else if constexpr (std::is_same_v<T, StraightFeed>)
    return "STRAIGHT_FEED";
  else if constexpr (std::is_same_v<T, ArcFeed>)
    return "ARC_FEED";
  else if constexpr (std::is_same_v<T, NurbsFeed>)
    return "NURBS_FEED";
  else if constexpr (std::is_same_v<T, SetFeedRate>)
    return "SET_FEED_RATE";
  else if constexpr (std::is_same_v<T, SetSpindleSpeed>)
    return "SET_SPINDLE_SPEED";
  else if constexpr (std::is_same_v<T, StartSpindleClockwise>)
    return "START_SPINDLE_CLOCKWISE";
  else if constexpr (std::is_same_v<T, StartSpindleCounterclockwise>)
    return "START_SPINDLE_COUNTERCLOCKWISE";
  else if constexpr (std::is_same_v<T, StopSpindleTurning>)
    return "STOP_SPINDLE_TURNING";
  else if constexpr (std::is_same_v<T, SpindleRetract>)
    return "SPINDLE_RETRACT";
  else if constexpr (std::is_same_v<T, SelectTool>)
    return "SELECT_TOOL";
  else if constexpr (std::is_same_v<T, ChangeTool>)
    return "CHANGE_TOOL";
  else if constexpr (std::is_same_v<T, UseToolLengthOffset>)
    return "USE_TOOL_LENGTH_OFFSET";
  else if constexpr (std::is_same_v<T, FloodOn>)
    return "FLOOD_ON";
  else if constexpr (std::is_same_v<T, FloodOff>)
    return "FLOOD_OFF";
  else if constexpr (std::is_same_v<T, MistOn>)
    return "MIST_ON";
  else if constexpr (std::is_same_v<T, MistOff>)
    return "MIST_OFF";
  else if constexpr (std::is_same_v<T, Dwell>)
    return "DWELL";
  else if constexpr (std::is_same_v<T, Comment>)
    return "COMMENT";
  else if constexpr (std::is_same_v<T, Message>)
    return "MESSAGE";
  else if constexpr (std::is_same_v<T, OptionalProgramStop>)
    return "OPTIONAL_PROGRAM_STOP";
  else if constexpr (std::is_same_v<T, ProgramStop>)
    return "PROGRAM_STOP";
  else if constexpr (std::is_same_v<T, ProgramEnd>)
    return "PROGRAM_END";
  else
    static_assert(is<T>, "every call needs a name");
}

constexpr std::string_view kBeginNames[] = {"PROJECT_BEGIN", "SETUP_BEGIN", "WORKPLAN_BEGIN",
                                            "WORKINGSTEP_BEGIN"};
constexpr std::string_view kEndNames[] = {"PROJECT_END", "SETUP_END", "WORKPLAN_END",
                                          "WORKINGSTEP_END"};

}  // namespace

std::string_view name(const Call& call) noexcept {
  return std::visit(
      [](const auto& c) -> std::string_view {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, Begin>)
          return marker_name(c.scope, true);
        else if constexpr (std::is_same_v<T, End>)
          return marker_name(c.scope, false);
        else if constexpr (std::is_same_v<T, Cycle>)
          return name(c.kind);
        else
          return fixed_name<T>();
      },
      call);
}

std::string_view marker_name(Scope scope, bool begin) noexcept {
  return (begin ? kBeginNames : kEndNames)[static_cast<int>(scope)];
}

std::string_view name(Scope scope) noexcept {
  switch (scope) {
    case Scope::Project:
      return "PROJECT";
    case Scope::Setup:
      return "SETUP";
    case Scope::Workplan:
      return "WORKPLAN";
    case Scope::Workingstep:
      return "WORKINGSTEP";
  }
  return "?";
}

std::string_view name(CycleKind kind) noexcept {
  switch (kind) {
    case CycleKind::Drill:
      return "DRILL_CYCLE";
    case CycleKind::PeckDrill:
      return "PECK_DRILL_CYCLE";
    case CycleKind::Tap:
      return "TAP_CYCLE";
    case CycleKind::Bore:
      return "BORE_CYCLE";
    case CycleKind::Ream:
      return "REAM_CYCLE";
  }
  return "?";
}

std::string_view name(Units units) noexcept {
  switch (units) {
    case Units::Inches:
      return "CANON_UNITS_INCHES";
    case Units::Millimetres:
      return "CANON_UNITS_MM";
    case Units::Centimetres:
      return "CANON_UNITS_CM";
  }
  return "?";
}

std::string_view name(Plane plane) noexcept {
  switch (plane) {
    case Plane::Xy:
      return "CANON_PLANE_XY";
    case Plane::Yz:
      return "CANON_PLANE_YZ";
    case Plane::Xz:
      return "CANON_PLANE_XZ";
  }
  return "?";
}

std::string_view name(FeedReference reference) noexcept {
  switch (reference) {
    case FeedReference::Workpiece:
      return "CANON_WORKPIECE";
    case FeedReference::Xyz:
      return "CANON_XYZ";
  }
  return "?";
}

bool is_motion(const Call& call) noexcept {
  return std::holds_alternative<StraightTraverse>(call) ||
         std::holds_alternative<StraightFeed>(call) || std::holds_alternative<ArcFeed>(call) ||
         std::holds_alternative<NurbsFeed>(call) || std::holds_alternative<Cycle>(call);
}

std::optional<PlaneArc> plane_arc(const ArcFeed& arc) noexcept {
  const double length = std::sqrt(arc.normal.i * arc.normal.i + arc.normal.j * arc.normal.j +
                                  arc.normal.k * arc.normal.k);
  if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
  const double i = arc.normal.i / length;
  const double j = arc.normal.j / length;
  const double k = arc.normal.k / length;
  const auto near_zero = [](double v) { return std::fabs(v) <= kPlaneTolerance; };
  const Pose& e = arc.end;
  const Point& c = arc.centre;
  PlaneArc out;
  double along = 0;
  if (near_zero(i) && near_zero(j)) {
    out = {Plane::Xy, e.x, e.y, c.x, c.y, 0, e.z};
    along = k;
  } else if (near_zero(j) && near_zero(k)) {
    out = {Plane::Yz, e.y, e.z, c.y, c.z, 0, e.x};
    along = i;
  } else if (near_zero(k) && near_zero(i)) {
    out = {Plane::Xz, e.z, e.x, c.z, c.x, 0, e.y};
    along = j;
  } else {
    return std::nullopt;
  }
  // The plane's own normal (first × second) is +Z, +X or +Y; an arc about the negative axis
  // turns the other way when seen from the positive one.
  out.rotation = along > 0 ? arc.turns : -arc.turns;
  return out;
}

ArcFeed arc_from_plane(const PlaneArc& p) noexcept {
  ArcFeed arc;
  arc.turns = p.rotation;
  switch (p.plane) {
    case Plane::Xy:
      arc.end = {p.first_end, p.second_end, p.axis_end_point, {}, {}};
      arc.centre = {p.first_axis, p.second_axis, p.axis_end_point};
      arc.normal = {0, 0, 1};
      break;
    case Plane::Yz:
      arc.end = {p.axis_end_point, p.first_end, p.second_end, {}, {}};
      arc.centre = {p.axis_end_point, p.first_axis, p.second_axis};
      arc.normal = {1, 0, 0};
      break;
    case Plane::Xz:
      arc.end = {p.second_end, p.axis_end_point, p.first_end, {}, {}};
      arc.centre = {p.second_axis, p.axis_end_point, p.first_axis};
      arc.normal = {0, 1, 0};
      break;
  }
  return arc;
}

bool valid(const NurbsFeed& nurbs) noexcept {
  if (nurbs.degree < 1) return false;
  const auto degree = static_cast<std::size_t>(nurbs.degree);
  if (nurbs.points.size() < degree + 1) return false;
  if (nurbs.knots.size() != nurbs.points.size() + degree + 1) return false;
  for (const auto& p : nurbs.points) {
    if (!(p.weight > 0) || !std::isfinite(p.weight) || !std::isfinite(p.x) || !std::isfinite(p.y) ||
        !std::isfinite(p.z))
      return false;
  }
  for (std::size_t n = 0; n < nurbs.knots.size(); ++n) {
    if (!std::isfinite(nurbs.knots[n])) return false;
    if (n > 0 && nurbs.knots[n] < nurbs.knots[n - 1]) return false;
  }
  return true;
}

}  // namespace ncpost::canon
