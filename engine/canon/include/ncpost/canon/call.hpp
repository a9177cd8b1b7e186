#pragma once
// The canonical machining program: the intermediate representation between the interpreters
// (STEP-NC, CLS, G-code) and the renderers (profile XSLT, text trace).
//
// In: nothing. Out: value types. One `Call` is one NIST RS274 canonical machining function
// (names and argument order as the NIST ISO 14649 interpreter and LinuxCNC `rs274` print
// them), a structure marker (program, setup, workplan, workingstep begin/end, carrying the
// STEP-NC entity) or a high-level drilling cycle. docs/canon.md is the reference.
//
// Units: lengths in the program's length unit (USE_LENGTH_UNITS), angles in degrees, feed
// rates in length units per minute, spindle speeds in revolutions per minute, times in
// seconds. Coordinates are absolute, in the program coordinate system.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "ncpost/canon/output_options.hpp"

namespace ncpost::canon {

// ---- Small geometric values --------------------------------------------------------------

struct Point {
  double x = 0;
  double y = 0;
  double z = 0;
  friend bool operator==(const Point&, const Point&) = default;
};

// Rotary axis positions A, B, C (degrees).
struct Rotary {
  double a = 0;
  double b = 0;
  double c = 0;
  friend bool operator==(const Rotary&, const Rotary&) = default;
};

// A direction (tool axis or arc normal) as components I, J, K. Not necessarily unit length
// when it comes from a reader; writers print what they are given.
struct Direction {
  double i = 0;
  double j = 0;
  double k = 1;
  friend bool operator==(const Direction&, const Direction&) = default;
};

// A motion end point. Motions carry rotary axes, a tool-axis vector, or both, whenever the
// input has a tool axis; a three-axis program leaves both empty.
struct Pose {
  double x = 0;
  double y = 0;
  double z = 0;
  std::optional<Rotary> rotary{};
  std::optional<Direction> tool_axis{};
  friend bool operator==(const Pose&, const Pose&) = default;
};

// ---- Set-up ------------------------------------------------------------------------------

enum class Units : std::uint8_t { Inches, Millimetres, Centimetres };
enum class FeedReference : std::uint8_t { Workpiece, Xyz };
// First and second axis of each plane, as rs274 orders them: XY → (X, Y), YZ → (Y, Z),
// XZ → (Z, X). The plane normal is first × second: +Z, +X, +Y.
enum class Plane : std::uint8_t { Xy, Yz, Xz };

struct UseLengthUnits {
  Units units = Units::Millimetres;
  friend bool operator==(const UseLengthUnits&, const UseLengthUnits&) = default;
};
struct SetOriginOffsets {
  Point offset{};
  std::optional<Rotary> rotary{};
  friend bool operator==(const SetOriginOffsets&, const SetOriginOffsets&) = default;
};
struct SetFeedReference {
  FeedReference reference = FeedReference::Xyz;
  friend bool operator==(const SetFeedReference&, const SetFeedReference&) = default;
};
struct SelectPlane {
  Plane plane = Plane::Xy;
  friend bool operator==(const SelectPlane&, const SelectPlane&) = default;
};

// ---- Motion ------------------------------------------------------------------------------

struct StraightTraverse {
  Pose to{};
  friend bool operator==(const StraightTraverse&, const StraightTraverse&) = default;
};
struct StraightFeed {
  Pose to{};
  friend bool operator==(const StraightFeed&, const StraightFeed&) = default;
};

// A circular or helical arc, stored in 3D so that no reader has to know the selected plane:
// - `end`: the end point (and the rotary axes / tool axis at the end);
// - `centre`: any point on the arc's axis; only its projection onto the arc plane matters
//   (arc_from_plane puts it at the end point's height);
// - `normal`: the arc axis. The trace and the XML give rs274's plane-relative arguments when
//   it is parallel to X, Y or Z (see plane_arc); any other normal is a tilted-plane arc;
// - `turns`: signed turn count as rs274's `rotation`: positive is counter-clockwise seeing
//   the plane from the tip of `normal`; |turns| - 1 full turns come before the arc to `end`.
//   Never 0.
// Helical when the end point's coordinate along the normal differs from the start's.
struct ArcFeed {
  Pose end{};
  Point centre{};
  Direction normal{};
  int turns = 1;
  friend bool operator==(const ArcFeed&, const ArcFeed&) = default;
};

struct ControlPoint {
  double x = 0;
  double y = 0;
  double z = 0;
  double weight = 1;
  friend bool operator==(const ControlPoint&, const ControlPoint&) = default;
};

// A NURBS curve. `points` starts with the current position (the curve is clamped, so it
// starts there) and ends at the motion's end point; knots.size() == points.size() + degree
// + 1 (see valid()). Rotary axes / tool axis, when present, are those at the end point.
struct NurbsFeed {
  int degree = 3;
  std::vector<ControlPoint> points{};
  std::vector<double> knots{};
  std::optional<Rotary> rotary{};
  std::optional<Direction> tool_axis{};
  friend bool operator==(const NurbsFeed&, const NurbsFeed&) = default;
};

// ---- Feed and spindle ---------------------------------------------------------------------

struct SetFeedRate {
  double rate = 0;  // length units per minute
  friend bool operator==(const SetFeedRate&, const SetFeedRate&) = default;
};
struct SetSpindleSpeed {
  double rpm = 0;
  friend bool operator==(const SetSpindleSpeed&, const SetSpindleSpeed&) = default;
};
struct StartSpindleClockwise {
  friend bool operator==(const StartSpindleClockwise&, const StartSpindleClockwise&) = default;
};
struct StartSpindleCounterclockwise {
  friend bool operator==(const StartSpindleCounterclockwise&,
                         const StartSpindleCounterclockwise&) = default;
};
struct StopSpindleTurning {
  friend bool operator==(const StopSpindleTurning&, const StopSpindleTurning&) = default;
};
struct SpindleRetract {
  friend bool operator==(const SpindleRetract&, const SpindleRetract&) = default;
};

// ---- Tools ---------------------------------------------------------------------------------

// SELECT_TOOL prepares the tool (T word); CHANGE_TOOL puts it in the spindle (M6). rs274
// prints both for `T1 M6`.
struct SelectTool {
  std::int32_t slot = 0;
  friend bool operator==(const SelectTool&, const SelectTool&) = default;
};
struct ChangeTool {
  std::int32_t slot = 0;
  friend bool operator==(const ChangeTool&, const ChangeTool&) = default;
};
struct UseToolLengthOffset {
  double length = 0;
  friend bool operator==(const UseToolLengthOffset&, const UseToolLengthOffset&) = default;
};

// ---- Coolant -------------------------------------------------------------------------------

struct FloodOn {
  friend bool operator==(const FloodOn&, const FloodOn&) = default;
};
struct FloodOff {
  friend bool operator==(const FloodOff&, const FloodOff&) = default;
};
struct MistOn {
  friend bool operator==(const MistOn&, const MistOn&) = default;
};
struct MistOff {
  friend bool operator==(const MistOff&, const MistOff&) = default;
};

// ---- Other ---------------------------------------------------------------------------------

struct Dwell {
  double seconds = 0;
  friend bool operator==(const Dwell&, const Dwell&) = default;
};
struct Comment {
  std::string text{};
  friend bool operator==(const Comment&, const Comment&) = default;
};
struct Message {
  std::string text{};
  friend bool operator==(const Message&, const Message&) = default;
};
struct OptionalProgramStop {
  friend bool operator==(const OptionalProgramStop&, const OptionalProgramStop&) = default;
};
struct ProgramStop {
  friend bool operator==(const ProgramStop&, const ProgramStop&) = default;
};
struct ProgramEnd {
  friend bool operator==(const ProgramEnd&, const ProgramEnd&) = default;
};

// ---- Structure markers ---------------------------------------------------------------------

// Project is the whole program (ISO 14649 PROJECT): its markers print as PROJECT_BEGIN and
// PROJECT_END, which keeps them apart from rs274's PROGRAM_END (M2).
enum class Scope : std::uint8_t { Project, Setup, Workplan, Workingstep };

// The STEP-NC entity a marker stands for: P21 instance id (0: none, e.g. a synthesised
// workplan), entity type as in the file (e.g. "MACHINING_WORKINGSTEP"; empty: none) and the
// entity's name attribute.
struct Entity {
  std::uint64_t id = 0;
  std::string type{};
  std::string name{};
  friend bool operator==(const Entity&, const Entity&) = default;
};

// Begin and End are emitted in matching pairs, properly nested; an End carries the same
// entity as its Begin so that both ends of a block in the trace name it. Workingsteps are
// leaves: no Begin{Workingstep} while one is open (the XML form closes it if it happens).
struct Begin {
  Scope scope = Scope::Project;
  Entity entity{};
  // Workingsteps only: how the renderer is to write it (output_options.hpp); empty elsewhere.
  OutputOptions options{};
  friend bool operator==(const Begin&, const Begin&) = default;
};
struct End {
  Scope scope = Scope::Project;
  Entity entity{};
  friend bool operator==(const End&, const End&) = default;
};

// ---- High-level cycles ---------------------------------------------------------------------

enum class CycleKind : std::uint8_t { Drill, PeckDrill, Tap, Bore, Ream };

// A canned hole-making cycle along -Z of the program coordinate system, at (x, y). A profile
// either prints it as its controller's cycle (G81/G82/G83/G73/G84/G85/G86/G89, CYCLE8x, ...)
// or asks expand_cycle (cycle.hpp) for plain motions. Heights are absolute Z values with
// safe_z >= r_z >= bottom_z:
// - safe_z: the plane the tool travels at before and after the hole (G98 initial level);
//   safe_z == r_z means "return to the R plane" (G99);
// - r_z: the R plane, where the rapid approach ends and feeding starts;
// - bottom_z: the final depth.
// The fields after `dwell` are used by the kinds named in their comments and ignored (and
// left out of the trace and the XML) for the others.
struct Cycle {
  CycleKind kind = CycleKind::Drill;
  double x = 0;
  double y = 0;
  double safe_z = 0;
  double r_z = 0;
  double bottom_z = 0;
  double feed = 0;   // cutting feed, length units per minute; Tap: pitch × spindle_speed
  double dwell = 0;  // seconds at the bottom (0: none)
  // PeckDrill: depth of each peck (> 0).
  double peck = 0;
  // PeckDrill: 0 → back to r_z after each peck (G83, chip clearing); > 0 → back off by this
  // distance and go on feeding (G73, chip breaking).
  double peck_retract = 0;
  // PeckDrill with full retract: the rapid back into the hole stops this far above the
  // previous peck's depth (LinuxCNC uses 0.254 mm / 0.010 in).
  double peck_clearance = 0;
  double pitch = 0;                // Tap: thread pitch, length units per revolution
  double spindle_speed = 0;        // Tap: rpm, for controllers whose tapping cycle takes S
  bool left_hand = false;          // Tap: left-hand thread (spindle counter-clockwise going in)
  bool spindle_stop = false;       // Bore: stop the spindle at the bottom and rapid out (G86)
  std::optional<Rotary> rotary{};  // copied to every motion of the expansion
  std::optional<Direction> tool_axis{};  // copied to every motion of the expansion
  friend bool operator==(const Cycle&, const Cycle&) = default;
};

// ---- The call ------------------------------------------------------------------------------

// A std::variant rather than a tagged struct: each call has exactly its own arguments, and
// std::visit makes every writer handle every call (a missing case does not compile). Most
// alternatives are a few doubles; strings and NURBS vectors are the exceptions.
using Call = std::variant<UseLengthUnits, SetOriginOffsets, SetFeedReference, SelectPlane,  //
                          StraightTraverse, StraightFeed, ArcFeed, NurbsFeed,               //
                          SetFeedRate, SetSpindleSpeed, StartSpindleClockwise,
                          StartSpindleCounterclockwise,                                           //
                          StopSpindleTurning, SpindleRetract,                                     //
                          SelectTool, ChangeTool, UseToolLengthOffset,                            //
                          FloodOn, FloodOff, MistOn, MistOff,                                     //
                          Dwell, Comment, Message, OptionalProgramStop, ProgramStop, ProgramEnd,  //
                          Begin, End, Cycle>;

// The function name as the trace prints it and the XML names its element, e.g.
// "STRAIGHT_FEED", "WORKINGSTEP_BEGIN", "PROJECT_END", "PECK_DRILL_CYCLE"; a tilted-plane arc is
// still "ARC_FEED" here (the trace prints it as ARC_FEED_3D).
[[nodiscard]] std::string_view name(const Call& call) noexcept;
[[nodiscard]] std::string_view marker_name(Scope scope, bool begin) noexcept;  // "SETUP_END"
[[nodiscard]] std::string_view name(Scope scope) noexcept;              // "PROJECT", "SETUP", ...
[[nodiscard]] std::string_view name(CycleKind kind) noexcept;           // "DRILL_CYCLE", ...
[[nodiscard]] std::string_view name(Units units) noexcept;              // "CANON_UNITS_MM", ...
[[nodiscard]] std::string_view name(Plane plane) noexcept;              // "CANON_PLANE_XY", ...
[[nodiscard]] std::string_view name(FeedReference reference) noexcept;  // "CANON_XYZ", ...

// True for the calls that move the tool: traverse, feed, arc, NURBS, cycle.
[[nodiscard]] bool is_motion(const Call& call) noexcept;

// ---- Arcs in rs274's plane-relative form ----------------------------------------------------

// ARC_FEED's arguments as rs274 prints them, for an arc whose normal is parallel to X, Y or Z.
struct PlaneArc {
  Plane plane = Plane::Xy;
  double first_end = 0;
  double second_end = 0;
  double first_axis = 0;   // centre, first coordinate
  double second_axis = 0;  // centre, second coordinate
  int rotation = 1;        // turns, signed relative to the plane's normal (first × second)
  double axis_end_point = 0;
  friend bool operator==(const PlaneArc&, const PlaneArc&) = default;
};

// How far (as the largest off-axis component of the unit normal) a normal may be from a
// coordinate axis and still count as parallel to it.
inline constexpr double kPlaneTolerance = 1e-9;

// The plane-relative form, or nullopt when the normal is zero or not parallel to an axis.
[[nodiscard]] std::optional<PlaneArc> plane_arc(const ArcFeed& arc) noexcept;

// The inverse, for readers of G-code and CLS: an ArcFeed from rs274's arguments. The centre
// gets the end point's coordinate along the normal; `end`'s rotary axes / tool axis are empty.
[[nodiscard]] ArcFeed arc_from_plane(const PlaneArc& plane_arc) noexcept;

// ---- Checks ---------------------------------------------------------------------------------

// A NURBS is usable when degree >= 1, there are at least degree + 1 points, every weight is
// > 0, knots.size() == points.size() + degree + 1, and the knots do not decrease.
[[nodiscard]] bool valid(const NurbsFeed& nurbs) noexcept;

}  // namespace ncpost::canon
