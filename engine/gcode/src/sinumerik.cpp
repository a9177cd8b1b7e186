// Sinumerik statements (docs/gcode.md, "Sinumerik"): the archive header, labels, GOTOF/GOTOB/
// GOTO/GOTOC, IF … ELSE … ENDIF and IF … GOTOx, WHILE/ENDWHILE, FOR/ENDFOR, REPEAT/UNTIL,
// LOOP/ENDLOOP, DEF, PROC, RET, MSG, named-variable assignments, the drilling cycles CYCLE81/82/
// 83/85/89 (also modal, MCALL), subprogram calls by name (NAME, NAME(args), L123, CALL "NAME",
// with P repeats). Words, R-parameter assignments and the G-function keywords (CIP, BSPLINE,
// TRANS, SUPA, ...) are read by the common block reader.

#include <algorithm>
#include <charconv>
#include <cmath>

#include "interpreter.hpp"

namespace ncpost::gcode::detail {

namespace {

bool ident_start(char c) noexcept {
  return is_letter(c) || c == '_' || c == '$';
}
bool ident_char(char c) noexcept {
  return is_letter(c) || is_digit(c) || c == '_' || c == '$';
}

std::size_t skip_spaces(std::string_view t, std::size_t p) {
  while (p < t.size() && t[p] == ' ') ++p;
  return p;
}

std::string_view identifier(std::string_view t, std::size_t pos) {
  std::size_t end = pos;
  if (end < t.size() && ident_start(t[end]))
    while (end < t.size() && ident_char(t[end])) ++end;
  return t.substr(pos, end - pos);
}

// The statement words that open or close a structure, for skipping over nested ones.
enum class Structure : std::uint8_t {
  None,
  If,
  Else,
  EndIf,
  While,
  EndWhile,
  For,
  EndFor,
  Repeat,
  Until,
  Loop,
  EndLoop
};

Structure structure_of(std::string_view t) {
  std::size_t p = skip_spaces(t, 0);
  if (p < t.size() && t[p] == 'N' && p + 1 < t.size() && is_digit(t[p + 1])) {
    ++p;
    while (p < t.size() && is_digit(t[p])) ++p;
    p = skip_spaces(t, p);
  }
  // A label in front ("LOOP1: WHILE ...").
  const std::string_view first = identifier(t, p);
  if (!first.empty() && p + first.size() < t.size() && t[p + first.size()] == ':')
    p = skip_spaces(t, p + first.size() + 1);
  const std::string_view k = identifier(t, p);
  if (k == "IF") {
    // IF ... GOTOx is a jump, not a structure.
    return t.find("GOTO", p) == std::string_view::npos ? Structure::If : Structure::None;
  }
  if (k == "ELSE") return Structure::Else;
  if (k == "ENDIF") return Structure::EndIf;
  if (k == "WHILE") return Structure::While;
  if (k == "ENDWHILE") return Structure::EndWhile;
  if (k == "FOR") return Structure::For;
  if (k == "ENDFOR") return Structure::EndFor;
  if (k == "REPEAT") return Structure::Repeat;
  if (k == "UNTIL") return Structure::Until;
  if (k == "LOOP") return Structure::Loop;
  if (k == "ENDLOOP") return Structure::EndLoop;
  return Structure::None;
}

}  // namespace

// Skips lines after the current one to the structure word that closes the one just opened
// (`open`), counting nested ones; `also` is accepted at the outer level (ELSE). Leaves the found
// line in line_, the cursor after it.
bool Interpreter::sinumerik_skip(Structure_ open, Structure_ close, Structure_ also) {
  const std::uint32_t from = line_->number;
  int depth = 0;
  while (!done_ && next_line()) {
    if (line_->has_error) continue;
    const auto s = static_cast<Structure_>(structure_of(line_->text));
    if (s == open) ++depth;
    if (s == close) {
      if (depth == 0) return true;
      --depth;
    }
    if (s == also && also != 0 && depth == 0) return true;
  }
  report_.add(sources_[position_.source].name, diag::Code::GcodeBadFlow, from, 0,
              "a structure without its end");
  done_ = true;
  return false;
}

bool Interpreter::sinumerik_jump(std::string_view keyword, std::string_view label,
                                 std::uint32_t col) {
  // GOTOF searches forward, GOTOB backward, GOTO both, GOTOC like GOTO without an error.
  const Position* target = find_label(position_.source, label);
  const bool forward_ok = !target || target->offset > position_.offset;
  const bool backward_ok = !target || target->offset <= position_.offset;
  if (!target || (keyword == "GOTOF" && !forward_ok) || (keyword == "GOTOB" && !backward_ok)) {
    if (keyword == "GOTOC") return true;
    return error(col, diag::Code::GcodeBadFlow,
                 std::string(keyword) + ": no label " + std::string(label) +
                     (keyword == "GOTOF"   ? " after this block"
                      : keyword == "GOTOB" ? " before this block"
                                           : ""));
  }
  Frame& frame = frames_.back();
  frame.loops.erase(std::remove_if(frame.loops.begin(), frame.loops.end(),
                                   [&](const Loop& l) { return l.start.offset > target->offset; }),
                    frame.loops.end());
  jump(*target);
  return true;
}

// A drilling cycle call: CYCLE81(RTP, RFP, SDIS, DP, DPR) and its relatives, at the current
// X Y (docs/gcode.md says what each parameter becomes and which values are refused).
bool Interpreter::sinumerik_cycle(const std::string& name,
                                  const std::vector<std::optional<double>>& a, std::uint32_t col) {
  auto arg = [&](std::size_t i) -> std::optional<double> {
    return i < a.size() ? a[i] : std::nullopt;
  };
  auto value = [&](std::size_t i) { return arg(i).value_or(0.0); };
  const auto refuse = [&](const std::string& why) {
    return error(col, diag::Code::GcodeUnsupported, name + ": " + why);
  };
  if (!arg(0) || !arg(1)) return refuse("RTP and RFP are needed");
  CycleCall c;
  c.x = converter_.at(0);
  c.y = converter_.at(1);
  c.clear = value(0);
  c.r = value(1) + std::abs(value(2));
  if (arg(3))
    c.bottom = value(3);
  else if (arg(4))
    c.bottom = value(1) - std::abs(value(4));
  else
    return refuse("neither DP nor DPR gives the depth");
  if (converter_.plane() != canon::Plane::Xy) return refuse("only in the XY plane (G17)");
  if (name == "CYCLE81") {
    c.kind = CycleKind::Drill;
  } else if (name == "CYCLE82") {
    c.kind = CycleKind::DrillDwell;
    c.dwell = value(5);
  } else if (name == "CYCLE83") {
    // (RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI, _AXN, _MDEP, _VRT, _DTD,
    // _DIS1): constant pecks only (the first depth one peck below R), no dwell at the start,
    // feed factor 1; VARI 1: back to R and in again to _DIS1 above the last depth; VARI 0:
    // back off by _VRT.
    const double dam = std::abs(value(7));
    if (dam <= 0) return refuse("a degression DAM is needed (the peck depth)");
    double first = 0;
    if (arg(5))
      first = c.r - value(5);
    else if (arg(6))
      first = std::abs(value(6)) + std::abs(value(2));
    else
      first = dam;
    if (std::abs(first - dam) > 1e-6)
      return refuse("a first depth other than the degression DAM (only constant pecks)");
    if (arg(9) && value(9) != 0) return refuse("a dwell at the start point (DTS)");
    if (arg(10) && value(10) != 1) return refuse("a feed factor FRF other than 1");
    c.peck = dam;
    c.dwell = value(8);
    const int vari = static_cast<int>(std::lround(value(11)));
    if (vari == 1) {
      c.kind = CycleKind::Peck;
      if (!arg(16) || value(16) <= 0)
        return refuse("VARI=1 with the clearance _DIS1 left to the controller");
      c.peck_clearance = value(16);
    } else {
      c.kind = CycleKind::ChipBreak;
      if (!arg(14) || value(14) <= 0)
        return refuse("VARI=0 with the back-off _VRT left to the controller");
      c.peck_retract = value(14);
    }
  } else if (name == "CYCLE85" || name == "CYCLE89") {
    // CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF): the canonical bore feeds in and out at
    // one feed; CYCLE89 (.., DTB) feeds both ways at F.
    c.kind = name == "CYCLE85" ? CycleKind::Bore : CycleKind::BoreDwell;
    c.dwell = value(5);
    if (name == "CYCLE85") {
      if (!arg(6) || !arg(7) || std::abs(value(6) - value(7)) > 1e-9)
        return refuse("different feeds in and out (FFR, RFF)");
      converter_.set_feed(value(6));
    }
  } else {
    return refuse("not converted (CYCLE81, CYCLE82, CYCLE83, CYCLE85, CYCLE89 are)");
  }
  if (!converter_.started()) converter_.start(program_name_);
  return converter_.cycle(c, where(), col);
}

// Reads `NAME(arg, , arg)`: each argument an expression or empty. `pos` at the '('.
bool Interpreter::sinumerik_arguments(std::size_t& pos, std::vector<std::optional<double>>& out) {
  const std::string_view t = text();
  out.clear();
  ++pos;  // (
  while (true) {
    pos = skip_spaces(t, pos);
    if (pos >= t.size()) return error(column(pos), diag::Code::GcodeBadStatement, "')' missing");
    if (t[pos] == ')') {
      if (!out.empty() || (pos > 0 && t[pos - 1] == ',')) out.emplace_back();
      ++pos;
      return true;
    }
    if (t[pos] == ',') {
      out.emplace_back();
      ++pos;
      continue;
    }
    Value v;
    if (!evaluate_at(pos, Evaluator::Mode::Full, v)) return false;
    out.emplace_back(v.number);
    pos = skip_spaces(t, pos);
    if (pos < t.size() && t[pos] == ',') {
      ++pos;
      if (skip_spaces(t, pos) < t.size() && t[skip_spaces(t, pos)] == ')') {
        out.emplace_back();
        pos = skip_spaces(t, pos) + 1;
        return true;
      }
      continue;
    }
    if (pos < t.size() && t[pos] == ')') {
      ++pos;
      return true;
    }
    return error(column(pos), diag::Code::GcodeBadStatement, "',' or ')' expected");
  }
}

bool Interpreter::sinumerik_call(std::string_view name, std::size_t pos, std::uint32_t col) {
  const std::string_view t = text();
  std::vector<std::optional<double>> args;
  pos = skip_spaces(t, pos);
  if (pos < t.size() && t[pos] == '(' && !sinumerik_arguments(pos, args)) return false;
  long long repeat = 1;
  pos = skip_spaces(t, pos);
  if (pos < t.size() && t[pos] == 'P') {
    ++pos;
    Value v;
    if (!evaluate_at(pos, Evaluator::Mode::Primary, v)) return false;
    repeat = std::llround(v.number);
  }
  pos = skip_spaces(t, pos);
  if (pos < t.size())
    return error(column(pos), diag::Code::GcodeBadStatement,
                 "unexpected text after the call of " + std::string(name));
  const auto file = find_file(name);
  if (!file)
    return error(col, diag::Code::GcodeMissingProgram,
                 "subprogram " + std::string(name) + " (" + std::string(name) +
                     ".SPF) is neither in the program nor among the uploaded files");
  if (repeat <= 0) return true;
  if (!call(*file, Position{*file, 0, 1}, FrameKind::Sinumerik, std::string(name), repeat - 1,
            true))
    return false;
  frames_.back().args = std::move(args);
  return true;
}

bool Interpreter::sinumerik_statement(std::size_t pos, bool& handled) {
  handled = true;
  const std::string_view t = text();
  const std::uint32_t start_col = column(pos);
  // The archive header of a main program or subprogram: %_N_NAME_MPF.
  if (t.compare(pos, 4, "%_N_") == 0) {
    std::string_view name = t.substr(pos + 4);
    for (const std::string_view suffix : {"_MPF", "_SPF"})
      if (name.size() > suffix.size() && name.substr(name.size() - suffix.size()) == suffix)
        name.remove_suffix(suffix.size());
    if (!executed_any_ && frames_.size() == 1 && !titled_) {
      titled_ = true;
      program_name_ = std::string(name);
    }
    return true;
  }
  // A label: NAME: at the start.
  std::string_view first = identifier(t, pos);
  if (!first.empty() && pos + first.size() < t.size() && t[pos + first.size()] == ':' &&
      (pos + first.size() + 1 >= t.size() || t[pos + first.size() + 1] != '=')) {
    pos = skip_spaces(t, pos + first.size() + 1);
    if (pos >= t.size()) return true;
    first = identifier(t, pos);
  }
  const std::string keyword(first);
  const std::size_t after = skip_spaces(t, pos + keyword.size());
  Frame& frame = frames_.back();
  auto innermost = [&](LoopKind kind) -> Loop* {
    for (auto it = frame.loops.rbegin(); it != frame.loops.rend(); ++it)
      if (it->kind == kind) return &*it;
    return nullptr;
  };
  auto pop_innermost = [&](LoopKind kind) {
    for (auto it = frame.loops.rbegin(); it != frame.loops.rend(); ++it)
      if (it->kind == kind) {
        frame.loops.erase(std::next(it).base());
        return;
      }
  };
  auto push = [&](Loop loop) {
    if (frame.loops.size() >= options_.max_call_depth)
      return error(start_col, diag::Code::GcodeNestingLimit, "structures nested too deep");
    frame.loops.push_back(std::move(loop));
    return true;
  };
  const Position next_line_position{position_.source, cursor_.offset(), position_.line + 1};

  if (keyword == "GOTOF" || keyword == "GOTOB" || keyword == "GOTO" || keyword == "GOTOC") {
    const std::string_view label = identifier(t, after);
    if (label.empty())
      return error(column(after), diag::Code::GcodeBadStatement, keyword + " without its label");
    return sinumerik_jump(keyword, label, start_col);
  }
  if (keyword == "IF") {
    std::size_t p = after;
    Value v;
    if (!evaluate_at(p, Evaluator::Mode::Full, v)) return false;
    if (v.machine)
      return error(start_col, diag::Code::GcodeMachineMotion,
                   "the program's flow depends on a value only the machine knows");
    const bool c = v.number != 0;
    p = skip_spaces(t, p);
    const std::string_view jump_kw = identifier(t, p);
    if (jump_kw.rfind("GOTO", 0) == 0) {
      if (!c) return true;
      const std::string_view label = identifier(t, skip_spaces(t, p + jump_kw.size()));
      return sinumerik_jump(jump_kw, label, start_col);
    }
    if (p < t.size())
      return error(column(p), diag::Code::GcodeBadStatement,
                   "IF: unexpected text after the condition");
    if (c) return true;
    // To the ELSE (its branch runs) or the ENDIF.
    return sinumerik_skip(static_cast<Structure_>(Structure::If),
                          static_cast<Structure_>(Structure::EndIf),
                          static_cast<Structure_>(Structure::Else));
  }
  if (keyword == "ELSE")
    return sinumerik_skip(static_cast<Structure_>(Structure::If),
                          static_cast<Structure_>(Structure::EndIf), 0);
  if (keyword == "ENDIF") return true;
  if (keyword == "WHILE") {
    std::size_t p = after;
    bool c = false;
    Value v;
    if (!evaluate_at(p, Evaluator::Mode::Full, v)) return false;
    if (v.machine)
      return error(start_col, diag::Code::GcodeMachineMotion,
                   "the program's flow depends on a value only the machine knows");
    c = v.number != 0;
    Loop* loop = innermost(LoopKind::While);
    const bool again = loop && loop->start.offset == position_.offset;
    if (c) return again ? true : push({"WHILE", LoopKind::While, position_, 0, {}, -1, 0});
    if (again) pop_innermost(LoopKind::While);
    return sinumerik_skip(static_cast<Structure_>(Structure::While),
                          static_cast<Structure_>(Structure::EndWhile), 0);
  }
  if (keyword == "ENDWHILE") {
    Loop* loop = innermost(LoopKind::While);
    if (!loop) return error(start_col, diag::Code::GcodeBadFlow, "ENDWHILE without WHILE");
    jump(loop->start);
    return true;
  }
  if (keyword == "FOR") {
    // FOR var = start TO end: the counter is an R parameter or a DEF variable; steps of 1.
    std::size_t p = after;
    const std::string_view var = identifier(t, p);
    p = skip_spaces(t, p + var.size());
    if (var.empty() || p >= t.size() || t[p] != '=')
      return error(column(p), diag::Code::GcodeBadStatement, "FOR without its counter = start");
    ++p;
    Value from;
    if (!evaluate_at(p, Evaluator::Mode::Full, from)) return false;
    p = skip_spaces(t, p);
    if (identifier(t, p) != "TO")
      return error(column(p), diag::Code::GcodeBadStatement, "FOR without TO");
    p += 2;
    Value to;
    if (!evaluate_at(p, Evaluator::Mode::Full, to)) return false;
    Loop loop{"FOR", LoopKind::For, next_line_position, 0, std::string(var), -1, to.number};
    if (var.size() > 1 && var[0] == 'R' && std::all_of(var.begin() + 1, var.end(), is_digit)) {
      std::from_chars(var.data() + 1, var.data() + var.size(), loop.counter_number);
      loop.counter.clear();
    }
    if (!sinumerik_set(loop.counter, loop.counter_number, from, start_col)) return false;
    if (from.number > to.number)
      return sinumerik_skip(static_cast<Structure_>(Structure::For),
                            static_cast<Structure_>(Structure::EndFor), 0);
    return push(std::move(loop));
  }
  if (keyword == "ENDFOR") {
    Loop* loop = innermost(LoopKind::For);
    if (!loop) return error(start_col, diag::Code::GcodeBadFlow, "ENDFOR without FOR");
    Value v;
    if (loop->counter.empty()) {
      v = parameters_.get(loop->counter_number).value;
    } else {
      v = parameters_.get_named(loop->counter).value_or(Value::of(0));
    }
    v.number += 1;
    if (!sinumerik_set(loop->counter, loop->counter_number, v, start_col)) return false;
    if (v.number <= loop->end + 1e-9) {
      jump(loop->start);
    } else {
      pop_innermost(LoopKind::For);
    }
    return true;
  }
  if (keyword == "REPEAT")
    return push({"REPEAT", LoopKind::Repeat, next_line_position, 0, {}, -1, 0});
  if (keyword == "UNTIL") {
    Loop* loop = innermost(LoopKind::Repeat);
    if (!loop) return error(start_col, diag::Code::GcodeBadFlow, "UNTIL without REPEAT");
    std::size_t p = after;
    Value v;
    if (!evaluate_at(p, Evaluator::Mode::Full, v)) return false;
    if (v.machine)
      return error(start_col, diag::Code::GcodeMachineMotion,
                   "the program's flow depends on a value only the machine knows");
    if (v.number == 0)
      jump(loop->start);
    else
      pop_innermost(LoopKind::Repeat);
    return true;
  }
  if (keyword == "LOOP") return push({"LOOP", LoopKind::Loop, next_line_position, 0, {}, -1, 0});
  if (keyword == "ENDLOOP") {
    Loop* loop = innermost(LoopKind::Loop);
    if (!loop) return error(start_col, diag::Code::GcodeBadFlow, "ENDLOOP without LOOP");
    jump(loop->start);
    return true;
  }
  if (keyword == "DEF") {
    // DEF REAL A=1, B / DEF INT N: numeric variables of this program (or subprogram call).
    std::size_t p = after;
    const std::string_view type = identifier(t, p);
    if (type != "REAL" && type != "INT" && type != "BOOL") {
      warn(start_col, diag::Code::GcodeIgnored,
           "DEF " + std::string(type) + ": only REAL, INT and BOOL variables are read");
      return true;
    }
    p = skip_spaces(t, p + type.size());
    while (p < t.size()) {
      const std::string_view name = identifier(t, p);
      if (name.empty())
        return error(column(p), diag::Code::GcodeBadStatement, "DEF: a name expected");
      p = skip_spaces(t, p + name.size());
      Value v = Value::of(0);
      if (p < t.size() && t[p] == '=') {
        ++p;
        if (!evaluate_at(p, Evaluator::Mode::Full, v)) return false;
        p = skip_spaces(t, p);
      }
      if (type == "INT") v.number = std::round(v.number);
      parameters_.set_named(name, v);
      if (p < t.size() && t[p] == ',')
        p = skip_spaces(t, p + 1);
      else if (p < t.size())
        return error(column(p), diag::Code::GcodeBadStatement, "DEF: ',' expected");
    }
    return true;
  }
  if (keyword == "PROC") {
    // PROC NAME(REAL A, INT B=2, VAR REAL C): the arguments of the call that brought us here.
    std::size_t p = after + identifier(t, after).size();
    p = skip_spaces(t, p);
    const std::vector<std::optional<double>>& args = frames_.back().args;
    if (p < t.size() && t[p] == '(') {
      ++p;
      std::size_t index = 0;
      while (p < t.size() && t[p] != ')') {
        p = skip_spaces(t, p);
        std::string_view word = identifier(t, p);
        if (word == "VAR") {
          p = skip_spaces(t, p + word.size());
          word = identifier(t, p);
        }
        if (word == "REAL" || word == "INT" || word == "BOOL") {
          p = skip_spaces(t, p + word.size());
          word = identifier(t, p);
        }
        if (word.empty())
          return error(column(p), diag::Code::GcodeBadStatement, "PROC: a parameter name expected");
        p = skip_spaces(t, p + word.size());
        Value v = Value::of(0);
        if (p < t.size() && t[p] == '=') {
          ++p;
          if (!evaluate_at(p, Evaluator::Mode::Full, v)) return false;
          p = skip_spaces(t, p);
        }
        if (index < args.size() && args[index]) v = Value::of(*args[index]);
        parameters_.set_named(word, v);
        ++index;
        if (p < t.size() && t[p] == ',') ++p;
      }
    }
    return true;
  }
  if (keyword == "RET") {
    if (frames_.size() < 2) {
      converter_.stop(Action::ProgramEnd);
      done_ = true;
      return true;
    }
    return_from_call(std::nullopt, std::nullopt);
    return true;
  }
  if (keyword == "MSG") {
    // MSG("text" << R1 << "more") shows a message; MSG() clears it.
    std::size_t p = after;
    if (p >= t.size() || t[p] != '(')
      return error(column(p), diag::Code::GcodeBadStatement, "MSG without (");
    ++p;
    std::string message;
    while (p < t.size() && t[p] != ')') {
      p = skip_spaces(t, p);
      if (t[p] == '"') {
        const std::size_t close = t.find('"', p + 1);
        if (close == std::string_view::npos)
          return error(column(p), diag::Code::GcodeUnclosedComment, "string not closed");
        // The string as written (the normaliser kept its case).
        message += std::string(line_->raw.substr(line_->column(p), close - p - 1));
        p = close + 1;
      } else if (t.compare(p, 2, "<<") == 0) {
        p += 2;
      } else if (t[p] == ')') {
        break;
      } else {
        Value v;
        if (!evaluate_at(p, Evaluator::Mode::FullToSpace, v)) return false;
        char buf[32];
        const int n = std::snprintf(buf, sizeof buf, "%g", v.number);
        message.append(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
      }
      p = skip_spaces(t, p);
    }
    if (!message.empty()) {
      if (!converter_.started()) converter_.start(program_name_);
      converter_.message(message);
    }
    return true;
  }
  if (keyword == "STOPRE" || keyword == "SAVE" || keyword == "DISPLOF" || keyword == "DISPLON" ||
      keyword == "SBLOF" || keyword == "SBLON")
    return true;
  if (keyword == "MCALL") {
    // MCALL CYCLE81(...): the cycle runs after every positioning block until MCALL alone.
    const std::string_view cycle = identifier(t, after);
    if (cycle.empty()) {
      mcall_.reset();
      return true;
    }
    std::size_t p = skip_spaces(t, after + cycle.size());
    std::vector<std::optional<double>> args;
    if (p >= t.size() || t[p] != '(' || !sinumerik_arguments(p, args))
      return p >= t.size() || t[p] != '(' ? error(column(p), diag::Code::GcodeBadStatement,
                                                  "MCALL: the cycle's (arguments) expected")
                                          : false;
    mcall_ = ModalCall{std::string(cycle), std::move(args), start_col};
    return true;
  }
  if (keyword.rfind("CYCLE", 0) == 0 && after < t.size() && t[after] == '(') {
    std::size_t p = after;
    std::vector<std::optional<double>> args;
    if (!sinumerik_arguments(p, args)) return false;
    if (keyword == "CYCLE832") {
      warn(start_col, diag::Code::GcodeIgnored, "CYCLE832 sets the machine's high-speed mode");
      return true;
    }
    return sinumerik_cycle(keyword, args, start_col);
  }
  if (keyword == "CALL" || keyword == "PCALL") {
    std::size_t p = after;
    if (p < t.size() && t[p] == '"') {
      const std::size_t close = t.find('"', p + 1);
      if (close == std::string_view::npos)
        return error(column(p), diag::Code::GcodeUnclosedComment, "string not closed");
      const std::string name(t.substr(p + 1, close - p - 1));
      return sinumerik_call(name, close + 1, start_col);
    }
    const std::string_view name = identifier(t, p);
    return sinumerik_call(name, p + name.size(), start_col);
  }
  if (keyword.size() >= 2 && keyword[0] == 'L' &&
      std::all_of(keyword.begin() + 1, keyword.end(), is_digit))
    return sinumerik_call(keyword, pos + keyword.size(), start_col);
  // A named-variable assignment: NAME = expression (R parameters are words' business).
  if (!keyword.empty() && after < t.size() && t[after] == '=' &&
      dialect_.word(keyword) == kNoWord &&
      !(keyword.size() > 1 && keyword[0] == 'R' &&
        std::all_of(keyword.begin() + 1, keyword.end(), is_digit))) {
    std::size_t p = pos;
    while (p < t.size()) {
      const std::string_view name = identifier(t, p);
      std::size_t q = skip_spaces(t, p + name.size());
      if (name.empty() || q >= t.size() || t[q] != '=') break;
      if (!parameters_.exists_named(name))
        return error(column(p), diag::Code::GcodeBadParameter,
                     "variable " + std::string(name) + " assigned before its DEF");
      ++q;
      Value v;
      if (!evaluate_at(q, Evaluator::Mode::FullToSpace, v)) return false;
      parameters_.set_named(name, v);
      p = skip_spaces(t, q);
    }
    if (p < t.size())
      return error(column(p), diag::Code::GcodeBadStatement, "unexpected text after an assignment");
    return true;
  }
  // A subprogram called by its name: an identifier that is no word and no keyword.
  if (keyword.size() >= 2 && dialect_.word(keyword) == kNoWord && !is_keyword(keyword) &&
      (after >= t.size() || t[after] == '(' || t[after] == 'P') &&
      !(keyword[0] == 'R' && std::all_of(keyword.begin() + 1, keyword.end(), is_digit)) &&
      !(keyword.size() >= 2 && is_letter(keyword[0]) && is_digit(keyword[1]) &&
        dialect_.letter_known[letter_word(keyword[0])]))
    return sinumerik_call(keyword, pos + keyword.size(), start_col);
  // Words.
  handled = false;
  if (pos != 0) {
    // A label stood in front: the rest of the block is words.
    handled = true;
    block_.clear();
    if (!read_words(pos, block_)) return false;
    if (!apply_assignments(block_)) return false;
    execute_block(block_);
  }
  return true;
}

bool Interpreter::is_keyword(std::string_view name) const {
  return std::any_of(dialect_.keywords.begin(), dialect_.keywords.end(),
                     [&](const auto& k) { return k.first == name; });
}

bool Interpreter::sinumerik_set(const std::string& name, double number, Value v,
                                std::uint32_t col) {
  if (name.empty()) return assign(Assignment{false, number, {}, v, col});
  if (!parameters_.exists_named(name))
    return error(col, diag::Code::GcodeBadParameter, "variable " + name + " used before its DEF");
  parameters_.set_named(name, v);
  return true;
}

// After a block that moved, a modal cycle (MCALL) runs at the new position.
void Interpreter::run_modal_call(const Block& b) {
  if (!mcall_) return;
  bool moved = false;
  for (const char letter : {'X', 'Y', 'Z'}) moved = moved || b.has(letter_word(letter));
  if (!moved) return;
  (void)sinumerik_cycle(mcall_->name, mcall_->args, mcall_->column);
}

}  // namespace ncpost::gcode::detail
