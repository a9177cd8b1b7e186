// The CL reader: one record at a time → canonical calls. docs/cls.md is the reference for what
// each major word becomes; the comments here say why where it is not obvious.

#include "ncpost/cls/reader.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>

#include "check_run.hpp"
#include "ncpost/canon/vec3.hpp"
#include "ncpost/cls/checks.hpp"
#include "records.hpp"

namespace ncpost::cls {

bool ReadResult::ok() const {
  return !cancelled && !diag::has_errors(diagnostics);
}

namespace {

using detail::is_word;
using detail::Position;
using detail::Record;

constexpr double kMmPerInch = 25.4;
constexpr double kPi = 3.14159265358979323846;
// Comments read before the first statement that needs the program's header are held back (the
// header waits for PARTNO/ and UNITS/); past this many the header is written anyway.
constexpr std::size_t kMaxHeldComments = 64;
// Distinct unknown major words reported (one warning each); beyond, one note says more exist.
constexpr std::size_t kMaxUnknownWords = 256;
// Records between two looks at the cancel flag.
constexpr std::uint64_t kCancelEvery = 4096;

using Vec = canon::Vec3;

enum class Word : std::uint8_t {
  Goto,
  Circle,
  Rapid,
  Fedrat,
  From,
  Godlta,
  Indirv,  // motion
  ToolPath,
  Tldata,
  Load,
  Loadtl,
  Select,
  Selctl,
  Cutter,  // tools
  Spindl,
  Coolnt,
  Cycle,
  Msys,
  Units,
  Set,
  EndOfPath,
  Fini,  // machine functions
  Pprint,
  Partno,
  Remark,
  Multax,
  Opstop,
  Stop,
  Delay,  // other
  Paint,
  Disply,
  Plot,
  Clprnt,
  Machin,
  Mode,
  End,
  Intol,
  Outtol,
  Toler,  // ignored, noted once
  Unknown,
};
constexpr std::size_t kWordCount = static_cast<std::size_t>(Word::Unknown) + 1;

struct WordName {
  std::string_view name;
  Word word;
};
constexpr std::array<WordName, kWordCount - 1> kWords = {{
    {"GOTO", Word::Goto},
    {"CIRCLE", Word::Circle},
    {"RAPID", Word::Rapid},
    {"FEDRAT", Word::Fedrat},
    {"FROM", Word::From},
    {"GODLTA", Word::Godlta},
    {"INDIRV", Word::Indirv},
    {"TOOL PATH", Word::ToolPath},
    {"TLDATA", Word::Tldata},
    {"LOAD", Word::Load},
    {"LOADTL", Word::Loadtl},
    {"SELECT", Word::Select},
    {"SELCTL", Word::Selctl},
    {"CUTTER", Word::Cutter},
    {"SPINDL", Word::Spindl},
    {"COOLNT", Word::Coolnt},
    {"CYCLE", Word::Cycle},
    {"MSYS", Word::Msys},
    {"UNITS", Word::Units},
    {"SET", Word::Set},
    {"END-OF-PATH", Word::EndOfPath},
    {"FINI", Word::Fini},
    {"PPRINT", Word::Pprint},
    {"PARTNO", Word::Partno},
    {"REMARK", Word::Remark},
    {"MULTAX", Word::Multax},
    {"OPSTOP", Word::Opstop},
    {"STOP", Word::Stop},
    {"DELAY", Word::Delay},
    {"PAINT", Word::Paint},
    {"DISPLY", Word::Disply},
    {"PLOT", Word::Plot},
    {"CLPRNT", Word::Clprnt},
    {"MACHIN", Word::Machin},
    {"MODE", Word::Mode},
    {"END", Word::End},
    {"INTOL", Word::Intol},
    {"OUTTOL", Word::Outtol},
    {"TOLER", Word::Toler},
}};

Word lookup(std::string_view word) {
  // GOTO is most of a file: look at it first.
  if (word.size() == 4 && is_word(word, "GOTO")) return Word::Goto;
  for (const auto& w : kWords)
    if (is_word(word, w.name)) return w.word;
  return Word::Unknown;
}

bool ignored_kind(Word w) {
  return w >= Word::Paint && w < Word::Unknown;
}

// How a feed or a cycle's feed is given.
enum class FeedPer : std::uint8_t { Minute, Revolution };

struct FeedWord {
  FeedPer per = FeedPer::Minute;
  std::optional<canon::Units> units;  // empty: the program's (PERMIN, PERREV)
};

std::optional<FeedWord> feed_word(std::string_view w) {
  if (is_word(w, "MMPM")) return FeedWord{FeedPer::Minute, canon::Units::Millimetres};
  if (is_word(w, "IPM")) return FeedWord{FeedPer::Minute, canon::Units::Inches};
  if (is_word(w, "PERMIN")) return FeedWord{FeedPer::Minute, std::nullopt};
  if (is_word(w, "MMPR")) return FeedWord{FeedPer::Revolution, canon::Units::Millimetres};
  if (is_word(w, "IPR")) return FeedWord{FeedPer::Revolution, canon::Units::Inches};
  if (is_word(w, "PERREV")) return FeedWord{FeedPer::Revolution, std::nullopt};
  return std::nullopt;
}

double mm_per_unit(canon::Units u) {
  switch (u) {
    case canon::Units::Inches:
      return kMmPerInch;
    case canon::Units::Centimetres:
      return 10;
    case canon::Units::Millimetres:
      return 1;
  }
  return 1;
}

// A CYCLE/ as read, applied at each GOTO/ until CYCLE/OFF.
struct CycleSpec {
  canon::CycleKind kind = canon::CycleKind::Drill;
  double depth = 0;
  double rapto = 0;    // start of feeding above the point
  double retract = 0;  // travel height above the point
  double dwell = 0;
  double peck = 0;
  std::optional<double> feed;
  FeedPer feed_per = FeedPer::Minute;
  bool left_hand = false;
  bool spindle_stop = false;
  std::uint32_t line = 0;
};

struct PendingCircle {
  Vec centre;
  Vec normal;  // unit
  double radius = 0;
  Position where;
};

struct PendingTool {
  std::int32_t slot = 0;  // 0: from the name
  std::string name;
  bool explicit_load = false;  // LOAD/TOOL or LOADTL/: always changed, even to the same tool
};

}  // namespace

class Reader::Impl {
 public:
  Impl(canon::Sink& sink, const ReadOptions& options)
      : sink_(sink),
        options_(options),
        records_(options.max_record_bytes),
        program_name_(options.program_name),
        units_(options.default_units) {
    if (options.checks && options.checks->enabled)
      checks_.emplace(*options.checks, [this](diag::Diagnostic d) { report(std::move(d)); });
  }

  void feed(std::string_view piece) {
    if (stopped_) return;
    records_.feed(
        piece, [this](const Record& r) { record(r); },
        [this](std::uint32_t line) { too_long(line); });
  }

  ReadResult finish() {
    const bool open = records_.finish([this](const Record& r) { record(r); },
                                      [this](std::uint32_t line) { too_long(line); });
    if (open && !stopped_)
      error(diag::Code::ClsOpenContinuation, records_.lines(), 1,
            "the file ends inside a record continued with $");
    if (!stopped_ && !after_fini_) end_program();
    ReadResult result;
    result.diagnostics = std::move(diagnostics_);
    result.calls = calls_;
    result.cancelled = cancelled_;
    if (checks_) result.selected_options = checks_->selected_options();
    return result;
  }

 private:
  // ---- Diagnostics -----------------------------------------------------------------------------

  void report(diag::Diagnostic d) {
    if (d.severity == diag::Severity::Error) {
      ++errors_;
      diagnostics_.push_back(std::move(d));
      if (options_.stop_at_first_error || errors_ >= options_.max_errors) stopped_ = true;
      return;
    }
    if (others_ < options_.max_errors) {
      ++others_;
      diagnostics_.push_back(std::move(d));
    } else if (!others_dropped_) {
      others_dropped_ = true;
      diagnostics_.push_back(diag::make(diag::Code::ClsTooManyDiagnostics, d.line, d.column,
                                        "further warnings and notes are not reported"));
    }
  }
  void error(diag::Code code, std::uint32_t line, std::uint32_t column, std::string message) {
    report(diag::make(code, line, column, std::move(message)));
  }
  void at(diag::Code code, Position p, std::string message) {
    report(diag::make(code, p.line, p.column, std::move(message)));
  }

  void too_long(std::uint32_t line) {
    error(diag::Code::ClsRecordTooLong, line, 1,
          "record longer than " + std::to_string(options_.max_record_bytes) +
              " bytes (max_record_bytes); skipped");
  }

  // ---- Output
  // ------------------------------------------------------------------------------------

  void emit(const canon::Call& call) {
    if (!header_done_) header();
    sink_.call(call);
    ++calls_;
  }

  void header() {
    header_done_ = true;
    if (!units_stated_)
      error(diag::Code::ClsAssumption, 0, 0,
            std::string("no UNITS/ before the first statement: ") +
                (options_.default_units == canon::Units::Inches ? "inches" : "millimetres") +
                " assumed");
    emit(canon::Begin{canon::Scope::Project, project()});
    emit(canon::UseLengthUnits{units_});
    emitted_units_ = units_;
    emit(canon::SetOriginOffsets{});
    emit(canon::SetFeedReference{canon::FeedReference::Xyz});
    emit(canon::SelectPlane{canon::Plane::Xy});
    for (auto& c : held_) emit(std::move(c));
    held_.clear();
  }

  [[nodiscard]] canon::Entity project() const {
    return canon::Entity{0, "CL_PROGRAM", program_name_};
  }

  void comment(std::string_view text) {
    if (text.empty()) return;
    if (!header_done_ && held_.size() < kMaxHeldComments) {
      held_.push_back(canon::Comment{std::string(text)});
      return;
    }
    emit(canon::Comment{std::string(text)});
  }

  // ---- Records
  // -----------------------------------------------------------------------------------

  void record(const Record& r) {
    if (stopped_) return;
    if (options_.cancel && (++records_read_ % kCancelEvery) == 0 &&
        options_.cancel->load(std::memory_order_relaxed)) {
      cancelled_ = true;
      stopped_ = true;
      return;
    }
    const std::string_view text = detail::trim(r.text);
    if (after_fini_) {
      if (!text.empty() && !after_fini_reported_) {
        after_fini_reported_ = true;
        at(diag::Code::ClsAfterFini, r.at(text), "records after FINI are ignored");
      }
      return;
    }
    if (!text.empty()) statement(r, text);
    if (!r.comment.empty() && !stopped_ && !after_fini_) comment(r.comment);
  }

  void statement(const Record& r, std::string_view text) {
    const std::size_t slash = text.find('/');
    std::string_view word = detail::trim(text.substr(0, slash));
    // Without a slash the arguments are the empty text at the end of the statement, so that a
    // "missing argument" diagnostic still points into the record.
    std::string_view args =
        slash == std::string_view::npos ? text.substr(text.size()) : text.substr(slash + 1);
    if (slash == std::string_view::npos) {
      // APT's text statements without a slash: PARTNO name, PPRINT text, REMARK text.
      const std::size_t space = text.find_first_of(" \t");
      const std::string_view first = text.substr(0, space);
      if (space != std::string_view::npos &&
          (is_word(first, "PARTNO") || is_word(first, "PPRINT") || is_word(first, "REMARK"))) {
        word = first;
        args = text.substr(space + 1);
      }
    }
    const Word w = lookup(word);
    switch (w) {
      case Word::Goto:
        return goto_(r, args);
      case Word::Circle:
        return circle(r, args);
      case Word::Rapid:
        rapid_next_ = true;
        return;
      case Word::Fedrat:
        return fedrat(r, args);
      case Word::From:
        return from(r, args);
      case Word::Godlta:
        return godlta(r, args);
      case Word::Indirv:
        return indirv(r, args);
      case Word::ToolPath:
        return tool_path(r, args);
      case Word::Tldata:
        return tldata(r, args);
      case Word::Load:
      case Word::Loadtl:
        return load(r, args, w == Word::Load);
      case Word::Select:
      case Word::Selctl:
        return select(r, args, w == Word::Select);
      case Word::Cutter:
        return cutter(r, args);
      case Word::Spindl:
        return spindl(r, args);
      case Word::Coolnt:
        return coolnt(r, args);
      case Word::Cycle:
        return cycle(r, args);
      case Word::Msys:
        return msys(r, args);
      case Word::Units:
        return units(r, args);
      case Word::Set:
        return set(r, args);
      case Word::EndOfPath:
        flush_tool();
        dangling_circle();
        close_operation();
        rapid_next_ = false;
        indirv_.reset();
        return;
      case Word::Fini:
        end_program();
        after_fini_ = true;
        return;
      case Word::Pprint:
      case Word::Remark:
        return comment(detail::unquote(args));
      case Word::Partno:
        return partno(args);
      case Word::Multax:
        return;  // tool axes come with each GOTO/ whether or not MULTAX/ is on
      case Word::Opstop:
        flush_tool();
        return emit(canon::OptionalProgramStop{});
      case Word::Stop:
        flush_tool();
        return emit(canon::ProgramStop{});
      case Word::Delay:
        return delay(r, args);
      case Word::Unknown:
        return unknown(r, word);
      default:
        if (ignored_kind(w)) return ignored(r, w, word);
        return;
    }
  }

  // Fields of `args` as numbers, from field `first` on, exactly `count` of them (or at least
  // `count` when `at_least`); reports CLS-001/002 and returns false otherwise.
  bool numbers(const Record& r, std::string_view args, std::size_t first, std::size_t count,
               double* out, std::string_view what) {
    if (fields_.size() < first + count) {
      at(diag::Code::ClsBadArguments, r.at(args.empty() ? r.text.substr(r.text.size()) : args),
         std::string(what) + " needs " + std::to_string(count) + " numbers");
      return false;
    }
    for (std::size_t i = 0; i < count; ++i) {
      const auto v = detail::parse_number(fields_[first + i]);
      if (!v) {
        at(diag::Code::ClsBadNumber, r.at(fields_[first + i]),
           std::string(what) + ": '" + std::string(fields_[first + i]) + "' is not a number");
        return false;
      }
      out[i] = *v;
    }
    return true;
  }

  // ---- Motion
  // ------------------------------------------------------------------------------------

  void goto_(const Record& r, std::string_view args) {
    double v[6];
    // Most of a file: plain numbers read in one pass; anything else is split and reported.
    std::size_t n = detail::fast_numbers(args, v, 6);
    if (n != 3 && n != 6) {
      detail::split_fields(args, fields_);
      n = fields_.size();
      if (n != 3 && n != 6) {
        at(diag::Code::ClsBadArguments, r.at(args), "GOTO/ takes x, y, z or x, y, z, i, j, k");
        return;
      }
      if (!numbers(r, args, 0, n, v, "GOTO/")) return;
    }
    Vec to{v[0], v[1], v[2]};
    if (incremental_) to = position_ + to;
    if (n == 6) {
      const Vec axis{v[3], v[4], v[5]};
      if (length(axis) == 0) {
        at(diag::Code::ClsBadArguments, r.at(args), "GOTO/: the tool axis is zero");
        return;
      }
      axis_ = axis;
    }
    const Position where = r.at(args);
    if (circle_) return arc(to, where);
    if (cycle_) return hole(to, where);
    move(to, rapid_next_, where);
  }

  void godlta(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    const std::size_t n = fields_.size();
    if (n != 1 && n != 3) {
      at(diag::Code::ClsBadArguments, r.at(args),
         "GODLTA/ takes a distance along the tool axis, or dx, dy, dz");
      return;
    }
    double v[3];
    if (!numbers(r, args, 0, n, v, "GODLTA/")) return;
    if (circle_) dangling_circle();
    Vec delta{v[0], n == 3 ? v[1] : 0, n == 3 ? v[2] : 0};
    if (n == 1) {
      const Vec a = axis_.value_or(Vec{0, 0, 1});
      delta = (v[0] / length(a)) * a;
    }
    move(position_ + delta, rapid_next_, r.at(fields_[0]));
  }

  void move(Vec to, bool rapid, Position where) {
    flush_tool();
    rapid_next_ = false;
    indirv_.reset();
    const canon::Pose pose = pose_at(to);
    check_axis(where);
    if (rapid)
      emit(canon::StraightTraverse{pose});
    else
      emit(canon::StraightFeed{pose});
    position_ = to;
  }

  void from(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    const std::size_t n = fields_.size();
    if (n != 3 && n != 6) {
      at(diag::Code::ClsBadArguments, r.at(args), "FROM/ takes x, y, z or x, y, z, i, j, k");
      return;
    }
    double v[6];
    if (!numbers(r, args, 0, n, v, "FROM/")) return;
    position_ = Vec{v[0], v[1], v[2]};
    if (n == 6 && length(Vec{v[3], v[4], v[5]}) > 0) axis_ = Vec{v[3], v[4], v[5]};
  }

  void indirv(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    double v[3];
    if (fields_.size() != 3) {
      at(diag::Code::ClsBadArguments, r.at(args), "INDIRV/ takes i, j, k");
      return;
    }
    if (!numbers(r, args, 0, 3, v, "INDIRV/")) return;
    indirv_ = Vec{v[0], v[1], v[2]};
  }

  void circle(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    double v[7];
    if (fields_.size() < 7) {
      at(diag::Code::ClsBadArguments, r.at(args),
         "CIRCLE/ takes the centre x, y, z, the axis i, j, k and the radius (and optional "
         "tolerances and tool sizes)");
      return;
    }
    if (!numbers(r, args, 0, 7, v, "CIRCLE/")) return;
    if (circle_) dangling_circle();
    const Vec axis{v[3], v[4], v[5]};
    if (length(axis) == 0 || !(v[6] > 0)) {
      at(diag::Code::ClsBadCircle, r.at(fields_[0]), "CIRCLE/ with a zero axis or radius");
      return;
    }
    if (rapid_next_) {
      at(diag::Code::ClsUnsupportedOption, r.at(fields_[0]),
         "RAPID before CIRCLE/: the arc is fed, not traversed");
      rapid_next_ = false;
    }
    circle_ = PendingCircle{{v[0], v[1], v[2]}, (1 / length(axis)) * axis, v[6], r.at(fields_[0])};
  }

  void dangling_circle() {
    if (!circle_) return;
    at(diag::Code::ClsBadCircle, circle_->where, "CIRCLE/ not followed by its GOTO/");
    circle_.reset();
  }

  // The CIRCLE/ and its GOTO/. The motion goes clockwise seen from the tip of the circle's axis
  // (docs/cls.md: what NX and APT CL files do, checked on the corpus), unless an INDIRV/ before
  // it points the other way round.
  void arc(Vec to, Position where) {
    const PendingCircle c = *circle_;
    circle_.reset();
    flush_tool();
    rapid_next_ = false;
    const Vec from_centre = position_ - c.centre;
    const Vec to_centre = to - c.centre;
    const Vec start = from_centre - dot(from_centre, c.normal) * c.normal;
    const Vec end = to_centre - dot(to_centre, c.normal) * c.normal;
    const double tolerance = std::max(options_.arc_tolerance, c.radius * 1e-9);
    if (std::fabs(length(start) - c.radius) > tolerance ||
        std::fabs(length(end) - c.radius) > tolerance) {
      at(diag::Code::ClsBadCircle, where,
         "the arc's start and end are " + detail::format_number(length(start)) + " and " +
             detail::format_number(length(end)) + " from the axis of CIRCLE/ (line " +
             std::to_string(c.where.line) + "), whose radius is " +
             detail::format_number(c.radius) + "; fed as a straight line");
      indirv_.reset();
      return move(to, false, where);
    }
    int turns = -1;
    if (indirv_) {
      const Vec clockwise_tangent = cross(start, c.normal);
      if (dot(clockwise_tangent, *indirv_) < 0) turns = 1;
      indirv_.reset();
    }
    canon::ArcFeed a;
    a.end = pose_at(to);
    const Vec centre = frame_point(c.centre);
    a.centre = canon::Point{centre.x, centre.y, centre.z};
    const Vec normal = frame_direction(c.normal);
    a.normal = canon::Direction{normal.x, normal.y, normal.z};
    a.turns = turns;
    if (const auto p = canon::plane_arc(a); p && p->plane != plane_) {
      plane_ = p->plane;
      emit(canon::SelectPlane{plane_});
    }
    check_axis(where);
    emit(a);
    position_ = to;
  }

  // ---- Frame (MSYS/) -------------------------------------------------------------------------

  [[nodiscard]] Vec frame_point(Vec p) const {
    if (!frame_) return p;
    return frame_->origin + frame_direction(p);
  }
  [[nodiscard]] Vec frame_direction(Vec d) const {
    if (!frame_) return d;
    return d.x * frame_->x + d.y * frame_->y + d.z * frame_->z;
  }
  [[nodiscard]] canon::Pose pose_at(Vec cl) const {
    const Vec p = frame_point(cl);
    canon::Pose pose{p.x, p.y, p.z, std::nullopt, std::nullopt};
    if (axis_) {
      const Vec a = frame_direction(*axis_);
      pose.tool_axis = canon::Direction{a.x, a.y, a.z};
    }
    return pose;
  }

  void check_axis(Position where) {
    if (!checks_) return;
    const Vec a = frame_direction(axis_.value_or(Vec{0, 0, 1}));
    checks_->tool_axis(canon::Direction{a.x, a.y, a.z}, where.line, where.column);
  }

  void msys(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    double v[9];
    if (fields_.size() != 9) {
      at(diag::Code::ClsBadArguments, r.at(args),
         "MSYS/ takes the origin x, y, z and the X and Y axis directions (9 numbers)");
      return;
    }
    if (!numbers(r, args, 0, 9, v, "MSYS/")) return;
    const Vec o{v[0], v[1], v[2]}, x{v[3], v[4], v[5]}, y{v[6], v[7], v[8]};
    constexpr double kTolerance = 1e-5;
    if (std::fabs(length(x) - 1) > kTolerance || std::fabs(length(y) - 1) > kTolerance ||
        std::fabs(dot(x, y)) > kTolerance) {
      at(diag::Code::ClsBadMsys, r.at(fields_[3]),
         "MSYS/: the X and Y axes must be unit vectors at right angles");
      return;
    }
    if (!options_.apply_msys) return;
    const bool identity =
        length(o) == 0 && x.x == 1 && x.y == 0 && x.z == 0 && y.x == 0 && y.y == 1 && y.z == 0;
    if (identity)
      frame_.reset();
    else
      frame_ = Frame{o, x, y, cross(x, y)};
  }

  // ---- Feed and spindle ---------------------------------------------------------------------

  // A length per minute or per revolution in `units` (empty: the program's) → program units.
  [[nodiscard]] double to_program(double value, std::optional<canon::Units> units) const {
    if (!units || *units == units_) return value;
    return value * mm_per_unit(*units) / mm_per_unit(units_);
  }

  void fedrat(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    std::optional<double> value;
    std::optional<FeedWord> unit;
    for (const auto f : fields_) {
      if (auto w = feed_word(f)) {
        unit = w;
      } else if (auto v = detail::parse_number(f); v && !value) {
        value = v;
      } else {
        at(diag::Code::ClsBadArguments, r.at(f),
           "FEDRAT/: '" + std::string(f) +
               "' is neither a feed nor MMPM, IPM, MMPR, IPR, "
               "PERMIN or PERREV");
        return;
      }
    }
    if (!value || !(*value > 0)) {
      at(diag::Code::ClsBadArguments, r.at(args), "FEDRAT/ needs a feed greater than 0");
      return;
    }
    flush_tool();
    if (unit) feed_per_ = unit->per;
    feed_ = to_program(*value, unit ? unit->units : std::nullopt);
    emit_feed(r.at(fields_[0]));
  }

  void emit_feed(Position where) {
    if (!feed_) return;
    if (feed_per_ == FeedPer::Minute) return emit(canon::SetFeedRate{*feed_});
    if (!(rpm_ > 0)) {
      at(diag::Code::ClsNoSpindleSpeed, where,
         "a feed per revolution without a spindle speed in force (SPINDL/ before FEDRAT/)");
      return;
    }
    emit(canon::SetFeedRate{*feed_ * rpm_});
  }

  void spindl(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    std::optional<double> speed;
    enum class Per { Rpm, Sfm, Smm } per = Per::Rpm;
    std::optional<bool> clockwise;
    bool off = false, on = false;
    for (std::size_t i = 0; i < fields_.size(); ++i) {
      const auto f = fields_[i];
      if (is_word(f, "RPM")) {
        per = Per::Rpm;
      } else if (is_word(f, "SFM")) {
        per = Per::Sfm;
      } else if (is_word(f, "SMM")) {
        per = Per::Smm;
      } else if (is_word(f, "CLW")) {
        clockwise = true;
      } else if (is_word(f, "CCLW")) {
        clockwise = false;
      } else if (is_word(f, "OFF")) {
        off = true;
      } else if (is_word(f, "ON")) {
        on = true;
      } else if (is_word(f, "MAXRPM") || is_word(f, "RANGE")) {
        ++i;  // its number is for the machine, not the program
      } else if (auto v = detail::parse_number(f); v && !speed) {
        speed = v;
      } else {
        at(diag::Code::ClsUnsupportedOption, r.at(f),
           "SPINDL/: '" + std::string(f) + "' is not supported; ignored");
      }
    }
    flush_tool();
    if (off) return emit(canon::StopSpindleTurning{});
    if (speed) {
      double rpm = *speed;
      if (per != Per::Rpm) {
        if (!(tool_diameter_ > 0)) {
          at(diag::Code::ClsNoSpindleSpeed, r.at(fields_[0]),
             "SPINDL/: a surface speed needs the tool's diameter (TLDATA/ or CUTTER/ before it)");
          return;
        }
        const double diameter_mm = tool_diameter_ * mm_per_unit(units_);
        rpm = per == Per::Sfm ? *speed * 12 * kMmPerInch / (kPi * diameter_mm)
                              : *speed * 1000 / (kPi * diameter_mm);
      }
      if (!(rpm >= 0)) {
        at(diag::Code::ClsBadArguments, r.at(fields_[0]), "SPINDL/: a negative speed");
        return;
      }
      rpm_ = rpm;
      emit(canon::SetSpindleSpeed{rpm_});
    }
    if (clockwise) clockwise_ = *clockwise;
    if (speed || clockwise || on) {
      if (clockwise_)
        emit(canon::StartSpindleClockwise{});
      else
        emit(canon::StartSpindleCounterclockwise{});
    }
    // A feed per revolution follows the spindle.
    if (speed && feed_per_ == FeedPer::Revolution && feed_) emit_feed(r.at(fields_[0]));
  }

  void coolnt(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    flush_tool();
    for (const auto f : fields_) {
      if (is_word(f, "ON") || is_word(f, "FLOOD")) {
        flood_ = true;
        emit(canon::FloodOn{});
      } else if (is_word(f, "MIST")) {
        mist_ = true;
        emit(canon::MistOn{});
      } else if (is_word(f, "THRU")) {
        at(diag::Code::ClsAssumption, r.at(f), "COOLNT/THRU (through the tool) given as flood");
        flood_ = true;
        emit(canon::FloodOn{});
      } else if (is_word(f, "OFF")) {
        if (mist_) emit(canon::MistOff{});
        if (flood_ || !mist_) emit(canon::FloodOff{});
        flood_ = mist_ = false;
      } else {
        at(diag::Code::ClsUnsupportedOption, r.at(f),
           "COOLNT/: '" + std::string(f) + "' is not supported; ignored");
      }
    }
  }

  void delay(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    double seconds = 0;
    if (fields_.size() != 1) {
      at(diag::Code::ClsBadArguments, r.at(args), "DELAY/ takes a time in seconds");
      return;
    }
    if (!numbers(r, args, 0, 1, &seconds, "DELAY/")) return;
    if (seconds < 0) {
      at(diag::Code::ClsBadArguments, r.at(fields_[0]), "DELAY/: a negative time");
      return;
    }
    flush_tool();
    emit(canon::Dwell{seconds});
  }

  // ---- Cycles ---------------------------------------------------------------------------------

  void cycle(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    const std::string_view kind = fields_[0];
    if (is_word(kind, "OFF")) {
      cycle_.reset();
      return;
    }
    CycleSpec c;
    c.line = r.line();
    if (is_word(kind, "DRILL")) {
      c.kind = canon::CycleKind::Drill;
    } else if (is_word(kind, "DEEP")) {
      c.kind = canon::CycleKind::PeckDrill;
    } else if (is_word(kind, "TAP")) {
      c.kind = canon::CycleKind::Tap;
    } else if (is_word(kind, "BORE")) {
      c.kind = canon::CycleKind::Bore;
    } else if (is_word(kind, "REAM")) {
      c.kind = canon::CycleKind::Ream;
    } else {
      at(diag::Code::ClsUnsupportedOption, r.at(kind),
         "CYCLE/" + std::string(kind) +
             " is not supported (DRILL, DEEP, TAP, BORE, REAM, OFF); "
             "its holes are not drilled");
      cycle_.reset();
      return;
    }
    std::optional<double> depth, clearance, rapto, retract;
    std::size_t positional = 0;
    for (std::size_t i = 1; i < fields_.size(); ++i) {
      const auto f = fields_[i];
      auto next_number = [&](std::optional<double>& into) {
        if (i + 1 >= fields_.size() || !detail::parse_number(fields_[i + 1])) {
          at(diag::Code::ClsBadCycle, r.at(f), "CYCLE/: " + std::string(f) + " needs a number");
          return false;
        }
        into = detail::parse_number(fields_[++i]);
        return true;
      };
      std::optional<double> scratch;
      if (auto w = feed_word(f)) {
        if (!next_number(scratch)) return;
        c.feed = to_program(*scratch, w->units);
        c.feed_per = w->per;
      } else if (is_word(f, "DEPTH") || is_word(f, "FEDTO")) {
        if (!next_number(depth)) return;
      } else if (is_word(f, "CLEAR")) {
        if (!next_number(clearance)) return;
      } else if (is_word(f, "RAPTO")) {
        if (!next_number(rapto)) return;
      } else if (is_word(f, "RTRCTO")) {
        if (!next_number(retract)) return;
      } else if (is_word(f, "DWELL")) {
        if (!next_number(scratch)) return;
        c.dwell = *scratch;
      } else if (is_word(f, "INCR") || is_word(f, "STEP") || is_word(f, "PECK")) {
        if (!next_number(scratch)) return;
        c.peck = *scratch;
      } else if (is_word(f, "ORIENT")) {
        c.spindle_stop = true;
        if (i + 1 < fields_.size() && detail::parse_number(fields_[i + 1])) ++i;
      } else if (is_word(f, "LEFT")) {
        c.left_hand = true;
      } else if (is_word(f, "RIGHT")) {
        c.left_hand = false;
      } else if (auto v = detail::parse_number(f)) {
        // ISO 4343's positional form: CYCLE/DRILL, depth, MMPM, feed, clearance.
        if (positional == 0 && !depth)
          depth = v;
        else if (positional <= 1 && !clearance)
          clearance = v;
        else
          at(diag::Code::ClsUnsupportedOption, r.at(f), "CYCLE/: an extra number; ignored");
        ++positional;
      } else {
        at(diag::Code::ClsUnsupportedOption, r.at(f),
           "CYCLE/: '" + std::string(f) + "' is not supported; ignored");
      }
    }
    if (!depth || !(*depth > 0)) {
      at(diag::Code::ClsBadCycle, r.at(kind), "CYCLE/ needs a depth greater than 0");
      cycle_.reset();
      return;
    }
    if (!clearance) clearance = rapto ? rapto : retract;
    if (!clearance) {
      at(diag::Code::ClsBadCycle, r.at(kind), "CYCLE/ needs a clearance (or RAPTO)");
      cycle_.reset();
      return;
    }
    c.depth = *depth;
    c.rapto = rapto.value_or(*clearance);
    c.retract = retract.value_or(*clearance);
    if (c.retract < c.rapto || c.rapto < 0 || c.dwell < 0) {
      at(diag::Code::ClsBadCycle, r.at(kind),
         "CYCLE/: the retract height is below the rapid-to height, or a height or dwell is "
         "negative");
      cycle_.reset();
      return;
    }
    if (c.kind == canon::CycleKind::PeckDrill && !(c.peck > 0)) {
      at(diag::Code::ClsBadCycle, r.at(kind), "CYCLE/DEEP needs a peck depth (INCR, d)");
      cycle_.reset();
      return;
    }
    cycle_ = c;
  }

  // A GOTO/ while a cycle is on: one hole, its top at `top`.
  void hole(Vec top, Position where) {
    flush_tool();
    rapid_next_ = false;
    const CycleSpec& s = *cycle_;
    const Vec axis_cl = axis_.value_or(Vec{0, 0, 1});
    const Vec a = (1 / length(axis_cl)) * axis_cl;
    const Vec axis = frame_direction(a);
    if (std::fabs(axis.x) > 1e-9 || std::fabs(axis.y) > 1e-9 || axis.z <= 0) {
      at(diag::Code::ClsBadCycle, where,
         "a cycle's hole along a tool axis other than +Z cannot be a canonical cycle");
      position_ = top + s.retract * a;
      return;
    }
    canon::Cycle c;
    c.kind = s.kind;
    const Vec p = frame_point(top);
    c.x = p.x;
    c.y = p.y;
    c.safe_z = frame_point(top + s.retract * a).z;
    c.r_z = frame_point(top + s.rapto * a).z;
    c.bottom_z = frame_point(top - s.depth * a).z;
    c.dwell = s.dwell;
    c.peck = s.peck;
    c.left_hand = s.left_hand || !clockwise_;
    c.spindle_stop = s.spindle_stop;
    const std::optional<double> feed = s.feed ? s.feed : feed_;
    const FeedPer per = s.feed ? s.feed_per : feed_per_;
    if (!feed) {
      at(diag::Code::ClsBadCycle, where, "a cycle without a feed (none in CYCLE/ or FEDRAT/)");
      position_ = top + s.retract * a;
      return;
    }
    if ((per == FeedPer::Revolution || s.kind == canon::CycleKind::Tap) && !(rpm_ > 0)) {
      at(diag::Code::ClsNoSpindleSpeed, where,
         "a cycle whose feed is per revolution, or a tap, needs a spindle speed in force");
      position_ = top + s.retract * a;
      return;
    }
    c.feed = per == FeedPer::Revolution ? *feed * rpm_ : *feed;
    if (s.kind == canon::CycleKind::Tap) {
      c.spindle_speed = rpm_;
      c.pitch = c.feed / rpm_;
    }
    if (axis_) c.tool_axis = canon::Direction{axis.x, axis.y, axis.z};
    check_axis(where);
    emit(c);
    position_ = top + s.retract * a;
  }

  // ---- Tools and operations ---------------------------------------------------------------------

  void tool_path(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    const std::string name(detail::unquote(fields_[0]));
    PendingTool tool;
    std::optional<Position> name_at;
    if (fields_.size() >= 3 && is_word(fields_[1], "TOOL")) {
      tool.name = std::string(detail::unquote(fields_[2]));
      name_at = r.at(fields_[2]);
    }
    begin_operation(name, r.line());
    if (!tool.name.empty()) {
      if (checks_) checks_->tool_name(tool.name, name_at->line, name_at->column);
      pending_tool_ = std::move(tool);
    }
  }

  void begin_operation(const std::string& name, std::uint32_t line) {
    flush_tool();
    dangling_circle();
    close_operation();
    operation_ = canon::Entity{line, "CL_OPERATION", name};
    canon::OutputOptions options;
    if (checks_) options = checks_->operation(name, line);
    emit(canon::Begin{canon::Scope::Workingstep, *operation_, options});
    tool_data_ = {};
  }

  void close_operation() {
    if (!operation_) return;
    emit(canon::End{canon::Scope::Workingstep, *operation_});
    operation_.reset();
    if (checks_) checks_->end_operation();
  }

  // The tool number of LOAD/TOOL,n / SELECT/TOOL,n (`word` is LOAD or SELECT) or of LOADTL/n /
  // SELCTL/n (`word` empty); reports and returns nullopt when there is none.
  std::optional<std::int32_t> tool_argument(const Record& r, std::string_view args,
                                            std::string_view word) {
    detail::split_fields(args, fields_);
    if (!word.empty() && !is_word(fields_[0], "TOOL")) {
      at(diag::Code::ClsUnsupportedOption, r.at(fields_[0]),
         std::string(word) + "/" + std::string(fields_[0]) + " is not supported (" +
             std::string(word) + "/TOOL,n); ignored");
      return std::nullopt;
    }
    const std::size_t at_field = word.empty() ? 0 : 1;
    if (fields_.size() <= at_field) {
      at(diag::Code::ClsBadTool, r.at(args), "no tool number");
      return std::nullopt;
    }
    const std::string_view f = fields_[at_field];
    const auto v = detail::parse_number(f);
    if (!v || *v != std::floor(*v) || *v < 1 || *v > 2147483647.0) {
      at(diag::Code::ClsBadTool, r.at(f), "'" + std::string(f) + "' is not a tool number");
      return std::nullopt;
    }
    return static_cast<std::int32_t>(*v);
  }

  // LOAD/TOOL,n[,...] or LOADTL/n[,...].
  void load(const Record& r, std::string_view args, bool with_word) {
    const auto slot = tool_argument(r, args, with_word ? "LOAD" : "");
    if (!slot) return;
    // In an NX operation whose tool change is still to come, LOAD/TOOL gives its number; in
    // APT CL each tool load starts an operation of its own.
    if (pending_tool_ && operation_ && pending_tool_->slot == 0) {
      pending_tool_->slot = *slot;
      pending_tool_->explicit_load = true;
      return;
    }
    begin_operation("TOOL " + std::to_string(*slot), r.line());
    pending_tool_ = PendingTool{*slot, {}, true};
    flush_tool();  // APT CL gives no tool data after the load to wait for
  }

  void select(const Record& r, std::string_view args, bool with_word) {
    const auto slot = tool_argument(r, args, with_word ? "SELECT" : "");
    if (!slot) return;
    emit(canon::SelectTool{*slot});
    selected_ = *slot;
  }

  void tool_data(ToolDimensions data, std::string_view word, std::uint32_t line) {
    if (data.diameter) tool_diameter_ = *data.diameter;
    tool_data_ = data;
    if (checks_) checks_->tool_data(data, word, line);
  }

  // TLDATA/MILL, diameter, lower radius, length, taper angle, tip angle [, x and y of the
  // radius's centre [, upper radius, x, y]]; TLDATA/DRILL [, type], diameter, corner radius,
  // length, point angle, flute length.
  void tldata(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    const std::string_view kind = fields_[0];
    double v[10];
    if (is_word(kind, "MILL")) {
      const std::size_t n = fields_.size() - 1;
      if (n != 5 && n != 7 && n != 10) {
        at(diag::Code::ClsBadArguments, r.at(args),
           "TLDATA/MILL takes 5, 7 or 10 numbers (diameter, lower radius, length, taper angle, "
           "tip angle, ...)");
        return;
      }
      if (!numbers(r, args, 1, n, v, "TLDATA/MILL")) return;
      return tool_data(ToolDimensions{v[0], v[1], v[2]}, "TLDATA", r.line());
    }
    if (is_word(kind, "DRILL")) {
      std::size_t first = 1;
      if (fields_.size() > 1 && !detail::parse_number(fields_[1])) first = 2;  // a drill type
      if (fields_.size() - first != 5) {
        at(diag::Code::ClsBadArguments, r.at(args),
           "TLDATA/DRILL takes 5 numbers (diameter, corner radius, length, point angle, flute "
           "length)");
        return;
      }
      if (!numbers(r, args, first, 5, v, "TLDATA/DRILL")) return;
      return tool_data(ToolDimensions{v[0], v[1], v[2]}, "TLDATA", r.line());
    }
    at(diag::Code::ClsUnsupportedOption, r.at(kind),
       "TLDATA/" + std::string(kind) + " is not supported (MILL, DRILL); ignored");
  }

  // CUTTER/d [, r [, e, f, a, b, h]]: APT's cutter, diameter and corner radius.
  void cutter(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    const std::size_t n = fields_.size();
    double v[7];
    if (n != 1 && n != 2 && n != 7) {
      at(diag::Code::ClsBadArguments, r.at(args), "CUTTER/ takes 1, 2 or 7 numbers");
      return;
    }
    if (!numbers(r, args, 0, n, v, "CUTTER/")) return;
    ToolDimensions d;
    d.diameter = v[0];
    if (n >= 2) d.corner_radius = v[1];
    tool_data(d, "CUTTER", r.line());
  }

  // The tool change an operation asked for, written before its first motion or machine function
  // (TLDATA/, LOAD/TOOL and comments may come between the operation and its first move).
  void flush_tool() {
    if (!pending_tool_) return;
    PendingTool t = std::move(*pending_tool_);
    pending_tool_.reset();
    std::int32_t slot = t.slot;
    if (slot == 0) slot = slot_for(t.name);
    if (slot == 0) return;
    if (slot == spindle_tool_ && !t.explicit_load) return;  // the same tool goes on cutting
    if (!t.name.empty()) emit(canon::Comment{"TOOL " + t.name});
    if (selected_ != slot) emit(canon::SelectTool{slot});
    emit(canon::ChangeTool{slot});
    emit(canon::UseToolLengthOffset{tool_data_.length.value_or(0)});
    spindle_tool_ = slot;
    selected_ = 0;
  }

  // A tool named T<n> (T15-D6-CR2) is tool n; other names get numbers in order of appearance,
  // skipping numbers already used.
  std::int32_t slot_for(const std::string& name) {
    if (name.size() >= 2 && (name[0] == 'T' || name[0] == 't')) {
      std::size_t i = 1;
      std::int64_t n = 0;
      while (i < name.size() && name[i] >= '0' && name[i] <= '9' && n < 100000000)
        n = n * 10 + (name[i++] - '0');
      const bool ends = i == name.size() || !std::isalnum(static_cast<unsigned char>(name[i]));
      if (i > 1 && ends && n >= 1 && n < 100000000) {
        used_slots_.insert(static_cast<std::int32_t>(n));
        return static_cast<std::int32_t>(n);
      }
    }
    if (const auto it = slots_.find(name); it != slots_.end()) return it->second;
    if (slots_.size() >= options_.max_tool_names) {
      error(diag::Code::ClsLimit, 0, 0,
            "more than " + std::to_string(options_.max_tool_names) +
                " distinct tool names (max_tool_names)");
      stopped_ = true;
      return 0;
    }
    while (used_slots_.count(next_slot_)) ++next_slot_;
    used_slots_.insert(next_slot_);
    slots_.emplace(name, next_slot_);
    return next_slot_;
  }

  // ---- Set-up words ---------------------------------------------------------------------------

  void units(const Record& r, std::string_view args) {
    const std::string_view u = detail::trim(args);
    canon::Units units;
    if (is_word(u, "MM"))
      units = canon::Units::Millimetres;
    else if (is_word(u, "INCHES") || is_word(u, "INCH"))
      units = canon::Units::Inches;
    else if (is_word(u, "CM"))
      units = canon::Units::Centimetres;
    else {
      at(diag::Code::ClsBadArguments, r.at(args), "UNITS/ takes MM, INCHES or CM");
      return;
    }
    units_ = units;
    units_stated_ = true;
    if (header_done_ && units_ != emitted_units_) {
      emitted_units_ = units_;
      emit(canon::UseLengthUnits{units_});
    }
  }

  void partno(std::string_view args) {
    const std::string_view name = detail::unquote(args);
    if (header_done_) return comment("PARTNO " + std::string(name));
    if (!name.empty()) program_name_ = std::string(name);
  }

  void set(const Record& r, std::string_view args) {
    detail::split_fields(args, fields_);
    if (fields_.size() == 2 && is_word(fields_[0], "MODE")) {
      if (is_word(fields_[1], "ABSOL")) {
        incremental_ = false;
        return;
      }
      if (is_word(fields_[1], "INCR")) {
        incremental_ = true;
        return;
      }
    }
    at(diag::Code::ClsUnsupportedOption, r.at(args),
       "SET/" + std::string(detail::trim(args)) +
           " is not supported (SET/MODE,ABSOL|INCR); "
           "ignored");
  }

  void ignored(const Record& r, Word w, std::string_view word) {
    const auto index = static_cast<std::size_t>(w);
    if (noted_[index]) return;
    noted_[index] = true;
    at(diag::Code::ClsIgnoredRecord, r.at(word),
       std::string(word) + "/ records are for display or bookkeeping and are ignored");
  }

  void unknown(const Record& r, std::string_view word) {
    if (unknown_words_.size() >= kMaxUnknownWords) {
      if (!unknown_overflow_) {
        unknown_overflow_ = true;
        at(diag::Code::ClsUnknownWord, r.at(word),
           "more unknown major words; they are ignored without further warnings");
      }
      return;
    }
    if (!unknown_words_.insert(std::string(word)).second) return;
    at(diag::Code::ClsUnknownWord, r.at(word),
       "unknown major word '" + std::string(word) + "'; its records are ignored");
  }

  void end_program() {
    flush_tool();
    dangling_circle();
    close_operation();
    emit(canon::ProgramEnd{});
    emit(canon::End{canon::Scope::Project, project()});
  }

  // ---- State ----------------------------------------------------------------------------------

  struct Frame {
    Vec origin, x, y, z;
  };

  canon::Sink& sink_;
  const ReadOptions options_;
  detail::RecordAssembler records_;
  std::vector<std::string_view> fields_;
  std::optional<detail::CheckRun> checks_;
  // diagnostics and flow
  std::vector<diag::Diagnostic> diagnostics_;
  std::size_t errors_ = 0;
  std::size_t others_ = 0;
  bool others_dropped_ = false;
  bool stopped_ = false;
  bool cancelled_ = false;
  bool after_fini_ = false;
  bool after_fini_reported_ = false;
  std::uint64_t records_read_ = 0;
  std::size_t calls_ = 0;
  std::array<bool, kWordCount> noted_{};
  std::set<std::string, std::less<>> unknown_words_;
  bool unknown_overflow_ = false;
  // header
  bool header_done_ = false;
  std::string program_name_;
  canon::Units units_;
  canon::Units emitted_units_ = canon::Units::Millimetres;
  bool units_stated_ = false;
  std::vector<canon::Comment> held_;
  // geometry, in the CL file's own coordinates
  std::optional<Frame> frame_;
  bool incremental_ = false;
  Vec position_{};
  std::optional<Vec> axis_;  // the last tool axis stated; none before the first
  bool rapid_next_ = false;
  std::optional<Vec> indirv_;
  std::optional<PendingCircle> circle_;
  canon::Plane plane_ = canon::Plane::Xy;
  // feed, spindle, coolant
  std::optional<double> feed_;  // program units per minute or per revolution
  FeedPer feed_per_ = FeedPer::Minute;
  double rpm_ = 0;
  bool clockwise_ = true;
  bool flood_ = false;
  bool mist_ = false;
  // cycles
  std::optional<CycleSpec> cycle_;
  // tools and operations
  std::optional<canon::Entity> operation_;
  std::optional<PendingTool> pending_tool_;
  ToolDimensions tool_data_;
  double tool_diameter_ = 0;
  std::int32_t spindle_tool_ = 0;
  std::int32_t selected_ = 0;
  std::unordered_map<std::string, std::int32_t> slots_;
  std::set<std::int32_t> used_slots_;
  std::int32_t next_slot_ = 1;
};

Reader::Reader(canon::Sink& sink, const ReadOptions& options)
    : impl_(std::make_unique<Impl>(sink, options)) {}
Reader::~Reader() = default;

void Reader::feed(std::string_view piece) {
  impl_->feed(piece);
}

ReadResult Reader::finish() {
  return impl_->finish();
}

ReadResult read(std::string_view text, canon::Sink& sink, const ReadOptions& options) {
  Reader reader(sink, options);
  reader.feed(text);
  return reader.finish();
}

}  // namespace ncpost::cls
