// The machine state both interpreters drive. See machine.hpp; the behaviour is the one
// docs/interpreter.md describes ("Each workingstep", "Toolpaths").

#include "ncpost/stepnc/machine.hpp"

#include <charconv>
#include <cmath>

#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::stepnc::detail {
namespace {

constexpr double kSamePoint = 1e-6;  // mm: positions closer than this are the same
constexpr double kSpindleToRpm = 60.0;
constexpr int kHighestToolNumber = 99999;

canon::Pose pose(Vec3 p, const std::optional<Vec3>& axis = std::nullopt) {
  canon::Pose out{p.x, p.y, p.z, std::nullopt, std::nullopt};
  if (axis) out.tool_axis = canon::Direction{axis->x, axis->y, axis->z};
  return out;
}

// "12" → 12; anything but a whole number in [1, kHighestToolNumber] → nullopt.
std::optional<int> tool_number(std::string_view name) {
  int n = 0;
  const auto [end, error] = std::from_chars(name.data(), name.data() + name.size(), n);
  if (error != std::errc() || end != name.data() + name.size() || n < 1 || n > kHighestToolNumber)
    return std::nullopt;
  return n;
}

}  // namespace

std::optional<ToolLoad> tool_load(std::uint64_t id, std::string name, double assembly_length,
                                  const ToolTable* table) {
  ToolLoad load{id, std::move(name), 0, assembly_length};
  if (table != nullptr) {
    const ToolTableEntry* entry = table->find(load.name);
    if (entry == nullptr) return std::nullopt;
    load.pocket = entry->pocket;
    load.length_offset = entry->length_offset;
    return load;
  }
  load.pocket =
      tool_number(load.name).value_or(static_cast<int>(std::min<std::uint64_t>(id, 2147483647)));
  return load;
}

void Machine::start_program(const canon::Entity& project) {
  emit(canon::Begin{canon::Scope::Project, project});
  emit(canon::UseLengthUnits{canon::Units::Millimetres});
  emit(canon::SetOriginOffsets{{0, 0, 0}, std::nullopt});
  emit(canon::SetFeedReference{canon::FeedReference::Xyz});
  emit(canon::SelectPlane{canon::Plane::Xy});
}

void Machine::end_program(const canon::Entity& project) {
  retract_to_security_plane();
  if (spindle_ && *spindle_ != 0) emit(canon::StopSpindleTurning{});
  if (flood_) emit(canon::FloodOff{});
  if (mist_) emit(canon::MistOff{});
  emit(canon::ProgramEnd{});
  emit(canon::End{canon::Scope::Project, project});
}

void Machine::change_tool(const ToolLoad& tool) {
  if (tool_ == tool.id) return;
  retract_to_security_plane();
  if (spindle_ && *spindle_ != 0) {
    emit(canon::StopSpindleTurning{});
    spindle_ = 0.0;
  }
  emit(canon::Comment{"TOOL " + tool.name});
  emit(canon::SelectTool{tool.pocket});
  emit(canon::ChangeTool{tool.pocket});
  emit(canon::UseToolLengthOffset{tool.length_offset});
  tool_ = tool.id;
}

void Machine::unload_tool() {
  emit(canon::ChangeTool{0});
  tool_.reset();
}

void Machine::feed_rate(double rate) {
  if (!feed_ || *feed_ != rate) emit(canon::SetFeedRate{rate});
  feed_ = rate;
}

void Machine::spindle(double s) {
  if (!spindle_ || *spindle_ != s) {
    if (s == 0) {
      emit(canon::StopSpindleTurning{});
    } else {
      emit(canon::SetSpindleSpeed{std::abs(s) * kSpindleToRpm});
      if (s < 0)
        emit(canon::StartSpindleClockwise{});
      else
        emit(canon::StartSpindleCounterclockwise{});
    }
  }
  spindle_ = s;
}

void Machine::coolant(std::optional<bool> flood, std::optional<bool> mist) {
  if (flood && *flood != flood_) {
    if (*flood)
      emit(canon::FloodOn{});
    else
      emit(canon::FloodOff{});
    flood_ = *flood;
  }
  if (mist && *mist != mist_) {
    if (*mist)
      emit(canon::MistOn{});
    else
      emit(canon::MistOff{});
    mist_ = *mist;
  }
}

void Machine::retract_to_security_plane() {
  if (!position_ || !security_z_ || position_->z >= *security_z_ - kSamePoint) return;
  position_->z = *security_z_;
  emit(canon::StraightTraverse{pose(*position_)});
}

void Machine::approach(Vec3 start, bool rapid_only) {
  if (position_ && (*position_ - start).length() < kSamePoint) return;
  if (!rapid_only) retract_to_security_plane();
  if (security_z_ && !rapid_only && start.z < *security_z_) {
    const Vec3 above{start.x, start.y, *security_z_};
    if (!position_ || (*position_ - above).length() >= kSamePoint)
      emit(canon::StraightTraverse{pose(above)});
  }
  emit(canon::StraightTraverse{pose(start)});
  position_ = start;
}

bool Machine::join(Vec3 start, bool first_of_list, bool rapid) {
  if (first_of_list || !position_) {
    approach(start, rapid);
    return false;
  }
  if ((*position_ - start).length() < kSamePoint) return false;
  if (rapid)
    emit(canon::StraightTraverse{pose(start)});
  else
    emit(canon::StraightFeed{pose(start)});
  position_ = start;
  return true;
}

void Machine::motion(const std::vector<Segment>& segments, const Frame& frame, bool rapid) {
  bool selected_xy = true;
  for (const Segment& s : segments) {
    const Vec3 end = frame.point(s.end);
    std::optional<Vec3> axis;
    if (s.tool_axis) axis = frame.direction(*s.tool_axis);
    switch (s.kind) {
      case Segment::Kind::Line:
        if (rapid)
          emit(canon::StraightTraverse{pose(end, axis)});
        else
          emit(canon::StraightFeed{pose(end, axis)});
        break;
      case Segment::Kind::Arc: {
        const Vec3 normal = frame.direction(s.normal);
        const Vec3 centre = frame.point(s.centre);
        const canon::Plane plane = std::abs(normal.x) > 1 - 1e-9   ? canon::Plane::Yz
                                   : std::abs(normal.y) > 1 - 1e-9 ? canon::Plane::Xz
                                                                   : canon::Plane::Xy;
        if ((plane == canon::Plane::Xy) != selected_xy || plane != canon::Plane::Xy) {
          emit(canon::SelectPlane{plane});
          selected_xy = plane == canon::Plane::Xy;
        }
        emit(canon::ArcFeed{pose(end, axis),
                            {centre.x, centre.y, centre.z},
                            {normal.x, normal.y, normal.z},
                            s.turns});
        break;
      }
      case Segment::Kind::Nurbs: {
        canon::NurbsFeed n;
        n.degree = s.degree;
        for (std::size_t i = 0; i < s.control_points.size(); ++i) {
          const Vec3 p = frame.point(s.control_points[i]);
          n.points.push_back({p.x, p.y, p.z, s.weights[i]});
        }
        n.knots = s.knots;
        emit(n);
        break;
      }
    }
    position_ = end;
  }
  if (!selected_xy) emit(canon::SelectPlane{canon::Plane::Xy});
}

}  // namespace ncpost::stepnc::detail
