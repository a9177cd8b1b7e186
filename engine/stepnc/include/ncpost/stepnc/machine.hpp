#pragma once
// The machine as the canonical program leaves it, and the calls that change it.
//
// Both interpreters drive this one class: engine/stepnc reads ISO 14649 (ARM) entities,
// engine/ap238 reads AP238 AIM ones, and each tells the machine what the program asks for (a
// tool, a feed, a coolant state, a path). What canonical calls that gives (a tool change
// retracts and stops the spindle first; a value is set only when it changes; the first path of
// a list is approached over the security plane) is decided here, once, so the same content
// gives the same canonical program whichever form it came in. Not an interface for the
// pipeline, the CLI or the server (namespace detail).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/canon/sink.hpp"
#include "ncpost/stepnc/curves.hpp"
#include "ncpost/stepnc/geometry.hpp"

namespace ncpost::stepnc {
struct ToolTable;
}

namespace ncpost::stepnc::detail {

// A tool as the machine loads it.
struct ToolLoad {
  std::uint64_t id = 0;  // P21 id of the tool instance: the same id is the same tool
  std::string name;      // ISO 14649 its_id, AP238 action_resource.name
  int pocket = 0;
  double length_offset = 0;  // mm
};

// The pocket and length offset of a tool: from `table` when there is one (nullopt when the
// table lacks the tool: the caller reports STEPNC-014); else the tool's name when it is a whole
// number from 1 to 99999 (a tool number), else its P21 id; the length is `assembly_length`.
[[nodiscard]] std::optional<ToolLoad> tool_load(std::uint64_t id, std::string name,
                                                double assembly_length, const ToolTable* table);

class Machine {
 public:
  explicit Machine(canon::Sink& sink) : out_(sink) {}

  void emit(const canon::Call& c) {
    ++calls_;
    out_.call(c);
  }
  [[nodiscard]] std::size_t calls() const { return calls_; }

  // PROJECT_BEGIN and the set-up every program starts with (mm, no offsets, XYZ feed, XY plane).
  void start_program(const canon::Entity& project);
  // Up to the security plane, spindle and coolant off, PROGRAM_END, PROJECT_END.
  void end_program(const canon::Entity& project);

  // ---- tools ----
  [[nodiscard]] bool holds(std::uint64_t tool_id) const { return tool_ == tool_id; }
  // Up to the security plane, spindle stopped, COMMENT("TOOL name"), SELECT_TOOL, CHANGE_TOOL,
  // USE_TOOL_LENGTH_OFFSET; nothing when that tool is loaded.
  void change_tool(const ToolLoad& tool);
  void unload_tool();  // CHANGE_TOOL(0)

  // ---- modal state: a call only when the value changes ----
  void feed_rate(double mm_per_minute);
  // ISO 14649's unit, revolutions per second; negative turns clockwise (NIST's and STEP Tools'
  // convention), 0 stops.
  void spindle(double revolutions_per_second);
  void coolant(std::optional<bool> flood, std::optional<bool> mist);
  [[nodiscard]] const std::optional<double>& feed() const { return feed_; }
  [[nodiscard]] const std::optional<double>& spindle_speed() const { return spindle_; }

  // ---- positions (machine coordinates, mm) ----
  void set_security_z(double z) { security_z_ = z; }
  [[nodiscard]] const std::optional<double>& security_z() const { return security_z_; }
  [[nodiscard]] const std::optional<Vec3>& position() const { return position_; }
  void set_position(Vec3 p) { position_ = p; }
  void retract_to_security_plane();
  // To `start`: nothing when the tool is there; else up to the security plane, across and down,
  // at rapid (`rapid_only`: straight there).
  void approach(Vec3 start, bool rapid_only);
  // Where a toolpath of a list begins. The first of a list (or any path while the position is
  // unknown) is approached; a later one that starts away from the tool moves there straight
  // (at rapid or feed, as the path itself moves) and true is returned: the caller reports the
  // gap (STEPNC-013).
  [[nodiscard]] bool join(Vec3 start, bool first_of_list, bool rapid);
  // The segments in `frame`: STRAIGHT_TRAVERSE or STRAIGHT_FEED, ARC_FEED (the plane selected
  // around arcs outside XY), NURBS_FEED.
  void motion(const std::vector<Segment>& segments, const Frame& frame, bool rapid);

 private:
  canon::Sink& out_;
  std::size_t calls_ = 0;
  std::optional<double> security_z_;
  std::optional<Vec3> position_;  // unknown until the first move
  std::optional<std::uint64_t> tool_;
  std::optional<double> feed_;
  std::optional<double> spindle_;
  bool flood_ = false;
  bool mist_ = false;
};

}  // namespace ncpost::stepnc::detail
