#pragma once
// The modal state machine: checked blocks (or, for Sinumerik and Heidenhain statements, its
// primitives directly) → canonical calls. It keeps what a controller keeps between blocks —
// units, plane, distance mode, motion mode, feed, spindle, tool, coolant, work offsets, the
// canned cycle's sticky values — and emits calls as LinuxCNC's canon prints them: coordinates
// in the current coordinate system and length unit, work offsets as SET_ORIGIN_OFFSETS.
//
// Structure markers: PROJECT_BEGIN/END around the program, and a WORKINGSTEP per tool's
// section (NC_SECTION, id = the 1-based line where it starts, name = the operation comment
// before it or the tool), as docs/gcode.md describes.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "block.hpp"
#include "lexer.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "parameters.hpp"
#include "report.hpp"

namespace ncpost::gcode::detail {

inline constexpr int kAxes = 9;  // X Y Z A B C U V W
using Axes = std::array<double, kAxes>;

// Where a diagnostic points: the file and line of the block being converted.
struct Where {
  std::string_view file;
  std::uint32_t line = 0;
};

// What the interpreter must do after a block: the converter does everything but flow.
struct FlowRequest {
  enum class Kind : std::uint8_t { None, End, Call, Return } kind = Kind::None;
  double program = 0;  // M98 P / G65 P: the program number
  bool has_program = false;
  int repeat = 1;                     // L / K repeats
  bool macro = false;                 // G65: the block's words become the call's locals
  bool local = false;                 // Haas M97: P names a block N of this program
  std::optional<double> return_line;  // M99 P: continue at this N in the caller
  std::uint32_t column = 0;
};

// A canned cycle as a front end describes it (Sinumerik CYCLE8x, Heidenhain CYCL DEF 20x give
// their parameters; word-address G8x blocks are read by the converter itself). Lengths in the
// program's unit, absolute values in the current coordinate system, along -Z in the XY plane.
struct CycleCall {
  CycleKind kind = CycleKind::Drill;
  double x = 0, y = 0;
  double clear = 0;  // level before and after
  double r = 0;      // feed starts here
  double bottom = 0;
  double dwell = 0;  // seconds
  double peck = 0;
  double peck_retract = 0;    // ChipBreak back-off
  double peck_clearance = 0;  // Peck: stop this far above the last depth
  double feed = 0;            // the cycle's own feed (Heidenhain Q206); 0: the feed in force
};

class Converter final : public StateView {
 public:
  Converter(const Dialect& dialect, canon::Sink& sink, Report& report, const ReadOptions& options);

  // PROJECT_BEGIN and the set-up calls; once, before the first block's calls.
  void start(const std::string& program_name);
  [[nodiscard]] bool started() const noexcept { return started_; }
  // Closes the open section, PROJECT_END. `ended`: a program end was converted.
  void finish();

  // Converts one checked block; false when it was refused (diagnostics added).
  bool execute(const Block& block, std::span<const Comment> comments, const Where& where,
               FlowRequest& flow);

  // ---- Primitives the statement front ends (Sinumerik, Heidenhain) use. Lengths in the
  // program's current unit, positions in the current coordinate system. ----
  void comment(std::string_view text, const Where& where);
  void message(std::string_view text);
  void set_metric(bool metric);
  void select_plane(canon::Plane plane);
  void set_feed(double units_per_minute);
  void set_spindle_speed(double rpm, const Where& where, std::uint32_t column);
  void spindle(int direction);  // 1 clockwise, -1 counter-clockwise, 0 stop
  void select_tool(int tool, const Where& where, std::uint32_t column);
  void change_tool(const Where& where, std::uint32_t column);
  void tool_length(bool on, int h, const Where& where);
  void coolant(bool mist, bool flood, bool off);
  void dwell(double seconds);
  void stop(Action action);  // ProgramStop, OptionalStop, PalletChange, ProgramEnd
  bool rapid(const Axes& target, const Where& where, std::uint32_t column);
  bool linear(const Axes& target, const Where& where, std::uint32_t column);
  // A plane arc: end point (all axes), centre (first, second in rs274's plane order), turns
  // signed as rs274's rotation (clockwise negative).
  bool arc(const Axes& target, double centre_first, double centre_second, int rotation,
           canon::Plane plane, const Where& where, std::uint32_t column);
  bool cycle(const CycleCall& call, const Where& where, std::uint32_t column);
  void set_translation(const Axes& offset);  // Sinumerik TRANS / Heidenhain datum shift

  [[nodiscard]] bool ended() const noexcept { return ended_; }
  [[nodiscard]] std::size_t calls() const noexcept { return calls_; }
  [[nodiscard]] bool metric_units() const noexcept { return metric_; }
  [[nodiscard]] bool incremental() const noexcept { return incremental_; }
  [[nodiscard]] canon::Plane plane() const noexcept { return plane_; }
  [[nodiscard]] double feed() const noexcept { return feed_; }
  // Current position in program units, current coordinate system.
  [[nodiscard]] double at(int axis) const noexcept;
  // The current position as the primitives take targets (internal units), and one coordinate
  // in program units (current system, or machine coordinates) turned into that form.
  [[nodiscard]] Axes target() const noexcept { return pos_; }
  [[nodiscard]] double internal(int axis, double program_value,
                                bool machine = false) const noexcept;
  void set_uses_rotary(bool uses) noexcept { uses_rotary_ = uses; }
  void set_label(std::string_view label) { pending_label_ = label; }

  // StateView (parameters read the state through it).
  [[nodiscard]] double position(int axis) const override;
  [[nodiscard]] double machine_position(int axis) const override;
  [[nodiscard]] int tool() const override { return tool_in_spindle_; }
  [[nodiscard]] int work_offset_index() const override { return work_index_; }
  [[nodiscard]] double work_offset(int index, int axis) const override;
  void set_work_offset(int index, int axis, double value) override;
  [[nodiscard]] double axis_offset(int axis) const override;
  [[nodiscard]] bool metric() const override { return metric_; }
  [[nodiscard]] std::optional<double> named(std::string_view name) const override;

  // The value of a named parameter the converter holds (#<_value> of a return).
  void set_return_value(std::optional<double> value) { return_value_ = value; }

 private:
  void emit(canon::Call call);
  template <class Move>
  void emit_move();
  void ensure_section(const Where& where);
  void open_section(const Where& where, const std::string& name);
  void close_section();
  void emit_offsets();
  [[nodiscard]] canon::Pose pose(const Axes& p) const;
  [[nodiscard]] double to_mm(double v) const noexcept { return metric_ ? v : v * 25.4; }
  [[nodiscard]] double from_mm(double v) const noexcept { return metric_ ? v : v / 25.4; }
  [[nodiscard]] double out(int axis, const Axes& p) const noexcept {
    return axis >= 3 && axis <= 5 ? p[axis] : from_mm(p[axis]);
  }
  [[nodiscard]] Axes total_offset() const noexcept;
  bool error(const Where& where, std::uint32_t column, diag::Code code, std::string message);
  void warn(const Where& where, std::uint32_t column, diag::Code code, std::string message);
  bool check_feed_motion(const Where& where, std::uint32_t column, double own_feed = 0);
  [[nodiscard]] bool check_limits(const Axes& p, const Where& where, std::uint32_t column);
  // A motion refused by check_limits: not made, but the blocks after it go on from its end, as
  // the program has them. False, for the caller to return.
  bool stop_at(const Axes& target) {
    pos_ = target;
    return false;
  }

  // Word-address conversion steps.
  bool word_target(const Block& b, Axes& target, bool machine) const;
  // LinuxCNC's polar words @ (distance) and ^ (angle) as X and Y (mm); false without them.
  bool polar(const Block& b, double& x, double& y) const;
  bool convert_motion(const CodeSpec& motion, const Block& b, const Where& where,
                      bool machine_coordinates);
  bool convert_arc(const CodeSpec& motion, const Block& b, const Where& where);
  bool convert_cycle(const CodeSpec& motion, const Block& b, const Where& where);
  bool convert_arc_through(const Block& b, const Where& where);
  bool add_spline_point(const Block& b, const Where& where);
  bool add_nurbs_point(const Block& b, const Where& where);
  void flush_spline();
  bool convert_g10(const Block& b, const Where& where, std::uint32_t column, const CodeSpec& spec);
  bool convert_home(const CodeSpec& code, const Block& b, const Where& where);
  void expand_cycle_motions(const CycleCall& c, const CodeSpec* spec, int first, int second,
                            int drill);
  [[nodiscard]] double scaled(const Block& b, WordId w) const noexcept;
  [[nodiscard]] std::uint32_t motion_column(const Block& b) const noexcept;
  [[nodiscard]] double length_word(const Block& b, WordId w) const noexcept;

  const Dialect& dialect_;
  canon::Sink& sink_;
  Report& report_;
  const ReadOptions& options_;

  bool started_ = false;
  bool ended_ = false;
  bool section_open_ = false;
  bool had_tool_change_ = false;
  std::string pending_label_;
  canon::Entity section_{};
  canon::Entity project_{};
  std::size_t calls_ = 0;

  // Modal state.
  bool metric_ = true;
  canon::Plane plane_ = canon::Plane::Xy;
  bool incremental_ = false;
  bool centre_absolute_ = false;
  enum class FeedMode : std::uint8_t { PerMinute, InverseTime, PerRevolution };
  FeedMode feed_mode_ = FeedMode::PerMinute;
  const CodeSpec* motion_ = nullptr;  // modal motion (G0..G3, a cycle) or nullptr (G80)
  bool retract_r_ = false;
  double feed_ = 0;  // program units per minute (or inverse time / per revolution)
  double spindle_speed_ = 0;
  int spindle_dir_ = 0;
  bool warned_spindle_ = false;
  bool warned_tool_length_ = false;
  int tool_selected_ = 0;
  int tool_in_spindle_ = 0;
  bool uses_rotary_ = false;
  canon::Call move_call_;  // emit_move's call, reused

  // Positions and offsets in mm (rotary axes in degrees).
  Axes pos_{};  // current coordinate system
  // [1..9] G54..G59.3, [10..57] the additional ones (G54.1 P1..P48); [0] stays zero.
  static constexpr int kWorkOffsets = 58;
  std::array<Axes, kWorkOffsets> work_offsets_{};
  int work_index_ = 1;
  Axes axis_offset_{};        // G92 / G52
  Axes axis_offset_saved_{};  // G92.2 keeps it for G92.3
  Axes translation_{};        // Sinumerik TRANS, Heidenhain datum shift
  Axes last_offsets_{};
  bool offsets_emitted_ = false;

  // Canned cycle's sticky values (program units as written, converted at use).
  std::optional<double> cycle_r_, cycle_bottom_;
  double cycle_q_ = 0, cycle_p_ = 0;
  double cycle_initial_ = 0;  // mm, along the cycle's axis: where the series of cycles began

  std::optional<double> return_value_;

  // A spline being gathered (Sinumerik BSPLINE), in program units.
  struct Spline {
    int degree = 3;
    std::vector<canon::ControlPoint> points;
    std::vector<double> intervals;  // BSPLINE: the knot steps PL
    bool explicit_knots = false;    // G06.2: the knots K as written
    std::vector<double> knots;
    Axes end{};
    std::string where_file;
    std::uint32_t where_line = 0;
    std::uint32_t column = 0;
  };
  std::optional<Spline> spline_;
  std::array<WordId, 3> spline_words_{kNoWord, kNoWord, kNoWord};   // PW, PL, SD
  std::array<WordId, 3> through_words_{kNoWord, kNoWord, kNoWord};  // I1, J1, K1
};

}  // namespace ncpost::gcode::detail
