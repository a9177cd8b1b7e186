// Tool axes → rotary positions, and the tool tip → linear positions, by a profile's kinematics.
// docs/kinematics.md derives each formula; this file follows its sections.

#include "ncpost/render/kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "ncpost/canon/vec3.hpp"

namespace ncpost::render {
namespace {

using profile::KinematicsType;
using profile::MachineAxis;
using profile::RotaryAxis;

constexpr double kDegree = std::numbers::pi / 180.0;
// Angles this close (degrees) count as equal: a limit reached exactly, two equal solutions.
constexpr double kAngleEpsilon = 1e-9;
// An arc or NURBS keeps the orientation when its tool axis is this close to the one in force.
constexpr double kSameAxis = 1e-7;

using Vec = canon::Vec3;
Vec vec(const std::array<double, 3>& a) {
  return {a[0], a[1], a[2]};
}

constexpr Vec kZ{0, 0, 1};

Vec unit(MachineAxis axis) {
  return axis == MachineAxis::X ? Vec{1, 0, 0} : axis == MachineAxis::Y ? Vec{0, 1, 0} : kZ;
}

// cos and sin of an angle in degrees, exact at whole quarter turns (so that a table at 90
// degrees gives 0, not 6e-17, in the coordinates written).
std::pair<double, double> cos_sin(double degrees) {
  const double quarters = degrees / 90.0;
  if (quarters == std::round(quarters) && std::abs(quarters) < 1e9) {
    const long q = ((std::lround(quarters) % 4) + 4) % 4;
    return {q == 0 ? 1.0 : q == 2 ? -1.0 : 0.0, q == 1 ? 1.0 : q == 3 ? -1.0 : 0.0};
  }
  return {std::cos(degrees * kDegree), std::sin(degrees * kDegree)};
}

// v turned by `degrees` about the machine axis (right-hand rule).
Vec rotate(Vec v, MachineAxis axis, double degrees) {
  const auto [c, s] = cos_sin(degrees);
  switch (axis) {
    case MachineAxis::X:
      return {v.x, c * v.y - s * v.z, s * v.y + c * v.z};
    case MachineAxis::Y:
      return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
    case MachineAxis::Z:
      break;
  }
  return {c * v.x - s * v.y, s * v.x + c * v.y, v.z};
}

// A point turned about the axis line through `through`.
Vec rotate_about(Vec p, MachineAxis axis, double degrees, Vec through) {
  return rotate(p - through, axis, degrees) + through;
}

// The physical turn of an axis's own part (head or table) for its position.
double turn_of(const RotaryAxis& axis, double position) {
  return axis.direction * position;
}

// Into (-180, 180].
double normalised(double degrees) {
  double d = std::remainder(degrees, 360.0);
  if (d <= -180.0) d += 360.0;
  return d == 0 ? 0.0 : d;
}

// The solver's form (docs/kinematics.md, "Inverse kinematics"): every machine type's tool axis
// in program coordinates is v = R(outer, alpha) R(tilt, beta) Z, where outer and tilt are
// the two rotary axes and alpha, beta their turns, with a sign per type: a table turns the
// workpiece, which turns the tool relative to it the other way.
struct Form {
  const RotaryAxis* outer;
  const RotaryAxis* tilt;
  double outer_sign;  // alpha = outer_sign * turn of the outer axis
  double tilt_sign;   // beta = tilt_sign * turn of the tilting axis
  bool outer_is_primary;
};

Form form_of(const profile::Kinematics& k) {
  switch (k.type) {
    case KinematicsType::HeadHead:
      return {&k.primary, &k.secondary, 1, 1, true};
    case KinematicsType::TableTable:
      return {&k.secondary, &k.primary, -1, -1, false};
    case KinematicsType::HeadTable:
      break;
  }
  return {&k.secondary, &k.primary, -1, 1, false};
}

// The position of `axis` nearest to `previous` among `raw` + whole turns: any for a continuous
// axis, within the limits for a limited one (none when no turn of `raw` is within them). Half
// a turn away either way is a tie: the value nearer 0, then the positive one.
std::optional<double> wrap(const RotaryAxis& axis, double raw, double previous) {
  const double turns = (previous - raw) / 360.0;
  double lowest = std::floor(turns);
  double highest = std::ceil(turns);
  if (!axis.continuous) {
    const double first = std::ceil((axis.min - kAngleEpsilon - raw) / 360.0);
    const double last = std::floor((axis.max + kAngleEpsilon - raw) / 360.0);
    if (first > last) return std::nullopt;
    lowest = std::clamp(lowest, first, last);
    highest = std::clamp(highest, first, last);
  }
  const double below = raw + 360.0 * lowest;
  const double above = raw + 360.0 * highest;
  const double to_below = std::abs(below - previous);
  const double to_above = std::abs(above - previous);
  if (std::abs(to_below - to_above) > kAngleEpsilon) return to_below < to_above ? below : above;
  if (std::abs(std::abs(below) - std::abs(above)) > kAngleEpsilon)
    return std::abs(below) < std::abs(above) ? below : above;
  return std::max(below, above);
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", std::abs(v) < 5e-7 ? 0.0 : v);
  return buffer;
}

std::string describe(const canon::Direction& d) {
  return "(" + number(d.i) + ", " + number(d.j) + ", " + number(d.k) + ")";
}

std::string describe(const profile::Kinematics& k, const RotaryPositions& p) {
  return std::string(1, k.primary.name) + number(p.primary) + " " + k.secondary.name +
         number(p.secondary);
}

std::string describe_limits(const RotaryAxis& axis) {
  if (axis.continuous) return std::string(1, axis.name) + " continuous";
  return std::string(1, axis.name) + " " + number(axis.min) + ".." + number(axis.max);
}

void place(canon::Pose& pose, const canon::Point& p) {
  pose.x = p.x;
  pose.y = p.y;
  pose.z = p.z;
}

}  // namespace

Kinematics::Kinematics(profile::Kinematics machine) : machine_(std::move(machine)) {}

std::vector<Kinematics::Candidate> Kinematics::candidates(const canon::Direction& axis,
                                                          const RotaryPositions& previous) const {
  Vec v{axis.i, axis.j, axis.k};
  const double size = length(v);
  if (!(size > 0) || !std::isfinite(size)) return {};
  v = (1.0 / size) * v;
  const Form f = form_of(machine_);
  const Vec a = unit(f.outer->axis);
  const MachineAxis tilt_axis = f.tilt->axis;
  const Vec b = unit(tilt_axis);
  // a . v is kept by the outer turn: p cos(beta) + q sin(beta) = a . v fixes the tilt.
  const double s = std::clamp(dot(a, v), -1.0, 1.0);
  const double p = dot(a, kZ);
  const double q = dot(a, cross(b, kZ));
  const double gamma = std::atan2(q, p);
  const Vec v_across = v - s * a;
  const bool singular = length(v_across) <= machine_.pole_tolerance;
  // On the pole the two tilts coincide: exactly, not within rounding.
  const double delta = singular ? (s > 0 ? 0.0 : std::numbers::pi) : std::acos(s);
  // Fixed arrays here and in choose(): this runs once per motion, and heap allocations were
  // a noticeable part of it.
  const std::array<double, 2> tilts{gamma + delta, gamma - delta};
  const std::size_t tilt_count =
      std::abs(normalised((2 * delta) / kDegree)) > kAngleEpsilon ? 2 : 1;
  const double previous_outer = f.outer_is_primary ? previous.primary : previous.secondary;

  std::vector<Candidate> out;
  out.reserve(tilt_count);
  for (std::size_t t = 0; t < tilt_count; ++t) {
    const double beta = tilts[t];
    double outer_position = previous_outer;
    if (!singular) {
      const Vec w = rotate(kZ, tilt_axis, beta / kDegree);
      const Vec w_across = w - dot(a, w) * a;
      const double alpha = std::atan2(dot(a, cross(w_across, v_across)), dot(w_across, v_across));
      outer_position = normalised(alpha / kDegree * f.outer_sign * f.outer->direction);
    }
    const double tilt_position = normalised(beta / kDegree * f.tilt_sign * f.tilt->direction);
    Candidate c;
    c.singular = singular;
    c.angles = f.outer_is_primary ? RotaryPositions{outer_position, tilt_position}
                                  : RotaryPositions{tilt_position, outer_position};
    out.push_back(c);
  }
  return out;
}

Kinematics::Choice Kinematics::choose(const canon::Direction& axis,
                                      const RotaryPositions& previous) const {
  Choice choice;
  const std::vector<Candidate> found = candidates(axis, previous);
  if (found.empty()) {
    choice.code = diag::Code::KinNoDirection;
    choice.refusal = "the tool axis " + describe(axis) + " is no direction";
    return choice;
  }
  choice.singular = found.front().singular;
  const Form f = form_of(machine_);
  const bool tilt_is_primary = !f.outer_is_primary;
  struct Reachable {
    RotaryPositions positions;
    double cost;
    double tilt;
  };
  std::array<Reachable, 2> reachable{};
  std::size_t reachable_count = 0;
  for (const Candidate& c : found) {
    const auto primary = wrap(machine_.primary, c.angles.primary, previous.primary);
    const auto secondary = wrap(machine_.secondary, c.angles.secondary, previous.secondary);
    if (!primary || !secondary) continue;
    const RotaryPositions p{*primary, *secondary};
    reachable[reachable_count++] = {
        p, std::abs(p.primary - previous.primary) + std::abs(p.secondary - previous.secondary),
        tilt_is_primary ? p.primary : p.secondary};
  }
  if (reachable_count == 0) {
    // Worded only here: formatting the candidates of every motion cost a third of a post.
    std::string tried;
    for (const Candidate& c : found)
      tried += (tried.empty() ? "" : " or ") + describe(machine_, c.angles);
    choice.refusal = "the tool axis " + describe(axis) + " needs " + tried + ", outside " +
                     describe_limits(machine_.primary) + ", " + describe_limits(machine_.secondary);
    return choice;
  }
  // The preferred side of the tilt first (Shortest has none), then the smaller motion, then
  // the positive tilt.
  const auto side = [&](const Reachable& r) {
    switch (machine_.solution) {
      case profile::RotarySolution::PositiveTilt:
        return r.tilt >= -kAngleEpsilon ? 0 : 1;
      case profile::RotarySolution::NegativeTilt:
        return r.tilt <= kAngleEpsilon ? 0 : 1;
      case profile::RotarySolution::Shortest:
        break;
    }
    return 0;
  };
  const auto better = [&](const Reachable& x, const Reachable& y) {
    if (side(x) != side(y)) return side(x) < side(y);
    if (std::abs(x.cost - y.cost) > kAngleEpsilon) return x.cost < y.cost;
    return x.tilt > y.tilt;
  };
  choice.positions =
      std::min_element(reachable.begin(), reachable.begin() + reachable_count, better)->positions;
  return choice;
}

canon::Direction Kinematics::tool_axis(const RotaryPositions& positions) const {
  const Form f = form_of(machine_);
  const double outer = f.outer_is_primary ? positions.primary : positions.secondary;
  const double tilt = f.outer_is_primary ? positions.secondary : positions.primary;
  const Vec w = rotate(kZ, f.tilt->axis, f.tilt_sign * turn_of(*f.tilt, tilt));
  const Vec v = rotate(w, f.outer->axis, f.outer_sign * turn_of(*f.outer, outer));
  return {v.x, v.y, v.z};
}

canon::Rotary Kinematics::rotary(const RotaryPositions& positions) const {
  canon::Rotary r;
  const auto put = [&](char name, double value) {
    (name == 'A' ? r.a : name == 'B' ? r.b : r.c) = value;
  };
  put(machine_.primary.name, positions.primary);
  put(machine_.secondary.name, positions.secondary);
  return r;
}

canon::Point Kinematics::machine_point(const canon::Point& tip, const RotaryPositions& positions,
                                       double tool_length, double pivot_scale) const {
  if (machine_.tool_centre_point) return tip;
  const RotaryAxis& primary = machine_.primary;
  const RotaryAxis& secondary = machine_.secondary;
  const double turn_p = turn_of(primary, positions.primary);
  const double turn_s = turn_of(secondary, positions.secondary);
  const Vec pivot_p = pivot_scale * vec(primary.pivot);
  const Vec pivot_s = pivot_scale * vec(secondary.pivot);
  const Vec length = tool_length * kZ;
  Vec p{tip.x, tip.y, tip.z};
  // The control puts the programmed point where the tip would be with the head at 0
  // (G43 along Z); the head's turns move the real tip by tip_from_gauge + length.
  Vec machine{};
  switch (machine_.type) {
    case KinematicsType::HeadHead: {
      const Vec inner = rotate_about(Vec{} - length, secondary.axis, turn_s, pivot_s);
      const Vec tip_from_gauge = rotate_about(inner, primary.axis, turn_p, pivot_p);
      machine = p - length - tip_from_gauge;
      break;
    }
    case KinematicsType::TableTable: {
      const Vec inner = rotate_about(p, secondary.axis, turn_s, pivot_s);
      machine = rotate_about(inner, primary.axis, turn_p, pivot_p);
      break;
    }
    case KinematicsType::HeadTable: {
      const Vec on_table = rotate_about(p, secondary.axis, turn_s, pivot_s);
      const Vec tip_from_gauge = rotate_about(Vec{} - length, primary.axis, turn_p, pivot_p);
      machine = on_table - length - tip_from_gauge;
      break;
    }
  }
  return {machine.x, machine.y, machine.z};
}

canon::Direction Kinematics::machine_direction(const canon::Direction& direction,
                                               const RotaryPositions& positions) const {
  if (machine_.tool_centre_point) return direction;
  Vec d{direction.i, direction.j, direction.k};
  switch (machine_.type) {
    case KinematicsType::HeadHead:
      break;
    case KinematicsType::TableTable:
      d = rotate(d, machine_.secondary.axis, turn_of(machine_.secondary, positions.secondary));
      d = rotate(d, machine_.primary.axis, turn_of(machine_.primary, positions.primary));
      break;
    case KinematicsType::HeadTable:
      d = rotate(d, machine_.secondary.axis, turn_of(machine_.secondary, positions.secondary));
      break;
  }
  return {d.x, d.y, d.z};
}

// ---- KinematicsConverter ----------------------------------------------------------------------

KinematicsConverter::KinematicsConverter(const profile::Kinematics& machine,
                                         double controller_unit_mm)
    : kinematics_(machine), controller_unit_mm_(controller_unit_mm) {}

canon::Point KinematicsConverter::to_machine(const canon::Point& p) const {
  return kinematics_.machine_point(p, positions_, tool_length_,
                                   controller_unit_mm_ / program_unit_mm_);
}

std::optional<KinematicsConverter::Issue> KinematicsConverter::same_orientation(
    const std::optional<canon::Direction>& axis, const char* what) const {
  if (!axis) return std::nullopt;
  const Vec v{axis->i, axis->j, axis->k};
  const double size = length(v);
  if (!(size > 0) || !std::isfinite(size))
    return Issue{diag::Code::KinNoDirection,
                 "the tool axis " + describe(*axis) + " is no direction"};
  const canon::Direction now = kinematics_.tool_axis(positions_);
  if (length((1.0 / size) * v - Vec{now.i, now.j, now.k}) > kSameAxis)
    return Issue{diag::Code::KinOrientationAlongCurve,
                 std::string("the tool axis changes along ") + what + " from " + describe(now) +
                     " to " + describe(*axis) + "; turn it with a straight motion first"};
  return std::nullopt;
}

std::optional<KinematicsConverter::Issue> KinematicsConverter::pose(canon::Pose& pose, bool feed,
                                                                    std::vector<Issue>& warnings) {
  RotaryPositions next = positions_;
  if (pose.tool_axis) {
    const Kinematics::Choice choice = kinematics_.choose(*pose.tool_axis, positions_);
    if (!choice.positions) return Issue{choice.code, choice.refusal};
    next = *choice.positions;
    const double limit = kinematics_.machine().rotation_warning;
    const auto& machine = kinematics_.machine();
    const std::pair<char, double> turns[] = {
        {machine.primary.name, next.primary - positions_.primary},
        {machine.secondary.name, next.secondary - positions_.secondary}};
    for (const auto& [name, turn] : turns) {
      if (feed && limit > 0 && std::abs(turn) > limit + kAngleEpsilon)
        warnings.push_back(
            {diag::Code::KinLargeRotation, std::string(1, name) + " turns by " + number(turn) +
                                               " degrees within one feed motion (to " +
                                               describe(machine, next) + ")"});
    }
    pose.rotary = kinematics_.rotary(next);
  }
  positions_ = next;
  place(pose, to_machine({pose.x, pose.y, pose.z}));
  return std::nullopt;
}

std::optional<KinematicsConverter::Issue> KinematicsConverter::convert(
    canon::Call& call, std::vector<Issue>& warnings) {
  if (const auto* units = std::get_if<canon::UseLengthUnits>(&call)) {
    program_unit_mm_ = units->units == canon::Units::Inches        ? 25.4
                       : units->units == canon::Units::Centimetres ? 10.0
                                                                   : 1.0;
    return std::nullopt;
  }
  if (const auto* offset = std::get_if<canon::UseToolLengthOffset>(&call)) {
    tool_length_ = offset->length;
    return std::nullopt;
  }
  if (auto* t = std::get_if<canon::StraightTraverse>(&call)) {
    canon::Pose p = t->to;
    auto issue = pose(p, false, warnings);
    if (!issue) t->to = p;
    return issue;
  }
  if (auto* f = std::get_if<canon::StraightFeed>(&call)) {
    canon::Pose p = f->to;
    auto issue = pose(p, true, warnings);
    if (!issue) f->to = p;
    return issue;
  }
  if (auto* arc = std::get_if<canon::ArcFeed>(&call)) {
    if (auto issue = same_orientation(arc->end.tool_axis, "an arc")) return issue;
    // The orientation stays: no rotary words on an arc (a control may refuse them there).
    arc->end.rotary.reset();
    place(arc->end, to_machine({arc->end.x, arc->end.y, arc->end.z}));
    arc->centre = to_machine(arc->centre);
    arc->normal = kinematics_.machine_direction(arc->normal, positions_);
    return std::nullopt;
  }
  if (auto* nurbs = std::get_if<canon::NurbsFeed>(&call)) {
    if (auto issue = same_orientation(nurbs->tool_axis, "a NURBS curve")) return issue;
    nurbs->rotary.reset();
    for (canon::ControlPoint& cp : nurbs->points) {
      const canon::Point m = to_machine({cp.x, cp.y, cp.z});
      cp.x = m.x;
      cp.y = m.y;
      cp.z = m.z;
    }
    return std::nullopt;
  }
  if (auto* cycle = std::get_if<canon::Cycle>(&call)) {
    if (auto issue = same_orientation(cycle->tool_axis, "a cycle")) return issue;
    const canon::Direction now = kinematics_.tool_axis(positions_);
    if (length(Vec{now.i, now.j, now.k} - kZ) > kSameAxis)
      return Issue{diag::Code::KinNativeCycleTilted,
                   "a native cycle with the tool along " + describe(now) +
                       ", not the program's Z axis (" +
                       describe(kinematics_.machine(), positions_) + ")"};
    // The tool is along Z, so the map to the machine turns about Z at most: the cycle's
    // levels move together.
    cycle->rotary.reset();
    const canon::Point m = to_machine({cycle->x, cycle->y, cycle->r_z});
    const double dz = m.z - cycle->r_z;
    cycle->x = m.x;
    cycle->y = m.y;
    cycle->safe_z += dz;
    cycle->r_z = m.z;
    cycle->bottom_z += dz;
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace ncpost::render
