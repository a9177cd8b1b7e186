// Heidenhain Klartext (conversational) — the reading subset docs/gcode.md lists: BEGIN/END PGM,
// TOOL DEF / TOOL CALL, L with FMAX / F / M, CC + C / CR / CP (helices), the cycles 200 and 203
// (multi-line CYCL DEF with ~ continuations, called with CYCL CALL or M99), 9 (dwell) and 7
// (datum shift), Q parameters (Q = formula, FN 0..13 arithmetic, FN 9..12 jumps, FN 14 error,
// FN 18 SYSREAD as a machine value), LBL / CALL LBL n [REP m] / LBL 0, CALL PGM, STOP.
// The motions go through the converter's primitives (the same conventions as every dialect).

#include "klartext.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>

namespace ncpost::gcode::detail {

namespace {

constexpr double kFmax = 1e30;

std::size_t skip_spaces(std::string_view t, std::size_t p) {
  while (p < t.size() && t[p] == ' ') ++p;
  return p;
}

std::string_view word_at(std::string_view t, std::size_t p) {
  std::size_t e = p;
  while (e < t.size() && t[e] != ' ') ++e;
  return t.substr(p, e - p);
}

bool starts(std::string_view t, std::size_t p, std::string_view w) {
  return p <= t.size() && t.compare(p, w.size(), w) == 0 &&
         (p + w.size() >= t.size() || t[p + w.size()] == ' ' || t[p + w.size()] == ':');
}

}  // namespace

void Interpreter::klartext_line() {
  if (!klartext_) klartext_ = std::make_unique<KlartextState>();
  KlartextState& k = *klartext_;
  const std::string_view t = line_->text;
  std::size_t pos = skip_spaces(t, 0);
  // The block number.
  while (pos < t.size() && is_digit(t[pos])) ++pos;
  pos = skip_spaces(t, pos);
  const std::uint32_t col = column(pos);
  if (!converter_.started() && !starts(t, pos, "BEGIN")) converter_.start(program_name_);
  // Comments: ';' to the line end (the lexer took them out), '*' blocks.
  if (pos >= t.size() || t[pos] == '*') {
    if (!converter_.started()) converter_.start(program_name_);
    for (const Comment& c : line_->comments) {
      std::string_view text = c.text;
      while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
      while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
      if (!text.empty()) converter_.comment(text, where());
    }
    if (pos < t.size()) converter_.comment(t.substr(pos + 1), where());
    return;
  }
  executed_any_ = true;
  // A value: +12.5, -Q3, +QL2, Q5 (a Q parameter carries its sign).
  auto value = [&](std::size_t& p, double& out) {
    Value v;
    if (!evaluate_at(p, Evaluator::Mode::Primary, v)) return false;
    if (v.machine)
      return error(column(p), diag::Code::GcodeMachineMotion,
                   "a coordinate that depends on a value only the machine knows");
    out = v.number;
    return true;
  };
  // The words of a positioning block: X Y Z A B C (I.. incremental), F, FMAX, FAUTO, R0/RL/RR,
  // DR+/DR-, M functions, and for C/CR/CP also R and IPA/IZ.
  struct Words {
    std::array<std::optional<double>, 6> axes;
    std::array<bool, 6> incremental{};
    std::optional<double> feed;
    bool fmax = false;
    int dr = 0;
    std::optional<double> radius, ipa, iz;
    std::vector<int> m;
  } w;
  auto read_words = [&](std::size_t p) {
    static constexpr std::string_view kAxisLetters = "XYZABC";
    while (true) {
      p = skip_spaces(t, p);
      if (p >= t.size()) return true;
      const std::uint32_t wc = column(p);
      const std::string_view word = word_at(t, p);
      if (word == "FMAX") {
        w.fmax = true;
        p += 4;
        continue;
      }
      if (word == "FAUTO" || word == "R0") {
        p += word.size();
        continue;
      }
      if (word == "RL" || word == "RR")
        return error(wc, diag::Code::GcodeUnsupported, "radius compensation (RL, RR)");
      if (word == "DR+" || word == "DR-") {
        w.dr = word.back() == '+' ? 1 : -1;
        p += 3;
        continue;
      }
      if (word.rfind("IPA", 0) == 0) {
        p += 3;
        double v = 0;
        if (!value(p, v)) return false;
        w.ipa = v;
        continue;
      }
      const char c = t[p];
      bool incremental = false;
      std::size_t q = p;
      if (c == 'I' && q + 1 < t.size() && kAxisLetters.find(t[q + 1]) != std::string_view::npos) {
        incremental = true;
        ++q;
      }
      const auto axis = kAxisLetters.find(t[q]);
      if (axis != std::string_view::npos && q + 1 < t.size() &&
          (t[q + 1] == '+' || t[q + 1] == '-' || t[q + 1] == 'Q' || is_digit(t[q + 1]))) {
        ++q;
        double v = 0;
        if (!value(q, v)) return false;
        if (incremental && axis == 2 && w.ipa) {
          w.iz = v;  // CP's IZ
        } else {
          w.axes[axis] = v;
          w.incremental[axis] = incremental;
        }
        p = q;
        continue;
      }
      if (c == 'F' && q + 1 < t.size()) {
        ++q;
        double v = 0;
        if (!value(q, v)) return false;
        w.feed = v;
        p = q;
        continue;
      }
      if (c == 'R' && q + 1 < t.size()) {
        ++q;
        double v = 0;
        if (!value(q, v)) return false;
        w.radius = v;
        p = q;
        continue;
      }
      if (c == 'M' && q + 1 < t.size() && is_digit(t[q + 1])) {
        ++q;
        double v = 0;
        bool integer = false;
        if (!Evaluator::scan_number(t, q, v, integer))
          return error(wc, diag::Code::GcodeBadNumber, "malformed M function");
        w.m.push_back(static_cast<int>(std::lround(v)));
        p = q;
        continue;
      }
      return error(wc, diag::Code::GcodeUnknownWord,
                   "unknown word '" + std::string(word) + "' in a Klartext block");
    }
  };
  // M functions in order: before the motion (spindle, coolant) and after it (stops, M99).
  auto m_before = [&]() {
    for (const int m : w.m) {
      if (const CodeSpec* spec = dialect_.m_code(m)) {
        switch (spec->action) {
          case Action::SpindleCw:
            converter_.spindle(1);
            break;
          case Action::SpindleCcw:
            converter_.spindle(-1);
            break;
          case Action::SpindleStop:
            converter_.spindle(0);
            break;
          case Action::FloodOn:
            converter_.coolant(false, true, false);
            break;
          case Action::MistOn:
            converter_.coolant(true, false, false);
            break;
          case Action::CoolantOff:
            converter_.coolant(false, false, true);
            break;
          case Action::SpindleCwCoolant:
            converter_.spindle(1);
            converter_.coolant(false, true, false);
            break;
          case Action::SpindleCcwCoolant:
            converter_.spindle(-1);
            converter_.coolant(false, true, false);
            break;
          case Action::Unsupported:
            return error(col, diag::Code::GcodeUnsupported, spec->text + ": " + spec->refusal);
          default:
            break;
        }
      } else {
        return error(col, diag::Code::GcodeUnknownCode, "unknown M function M" + std::to_string(m));
      }
    }
    return true;
  };
  auto m_after = [&]() {
    for (const int m : w.m) {
      const CodeSpec* spec = dialect_.m_code(m);
      if (!spec) continue;
      switch (spec->action) {
        case Action::ProgramStop:
        case Action::OptionalStop:
          converter_.stop(spec->action);
          break;
        case Action::ProgramEnd:
          converter_.stop(Action::ProgramEnd);
          done_ = true;
          break;
        case Action::CycleCall:
          klartext_cycle_call(col);
          break;
        default:
          break;
      }
    }
  };
  bool machine = false;  // M91: this block in machine coordinates
  auto target_of = [&]() {
    Axes target = converter_.target();
    for (int a = 0; a < 6; ++a) {
      if (!w.axes[static_cast<std::size_t>(a)]) continue;
      const double v = *w.axes[static_cast<std::size_t>(a)];
      const double current = converter_.at(a);
      target[static_cast<std::size_t>(a)] = converter_.internal(
          a, w.incremental[static_cast<std::size_t>(a)] ? current + v : v, machine);
    }
    return target;
  };
  auto set_feed = [&]() {
    if (w.feed && !w.fmax) converter_.set_feed(*w.feed);
  };

  // ---- Statements ----
  if (starts(t, pos, "BEGIN")) {
    // BEGIN PGM NAME MM|INCH
    std::size_t p = skip_spaces(t, pos + 5);
    if (starts(t, p, "PGM")) p = skip_spaces(t, p + 3);
    const std::string_view name = word_at(t, p);
    const std::string_view unit = word_at(t, skip_spaces(t, p + name.size()));
    if (frames_.size() == 1 && !titled_) {
      titled_ = true;
      program_name_ = std::string(name);
    }
    if (!converter_.started()) converter_.start(program_name_);
    if (unit == "INCH") converter_.set_metric(false);
    if (unit == "MM") converter_.set_metric(true);
    return;
  }
  if (starts(t, pos, "END")) {
    if (frames_.size() > 1) {
      return_from_call(std::nullopt, std::nullopt);
      return;
    }
    if (!converter_.ended()) converter_.stop(Action::ProgramEnd);
    done_ = true;
    return;
  }
  if (starts(t, pos, "BLK")) return;  // the blank form: for the simulation
  if (starts(t, pos, "STOP")) {
    std::size_t p = pos + 4;
    if (!read_words(p)) return;
    if (!m_before()) return;
    converter_.stop(Action::ProgramStop);
    m_after();
    return;
  }
  if (starts(t, pos, "TOOL")) {
    std::size_t p = skip_spaces(t, pos + 4);
    const bool call = starts(t, p, "CALL");
    if (!call && !starts(t, p, "DEF")) {
      error(col, diag::Code::GcodeBadStatement, "TOOL without CALL or DEF");
      return;
    }
    p = skip_spaces(t, p + (call ? 4 : 3));
    if (p < t.size() && t[p] == '"') {
      error(column(p), diag::Code::GcodeUnsupported, "tools called by name (TOOL CALL \"..\")");
      return;
    }
    // TOOL CALL Z S..: no tool number, only a new speed (or feed) for the tool in the spindle.
    const bool numbered = p < t.size() && (is_digit(t[p]) || t[p] == 'Q' || t[p] == '+');
    double tool = 0;
    if (numbered || !call) {
      if (!value(p, tool)) return;
      converter_.select_tool(static_cast<int>(std::lround(tool)), where(), col);
    }
    if (!call) return;
    // TOOL CALL n Z S.. F..: the tool axis (Z only), the speed, a feed.
    while (true) {
      p = skip_spaces(t, p);
      if (p >= t.size()) break;
      const char c = t[p];
      if (c == 'Z' && (p + 1 >= t.size() || t[p + 1] == ' ')) {
        ++p;
        continue;
      }
      if (c == 'X' || c == 'Y') {
        error(column(p), diag::Code::GcodeUnsupported, "a tool axis other than Z");
        return;
      }
      if (c == 'S' || c == 'F' || c == 'D') {
        ++p;
        if (p < t.size() && t[p] == 'L') ++p;  // DL, DR: oversizes, not read
        double v = 0;
        if (!value(p, v)) return;
        if (c == 'S') converter_.set_spindle_speed(v, where(), col);
        if (c == 'F') converter_.set_feed(v);
        continue;
      }
      error(column(p), diag::Code::GcodeUnknownWord, "unknown word in TOOL CALL");
      return;
    }
    if (!numbered) return;
    converter_.change_tool(where(), col);
    // The TNC applies the tool's length with the call.
    converter_.tool_length(true, static_cast<int>(std::lround(tool)), where());
    return;
  }
  if (starts(t, pos, "L")) {
    std::size_t p = pos + 1;
    if (!read_words(p)) return;
    for (const int m : w.m) machine = machine || m == 91;
    if (!m_before()) return;
    set_feed();
    bool axes = false;
    for (const auto& a : w.axes) axes = axes || a.has_value();
    if (axes) {
      const Axes target = target_of();
      if (w.fmax)
        converter_.rapid(target, where(), col);
      else
        converter_.linear(target, where(), col);
    }
    m_after();
    return;
  }
  if (starts(t, pos, "CC")) {
    std::size_t p = pos + 2;
    if (!read_words(p)) return;
    // CC without coordinates: the current position.
    const double x = w.axes[0] ? (w.incremental[0] ? converter_.at(0) + *w.axes[0] : *w.axes[0])
                               : converter_.at(0);
    const double y = w.axes[1] ? (w.incremental[1] ? converter_.at(1) + *w.axes[1] : *w.axes[1])
                               : converter_.at(1);
    k.cc_x = x;
    k.cc_y = y;
    k.cc = true;
    return;
  }
  if (starts(t, pos, "C") || starts(t, pos, "CR") || starts(t, pos, "CP")) {
    const bool cr = starts(t, pos, "CR");
    const bool cp = starts(t, pos, "CP");
    std::size_t p = pos + (cr || cp ? 2 : 1);
    if (!read_words(p)) return;
    if (!m_before()) return;
    set_feed();
    if (w.dr == 0) {
      error(col, diag::Code::GcodeMissingWord, "an arc without its direction DR+ or DR-");
      return;
    }
    if (converter_.plane() != canon::Plane::Xy) {
      error(col, diag::Code::GcodeUnsupported, "arcs outside the XY plane");
      return;
    }
    double cx = k.cc_x, cy = k.cc_y;
    Axes target = target_of();
    int rotation = w.dr;
    if (cp) {
      // CP IPA<total angle> IZ<height> DR±: a helix about CC from here.
      if (!w.ipa) {
        error(col, diag::Code::GcodeMissingWord, "CP without its angle IPA");
        return;
      }
      const double x0 = converter_.at(0), y0 = converter_.at(1);
      const double r = std::hypot(x0 - cx, y0 - cy);
      const double a = std::atan2(y0 - cy, x0 - cx) + *w.ipa * std::numbers::pi / 180;
      target[0] = converter_.internal(0, cx + r * std::cos(a));
      target[1] = converter_.internal(1, cy + r * std::sin(a));
      if (w.iz) target[2] = converter_.internal(2, converter_.at(2) + *w.iz);
      const int turns = static_cast<int>(std::ceil(std::abs(*w.ipa) / 360 - 1e-9));
      rotation = w.dr * std::max(turns, 1);
      if ((*w.ipa > 0) != (w.dr > 0)) {
        error(col, diag::Code::GcodeConflictingWords, "CP: IPA and DR turn different ways");
        return;
      }
    } else if (cr) {
      // CR X Y R±r DR±: the centre from the radius (R+ the shorter arc, as FANUC's R).
      if (!w.radius) {
        error(col, diag::Code::GcodeMissingWord, "CR without its radius R");
        return;
      }
      const double x0 = converter_.at(0), y0 = converter_.at(1);
      const double x1 = w.axes[0] ? (w.incremental[0] ? x0 + *w.axes[0] : *w.axes[0]) : x0;
      const double y1 = w.axes[1] ? (w.incremental[1] ? y0 + *w.axes[1] : *w.axes[1]) : y0;
      const double r = std::abs(*w.radius);
      const double half = std::hypot(x1 - x0, y1 - y0) / 2;
      if (half == 0 || half - r > 1e-6) {
        error(col, diag::Code::GcodeArcGeometry, "CR: a radius that cannot reach the end point");
        return;
      }
      const double h = half >= r ? 0 : std::sqrt(r * r - half * half);
      const bool right = (w.dr < 0 && *w.radius > 0) || (w.dr > 0 && *w.radius < 0);
      const double theta =
          std::atan2(y1 - y0, x1 - x0) + (right ? -std::numbers::pi / 2 : std::numbers::pi / 2);
      cx = (x0 + x1) / 2 + h * std::cos(theta);
      cy = (y0 + y1) / 2 + h * std::sin(theta);
    } else if (!k.cc) {
      error(col, diag::Code::GcodeMissingWord, "C without a circle centre CC before it");
      return;
    }
    converter_.arc(target, converter_.internal(0, cx), converter_.internal(1, cy), rotation,
                   canon::Plane::Xy, where(), col);
    m_after();
    return;
  }
  if (starts(t, pos, "CT") || starts(t, pos, "RND") || starts(t, pos, "CHF") ||
      starts(t, pos, "APPR") || starts(t, pos, "DEP")) {
    error(col, diag::Code::GcodeUnsupported,
          std::string(word_at(t, pos)) +
              ": tangential arcs, roundings, chamfers and approach/departure blocks");
    return;
  }
  if (starts(t, pos, "CYCL")) {
    std::size_t p = skip_spaces(t, pos + 4);
    if (starts(t, p, "CALL")) {
      std::size_t q = p + 4;
      if (!read_words(q)) return;
      if (!m_before()) return;
      klartext_cycle_call(col);
      m_after();
      return;
    }
    if (!starts(t, p, "DEF")) {
      error(col, diag::Code::GcodeBadStatement, "CYCL without DEF or CALL");
      return;
    }
    p = skip_spaces(t, p + 3);
    double number = 0;
    bool integer = false;
    const std::size_t at = p;
    if (!Evaluator::scan_number(t, p, number, integer)) {
      error(column(at), diag::Code::GcodeBadNumber, "CYCL DEF without its number");
      return;
    }
    if (std::abs(number - 9.0) < 1e-9) {  // 9.0 DWELL TIME
      k.dwell_next = true;
      return;
    }
    if (std::abs(number - 9.1) < 1e-9) {  // 9.1 DWELL 1.5
      std::size_t q = skip_spaces(t, p);
      if (starts(t, q, "DWELL")) q = skip_spaces(t, q + 5);
      double seconds = 0;
      if (!value(q, seconds)) return;
      converter_.dwell(seconds);
      return;
    }
    if (std::abs(number - 7.0) < 1e-9) {  // 7.0 DATUM SHIFT, then 7.1 X.., 7.2 Y.., 7.3 Z..
      k.datum = {0, 0, 0};
      return;
    }
    if (number > 7.05 && number < 7.35) {
      std::size_t q = skip_spaces(t, p);
      if (!read_words(q)) return;
      for (int a = 0; a < 3; ++a)
        if (w.axes[static_cast<std::size_t>(a)])
          k.datum[static_cast<std::size_t>(a)] = *w.axes[static_cast<std::size_t>(a)];
      Axes shift{};
      for (int a = 0; a < 3; ++a)
        shift[static_cast<std::size_t>(a)] = k.datum[static_cast<std::size_t>(a)];
      converter_.set_translation(shift);
      return;
    }
    if (number != 200 && number != 203) {
      error(col, diag::Code::GcodeUnsupported,
            "cycle " + std::string(word_at(t, at)) + " (cycles 200, 203, 7 and 9 are read)");
      return;
    }
    // The Q lines follow, while the line before ends with '~'.
    k.cycle = static_cast<int>(number);
    k.q.clear();
    auto continues = [&]() {
      std::string_view raw = line_->raw;
      while (!raw.empty() && (raw.back() == ' ' || raw.back() == '\t')) raw.remove_suffix(1);
      return !raw.empty() && raw.back() == '~';
    };
    while (continues()) {
      if (!next_line()) break;
      const std::string_view s = line_->text;
      std::size_t q = skip_spaces(s, 0);
      double index = 0;
      if (!klartext_q_target(q, index)) return;
      q = skip_spaces(s, q);
      double v = 0;
      if (starts(s, q, "FMAX") || starts(s, q, "FAUTO")) {
        v = kFmax;
      } else if (!value(q, v)) {
        return;
      }
      k.q[static_cast<int>(index)] = v;
    }
    return;
  }
  if (starts(t, pos, "LBL")) {
    // LBL 0 ends a subprogram; other labels are jump targets.
    std::size_t p = skip_spaces(t, pos + 3);
    if (starts(t, p, "0") && frames_.size() > 1 && frames_.back().kind == FrameKind::Label) {
      return_from_call(std::nullopt, std::nullopt);
      return;
    }
    return;
  }
  if (starts(t, pos, "CALL")) {
    std::size_t p = skip_spaces(t, pos + 4);
    if (starts(t, p, "PGM")) {
      p = skip_spaces(t, p + 3);
      std::string_view name = word_at(t, p);
      if (const auto slash = name.find_last_of("/\\:"); slash != std::string_view::npos)
        name.remove_prefix(slash + 1);
      if (const auto dot = name.rfind('.'); dot != std::string_view::npos)
        name = name.substr(0, dot);
      const auto file = find_file(name);
      if (!file) {
        error(col, diag::Code::GcodeMissingProgram,
              "program " + std::string(name) +
                  " is neither in the program nor among the uploaded files");
        return;
      }
      (void)call(*file, Position{*file, 0, 1}, FrameKind::Sinumerik, std::string(name), 0, false);
      return;
    }
    if (!starts(t, p, "LBL")) {
      error(col, diag::Code::GcodeBadStatement, "CALL without PGM or LBL");
      return;
    }
    p = skip_spaces(t, p + 3);
    const std::string_view label = word_at(t, p);
    p = skip_spaces(t, p + label.size());
    long long rep = 0;
    if (starts(t, p, "REP")) {
      p = skip_spaces(t, p + 3);
      double v = 0;
      if (!value(p, v)) return;
      rep = std::llround(v);
    }
    const Position* target = find_label(position_.source, "LBL" + std::string(label));
    if (!target) {
      error(col, diag::Code::GcodeBadFlow,
            "CALL LBL " + std::string(label) + ": no LBL " + std::string(label));
      return;
    }
    if (rep > 0) {
      // A section repeat: back to the label rep more times, counted at this CALL.
      Frame& frame = frames_.back();
      const std::string key = "REP@" + std::to_string(position_.offset);
      auto it = std::find_if(frame.loops.begin(), frame.loops.end(),
                             [&](const Loop& l) { return l.label == key; });
      if (it == frame.loops.end()) {
        if (frame.loops.size() >= options_.max_call_depth) {
          error(col, diag::Code::GcodeNestingLimit, "repeats nested too deep");
          return;
        }
        frame.loops.push_back({key, LoopKind::Repeat, *target, rep, {}, -1, 0});
        it = std::prev(frame.loops.end());
      }
      if (it->remaining-- > 0) {
        const Position to = *target;
        jump(to);
      } else {
        frame.loops.erase(it);
      }
      return;
    }
    const Position to = *target;
    (void)call(position_.source, to, FrameKind::Label, "LBL" + std::string(label), 0, false);
    return;
  }
  if (starts(t, pos, "FN")) {
    klartext_fn(pos);
    return;
  }
  if (t[pos] == 'Q') {
    // Q1 = formula (also QL, QR).
    std::size_t p = pos;
    double index = 0;
    if (!klartext_q_target(p, index)) return;
    Value v;
    if (!evaluate_at(p, Evaluator::Mode::Full, v)) return;
    (void)assign(Assignment{false, index, {}, v, col});
    return;
  }
  error(col, diag::Code::GcodeUnsupported,
        "Klartext block '" + std::string(word_at(t, pos)) + "' is not read by this subset");
}

// "Q5 =", "QL2 =", "QR1 =" at `p` of the line: the parameter's number in the one table (QL
// +10000, QR +20000, as the evaluator reads them) and `p` after the '='.
bool Interpreter::klartext_q_target(std::size_t& p, double& index) {
  const std::string_view t = line_->text;
  p = skip_spaces(t, p);
  if (p >= t.size() || t[p] != 'Q')
    return error(column(p), diag::Code::GcodeBadStatement, "a Q parameter expected");
  ++p;
  double offset = 0;
  if (p < t.size() && (t[p] == 'L' || t[p] == 'R')) {
    offset = t[p] == 'L' ? 10000 : 20000;
    ++p;
  }
  bool integer = false;
  if (!Evaluator::scan_number(t, p, index, integer))
    return error(column(p), diag::Code::GcodeBadParameter, "Q parameter number");
  index += offset;
  p = skip_spaces(t, p);
  if (p >= t.size() || t[p] != '=')
    return error(column(p), diag::Code::GcodeBadStatement, "'=' expected after a Q parameter");
  ++p;
  return true;
}

// CYCL CALL / M99: cycle 200 or 203 at the current X Y (docs/gcode.md says how the Q parameters
// become the canonical cycle and which values are refused).
void Interpreter::klartext_cycle_call(std::uint32_t col) {
  KlartextState& k = *klartext_;
  if (k.cycle == 0) {
    error(col, diag::Code::GcodeBadFlow, "CYCL CALL without a CYCL DEF");
    return;
  }
  auto q = [&](int i) -> std::optional<double> {
    const auto it = k.q.find(i);
    return it == k.q.end() ? std::nullopt : std::optional<double>(it->second);
  };
  for (const int needed : {200, 201, 202, 203, 204, 206}) {
    if (!q(needed)) {
      error(col, diag::Code::GcodeMissingWord,
            "cycle " + std::to_string(k.cycle) + " without Q" + std::to_string(needed));
      return;
    }
  }
  const auto refuse = [&](const std::string& why) {
    error(col, diag::Code::GcodeUnsupported, "cycle " + std::to_string(k.cycle) + ": " + why);
  };
  if (q(210).value_or(0) != 0) return refuse("a dwell at the top (Q210)");
  CycleCall c;
  c.x = converter_.at(0);
  c.y = converter_.at(1);
  const double surface = *q(203);
  c.r = surface + *q(200);
  c.bottom = surface + *q(201);
  c.clear = surface + std::max(*q(204), *q(200));
  c.feed = *q(206);
  c.dwell = q(211).value_or(0);
  c.peck = *q(202);
  c.peck_clearance = *q(200);
  if (k.cycle == 203) {
    if (q(212).value_or(0) != 0) return refuse("a decrement (Q212)");
    if (q(205).value_or(0) != 0) return refuse("a minimum plunging depth (Q205)");
    if (q(208).value_or(kFmax) != kFmax) return refuse("a retraction at a feed (Q208)");
    if (q(213).value_or(0) > 0) c.peck_retract = q(256).value_or(0);
  }
  if (c.peck < -*q(201) - 1e-9)
    c.kind = c.peck_retract > 0 ? CycleKind::ChipBreak : CycleKind::Peck;
  else
    c.kind = c.dwell > 0 ? CycleKind::DrillDwell : CycleKind::Drill;
  if (c.kind == CycleKind::ChipBreak) c.peck_clearance = 0;
  (void)converter_.cycle(c, where(), col);
}

// FN 0..13 arithmetic, FN 9..12 conditional jumps, FN 14 error, FN 16 print, FN 18 SYSREAD.
void Interpreter::klartext_fn(std::size_t pos) {
  const std::string_view t = line_->text;
  const std::uint32_t col = column(pos);
  std::size_t p = skip_spaces(t, pos + 2);
  double number = 0;
  bool integer = false;
  if (!Evaluator::scan_number(t, p, number, integer)) {
    error(column(p), diag::Code::GcodeBadStatement, "FN without its number");
    return;
  }
  const int fn = static_cast<int>(number);
  p = skip_spaces(t, p);
  if (p < t.size() && t[p] == ':') p = skip_spaces(t, p + 1);
  auto operand = [&](Value& v) {
    p = skip_spaces(t, p);
    const bool ok = evaluate_at(p, Evaluator::Mode::Primary, v);
    p = skip_spaces(t, p);
    return ok;
  };
  if (fn == 14) {
    error(col, diag::Code::GcodeAbort,
          "FN 14: the program stops with its error " + std::string(t.substr(p)));
    done_ = true;
    return;
  }
  if (fn == 16 || fn == 15) return;  // printing
  if (fn == 18) {
    // FN 18: SYSREAD Q1 = ID..: what only the machine knows.
    if (t.compare(p, 7, "SYSREAD") == 0) p = skip_spaces(t, p + 7);
    double index = 0;
    if (!klartext_q_target(p, index)) return;
    warn(col, diag::Code::GcodeMachineValue,
         "FN 18 SYSREAD" + std::string(t.substr(p)) +
             " is known only to the machine; read as the assumed 0");
    (void)assign(Assignment{false, index, {}, Value{0, false, true}, col});
    return;
  }
  if (fn >= 9 && fn <= 12) {
    // FN 9: IF +Q1 EQU +Q2 GOTO LBL 5 (10 NE, 11 GT, 12 LT).
    if (t.compare(p, 2, "IF") == 0) p += 2;
    Value a, b;
    if (!operand(a)) return;
    const std::string_view op = word_at(t, p);
    p += op.size();
    if (!operand(b)) return;
    if (a.machine || b.machine) {
      error(col, diag::Code::GcodeMachineMotion,
            "the program's flow depends on a value only the machine knows");
      return;
    }
    bool c = false;
    switch (fn) {
      case 9:
        c = std::abs(a.number - b.number) < 1e-9;
        break;
      case 10:
        c = std::abs(a.number - b.number) >= 1e-9;
        break;
      case 11:
        c = a.number > b.number;
        break;
      default:
        c = a.number < b.number;
        break;
    }
    if (t.compare(p, 4, "GOTO") == 0) p = skip_spaces(t, p + 4);
    if (t.compare(p, 3, "LBL") == 0) p = skip_spaces(t, p + 3);
    const std::string_view label = word_at(t, p);
    if (!c) return;
    const Position* to = find_label(position_.source, "LBL" + std::string(label));
    if (!to) {
      error(col, diag::Code::GcodeBadFlow, "GOTO LBL " + std::string(label) + ": no such label");
      return;
    }
    const Position at = *to;
    jump(at);
    return;
  }
  double index = 0;
  if (!klartext_q_target(p, index)) return;
  Value a, b, r;
  const std::size_t operand_at = skip_spaces(t, p);
  if (!operand(a)) return;
  bool ok = true;
  switch (fn) {
    case 0:
      r = a;
      break;
    case 1:
    case 2:
    case 3:
    case 4: {
      // The operator between the two operands is the one FN says; skip its sign.
      if (p < t.size() && (t[p] == '+' || t[p] == '-' || t[p] == '*' || t[p] == '/') &&
          p + 1 < t.size() && (t[p + 1] == ' '))
        ++p;
      if (!operand(b)) return;
      const Operator op = fn == 1   ? Operator::Add
                          : fn == 2 ? Operator::Sub
                          : fn == 3 ? Operator::Mul
                                    : Operator::Div;
      ok = evaluator_.binary(op, a, b, r);
      break;
    }
    case 5:
    case 6:
    case 7: {
      // FN 5: Q = SQRT a, FN 6: Q = SIN a, FN 7: Q = COS a; the function's name is optional
      // (when written, the evaluator applies it to the value after it).
      const std::string_view name = fn == 5 ? "SQRT" : fn == 6 ? "SIN" : "COS";
      if (t.compare(operand_at, name.size(), name) == 0) {
        r = a;
        break;
      }
      const Function f = fn == 5 ? Function::Sqrt : fn == 6 ? Function::Sin : Function::Cos;
      ok = evaluator_.function(f, &a, 1, r);
      break;
    }
    case 8:
    case 13: {
      // FN 8: Q = +a LEN +b (the root of the sum of squares); FN 13: Q = +a ANG +b (the angle).
      const std::string_view op = word_at(t, p);
      p += op.size();
      if (!operand(b)) return;
      if (fn == 8) {
        r = Value{std::hypot(a.number, b.number), false, a.machine || b.machine};
      } else {
        const Value args[2] = {b, a};
        ok = evaluator_.function(Function::Atan2, args, 2, r);
      }
      break;
    }
    default:
      error(col, diag::Code::GcodeUnsupported, "FN " + std::to_string(fn) + " is not read");
      return;
  }
  if (!ok) {
    report_eval_error();
    return;
  }
  (void)assign(Assignment{false, index, {}, r, col});
}

}  // namespace ncpost::gcode::detail
