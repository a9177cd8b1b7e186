#include "converter.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>

#include "ncpost/canon/cycle.hpp"

namespace ncpost::gcode::detail {

namespace {

constexpr WordId kX = letter_word('X'), kY = letter_word('Y');
constexpr WordId kI = letter_word('I'), kJ = letter_word('J'), kK = letter_word('K');
constexpr WordId kF = letter_word('F'), kS = letter_word('S'), kT = letter_word('T');
constexpr WordId kH = letter_word('H'), kL = letter_word('L'), kP = letter_word('P');
constexpr WordId kQ = letter_word('Q'), kR = letter_word('R'), kN = letter_word('N');
constexpr WordId kG = letter_word('G'), kM = letter_word('M'), kO = letter_word('O');
constexpr WordId kD = letter_word('D'), kE = letter_word('E');

// Axis k (0..8) is written with this letter.
constexpr std::array<char, kAxes> kAxisLetters = {'X', 'Y', 'Z', 'A', 'B', 'C', 'U', 'V', 'W'};
constexpr WordId axis_word(int k) noexcept {
  return letter_word(kAxisLetters[static_cast<std::size_t>(k)]);
}
constexpr bool is_rotary(int k) noexcept {
  return k >= 3 && k <= 5;
}

// rs274's plane order: the first and second axis of the plane and the axis normal to it.
struct PlaneAxes {
  int first, second, normal;
  WordId first_offset, second_offset;  // the centre words of the first and second axis
};
PlaneAxes plane_axes(canon::Plane p) noexcept {
  switch (p) {
    case canon::Plane::Xy:
      return {0, 1, 2, kI, kJ};
    case canon::Plane::Xz:
      return {2, 0, 1, kK, kI};
    case canon::Plane::Yz:
      return {1, 2, 0, kJ, kK};
  }
  return {0, 1, 2, kI, kJ};
}

std::string number_text(double v) {
  char buf[64];
  const int n = std::snprintf(buf, sizeof buf, "%.4f", v);
  return std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
}

bool is_motion_action(Action a) noexcept {
  return a == Action::Rapid || a == Action::Linear || a == Action::ArcCw || a == Action::ArcCcw ||
         a == Action::Cycle || a == Action::CycleCancel || a == Action::ArcThroughPoint ||
         a == Action::SplineB || a == Action::SplineNurbs;
}

// Re-maps the cycle frame (first plane axis, second plane axis, drill axis) onto X Y Z, for
// cycles in the XZ and YZ planes that canon::expand_cycle (XY only) expands.
class PlaneSink final : public canon::Sink {
 public:
  PlaneSink(canon::Sink& out, int first, int second, int drill)
      : out_(out), first_(first), second_(second), drill_(drill) {}
  void call(const canon::Call& call) override {
    auto map = [&](canon::Pose& p) {
      std::array<double, 3> xyz{};
      xyz[static_cast<std::size_t>(first_)] = p.x;
      xyz[static_cast<std::size_t>(second_)] = p.y;
      xyz[static_cast<std::size_t>(drill_)] = p.z;
      p.x = xyz[0];
      p.y = xyz[1];
      p.z = xyz[2];
    };
    if (const auto* t = std::get_if<canon::StraightTraverse>(&call)) {
      canon::StraightTraverse m = *t;
      map(m.to);
      out_.call(m);
    } else if (const auto* f = std::get_if<canon::StraightFeed>(&call)) {
      canon::StraightFeed m = *f;
      map(m.to);
      out_.call(m);
    } else {
      out_.call(call);
    }
  }

 private:
  canon::Sink& out_;
  int first_, second_, drill_;
};

}  // namespace

Converter::Converter(const Dialect& dialect, canon::Sink& sink, Report& report,
                     const ReadOptions& options)
    : dialect_(dialect), sink_(sink), report_(report), options_(options) {
  metric_ = dialect.metric;
  centre_absolute_ = dialect.arcs.centre_absolute;
  retract_r_ = dialect.initial_retract_r;
  if (dialect.initial_motion >= 0)
    motion_ = &dialect.codes[static_cast<std::size_t>(dialect.initial_motion)];
  spline_words_ = {dialect.word("PW"), dialect.word("PL"), dialect.word("SD")};
  through_words_ = {dialect.word("I1"), dialect.word("J1"), dialect.word("K1")};
}

void Converter::emit(canon::Call call) {
  sink_.call(call);
  ++calls_;
}

// A straight move to pos_, written field by field into a call kept for the purpose: building a
// Pose and copying it into a fresh variant costs a store-forwarding stall per motion.
template <class Move>
void Converter::emit_move() {
  Move& move = move_call_.emplace<Move>();
  move.to.x = from_mm(pos_[0]);
  move.to.y = from_mm(pos_[1]);
  move.to.z = from_mm(pos_[2]);
  if (uses_rotary_) move.to.rotary.emplace(canon::Rotary{pos_[3], pos_[4], pos_[5]});
  sink_.call(move_call_);
  ++calls_;
}

void Converter::start(const std::string& program_name) {
  if (started_) return;
  started_ = true;
  project_ = canon::Entity{0, "NC_PROGRAM", program_name};
  emit(canon::Begin{canon::Scope::Project, project_});
  emit(canon::UseLengthUnits{metric_ ? canon::Units::Millimetres : canon::Units::Inches});
  emit(canon::SetOriginOffsets{{0, 0, 0}, std::nullopt});
  emit(canon::SetFeedReference{canon::FeedReference::Xyz});
  emit(canon::SelectPlane{canon::Plane::Xy});
}

void Converter::finish() {
  if (!started_) start("program");
  flush_spline();
  close_section();
  emit(canon::End{canon::Scope::Project, project_});
}

// ---- Sections --------------------------------------------------------------------------------

void Converter::open_section(const Where& where, const std::string& name) {
  close_section();
  section_ = canon::Entity{where.line, "NC_SECTION", name};
  emit(canon::Begin{canon::Scope::Workingstep, section_});
  section_open_ = true;
  pending_label_.clear();
}

void Converter::close_section() {
  if (!section_open_) return;
  emit(canon::End{canon::Scope::Workingstep, section_});
  section_open_ = false;
}

// The part before the first tool change becomes a section of its own when it moves.
void Converter::ensure_section(const Where& where) {
  if (section_open_ || had_tool_change_) return;
  open_section(
      where, pending_label_.empty() ? std::string("before the first tool change") : pending_label_);
}

// ---- Diagnostics -----------------------------------------------------------------------------

bool Converter::error(const Where& where, std::uint32_t column, diag::Code code,
                      std::string message) {
  report_.add(where.file, code, where.line, column, std::move(message));
  return false;
}

void Converter::warn(const Where& where, std::uint32_t column, diag::Code code,
                     std::string message) {
  report_.add(where.file, code, where.line, column, std::move(message));
}

// ---- State as parameters see it --------------------------------------------------------------

Axes Converter::total_offset() const noexcept {
  Axes t{};
  for (int k = 0; k < kAxes; ++k) {
    const auto i = static_cast<std::size_t>(k);
    t[i] =
        work_offsets_[static_cast<std::size_t>(work_index_)][i] + axis_offset_[i] + translation_[i];
  }
  return t;
}

double Converter::at(int axis) const noexcept {
  return out(axis, pos_);
}
double Converter::internal(int axis, double v, bool machine) const noexcept {
  const auto i = static_cast<std::size_t>(axis);
  const double value = is_rotary(axis) ? v : to_mm(v);
  return machine ? value - total_offset()[i] : value;
}
double Converter::position(int axis) const {
  return axis >= 0 && axis < kAxes ? at(axis) : 0;
}
double Converter::machine_position(int axis) const {
  if (axis < 0 || axis >= kAxes) return 0;
  const auto i = static_cast<std::size_t>(axis);
  Axes m{};
  m[i] = pos_[i] + total_offset()[i];
  return out(axis, m);
}
double Converter::work_offset(int index, int axis) const {
  if (index < 1 || index >= kWorkOffsets || axis < 0 || axis >= kAxes) return 0;
  Axes v = work_offsets_[static_cast<std::size_t>(index)];
  return out(axis, v);
}
void Converter::set_work_offset(int index, int axis, double value) {
  if (index < 1 || index >= kWorkOffsets || axis < 0 || axis >= kAxes) return;
  work_offsets_[static_cast<std::size_t>(index)][static_cast<std::size_t>(axis)] =
      is_rotary(axis) ? value : to_mm(value);
}
double Converter::axis_offset(int axis) const {
  if (axis < 0 || axis >= kAxes) return 0;
  return out(axis, axis_offset_);
}

std::optional<double> Converter::named(std::string_view name) const {
  // LinuxCNC's predefined named parameters (names are read in upper case).
  static constexpr std::array<std::string_view, kAxes> kPos = {"_X", "_Y", "_Z", "_A", "_B",
                                                               "_C", "_U", "_V", "_W"};
  for (int k = 0; k < kAxes; ++k)
    if (name == kPos[static_cast<std::size_t>(k)]) return at(k);
  if (name == "_METRIC") return metric_ ? 1.0 : 0.0;
  if (name == "_IMPERIAL") return metric_ ? 0.0 : 1.0;
  if (name == "_ABSOLUTE") return incremental_ ? 0.0 : 1.0;
  if (name == "_INCREMENTAL") return incremental_ ? 1.0 : 0.0;
  if (name == "_CURRENT_TOOL") return tool_in_spindle_;
  if (name == "_SELECTED_TOOL") return tool_selected_;
  if (name == "_FEED") return feed_;
  if (name == "_RPM") return spindle_speed_;
  if (name == "_SPINDLE_ON") return spindle_dir_ != 0 ? 1.0 : 0.0;
  if (name == "_COORD_SYSTEM") return 530.0 + 10.0 * work_index_ + (work_index_ > 6 ? 0.0 : 0.0);
  if (name == "_TASK") return 0.0;  // rs274 runs outside the task: 0
  if (name == "_VALUE") return return_value_.value_or(0.0);
  if (name == "_VALUE_RETURNED") return return_value_.has_value() ? 1.0 : 0.0;
  return std::nullopt;
}

// ---- Output ----------------------------------------------------------------------------------

canon::Pose Converter::pose(const Axes& p) const {
  canon::Pose pose{from_mm(p[0]), from_mm(p[1]), from_mm(p[2]), std::nullopt, std::nullopt};
  if (uses_rotary_) pose.rotary = canon::Rotary{p[3], p[4], p[5]};
  return pose;
}

void Converter::emit_offsets() {
  const Axes t = total_offset();
  if (offsets_emitted_ && t == last_offsets_) return;
  last_offsets_ = t;
  offsets_emitted_ = true;
  canon::SetOriginOffsets o{{from_mm(t[0]), from_mm(t[1]), from_mm(t[2])}, std::nullopt};
  if (uses_rotary_) o.rotary = canon::Rotary{t[3], t[4], t[5]};
  emit(o);
}

void Converter::comment(std::string_view text, const Where&) {
  pending_label_.assign(text);
  emit(canon::Comment{std::string(text)});
}

void Converter::message(std::string_view text) {
  emit(canon::Message{std::string(text)});
}

void Converter::set_metric(bool metric) {
  if (metric == metric_) return;
  metric_ = metric;
  emit(canon::UseLengthUnits{metric ? canon::Units::Millimetres : canon::Units::Inches});
  // The feed rate keeps its number (rs274 too); coordinates are kept in mm inside.
}

void Converter::select_plane(canon::Plane plane) {
  plane_ = plane;
  emit(canon::SelectPlane{plane});
}

void Converter::set_feed(double rate) {
  feed_ = rate;
  emit(canon::SetFeedRate{rate});
}

void Converter::set_spindle_speed(double rpm, const Where& where, std::uint32_t column) {
  if (rpm < 0) {
    error(where, column, diag::Code::GcodeBadWordValue, "negative spindle speed");
    return;
  }
  if (options_.limits && options_.limits->max_spindle && rpm > *options_.limits->max_spindle) {
    report_.add(where.file, diag::Code::GcodeLimit,
                options_.limits->errors ? diag::Severity::Error : diag::Severity::Warning,
                where.line, column,
                "spindle speed " + number_text(rpm) + " beyond the limit " +
                    number_text(*options_.limits->max_spindle));
  }
  spindle_speed_ = rpm;
  emit(canon::SetSpindleSpeed{rpm});
}

void Converter::spindle(int direction) {
  spindle_dir_ = direction;
  if (direction > 0) {
    emit(canon::StartSpindleClockwise{});
    warned_spindle_ = false;
  } else if (direction < 0) {
    emit(canon::StartSpindleCounterclockwise{});
    warned_spindle_ = false;
  } else {
    emit(canon::StopSpindleTurning{});
  }
}

void Converter::select_tool(int tool, const Where& where, std::uint32_t column) {
  if (tool < 0) {
    error(where, column, diag::Code::GcodeBadWordValue, "negative tool number");
    return;
  }
  if (options_.tools && tool > 0 &&
      std::find(options_.tools->begin(), options_.tools->end(), tool) == options_.tools->end()) {
    error(where, column, diag::Code::GcodeUnknownTool,
          "tool " + std::to_string(tool) + " is not in the tool table");
  }
  if (options_.limits) {
    const auto& l = *options_.limits;
    if ((l.min_tool && tool < *l.min_tool) || (l.max_tool && tool > *l.max_tool))
      report_.add(where.file, diag::Code::GcodeLimit,
                  l.errors ? diag::Severity::Error : diag::Severity::Warning, where.line, column,
                  "tool number " + std::to_string(tool) + " beyond the profile's limits");
  }
  tool_selected_ = tool;
  emit(canon::SelectTool{tool});
}

void Converter::change_tool(const Where& where, std::uint32_t) {
  had_tool_change_ = true;
  open_section(where,
               pending_label_.empty() ? "T" + std::to_string(tool_selected_) : pending_label_);
  tool_in_spindle_ = tool_selected_;
  emit(canon::ChangeTool{tool_selected_});
}

void Converter::tool_length(bool on, int h, const Where& where) {
  if (!on) {
    emit(canon::UseToolLengthOffset{0});
    return;
  }
  for (const auto& [tool, length] : options_.tool_lengths) {
    if (tool == h) {
      emit(canon::UseToolLengthOffset{from_mm(length)});
      return;
    }
  }
  // The length lives in the machine's tool table. The canonical call needs a number: the
  // dialect's documented assumption (docs/gcode.md), which no motion depends on. Said once.
  if (!warned_tool_length_) {
    warned_tool_length_ = true;
    report_.add(where.file, diag::Code::GcodeMachineValue, where.line, 0,
                "tool lengths (H" + std::to_string(h) +
                    " and any other) are the machine's: USE_TOOL_LENGTH_OFFSET carries the "
                    "assumed " +
                    number_text(dialect_.assumed_tool_length));
  }
  emit(canon::UseToolLengthOffset{dialect_.assumed_tool_length});
}

void Converter::coolant(bool mist, bool flood, bool off) {
  if (mist) emit(canon::MistOn{});
  if (flood) emit(canon::FloodOn{});
  if (off) {
    emit(canon::MistOff{});
    emit(canon::FloodOff{});
  }
}

void Converter::dwell(double seconds) {
  emit(canon::Dwell{seconds});
}

void Converter::stop(Action action) {
  switch (action) {
    case Action::ProgramStop:
    case Action::PalletChange:
      emit(canon::ProgramStop{});
      break;
    case Action::OptionalStop:
      emit(canon::OptionalProgramStop{});
      break;
    case Action::ProgramEnd:
      close_section();
      emit(canon::ProgramEnd{});
      ended_ = true;
      break;
    default:
      break;
  }
}

void Converter::set_translation(const Axes& offset) {
  for (int k = 0; k < kAxes; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double v = is_rotary(k) ? offset[i] : to_mm(offset[i]);
    pos_[i] -= v - translation_[i];
    translation_[i] = v;
  }
  emit_offsets();
}

// ---- Motion primitives -----------------------------------------------------------------------

// False when `p` is past the target's travel and the profile makes that an error: the motion
// is then not made (the renderer would only report it again, without the line).
bool Converter::check_limits(const Axes& p, const Where& where, std::uint32_t column) {
  if (!options_.limits) return true;
  const auto& l = *options_.limits;
  const std::array<const std::optional<MachineLimits::Range>*, 3> ranges = {&l.x, &l.y, &l.z};
  for (int k = 0; k < 3; ++k) {
    const auto& r = *ranges[static_cast<std::size_t>(k)];
    if (!*ranges[static_cast<std::size_t>(k)]) continue;
    const double v =
        l.metric ? p[static_cast<std::size_t>(k)] : p[static_cast<std::size_t>(k)] / 25.4;
    if (v < r->min - 1e-9 || v > r->max + 1e-9) {
      report_.add(where.file, diag::Code::GcodeLimit,
                  l.errors ? diag::Severity::Error : diag::Severity::Warning, where.line, column,
                  std::string(1, kAxisLetters[static_cast<std::size_t>(k)]) + " " + number_text(v) +
                      " beyond the travel [" + number_text(r->min) + ", " + number_text(r->max) +
                      "]");
      return !l.errors;
    }
  }
  return true;
}

bool Converter::check_feed_motion(const Where& where, std::uint32_t column, double own_feed) {
  if (feed_ <= 0 && own_feed <= 0)
    return error(where, column, diag::Code::GcodeNoFeed,
                 feed_mode_ == FeedMode::InverseTime
                     ? "feed motion in inverse time mode (G93) without F"
                     : "feed motion with no feed rate in force (F)");
  if (options_.limits && options_.limits->max_feed && feed_mode_ == FeedMode::PerMinute &&
      feed_ > *options_.limits->max_feed) {
    report_.add(where.file, diag::Code::GcodeLimit,
                options_.limits->errors ? diag::Severity::Error : diag::Severity::Warning,
                where.line, column,
                "feed " + number_text(feed_) + " beyond the limit " +
                    number_text(*options_.limits->max_feed));
  }
  if (spindle_dir_ == 0 && !warned_spindle_) {
    warned_spindle_ = true;
    warn(where, column, diag::Code::GcodeSpindleStopped,
         "feed motion while the spindle is stopped");
  }
  return true;
}

bool Converter::rapid(const Axes& target, const Where& where, std::uint32_t column) {
  ensure_section(where);
  if (!check_limits(target, where, column)) return stop_at(target);
  pos_ = target;
  emit_move<canon::StraightTraverse>();
  return true;
}

bool Converter::linear(const Axes& target, const Where& where, std::uint32_t column) {
  if (!check_feed_motion(where, column)) return false;
  ensure_section(where);
  if (!check_limits(target, where, column)) return stop_at(target);
  if (feed_mode_ == FeedMode::InverseTime) {
    // The canonical feed is per minute: the move takes 1/F minutes.
    double length = 0;
    for (int k = 0; k < 3; ++k)
      length +=
          std::pow(target[static_cast<std::size_t>(k)] - pos_[static_cast<std::size_t>(k)], 2);
    emit(canon::SetFeedRate{from_mm(std::sqrt(length)) * feed_});
  }
  pos_ = target;
  emit_move<canon::StraightFeed>();
  return true;
}

bool Converter::arc(const Axes& target, double centre_first, double centre_second, int rotation,
                    canon::Plane plane, const Where& where, std::uint32_t column) {
  if (!check_feed_motion(where, column)) return false;
  ensure_section(where);
  if (!check_limits(target, where, column)) return stop_at(target);
  const PlaneAxes pa = plane_axes(plane);
  canon::PlaneArc p;
  p.plane = plane;
  p.first_end = from_mm(target[static_cast<std::size_t>(pa.first)]);
  p.second_end = from_mm(target[static_cast<std::size_t>(pa.second)]);
  p.first_axis = from_mm(centre_first);
  p.second_axis = from_mm(centre_second);
  p.rotation = rotation;
  p.axis_end_point = from_mm(target[static_cast<std::size_t>(pa.normal)]);
  canon::ArcFeed a = canon::arc_from_plane(p);
  if (uses_rotary_) a.end.rotary = canon::Rotary{target[3], target[4], target[5]};
  pos_ = target;
  emit(a);
  return true;
}

bool Converter::cycle(const CycleCall& c, const Where& where, std::uint32_t column) {
  if (!check_feed_motion(where, column, c.feed)) return false;
  if (c.r < c.bottom - 1e-9)
    return error(where, column, diag::Code::GcodeCycleGeometry,
                 "the cycle's R level " + number_text(c.r) + " is below its bottom " +
                     number_text(c.bottom));
  if ((c.kind == CycleKind::Peck || c.kind == CycleKind::ChipBreak) && c.peck <= 0)
    return error(where, column, diag::Code::GcodeCycleGeometry,
                 "peck drilling without a positive peck depth (Q)");
  ensure_section(where);
  Axes t = pos_;
  t[0] = to_mm(c.x);
  t[1] = to_mm(c.y);
  if (!check_limits(t, where, column)) return false;
  canon::Cycle cy;
  cy.x = c.x;
  cy.y = c.y;
  cy.safe_z = std::max(c.clear, c.r);
  cy.r_z = c.r;
  cy.bottom_z = c.bottom;
  cy.feed = c.feed > 0 ? c.feed : feed_;
  cy.dwell = c.dwell;
  switch (c.kind) {
    case CycleKind::Drill:
    case CycleKind::DrillDwell:
      cy.kind = canon::CycleKind::Drill;
      break;
    case CycleKind::Peck:
      cy.kind = canon::CycleKind::PeckDrill;
      cy.peck = c.peck;
      cy.peck_clearance = c.peck_clearance;
      break;
    case CycleKind::ChipBreak:
      cy.kind = canon::CycleKind::PeckDrill;
      cy.peck = c.peck;
      cy.peck_retract = c.peck_retract;
      break;
    case CycleKind::Tap:
    case CycleKind::TapLeft:
      cy.kind = canon::CycleKind::Tap;
      cy.left_hand = c.kind == CycleKind::TapLeft;
      cy.spindle_speed = spindle_speed_;
      cy.pitch = spindle_speed_ > 0 ? feed_ / spindle_speed_ : 0;
      break;
    case CycleKind::Bore:
    case CycleKind::BoreDwell:
      cy.kind = canon::CycleKind::Bore;
      break;
    case CycleKind::BoreStop:
      cy.kind = canon::CycleKind::Bore;
      cy.spindle_stop = true;
      break;
  }
  if (uses_rotary_) cy.rotary = canon::Rotary{pos_[3], pos_[4], pos_[5]};
  emit(cy);
  // A cycle with its own feed leaves the feed in force as it was (Heidenhain's Q206).
  if (c.feed > 0 && feed_ > 0 && c.feed != feed_) emit(canon::SetFeedRate{feed_});
  pos_[0] = to_mm(c.x);
  pos_[1] = to_mm(c.y);
  pos_[2] = to_mm(cy.safe_z);
  return true;
}

// ---- Word-address blocks ---------------------------------------------------------------------

// Where a motion's diagnostics point: its motion code, or its first axis word.
std::uint32_t Converter::motion_column(const Block& b) const noexcept {
  for (const CodeRef& c : b.codes)
    if (is_motion_action(c.spec->action)) return c.column;
  std::uint32_t column = 0;
  for (std::uint64_t bits = b.present.to_ullong(); bits != 0; bits &= bits - 1) {
    const auto w = static_cast<std::size_t>(std::countr_zero(bits));
    if (w >= dialect_.words.size()) continue;
    const WordKind k = dialect_.words[w].kind;
    if ((k == WordKind::Axis || k == WordKind::PolarRadius || k == WordKind::PolarAngle) &&
        (column == 0 || b.word(static_cast<WordId>(w)).column < column))
      column = b.word(static_cast<WordId>(w)).column;
  }
  return column == 0 ? b.first_column : column;
}

// Sinumerik CIP: the circle from here through the intermediate point (I1= J1= K1=) to the end
// point, in whatever plane the three points span (a tilted plane is a 3D arc).
bool Converter::convert_arc_through(const Block& b, const Where& where) {
  const std::uint32_t column = motion_column(b);
  Axes target;
  word_target(b, target, false);
  std::array<double, 3> mid{pos_[0], pos_[1], pos_[2]};
  bool any = false;
  for (int k = 0; k < 3; ++k) {
    const WordId w = through_words_[static_cast<std::size_t>(k)];
    if (w == kNoWord || !b.has(w)) continue;
    any = true;
    const double v = length_word(b, w);
    mid[static_cast<std::size_t>(k)] = incremental_ ? pos_[static_cast<std::size_t>(k)] + v : v;
  }
  if (!any)
    return error(where, column, diag::Code::GcodeMissingWord,
                 "a circle through a point (CIP) without its intermediate point (I1, J1, K1)");
  // Centre of the circle through a, m, e: a + (|u|² (v×w)... in the plane of u = m - a, v = e - a.
  const std::array<double, 3> a{pos_[0], pos_[1], pos_[2]}, e{target[0], target[1], target[2]};
  const std::array<double, 3> u{mid[0] - a[0], mid[1] - a[1], mid[2] - a[2]};
  const std::array<double, 3> v{e[0] - a[0], e[1] - a[1], e[2] - a[2]};
  const auto cross = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return std::array<double, 3>{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2],
                                 p[0] * q[1] - p[1] * q[0]};
  };
  const auto dot = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
    return p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
  };
  const std::array<double, 3> n = cross(u, v);
  const double nn = dot(n, n);
  if (nn < 1e-18)
    return error(where, column, diag::Code::GcodeArcGeometry,
                 "the three points of a CIP circle lie on one line");
  // c - a = (|u|² (v × n) + |v|² (n × u)) / (2 |n|²)
  const std::array<double, 3> vn = cross(v, n), nu = cross(n, u);
  const double uu = dot(u, u), vv = dot(v, v);
  canon::ArcFeed arc;
  arc.centre = {from_mm(a[0] + (uu * vn[0] + vv * nu[0]) / (2 * nn)),
                from_mm(a[1] + (uu * vn[1] + vv * nu[1]) / (2 * nn)),
                from_mm(a[2] + (uu * vn[2] + vv * nu[2]) / (2 * nn))};
  const double len = std::sqrt(nn);
  // From a through m to e is counter-clockwise about u × v.
  arc.normal = {n[0] / len, n[1] / len, n[2] / len};
  // Snap a normal that is an axis to it exactly, so the arc has its plane form.
  for (double* c : {&arc.normal.i, &arc.normal.j, &arc.normal.k})
    if (std::abs(std::abs(*c) - 1) < 1e-12) *c = *c > 0 ? 1 : -1;
  arc.turns = 1;
  if (!check_feed_motion(where, column)) return false;
  ensure_section(where);
  if (!check_limits(target, where, column)) return stop_at(target);
  arc.end = pose(target);
  pos_ = target;
  emit(arc);
  return true;
}

// Sinumerik BSPLINE: each block is a control point (PW= its weight, PL= the knot step before the
// next, SD= the degree in the first block); the curve is emitted as one NURBS_FEED when a block
// that does not continue it comes.
bool Converter::add_spline_point(const Block& b, const Where& where) {
  const std::uint32_t column = motion_column(b);
  Axes target;
  word_target(b, target, false);
  if (!spline_) {
    if (!check_feed_motion(where, column)) return false;
    ensure_section(where);
    spline_ = Spline{};  // not emplace(): clang 14 (the fuzz build) rejects it here
    spline_->points.push_back({from_mm(pos_[0]), from_mm(pos_[1]), from_mm(pos_[2]), 1.0});
    spline_->degree = 3;
    if (spline_words_[2] != kNoWord && b.has(spline_words_[2]))
      spline_->degree = static_cast<int>(std::lround(b.value(spline_words_[2])));
    spline_->where_file = std::string(where.file);
    spline_->where_line = where.line;
    spline_->column = column;
  }
  const double w =
      spline_words_[0] != kNoWord && b.has(spline_words_[0]) ? b.value(spline_words_[0]) : 1.0;
  const double pl =
      spline_words_[1] != kNoWord && b.has(spline_words_[1]) ? b.value(spline_words_[1]) : 0.0;
  if (w <= 0)
    return error(where, column, diag::Code::GcodeBadWordValue,
                 "a spline weight (PW) must be positive");
  if (!check_limits(target, where, column)) return false;
  spline_->points.push_back({from_mm(target[0]), from_mm(target[1]), from_mm(target[2]), w});
  spline_->intervals.push_back(pl);
  spline_->end = target;
  return true;
}

// Mitsubishi/FANUC G06.2 P<order> K<knot> X Y Z R<weight>: the first block's point is the start
// point; each block adds a control point and a knot, blocks of K alone the last knots.
bool Converter::add_nurbs_point(const Block& b, const Where& where) {
  const std::uint32_t column = motion_column(b);
  bool code = false;  // G06.2 written in this block: a new curve
  for (const CodeRef& c : b.codes) code = code || c.spec->action == Action::SplineNurbs;
  const bool starts = !spline_ || !spline_->explicit_knots || code;
  if (starts) {
    flush_spline();
    if (!check_feed_motion(where, column)) return false;
    ensure_section(where);
    if (!b.has(kP))
      return error(where, column, diag::Code::GcodeMissingWord, "G06.2 without its order P");
    spline_ = Spline{};  // not emplace(): clang 14 (the fuzz build) rejects it here
    spline_->explicit_knots = true;
    spline_->degree = static_cast<int>(std::lround(b.value(kP))) - 1;
    spline_->where_file = std::string(where.file);
    spline_->where_line = where.line;
    spline_->column = column;
    spline_->end = pos_;
  }
  if (b.has(kK)) spline_->knots.push_back(b.value(kK));
  bool axes = false;
  for (int k = 0; k < kAxes; ++k) axes = axes || b.has(axis_word(k));
  if (axes || starts) {
    Axes target;
    word_target(b, target, false);
    const double w = b.has(kR) ? b.value(kR) : 1.0;
    if (w <= 0)
      return error(where, column, diag::Code::GcodeBadWordValue,
                   "a NURBS weight (R) must be positive");
    if (!check_limits(target, where, column)) return false;
    spline_->points.push_back({from_mm(target[0]), from_mm(target[1]), from_mm(target[2]), w});
    spline_->end = target;
  }
  return true;
}

void Converter::flush_spline() {
  if (!spline_) return;
  Spline s = std::move(*spline_);
  spline_.reset();
  canon::NurbsFeed n;
  n.degree = s.degree;
  n.points = std::move(s.points);
  if (s.explicit_knots) {
    n.knots = std::move(s.knots);
    if (!canon::valid(n)) {
      error(Where{s.where_file, s.where_line}, s.column, diag::Code::GcodeBadWordValue,
            "a G06.2 NURBS that makes no valid curve (order " + std::to_string(s.degree + 1) +
                ", " + std::to_string(n.points.size()) + " points, " +
                std::to_string(n.knots.size()) + " knots)");
      return;
    }
    if (uses_rotary_) n.rotary = canon::Rotary{s.end[3], s.end[4], s.end[5]};
    pos_ = s.end;
    emit(n);
    return;
  }
  // Clamped: degree + 1 equal knots, the steps PL in order, the end knot repeated up to
  // points + degree + 1 knots (a PL left out is a step of 0: Sinumerik's default spacing
  // is not modelled, docs/gcode.md).
  n.knots.assign(static_cast<std::size_t>(std::max(s.degree, 0)) + 1, 0.0);
  double u = 0;
  for (const double pl : s.intervals)
    if (pl > 0) n.knots.push_back(u += pl);
  while (n.knots.size() < n.points.size() + static_cast<std::size_t>(std::max(s.degree, 0)) + 1)
    n.knots.push_back(u > 0 ? u : 1.0);
  if (u == 0)
    for (std::size_t i = static_cast<std::size_t>(std::max(s.degree, 0)) + 1; i < n.knots.size();
         ++i)
      n.knots[i] = 1.0;
  if (!canon::valid(n)) {
    error(Where{s.where_file, s.where_line}, s.column, diag::Code::GcodeBadWordValue,
          "a spline that makes no valid NURBS (degree " + std::to_string(s.degree) + ", " +
              std::to_string(n.points.size()) + " points)");
    return;
  }
  if (uses_rotary_) n.rotary = canon::Rotary{s.end[3], s.end[4], s.end[5]};
  pos_ = s.end;
  emit(n);
}

double Converter::scaled(const Block& b, WordId w) const noexcept {
  const Word& word = b.word(w);
  if (dialect_.integer_literal_increments && word.integer_literal) {
    const WordKind kind = dialect_.words[w].kind;
    if (kind == WordKind::Axis || kind == WordKind::Length)
      return word.value * (metric_ ? dialect_.increment_mm : dialect_.increment_inch);
  }
  return word.value;
}

double Converter::length_word(const Block& b, WordId w) const noexcept {
  return to_mm(scaled(b, w));
}

// The block's axis words as a target in the current coordinate system (mm), from the current
// position: absolute or incremental, or (machine) in machine coordinates (G53).
bool Converter::polar(const Block& b, double& x, double& y) const {
  const WordId wr = dialect_.polar_radius, wa = dialect_.polar_angle;
  const bool has_r = wr != kNoWord && b.has(wr);
  const bool has_a = wa != kNoWord && b.has(wa);
  if (!has_r && !has_a) return false;
  // LinuxCNC: about the origin of the current coordinate system; in G91 the distance and the
  // angle add to the current point's.
  const double r0 = std::hypot(pos_[0], pos_[1]);
  const double a0 = std::atan2(pos_[1], pos_[0]) * 180 / std::numbers::pi;
  double r = r0, a = a0;
  if (incremental_) {
    if (has_r) r += length_word(b, wr);
    if (has_a) a += b.value(wa);
  } else {
    if (has_r) r = length_word(b, wr);
    if (has_a) a = b.value(wa);
  }
  x = r * std::cos(a * std::numbers::pi / 180);
  y = r * std::sin(a * std::numbers::pi / 180);
  return true;
}

bool Converter::word_target(const Block& b, Axes& target, bool machine) const {
  target = pos_;
  bool any = false;
  if (double x = 0, y = 0; polar(b, x, y)) {
    target[0] = x;
    target[1] = y;
    any = true;
  }
  const Axes offset = machine ? total_offset() : Axes{};
  for (int k = 0; k < kAxes; ++k) {
    const WordId w = axis_word(k);
    if (!b.has(w)) continue;
    any = true;
    const auto i = static_cast<std::size_t>(k);
    const double v = is_rotary(k) ? scaled(b, w) : length_word(b, w);
    const Word::Distance d = b.word(w).distance;
    const bool incremental =
        d == Word::Distance::Modal ? incremental_ : d == Word::Distance::Incremental;
    if (machine)
      target[i] = v - offset[i];
    else
      target[i] = incremental ? pos_[i] + v : v;
  }
  return any;
}

bool Converter::convert_motion(const CodeSpec& motion, const Block& b, const Where& where,
                               bool machine_coordinates) {
  const std::uint8_t plane_bit = plane_ == canon::Plane::Xy   ? 1
                                 : plane_ == canon::Plane::Xz ? 2
                                                              : 4;
  if ((motion.planes & plane_bit) == 0)
    return error(where, motion_column(b), diag::Code::GcodeUnsupported,
                 motion.text + " in the " + (plane_bit == 2 ? "XZ" : "YZ") + " plane" +
                     (motion.refusal.empty() ? "" : " (" + motion.refusal + ")"));
  switch (motion.action) {
    case Action::Rapid:
    case Action::Linear: {
      Axes target;
      if (!word_target(b, target, machine_coordinates)) return true;
      const std::uint32_t column = motion_column(b);
      return motion.action == Action::Rapid ? rapid(target, where, column)
                                            : linear(target, where, column);
    }
    case Action::ArcCw:
    case Action::ArcCcw:
      return convert_arc(motion, b, where);
    case Action::Cycle:
      return convert_cycle(motion, b, where);
    case Action::ArcThroughPoint:
      return convert_arc_through(b, where);
    case Action::SplineB:
      return add_spline_point(b, where);
    case Action::SplineNurbs:
      return add_nurbs_point(b, where);
    default:
      return true;
  }
}

bool Converter::convert_arc(const CodeSpec& motion, const Block& b, const Where& where) {
  const PlaneAxes pa = plane_axes(plane_);
  const std::uint32_t column = motion_column(b);
  Axes target;
  word_target(b, target, false);
  const auto f = static_cast<std::size_t>(pa.first);
  const auto s = static_cast<std::size_t>(pa.second);
  const double x0 = pos_[f], y0 = pos_[s];
  const double x1 = target[f], y1 = target[s];
  const bool cw = motion.action == Action::ArcCw;
  const WordId radius_word = dialect_.arcs.radius;
  const bool has_r = radius_word != kNoWord && b.has(radius_word);
  const bool has_centre = b.has(pa.first_offset) || b.has(pa.second_offset);
  int turns = 1;
  if (dialect_.arcs.turns != kNoWord && b.has(dialect_.arcs.turns)) {
    // LinuxCNC's P counts the turns (P1: the arc itself); Sinumerik's TURN= the extra ones.
    const double p = scaled(b, dialect_.arcs.turns) + (dialect_.arcs.turns_extra ? 1 : 0);
    if (p < 1 || std::abs(p - std::round(p)) > 1e-9)
      return error(where, b.word(dialect_.arcs.turns).column, diag::Code::GcodeBadWordValue,
                   "the number of turns of an arc must be a whole number, at least 1");
    turns = static_cast<int>(std::lround(p));
  }
  double cx = 0, cy = 0;
  const double tol_abs = metric_ ? dialect_.arcs.tolerance_mm : dialect_.arcs.tolerance_inch * 25.4;
  if (has_r) {
    const double r = length_word(b, radius_word);
    const double abs_r = std::abs(r);
    const double half = std::hypot(x1 - x0, y1 - y0) / 2;
    if (half == 0)
      return error(where, b.word(radius_word).column, diag::Code::GcodeArcGeometry,
                   "a radius-format arc whose end point is its start point");
    if (abs_r == 0)
      return error(where, b.word(radius_word).column, diag::Code::GcodeArcGeometry,
                   "an arc of radius zero");
    const double slack = metric_ ? 0.002 : 0.0002 * 25.4;  // rs274: a semicircle's rounding
    if (half - abs_r > slack)
      return error(
          where, b.word(radius_word).column, diag::Code::GcodeArcGeometry,
          "arc radius " + number_text(from_mm(abs_r)) + " too small to reach the end point");
    const double h = half >= abs_r ? 0 : std::sqrt(abs_r * abs_r - half * half);
    const double mx = (x0 + x1) / 2, my = (y0 + y1) / 2;
    // The centre is on the right of the chord for a clockwise arc of less than half a turn.
    const double theta =
        std::atan2(y1 - y0, x1 - x0) +
        (((cw && r > 0) || (!cw && r < 0)) ? -std::numbers::pi / 2 : std::numbers::pi / 2);
    cx = mx + h * std::cos(theta);
    cy = my + h * std::sin(theta);
  } else if (has_centre) {
    const double i = b.has(pa.first_offset) ? length_word(b, pa.first_offset) : 0;
    const double j = b.has(pa.second_offset) ? length_word(b, pa.second_offset) : 0;
    if (centre_absolute_) {
      const Axes off{};  // absolute centres are in the current coordinate system
      (void)off;
      cx = b.has(pa.first_offset) ? i : x0;
      cy = b.has(pa.second_offset) ? j : y0;
    } else {
      cx = x0 + i;
      cy = y0 + j;
    }
    const double r1 = std::hypot(x0 - cx, y0 - cy);
    const double r2 = std::hypot(x1 - cx, y1 - cy);
    if (r1 == 0 && r2 == 0)
      return error(where, column, diag::Code::GcodeArcGeometry, "an arc of radius zero");
    const double abs_err = std::abs(r1 - r2);
    const double rel_err = abs_err / std::max(r1, r2);
    if (tol_abs > 0 && (abs_err > tol_abs * dialect_.arcs.absolute_factor ||
                        (abs_err > tol_abs && rel_err > dialect_.arcs.relative))) {
      return error(
          where, column, diag::Code::GcodeArcRadius,
          "radius to end of arc differs from radius to start: r1=" + number_text(from_mm(r1)) +
              " r2=" + number_text(from_mm(r2)) + " abs_err=" + number_text(from_mm(abs_err)) +
              " rel_err=" + number_text(rel_err * 100) + "%");
    }
  } else {
    return error(where, column, diag::Code::GcodeMissingWord,
                 "an arc without its centre (I, J, K) or radius");
  }
  return arc(target, cx, cy, cw ? -turns : turns, plane_, where, column);
}

void Converter::expand_cycle_motions(const CycleCall& c, const CodeSpec* spec, int first,
                                     int second, int drill) {
  // The cycle in its own frame (first, second, drill) through canon::expand_cycle, or — for the
  // LinuxCNC cycles that feed out to the clearance level — written here.
  const bool to_clear = spec && spec->cycle.feed_out_to_clear;
  PlaneSink mapped(sink_, first, second, drill);
  auto point = [&](double a, double bb, double d) {
    Axes p = pos_;
    p[static_cast<std::size_t>(first)] = to_mm(a);
    p[static_cast<std::size_t>(second)] = to_mm(bb);
    p[static_cast<std::size_t>(drill)] = to_mm(d);
    return p;
  };
  if (to_clear) {
    const double safe = std::max(c.clear, c.r);
    auto traverse = [&](double d) {
      pos_ = point(c.x, c.y, d);
      emit(canon::StraightTraverse{pose(pos_)});
    };
    auto feed = [&](double d) {
      pos_ = point(c.x, c.y, d);
      emit(canon::StraightFeed{pose(pos_)});
    };
    traverse(safe);
    traverse(c.r);
    feed(c.bottom);
    if (c.kind == CycleKind::Tap || c.kind == CycleKind::TapLeft) {
      emit(canon::StopSpindleTurning{});
      if (c.kind == CycleKind::Tap)
        emit(canon::StartSpindleCounterclockwise{});
      else
        emit(canon::StartSpindleClockwise{});
      if (c.dwell > 0) emit(canon::Dwell{c.dwell});
      feed(safe);
      emit(canon::StopSpindleTurning{});
      if (c.kind == CycleKind::Tap)
        emit(canon::StartSpindleClockwise{});
      else
        emit(canon::StartSpindleCounterclockwise{});
    } else {
      if (c.dwell > 0) emit(canon::Dwell{c.dwell});
      feed(safe);
    }
    return;
  }
  canon::Cycle cy;
  cy.x = c.x;
  cy.y = c.y;
  cy.safe_z = std::max(c.clear, c.r);
  cy.r_z = c.r;
  cy.bottom_z = c.bottom;
  cy.feed = feed_;
  cy.dwell = c.dwell;
  cy.peck = c.peck;
  cy.peck_retract = c.peck_retract;
  cy.peck_clearance = c.peck_clearance;
  switch (c.kind) {
    case CycleKind::Drill:
    case CycleKind::DrillDwell:
      cy.kind = canon::CycleKind::Drill;
      break;
    case CycleKind::Peck:
    case CycleKind::ChipBreak:
      cy.kind = canon::CycleKind::PeckDrill;
      break;
    case CycleKind::Tap:
    case CycleKind::TapLeft:
      cy.kind = canon::CycleKind::Tap;
      cy.left_hand = c.kind == CycleKind::TapLeft;
      break;
    case CycleKind::Bore:
    case CycleKind::BoreDwell:
      cy.kind = canon::CycleKind::Bore;
      break;
    case CycleKind::BoreStop:
      cy.kind = canon::CycleKind::Bore;
      cy.spindle_stop = true;
      break;
  }
  struct Counting final : canon::Sink {
    canon::Sink& out;
    std::size_t& count;
    Counting(canon::Sink& o, std::size_t& c) : out(o), count(c) {}
    void call(const canon::Call& call) override {
      out.call(call);
      ++count;
    }
  } counting(mapped, calls_);
  PlaneSink& target = mapped;
  (void)target;
  (void)canon::expand_cycle(cy, counting);
  pos_ = point(c.x, c.y, cy.safe_z);
}

bool Converter::convert_cycle(const CodeSpec& motion, const Block& b, const Where& where) {
  const std::uint32_t column = motion_column(b);
  // The cycle's plane: positions in the plane, the drill along its normal (toward minus).
  const PlaneAxes pa = plane_axes(plane_);
  const int first = pa.first, second = pa.second, drill = pa.normal;
  const WordId drill_word = axis_word(drill);
  const CycleRules& rules = dialect_.cycles;
  for (int k = 3; k < kAxes; ++k)
    if (b.has(axis_word(k)))
      return error(where, b.word(axis_word(k)).column, diag::Code::GcodeUnusedWord,
                   std::string("cannot put an ") + kAxisLetters[static_cast<std::size_t>(k)] +
                       " word in a canned cycle");
  if (b.has(drill_word)) cycle_bottom_ = scaled(b, drill_word);
  if (b.has(rules.r_plane)) cycle_r_ = scaled(b, rules.r_plane);
  if (b.has(rules.peck)) cycle_q_ = scaled(b, rules.peck);
  if (b.has(rules.dwell)) cycle_p_ = b.value(rules.dwell);
  if (!cycle_bottom_)
    return error(where, column, diag::Code::GcodeMissingWord,
                 std::string("a canned cycle without its depth (") +
                     kAxisLetters[static_cast<std::size_t>(drill)] + ")");
  if (!cycle_r_)
    return error(where, column, diag::Code::GcodeMissingWord, "a canned cycle without R");
  int repeat = 1;
  if (rules.repeat != kNoWord && b.has(rules.repeat)) {
    const double l = b.value(rules.repeat);
    if (l < 0 || std::abs(l - std::round(l)) > 1e-9)
      return error(where, b.word(rules.repeat).column, diag::Code::GcodeBadWordValue,
                   "a cycle's repeat count must be a non-negative integer");
    repeat = static_cast<int>(std::lround(l));
  }
  if (!check_feed_motion(where, column)) return false;
  const auto fi = static_cast<std::size_t>(first), si = static_cast<std::size_t>(second),
             di = static_cast<std::size_t>(drill);
  const double old = from_mm(pos_[di]);
  const double initial = from_mm(cycle_initial_);
  double r = 0, bottom = 0;
  if (incremental_) {
    r = initial + *cycle_r_;
    bottom = r + *cycle_bottom_;
  } else {
    r = *cycle_r_;
    bottom = *cycle_bottom_;
  }
  if (bottom > r + 1e-9)
    return error(
        where, column, diag::Code::GcodeCycleGeometry,
        "the cycle's R level " + number_text(r) + " is below its bottom " + number_text(bottom));
  ensure_section(where);
  // Below the R level: up to it first, over the current position (LinuxCNC, FANUC).
  if (old < r) {
    Axes up = pos_;
    up[di] = to_mm(r);
    pos_ = up;
    emit(canon::StraightTraverse{pose(pos_)});
  }
  const double clear = retract_r_ ? r : std::max(initial, r);
  CycleCall c;
  c.kind = motion.cycle.kind;
  c.clear = clear;
  c.r = r;
  c.bottom = bottom;
  c.dwell =
      (c.kind == CycleKind::DrillDwell || c.kind == CycleKind::BoreStop ||
       c.kind == CycleKind::BoreDwell || c.kind == CycleKind::Tap || c.kind == CycleKind::TapLeft)
          ? cycle_p_ * rules.dwell_scale
          : 0;
  c.peck = cycle_q_;
  const bool inch = !metric_;
  if (c.kind == CycleKind::Peck)
    c.peck_clearance = inch ? rules.peck_clearance_inch : rules.peck_clearance_mm;
  if (c.kind == CycleKind::ChipBreak)
    c.peck_retract = inch ? rules.chip_break_inch : rules.chip_break_mm;
  if ((c.kind == CycleKind::Peck || c.kind == CycleKind::ChipBreak) && c.peck <= 0)
    return error(where, column, diag::Code::GcodeCycleGeometry,
                 "peck drilling without a positive peck depth (Q)");
  const bool exact = plane_ == canon::Plane::Xy && !motion.cycle.feed_out_to_clear;
  const double inc_first = b.has(axis_word(first)) ? length_word(b, axis_word(first)) : 0;
  const double inc_second = b.has(axis_word(second)) ? length_word(b, axis_word(second)) : 0;
  for (int n = 0; n < repeat; ++n) {
    double a = pos_[fi], bb = pos_[si];
    if (double px = 0, py = 0; polar(b, px, py)) {
      if (plane_ != canon::Plane::Xy)
        return error(where, column, diag::Code::GcodeUnsupported,
                     "polar coordinates outside the XY plane");
      a = px;
      bb = py;
    } else if (incremental_) {
      a += inc_first;
      bb += inc_second;
    } else {
      if (b.has(axis_word(first))) a = inc_first;
      if (b.has(axis_word(second))) bb = inc_second;
    }
    c.x = from_mm(a);
    c.y = from_mm(bb);
    Axes t = pos_;
    t[fi] = a;
    t[si] = bb;
    if (!check_limits(t, where, column)) return false;
    // Above the level the cycle returns to (G99 from higher up): over the hole at the current
    // level first, then down — the canonical cycle travels at its safe level, which is R here.
    if (pos_[di] > to_mm(clear) + 1e-9) {
      pos_ = t;
      emit(canon::StraightTraverse{pose(pos_)});
    }
    if (exact) {
      if (!cycle(c, where, column)) return false;
    } else {
      expand_cycle_motions(c, &motion, first, second, drill);
    }
  }
  return true;
}

// G10: L2 sets work offset P (LinuxCNC and FANUC; P0 the current one in LinuxCNC); L20 sets
// it so that the current point gets the given coordinates (LinuxCNC) or, in a dialect whose
// G10 has index 1, sets additional work offset P (FANUC, G54.1 P); L1/L10..L13 the tool table.
bool Converter::convert_g10(const Block& b, const Where& where, std::uint32_t column,
                            const CodeSpec& spec) {
  if (!b.has(kL))
    return error(where, column, diag::Code::GcodeMissingWord, "G10 without its L word");
  const int l = static_cast<int>(std::lround(b.value(kL)));
  if (l == 1 || l == 10 || l == 11 || l == 12 || l == 13 || l == 3) {
    // The tool table: its lengths are not part of the canonical program.
    warn(where, column, diag::Code::GcodeIgnored,
         "G10 L" + std::to_string(l) +
             " changes the machine's tool table; not in the canonical program");
    return true;
  }
  if (l != 2 && l != 20)
    return error(where, column, diag::Code::GcodeUnsupported, "G10 L" + std::to_string(l));
  if (!b.has(kP))
    return error(where, column, diag::Code::GcodeMissingWord,
                 "G10 L" + std::to_string(l) + " without P");
  const bool fanuc_additional = spec.index == 1 && l == 20;
  int p = static_cast<int>(std::lround(b.value(kP)));
  if (fanuc_additional) {
    if (p < 1 || p > kWorkOffsets - 10)
      return error(where, b.word(kP).column, diag::Code::GcodeBadWordValue,
                   "G10 L20 P must be 1 to " + std::to_string(kWorkOffsets - 10));
    p += 9;
  } else {
    if (p == 0 && spec.index == 0) p = work_index_;
    if (p < 1 || p > 9)
      return error(where, b.word(kP).column, diag::Code::GcodeBadWordValue,
                   "G10 P must select a coordinate system " +
                       std::string(spec.index == 0 ? "0..9" : "1..6"));
  }
  if (b.has(kR) && std::abs(b.value(kR)) > 1e-12)
    return error(where, b.word(kR).column, diag::Code::GcodeUnsupported,
                 "coordinate system rotation (G10 ... R)");
  auto& offset = work_offsets_[static_cast<std::size_t>(p)];
  for (int k = 0; k < kAxes; ++k) {
    const WordId w = axis_word(k);
    if (!b.has(w)) continue;
    const auto i = static_cast<std::size_t>(k);
    const double v = is_rotary(k) ? scaled(b, w) : length_word(b, w);
    if (l == 2 || fanuc_additional) {
      offset[i] = incremental_ ? offset[i] + v : v;
    } else {
      // L20: the current position becomes v in coordinate system p.
      const double machine = pos_[i] + total_offset()[i];
      offset[i] = machine - axis_offset_[i] - translation_[i] - v;
    }
  }
  if (p == work_index_) {
    // The active system moved: the same machine position has new program coordinates.
    const Axes before = last_offsets_;
    const Axes now = total_offset();
    for (int k = 0; k < kAxes; ++k) {
      const auto i = static_cast<std::size_t>(k);
      pos_[i] += (offsets_emitted_ ? before[i] : 0) - now[i];
    }
    emit_offsets();
  }
  return true;
}

bool Converter::convert_home(const CodeSpec& code, const Block& b, const Where& where) {
  // Through the given point (absolute or incremental) to the reference position of the axes
  // given (all axes when none is). The reference position is a machine value: LinuxCNC keeps it
  // in parameters #5161.. (G28) and #5181.. (G30), which rs274 starts at 0; a FANUC reference
  // point is the machine's own (assumed at machine zero, with a warning).
  Axes via;
  const bool any = word_target(b, via, false);
  ensure_section(where);
  if (any)
    rapid(via, where, b.first_column);
  else
    rapid(pos_, where, b.first_column);
  if (!dialect_.parameters.named)
    warn(where, b.first_column, diag::Code::GcodeMachineValue,
         code.text + ": the reference position is the machine's; assumed at machine zero");
  Axes home = pos_;
  const Axes offset = total_offset();
  for (int k = 0; k < kAxes; ++k) {
    if (any && !b.has(axis_word(k))) continue;
    const auto i = static_cast<std::size_t>(k);
    home[i] = 0 - offset[i];
  }
  return rapid(home, where, b.first_column);
}

bool Converter::execute(const Block& b, std::span<const Comment> comments, const Where& where,
                        FlowRequest& flow) {
  // Copied from a constant: a temporary built on the stack and read back whole stalls the
  // store buffer, once per block.
  static const FlowRequest kNoFlow{};
  flow = kNoFlow;
  // ---- Check: modal groups, refused codes, required and unused words ----
  const CodeSpec* motion = nullptr;
  // Not zeroed: only the first non_motion_count are read (zeroing it was a `rep stos` per block).
  const CodeSpec* non_motion[16];
  std::size_t non_motion_count = 0;
  std::uint64_t groups_seen = 0;
  for (const CodeRef& c : b.codes) {
    const CodeSpec& spec = *c.spec;
    if (spec.group >= 0) {
      const std::uint64_t bit = std::uint64_t{1} << (spec.group & 63);
      if (groups_seen & bit)
        return error(where, c.column, diag::Code::GcodeModalConflict,
                     "two codes of the modal group '" +
                         dialect_.modal_groups[static_cast<std::size_t>(spec.group)] +
                         "' in one block (" + spec.text + ")");
      groups_seen |= bit;
    }
    if (spec.action == Action::Unsupported)
      return error(where, c.column, diag::Code::GcodeUnsupported,
                   spec.text + ": " + (spec.refusal.empty() ? "not supported" : spec.refusal));
    if (spec.action == Action::Lathe)
      return error(where, c.column, diag::Code::GcodeLathe,
                   spec.text + ": " + (spec.refusal.empty() ? "a lathe cycle" : spec.refusal) +
                       " (lathe programs are out of scope)");

    if (is_motion_action(spec.action))
      motion = &spec;
    else if (non_motion_count < std::size(non_motion))
      non_motion[non_motion_count++] = &spec;
  }
  bool axes = (dialect_.polar_radius != kNoWord && b.has(dialect_.polar_radius)) ||
              (dialect_.polar_angle != kNoWord && b.has(dialect_.polar_angle));
  if (axes && (b.has(kX) || b.has(kY)))
    return error(where, b.first_column, diag::Code::GcodeConflictingWords,
                 "polar coordinates (@, ^) with X or Y in one block");
  for (int k = 0; k < kAxes; ++k) axes = axes || b.has(axis_word(k));
  const CodeSpec* uses_axes = nullptr;  // a non-motion code that takes the axis words
  for (std::size_t i = 0; i < non_motion_count; ++i) {
    const Action a = non_motion[i]->action;
    if (a == Action::SetCoordinateData || a == Action::AxisOffset || a == Action::LocalOffset ||
        a == Action::Home || a == Action::Home2 || a == Action::MacroCall ||
        a == Action::Translate || a == Action::TranslateAdd || a == Action::OnlyWithoutWords)
      uses_axes = non_motion[i];
    // FANUC G4 X1.5: the X is the dwell's time.
    if (a == Action::Dwell)
      for (const DwellWord& d : dialect_.dwell.words)
        if (b.has(d.word) && dialect_.words[d.word].kind == WordKind::Axis)
          uses_axes = non_motion[i];
  }
  // An arc may have only its centre words: a full circle where the tool stands (LinuxCNC).
  const bool centre_words = b.has(kI) || b.has(kJ) || b.has(kK) ||
                            (dialect_.arcs.radius != kNoWord && b.has(dialect_.arcs.radius));
  const CodeSpec* modal = motion ? motion : motion_;
  const bool arc_mode =
      modal && (modal->action == Action::ArcCw || modal->action == Action::ArcCcw);
  // G06.2: blocks of knots alone (K) go on with the NURBS too.
  const bool knot_only = modal && modal->action == Action::SplineNurbs && b.has(kK);
  const CodeSpec* effective_motion =
      motion
          ? motion
          : ((axes || (arc_mode && centre_words) || knot_only) && !uses_axes ? motion_ : nullptr);
  if (axes && !uses_axes && (!effective_motion || effective_motion->action == Action::CycleCancel))
    return error(where, b.first_column, diag::Code::GcodeUnusedWord,
                 "axis words without a code that uses them (no motion mode in force)");
  // Required words of each code.
  auto check_required = [&](const CodeSpec& spec, std::uint32_t column) {
    for (const WordId w : spec.requires_all)
      if (!b.has(w))
        return error(where, column, diag::Code::GcodeMissingWord,
                     spec.text + " without its " + dialect_.words[w].name + " word");
    if (!spec.requires_one_of.empty()) {
      bool found = false;
      for (const WordId w : spec.requires_one_of) found = found || b.has(w);
      if (!found) {
        std::string names;
        for (const WordId w : spec.requires_one_of)
          names += (names.empty() ? "" : ", ") + dialect_.words[w].name;
        return error(where, column, diag::Code::GcodeMissingWord,
                     spec.text + " needs one of " + names);
      }
    }
    return true;
  };
  for (const CodeRef& c : b.codes)
    if (!check_required(*c.spec, c.column)) return false;
  if (motion && motion->action != Action::CycleCancel && !axes && !uses_axes &&
      motion->action != Action::Cycle) {
    // A motion code alone changes the mode (LinuxCNC: "G1" alone is fine) unless it needs axes.
  }
  // Every word must be used by a code of the block, be a free word, or be an axis word with a
  // motion in force.
  // Over the block's words only (the bits set), not every word of the dialect.
  static_assert(kMaxWords <= 64, "the present words fit one 64-bit mask");
  for (std::uint64_t bits = b.present.to_ullong(); bits != 0; bits &= bits - 1) {
    const auto w = static_cast<std::size_t>(std::countr_zero(bits));
    if (w >= dialect_.words.size()) continue;
    const WordKind kind = dialect_.words[w].kind;
    if (kind == WordKind::Feed || kind == WordKind::Speed || kind == WordKind::Tool ||
        kind == WordKind::GCode || kind == WordKind::MCode || kind == WordKind::LineNumber ||
        kind == WordKind::Program || kind == WordKind::Axis || kind == WordKind::PolarRadius ||
        kind == WordKind::PolarAngle || kind == WordKind::ToolOffset)
      continue;
    // A word two codes of the block could take is ambiguous (LinuxCNC: G64 and M19 both take R).
    bool used = false;
    const CodeSpec* user = nullptr;
    for (const CodeRef& c : b.codes) {
      if (std::find(c.spec->allows.begin(), c.spec->allows.end(), w) == c.spec->allows.end())
        continue;
      if (user)
        return error(where, b.word(static_cast<WordId>(w)).column,
                     diag::Code::GcodeConflictingWords,
                     dialect_.words[w].name + " word is ambiguous: " + user->text + " and " +
                         c.spec->text + " both use it (use separate blocks)");
      user = c.spec;
      used = true;
    }
    if (!used && effective_motion && !motion)
      used = std::find(effective_motion->allows.begin(), effective_motion->allows.end(), w) !=
             effective_motion->allows.end();
    if (!used)
      return error(where, b.word(static_cast<WordId>(w)).column, diag::Code::GcodeUnusedWord,
                   dialect_.words[w].name + " word with no code that uses it");
  }
  if (dialect_.arcs.radius != kNoWord && effective_motion &&
      (effective_motion->action == Action::ArcCw || effective_motion->action == Action::ArcCcw) &&
      b.has(dialect_.arcs.radius)) {
    const PlaneAxes pa = plane_axes(plane_);
    if (b.has(pa.first_offset) || b.has(pa.second_offset))
      return error(where, b.word(dialect_.arcs.radius).column, diag::Code::GcodeConflictingWords,
                   "an arc with both a radius and centre words");
  }
  for (int k = 0; k < kAxes; ++k) {
    const WordId w = axis_word(k);
    if (b.has(w) && b.word(w).machine)
      return error(where, b.word(w).column, diag::Code::GcodeMachineMotion,
                   std::string("the ") + kAxisLetters[static_cast<std::size_t>(k)] +
                       " word's value depends on a value only the machine knows");
  }

  // ---- Convert, in LinuxCNC's order of execution ----
  const bool spline_mode = effective_motion && (effective_motion->action == Action::SplineB ||
                                                effective_motion->action == Action::SplineNurbs);
  if (spline_ && (!spline_mode || !(axes || knot_only) || b.codes.size() > (motion ? 1u : 0u) ||
                  b.has(kT) || b.has(kS)))
    flush_spline();
  // A macro call's words are its arguments (FANUC G65 P9010 X.. F..): nothing else happens.
  for (const CodeRef& c : b.codes) {
    if (c.spec->action != Action::MacroCall) continue;
    if (!started_) start(options_.program_name);
    flow.kind = FlowRequest::Kind::Call;
    flow.macro = true;
    flow.column = c.column;
    flow.has_program = b.has(kP);
    flow.program = b.value(kP);
    if (b.has(kL)) flow.repeat = static_cast<int>(std::lround(b.value(kL)));
    return true;
  }
  for (const CodeRef& c : b.codes)
    if (c.spec->warn)
      warn(where, c.column, diag::Code::GcodeIgnored,
           c.spec->text + " has no effect on the canonical program" +
               (c.spec->refusal.empty() ? "" : " (" + c.spec->refusal + ")"));
  if (!started_) start(options_.program_name);
  for (const Comment& c : comments) {
    // (MSG, ...) and the other command comments are the interpreter's business; plain ones are
    // COMMENT calls. Where ( ) is the comment form, ';' only ends the block (FANUC's EOB, a
    // LinuxCNC remark): rs274 prints no COMMENT for it.
    std::string_view text = c.text;
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    if (text.empty() || (c.semicolon && dialect_.parenthesis_comments)) continue;
    comment(text, where);
  }
  // Which actions the block's codes have, as bits: most of the look-ups below find nothing,
  // and then cost a bit test instead of a walk over the codes.
  static_assert(sizeof(Action) == 1, "an action is one of at most 256");
  std::array<std::uint64_t, 4> actions{};
  for (const CodeRef& c : b.codes) {
    const auto a = static_cast<std::uint8_t>(c.spec->action);
    actions[a >> 6] |= std::uint64_t{1} << (a & 63);
  }
  const bool other_codes = non_motion_count > 0;
  auto find = [&](Action a) -> const CodeRef* {
    const auto i = static_cast<std::uint8_t>(a);
    if (((actions[i >> 6] >> (i & 63)) & 1) == 0) return nullptr;
    for (const CodeRef& c : b.codes)
      if (c.spec->action == a) return &c;
    return nullptr;
  };
  // A block of motion words and codes alone (most blocks of a CAM program) has none of the
  // look-ups below to make.
  if (other_codes) {
    if (find(Action::FeedInverseTime)) feed_mode_ = FeedMode::InverseTime;
    if (find(Action::FeedPerMinute)) feed_mode_ = FeedMode::PerMinute;
    if (find(Action::FeedPerRevolution)) feed_mode_ = FeedMode::PerRevolution;
  }
  // Sinumerik G4 F2: the F is the dwell's time, not a feed.
  bool f_is_dwell = false;
  if (find(Action::Dwell))
    for (const DwellWord& d : dialect_.dwell.words)
      f_is_dwell = f_is_dwell || (d.word == kF && b.has(kF));
  if (b.has(kF) && !f_is_dwell) {
    const double f = b.value(kF);
    if (f < 0)
      return error(where, b.word(kF).column, diag::Code::GcodeBadWordValue, "negative feed rate");
    if (b.word(kF).machine)
      return error(where, b.word(kF).column, diag::Code::GcodeMachineMotion,
                   "the feed rate depends on a value only the machine knows");
    if (feed_mode_ == FeedMode::PerRevolution) {
      // Canonical feeds are per minute: F per revolution times the spindle speed.
      feed_ = f;
      emit(canon::SetFeedRate{f * spindle_speed_});
    } else if (feed_mode_ == FeedMode::InverseTime) {
      feed_ = f;  // per move; the canonical feed is set with each motion
    } else {
      set_feed(f);
    }
  }
  if (b.has(kS)) set_spindle_speed(b.value(kS), where, b.word(kS).column);
  if (b.has(kT) && dialect_.words[kT].kind == WordKind::Tool) {
    const double t = b.value(kT);
    if (std::abs(t - std::round(t)) > 1e-9)
      return error(where, b.word(kT).column, diag::Code::GcodeBadWordValue,
                   "a tool number must be an integer");
    select_tool(static_cast<int>(std::lround(t)), where, b.word(kT).column);
  }
  if (other_codes) {
    if (const CodeRef* c = find(Action::SetTool)) {
      const double q = b.value(kQ);
      tool_selected_ = tool_in_spindle_ = static_cast<int>(std::lround(q));
      (void)c;
    }
    if (const CodeRef* c = find(Action::ToolChange)) change_tool(where, c->column);
  }
  // Sinumerik D: the tool offset (its length) on, or off with D0.
  if (b.has(kD) && dialect_.words[kD].kind == WordKind::ToolOffset) {
    if (b.value(kD) == 0)
      tool_length(false, 0, where);
    else
      tool_length(true, tool_in_spindle_, where);
  }
  if (other_codes) {
    if (find(Action::SpindleCw)) spindle(1);
    if (find(Action::SpindleCcw)) spindle(-1);
    if (find(Action::SpindleStop)) spindle(0);
    {
      const bool mist = find(Action::MistOn) != nullptr;
      const bool flood = find(Action::FloodOn) != nullptr;
      const bool off = find(Action::CoolantOff) != nullptr;
      if (mist || flood || off) coolant(mist, flood, off);
    }
    if (const CodeRef* c = find(Action::Dwell)) {
      double seconds = 0;
      bool found = false;
      for (const DwellWord& d : dialect_.dwell.words) {
        if (b.has(d.word)) {
          const bool integer = b.word(d.word).integer_literal && d.integer_scale > 0;
          seconds = b.value(d.word) * (integer ? d.integer_scale : d.scale);
          found = true;
          break;
        }
      }
      if (!found)
        return error(where, c->column, diag::Code::GcodeMissingWord,
                     c->spec->text + " without its time");
      if (seconds < 0)
        return error(where, c->column, diag::Code::GcodeBadWordValue, "negative dwell time");
      dwell(seconds);
    }
    if (find(Action::PlaneXy)) select_plane(canon::Plane::Xy);
    if (find(Action::PlaneXz)) select_plane(canon::Plane::Xz);
    if (find(Action::PlaneYz)) select_plane(canon::Plane::Yz);
    if (find(Action::UnitsInch)) set_metric(false);
    if (find(Action::UnitsMm)) set_metric(true);
    if (find(Action::CutterCompOff)) {
    }
    if (const CodeRef* c = find(Action::ToolLengthOffset)) {
      const int h = b.has(kH) ? static_cast<int>(std::lround(b.value(kH))) : tool_in_spindle_;
      tool_length(true, h, where);
      (void)c;
    }
    if (find(Action::ToolLengthCancel)) tool_length(false, 0, where);
    if (const CodeRef* c = find(Action::WorkOffset)) {
      int index = c->spec->index;
      if (index == 0) {
        // G54.1 P1..P48: the additional work offsets, after the nine standard ones.
        // Okuma's G15 H1 names its offset with H.
        const WordId iw = c->spec->index_word != kNoWord ? c->spec->index_word : kP;
        if (!b.has(iw))
          return error(where, c->column, diag::Code::GcodeMissingWord,
                       c->spec->text + " without " + dialect_.words[iw].name);
        const double p = b.value(iw);
        if (p < 1 || p > kWorkOffsets - 10 || std::abs(p - std::round(p)) > 1e-9)
          return error(where, b.word(iw).column, diag::Code::GcodeBadWordValue,
                       c->spec->text + " P must be 1 to " + std::to_string(kWorkOffsets - 10));
        index = 9 + static_cast<int>(std::lround(p));
      }
      const Axes before = total_offset();
      work_index_ = index;
      const Axes now = total_offset();
      for (std::size_t i = 0; i < pos_.size(); ++i) pos_[i] += before[i] - now[i];
      if (started_) emit_offsets();
    }
    if (find(Action::WorkOffsetNone)) {
      const Axes before = total_offset();
      work_index_ = 0;
      const Axes now = total_offset();
      for (std::size_t i = 0; i < pos_.size(); ++i) pos_[i] += before[i] - now[i];
      emit_offsets();
    }
    if (find(Action::Absolute)) incremental_ = false;
    if (find(Action::Incremental)) incremental_ = true;
    if (find(Action::ArcCentreAbsolute)) centre_absolute_ = true;
    if (find(Action::ArcCentreIncremental)) centre_absolute_ = false;
    if (find(Action::RetractInitial)) retract_r_ = false;
    if (find(Action::RetractR)) retract_r_ = true;
  }

  // Group 0: coordinate data, reference moves, axis offsets.
  bool machine_coordinates = false;
  if (other_codes) {
    if (const CodeRef* c = find(Action::MachineCoordinates)) {
      if (incremental_)
        return error(where, c->column, diag::Code::GcodeUnsupported,
                     c->spec->text + " in incremental mode");
      machine_coordinates = true;
    }
    if (const CodeRef* c = find(Action::SetCoordinateData))
      if (!convert_g10(b, where, c->column, *c->spec)) return false;
    if (const CodeRef* c = find(Action::Home))
      if (!convert_home(*c->spec, b, where)) return false;
    if (const CodeRef* c = find(Action::Home2))
      if (!convert_home(*c->spec, b, where)) return false;
    if (find(Action::AxisOffset) || find(Action::LocalOffset)) {
      const bool local = find(Action::LocalOffset) != nullptr;
      const Axes before = total_offset();
      for (int k = 0; k < kAxes; ++k) {
        const WordId w = axis_word(k);
        if (!b.has(w)) continue;
        const auto i = static_cast<std::size_t>(k);
        const double v = is_rotary(k) ? scaled(b, w) : length_word(b, w);
        if (local) {
          axis_offset_[i] = v;
        } else {
          // G92: the current position becomes v.
          axis_offset_[i] = pos_[i] + axis_offset_[i] - v;
        }
      }
      const Axes now = total_offset();
      for (std::size_t i = 0; i < pos_.size(); ++i) pos_[i] += before[i] - now[i];
      emit_offsets();
    }
    if (const CodeRef* c = find(Action::OnlyWithoutWords)) {
      // ROT, SCALE, MIRROR ...: alone they reset what this reader never sets; with values they
      // would rotate, scale or mirror the coordinates.
      bool words = false;
      for (std::size_t w = 0; w < dialect_.words.size(); ++w) {
        const WordKind k = dialect_.words[w].kind;
        words = words || (b.has(static_cast<WordId>(w)) && k != WordKind::LineNumber &&
                          k != WordKind::GCode && k != WordKind::MCode);
      }
      if (words)
        return error(
            where, c->column, diag::Code::GcodeUnsupported,
            c->spec->text + ": " + (c->spec->refusal.empty() ? "not supported" : c->spec->refusal));
    }
    if (find(Action::Translate) || find(Action::TranslateAdd)) {
      // Sinumerik TRANS replaces the programmable offset (TRANS alone cancels it), ATRANS adds
      // to it; in the program's unit, along the current coordinate system.
      Axes t{};
      const bool add = find(Action::TranslateAdd) != nullptr;
      for (int k = 0; k < kAxes; ++k) {
        const auto i = static_cast<std::size_t>(k);
        const double current = is_rotary(k) ? translation_[i] : from_mm(translation_[i]);
        const WordId w = axis_word(k);
        const double v = b.has(w) ? scaled(b, w) : 0;
        t[i] = add ? current + v : v;
      }
      set_translation(t);
    }
    if (find(Action::AxisOffsetCancel) || find(Action::AxisOffsetRestore)) {
      const Axes before = total_offset();
      if (find(Action::AxisOffsetRestore)) {
        axis_offset_ = axis_offset_saved_;
      } else {
        axis_offset_saved_ = axis_offset_;
        axis_offset_ = Axes{};
      }
      const Axes now = total_offset();
      for (std::size_t i = 0; i < pos_.size(); ++i) pos_[i] += before[i] - now[i];
      emit_offsets();
    }
  }

  // Motion.
  if (motion) {
    if (motion->action == Action::CycleCancel) {
      motion_ = nullptr;
      cycle_r_.reset();
      cycle_bottom_.reset();
    } else {
      if (motion->action == Action::Cycle && motion_ != motion) {
        // A new series of cycles starts: its initial level (G98 returns there; G91's R counts
        // from it) is where the tool stands now. R, Q, P and the depth stay from the last one.
        cycle_initial_ = pos_[static_cast<std::size_t>(plane_axes(plane_).normal)];
      }
      motion_ = motion;
    }
  }
  if (effective_motion && effective_motion->action != Action::CycleCancel &&
      (axes || (arc_mode && centre_words) || knot_only)) {
    // A spline's control points are gathered while its blocks come one after the other.
    if (!spline_mode) flush_spline();
    if (machine_coordinates && effective_motion->action != Action::Rapid &&
        effective_motion->action != Action::Linear)
      return error(where, b.first_column, diag::Code::GcodeUnsupported,
                   "G53 with a motion other than G0 or G1");
    if (!convert_motion(*effective_motion, b, where, machine_coordinates)) return false;
  }

  // Stops and program end; flow.
  if (find(Action::ProgramStop)) stop(Action::ProgramStop);
  if (find(Action::OptionalStop)) stop(Action::OptionalStop);
  if (find(Action::PalletChange)) stop(Action::PalletChange);
  if (const CodeRef* c = find(Action::SubprogramCall)) {
    flow.kind = FlowRequest::Kind::Call;
    flow.column = c->column;
    if (b.has(kP)) {
      flow.program = b.value(kP);
      flow.has_program = true;
    }
    if (b.has(kL)) flow.repeat = static_cast<int>(std::lround(b.value(kL)));
    if (b.has(kK) && !b.has(kL)) flow.repeat = static_cast<int>(std::lround(b.value(kK)));
  }
  if (const CodeRef* c = find(Action::LocalCall)) {
    flow.kind = FlowRequest::Kind::Call;
    flow.local = true;
    flow.column = c->column;
    flow.has_program = b.has(kP);
    flow.program = b.value(kP);
    if (b.has(kL)) flow.repeat = static_cast<int>(std::lround(b.value(kL)));
  }
  if (const CodeRef* c = find(Action::SubprogramReturn)) {
    flow.kind = FlowRequest::Kind::Return;
    flow.column = c->column;
    if (b.has(kP)) flow.return_line = b.value(kP);
  }
  if (find(Action::ProgramEnd)) {
    stop(Action::ProgramEnd);
    flow.kind = FlowRequest::Kind::End;
  }
  (void)kN, (void)kG, (void)kM, (void)kO, (void)kD, (void)kE;
  return true;
}

}  // namespace ncpost::gcode::detail
