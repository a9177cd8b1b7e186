#include "interpreter.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>

#include "klartext.hpp"

namespace ncpost::gcode::detail {

namespace {

// How often the cancel flag is polled (in lines).
constexpr std::uint64_t kCancelPollLines = 256;

// The number of a label written as digits, without leading zeros ("0010" → "10").
std::string number_key(double number) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<long long>(std::llround(number)));
  return std::string(buf, r.ptr);
}

bool starts_with(std::string_view text, std::size_t pos, std::string_view word) {
  return pos <= text.size() && text.compare(pos, word.size(), word) == 0;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string upper_copy(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = upper(c);
  return out;
}

// A file's name without folder and extension, upper case: what calls name it by.
std::string stem_of(std::string_view name) {
  if (const auto slash = name.find_last_of("/\\"); slash != std::string_view::npos)
    name.remove_prefix(slash + 1);
  if (const auto dot = name.rfind('.'); dot != std::string_view::npos && dot > 0)
    name = name.substr(0, dot);
  return upper_copy(name);
}

// Whether a line holds G65 or G66 (any case), whose letters are a macro's arguments.
bool calls_macro(std::string_view line) {
  for (std::size_t i = 0; i + 2 < line.size(); ++i)
    if (upper(line[i]) == 'G' && line[i + 1] == '6' && (line[i + 2] == '5' || line[i + 2] == '6'))
      return true;
  return false;
}

// Whether the text (outside comments) has a rotary axis word: then every canonical motion
// carries A, B, C (docs/canon.md: a program's motions either all have them or none does).
// One pass over the bytes, which looks closer only at A, B, C and comment starts.
bool has_rotary_words(std::string_view text, const Dialect& dialect) {
  for (const char letter : {'A', 'B', 'C'}) {
    const WordId w = letter_word(letter);
    if (!dialect.letter_known[w] || dialect.words[w].kind != WordKind::Axis) return false;
  }
  enum : std::uint8_t { Other, Letter, Paren, Semicolon };
  std::array<std::uint8_t, 256> kind{};
  for (const char c : {'A', 'B', 'C', 'a', 'b', 'c'}) kind[static_cast<unsigned char>(c)] = Letter;
  if (dialect.parenthesis_comments) kind['('] = Paren;
  if (dialect.semicolon_comments) kind[';'] = Semicolon;
  const char* const s = text.data();
  const std::size_t n = text.size();
  const auto line_end = [&](std::size_t from) {
    const void* nl = std::memchr(s + from, '\n', n - from);
    return nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - s) : n;
  };
  // Sixteen bytes at a time (vector extensions of GCC and Clang: SSE2 on x86-64): most
  // stretches of a program hold none of the bytes looked at. Lower-casing by OR 0x20 may also
  // flag a few control bytes, which the byte loop then just passes.
  using Bytes = unsigned char __attribute__((vector_size(16)));
  const auto any_looked_at = [](const char* p) {
    Bytes bytes;
    std::memcpy(&bytes, p, sizeof bytes);
    const Bytes lower = bytes | static_cast<unsigned char>(0x20);
    const auto hits =
        (lower == 'a') | (lower == 'b') | (lower == 'c') | (bytes == '(') | (bytes == ';');
    std::uint64_t halves[2];
    std::memcpy(halves, &hits, sizeof halves);
    return (halves[0] | halves[1]) != 0;
  };
  std::size_t i = 0;
  while (i < n) {
    if (i + 16 <= n && !any_looked_at(s + i)) {
      i += 16;
      continue;
    }
    const std::size_t stop = std::min(n, i + 16);
    for (; i < stop; ++i) {
      const std::uint8_t k = kind[static_cast<unsigned char>(s[i])];
      if (k == Other) continue;
      if (k == Paren) {
        // A comment to its ')' (or the line's end, where an unclosed one ends).
        while (i + 1 < n && s[i + 1] != ')' && s[i + 1] != '\n') ++i;
        if (i + 1 < n && s[i + 1] == ')') ++i;
        continue;
      }
      if (k == Semicolon) {
        i = line_end(i) - 1;  // the loop's ++i steps onto the '\n'
        continue;
      }
      if (i > 0 && (is_letter(s[i - 1]) || s[i - 1] == '_' || s[i - 1] == '$')) continue;
      std::size_t j = i + 1;
      while (j < n && (s[j] == ' ' || s[j] == '\t')) ++j;
      if (j >= n) continue;
      const char v = s[j];
      if (!(is_digit(v) || v == '-' || v == '+' || v == '.' || v == '#' || v == '[' || v == '='))
        continue;
      // A macro call's letters are its arguments (G65 P9010 A15.), not axes: its line is
      // skipped.
      std::size_t begin = i;
      while (begin > 0 && s[begin - 1] != '\n') --begin;
      const std::size_t end = line_end(i);
      if (!calls_macro(text.substr(begin, end - begin))) return true;
      i = end;
    }
  }
  return false;
}

}  // namespace

std::uint32_t long_word_initials(const Dialect& dialect) noexcept {
  std::uint32_t initials = 0;
  for (std::size_t w = 26; w < dialect.words.size(); ++w) {
    const std::string& name = dialect.words[w].name;
    if (name.size() > 1 && name[0] >= 'A' && name[0] <= 'Z') initials |= 1u << (name[0] - 'A');
  }
  return initials;
}

Interpreter::Interpreter(std::string_view text, const Dialect& dialect, canon::Sink& sink,
                         const ReadOptions& options, BlockObserver* observer)
    : dialect_(dialect),
      options_(options),
      observer_(observer),
      report_(options.max_errors),
      sink_(sink),
      converter_(dialect, sink, report_, options),
      parameters_(dialect.parameters, converter_),
      evaluator_(dialect, parameters_, options.max_expression_depth) {
  sources_.push_back(Source{options.program_name, text, std::nullopt, std::nullopt});
  bool rotary = has_rotary_words(text, dialect);
  for (const auto& f : options.subprograms) {
    sources_.push_back(Source{f.name, f.text, std::nullopt, std::nullopt});
    rotary = rotary || has_rotary_words(f.text, dialect);
  }
  converter_.set_uses_rotary(rotary);
  cursor_ = LineCursor(text);
  frames_.push_back(Frame{});
  program_name_ = options.program_name;
}

Interpreter::~Interpreter() = default;

ReadResult Interpreter::result() && {
  ReadResult r;
  r.diagnostics = std::move(report_).take();
  r.calls = converter_.calls();
  r.cancelled = cancelled_;
  return r;
}

// ---- Diagnostics -----------------------------------------------------------------------------

bool Interpreter::error(std::uint32_t col, diag::Code code, std::string message) {
  if (!report_.add(sources_[position_.source].name, code, line_->number, col, std::move(message)))
    done_ = true;
  return false;
}

void Interpreter::warn(std::uint32_t col, diag::Code code, std::string message) {
  report_.add(sources_[position_.source].name, code, line_->number, col, std::move(message));
}

void Interpreter::report_eval_error() {
  const EvalError& e = evaluator_.error();
  error(column(e.pos), e.code, e.message);
}

void Interpreter::warn_machine_reads() {
  auto& reads = evaluator_.machine_reads();
  for (const MachineRead& r : reads) {
    char buf[32];
    const int n = std::snprintf(buf, sizeof buf, "%g", r.assumed);
    warn(0, diag::Code::GcodeMachineValue,
         r.name + " is known only to the machine; read as the assumed " +
             std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0));
  }
  reads.clear();
}

bool Interpreter::evaluate_at(std::size_t& pos, Evaluator::Mode mode, Value& out) {
  const bool ok = evaluator_.evaluate(text(), pos, mode, out);
  warn_machine_reads();
  if (!ok) report_eval_error();
  return ok;
}

bool Interpreter::evaluate_condition(std::size_t& pos, bool& result) {
  Value v;
  if (!evaluate_at(pos, Evaluator::Mode::Primary, v)) return false;
  if (v.machine)
    return error(column(pos), diag::Code::GcodeMachineMotion,
                 "the program's flow depends on a value only the machine knows");
  result = v.number != 0 && !v.vacant;
  return true;
}

// ---- Lines -----------------------------------------------------------------------------------

bool Interpreter::next_line() {
  while (!done_) {
    if (cursor_.at_end()) {
      if (frames_.size() > 1) {
        const Frame& f = frames_.back();
        // A subprogram file may end without its return (FANUC files often do): an implicit
        // return, as the controllers make it.
        if (f.kind == FrameKind::OWord) {
          line_->number = position_.line;
          error(0, diag::Code::GcodeBadFlow,
                "end of file inside subprogram " + f.label + " (no endsub)");
          done_ = true;
          return false;
        }
        return_from_call(std::nullopt, std::nullopt);
        continue;
      }
      return false;
    }
    position_.offset = cursor_.offset();
    std::uint32_t number = 0;
    const std::string_view raw = cursor_.next(number);
    position_.line = number;
    if (++steps_ > options_.max_steps) {
      set_unread_line(raw, number);
      error(0, diag::Code::GcodeStepLimit,
            "more than " + std::to_string(options_.max_steps) +
                " blocks evaluated (ReadOptions::max_steps): an endless loop?");
      done_ = true;
      return false;
    }
    if (options_.cancel && steps_ % kCancelPollLines == 0 &&
        options_.cancel->load(std::memory_order_relaxed)) {
      cancelled_ = true;
      done_ = true;
      return false;
    }
    if (raw.size() > options_.max_line_length) {
      set_unread_line(raw.substr(0, 0), number);
      error(1, diag::Code::GcodeLineTooLong,
            "line of " + std::to_string(raw.size()) + " bytes (ReadOptions::max_line_length is " +
                std::to_string(options_.max_line_length) + ")");
      continue;
    }
    load_line(raw, number);
    return true;
  }
  return false;
}

void Interpreter::load_line(std::string_view raw, std::uint32_t number) {
  if (raw.size() > kCachedLineMax) {
    line_ = &spare_line_;
    normalise(raw, lexing_, spare_line_);
  } else {
    const std::uint64_t mixed =
        (static_cast<std::uint64_t>(position_.offset) + position_.source) * 0x9E3779B97F4A7C15ull;
    CachedLine& slot = line_cache_[(mixed >> 32) % kLineCacheSize];
    if (slot.source != position_.source || slot.offset != position_.offset) {
      slot.source = position_.source;
      slot.offset = position_.offset;
      normalise(raw, lexing_, slot.line);
    }
    line_ = &slot.line;
  }
  line_->number = number;
}

void Interpreter::set_unread_line(std::string_view raw, std::uint32_t number) {
  line_ = &spare_line_;
  normalise({}, lexing_, spare_line_);
  spare_line_.raw = raw;
  spare_line_.number = number;
}

void Interpreter::detach_line() {
  if (line_ == &spare_line_) return;
  spare_line_ = *line_;
  line_ = &spare_line_;
}

void Interpreter::jump(const Position& p) {
  position_.source = p.source;
  cursor_ = LineCursor(sources_[p.source].text);
  cursor_.seek(p.offset, p.line);
}

// Reads lines after the current one until an O-word line `o<label> <keyword>` with one of
// `keywords`; leaves it in line_ (the cursor after it). False, with an error, when the file
// ends first.
bool Interpreter::skip_to(const std::vector<std::string_view>& keywords, std::string_view label,
                          std::string_view& found) {
  // O-word lines `o<label> <keyword>`.
  const std::uint32_t from_line = line_->number;
  const std::string from_file = sources_[position_.source].name;
  while (!done_) {
    if (cursor_.at_end()) break;
    position_.offset = cursor_.offset();
    std::uint32_t number = 0;
    const std::string_view raw = cursor_.next(number);
    position_.line = number;
    if (++steps_ > options_.max_steps) {
      set_unread_line(raw, number);
      error(0, diag::Code::GcodeStepLimit,
            "more than " + std::to_string(options_.max_steps) +
                " blocks evaluated (ReadOptions::max_steps)");
      done_ = true;
      return false;
    }
    if (raw.size() > options_.max_line_length) {
      set_unread_line(raw.substr(0, 0), number);
      continue;
    }
    load_line(raw, number);
    const std::string_view t = line_->text;
    std::size_t pos = 0;
    if (pos < t.size() && t[pos] == 'N') {
      ++pos;
      while (pos < t.size() && (is_digit(t[pos]) || t[pos] == '.' || t[pos] == ' ')) ++pos;
    }
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (pos >= t.size() || t[pos] != 'O') continue;
    std::size_t p = pos;
    std::string l;
    // A label that does not parse is not ours.
    if (!read_o_label(t, p, l)) continue;
    if (l != label) continue;
    while (p < t.size() && t[p] == ' ') ++p;
    for (const std::string_view k : keywords) {
      if (starts_with(t, p, k) && (p + k.size() >= t.size() || !is_letter(t[p + k.size()]))) {
        found = k;
        return true;
      }
    }
  }
  report_.add(
      from_file, diag::Code::GcodeBadFlow, from_line, 0,
      "o" + std::string(label) + ": its end (" + std::string(keywords.back()) + ") is missing");
  done_ = true;
  return false;
}

// ---- Subprograms -----------------------------------------------------------------------------

std::optional<std::size_t> Interpreter::find_file(std::string_view name) {
  // By the name without folder and extension, case-insensitive.
  const std::string wanted = upper_copy(name);
  for (std::size_t i = 1; i < sources_.size(); ++i)
    if (stem_of(sources_[i].name) == wanted) return i;
  return std::nullopt;
}

void Interpreter::index_subprograms(Source& s) {
  s.subprograms.emplace();
  LineCursor c(s.text);
  Line line;
  int percents = 0;
  while (!c.at_end()) {
    const std::size_t offset = c.offset();
    std::uint32_t number = 0;
    const std::string_view raw = c.next(number);
    if (raw.size() > options_.max_line_length) continue;
    normalise(raw, lexing_, line);
    const std::string_view t = line.text;
    std::size_t pos = 0;
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (pos < t.size() && t[pos] == 'N') {
      ++pos;
      while (pos < t.size() && (is_digit(t[pos]) || t[pos] == '.')) ++pos;
    }
    if (pos >= t.size()) continue;
    // Nothing after the second '%' is part of the file's program.
    if (dialect_.percent_delimits && t[pos] == '%' && ++percents == 2) break;
    const Position after{static_cast<std::size_t>(&s - sources_.data()), c.offset(), number + 1};
    (void)offset;
    if (t[pos] == 'O' || ((t[pos] == ':' || (t[pos] == '%' && !dialect_.percent_delimits)) &&
                          dialect_.flow.fanuc_subprograms)) {
      std::size_t p = pos;
      std::string label;
      if (t[p] == ':' || t[p] == '%') {
        ++p;
        std::size_t q = p;
        while (q < t.size() && is_digit(t[q])) ++q;
        if (q == p) continue;
        double v = 0;
        std::from_chars(t.data() + p, t.data() + q, v);
        label = number_key(v);
        p = q;
      } else if (!read_o_label(t, p, label)) {
        continue;
      }
      while (p < t.size() && t[p] == ' ') ++p;
      const bool sub = starts_with(t, p, "SUB") && (p + 3 >= t.size() || !is_letter(t[p + 3]));
      const bool bare = p >= t.size();
      // A subroutine file holds its one subroutine, named as the file: LinuxCNC does not see
      // others defined after it there.
      if (sub && dialect_.flow.o_words &&
          (&s == &sources_[0] || label == "<" + stem_of(s.name) + ">" || label == stem_of(s.name)))
        s.subprograms->try_emplace("o:" + label, after);
      if (bare && dialect_.flow.fanuc_subprograms && label.front() != '<')
        s.subprograms->try_emplace("f:" + label, after);
    }
  }
}

std::optional<Position> Interpreter::find_fanuc_program(double number, std::size_t& source) {
  const std::string key = "f:" + number_key(number);
  auto look = [&](std::size_t i) -> std::optional<Position> {
    Source& s = sources_[i];
    if (!s.subprograms) index_subprograms(s);
    const auto it = s.subprograms->find(key);
    if (it == s.subprograms->end()) return std::nullopt;
    source = i;
    return it->second;
  };
  if (auto p = look(position_.source)) return p;
  if (auto p = look(0)) return p;
  // A file of its own: O1234.nc, 1234, o1234.ngc ...
  for (std::size_t i = 1; i < sources_.size(); ++i) {
    const std::string stem = stem_of(sources_[i].name);
    std::string_view n = stem;
    if (!n.empty() && n.front() == 'O') n.remove_prefix(1);
    if (n.empty() || !std::all_of(n.begin(), n.end(), [](char c) { return is_digit(c); })) continue;
    double v = 0;
    std::from_chars(n.data(), n.data() + n.size(), v);
    if (number_key(v) != number_key(number)) continue;
    if (auto p = look(i)) return p;
    source = i;
    return Position{i, 0, 1};
  }
  return std::nullopt;
}

bool Interpreter::call(std::size_t source, const Position& target, FrameKind kind,
                       std::string label, long long repeat, bool locals) {
  if (frames_.size() >= options_.max_call_depth)
    return error(0, diag::Code::GcodeNestingLimit,
                 "subprogram calls nested deeper than " + std::to_string(options_.max_call_depth) +
                     " (ReadOptions::max_call_depth)");
  Frame f;
  f.kind = kind;
  f.label = std::move(label);
  f.back = Position{position_.source, cursor_.offset(), position_.line + 1};
  f.start = target;
  f.start.source = source;
  f.repeat = repeat;
  f.locals = locals;
  if (locals) parameters_.push_frame();
  frames_.push_back(std::move(f));
  jump(frames_.back().start);
  return true;
}

void Interpreter::return_from_call(std::optional<double> value,
                                   std::optional<std::string> label_to_go) {
  Frame& f = frames_.back();
  if (f.repeat > 0) {
    --f.repeat;
    f.loops.clear();
    jump(f.start);
    return;
  }
  if (f.locals) parameters_.pop_frame();
  const Position back = f.back;
  frames_.pop_back();
  converter_.set_return_value(value);
  jump(back);
  if (label_to_go) {
    const Position* p = find_label(back.source, *label_to_go);
    if (!p) {
      error(0, diag::Code::GcodeBadFlow, "M99 P: no block N" + *label_to_go + " in the caller");
      return;
    }
    jump(*p);
  }
}

void Interpreter::index_labels(Source& s) {
  s.labels.emplace();
  LineCursor c(s.text);
  Line line;
  const std::size_t index = static_cast<std::size_t>(&s - sources_.data());
  while (!c.at_end()) {
    const std::size_t offset = c.offset();
    std::uint32_t number = 0;
    const std::string_view raw = c.next(number);
    if (raw.size() > options_.max_line_length) continue;
    normalise(raw, lexing_, line);
    const std::string_view t = line.text;
    std::size_t pos = 0;
    while (pos < t.size() && t[pos] == ' ') ++pos;
    const Position here{index, offset, number};
    if (pos < t.size() && t[pos] == 'N' && pos + 1 < t.size() && is_digit(t[pos + 1])) {
      std::size_t q = pos + 1;
      while (q < t.size() && is_digit(t[q])) ++q;
      double v = 0;
      std::from_chars(t.data() + pos + 1, t.data() + q, v);
      s.labels->try_emplace("N" + number_key(v), here);
      pos = q;
      while (pos < t.size() && t[pos] == ' ') ++pos;
    }
    // Heidenhain labels: [block number] LBL n / LBL "name".
    if (dialect_.syntax == Syntax::Klartext) {
      while (pos < t.size() && is_digit(t[pos])) ++pos;
      while (pos < t.size() && t[pos] == ' ') ++pos;
      if (t.compare(pos, 4, "LBL ") == 0) {
        std::size_t q = pos + 4;
        while (q < t.size() && t[q] == ' ') ++q;
        std::size_t e = q;
        while (e < t.size() && t[e] != ' ') ++e;
        s.labels->try_emplace("LBL" + std::string(t.substr(q, e - q)), here);
      }
      continue;
    }
    // Sinumerik labels: NAME: at the start of the block.
    if (dialect_.flow.sinumerik && pos < t.size() && (is_letter(t[pos]) || t[pos] == '_')) {
      std::size_t q = pos;
      while (q < t.size() && (is_letter(t[q]) || is_digit(t[q]) || t[q] == '_')) ++q;
      if (q < t.size() && t[q] == ':' && (q + 1 >= t.size() || t[q + 1] != '=')) {
        s.labels->try_emplace(std::string(t.substr(pos, q - pos)), here);
      }
    }
  }
}

const Position* Interpreter::find_label(std::size_t source, std::string_view label) {
  Source& s = sources_[source];
  if (!s.labels) index_labels(s);
  const auto it = s.labels->find(label);
  return it == s.labels->end() ? nullptr : &it->second;
}

// ---- Blocks ----------------------------------------------------------------------------------

bool Interpreter::read_word_value(std::size_t& pos, Value& value, bool& integer_literal,
                                  bool equals) {
  const std::string_view t = text();
  // The common case first: a plain number, without the evaluator.
  std::size_t p = pos;
  double sign = 1;
  if (p < t.size() && (t[p] == '-' || t[p] == '+') && p + 1 < t.size() &&
      (is_digit(t[p + 1]) || t[p + 1] == '.')) {
    sign = t[p] == '-' ? -1 : 1;
    ++p;
  }
  if (p < t.size() && (is_digit(t[p]) || t[p] == '.')) {
    double v = 0;
    bool integer = false;
    if (!Evaluator::scan_number(t, p, v, integer))
      return error(column(pos), diag::Code::GcodeBadNumber, "malformed number");
    // Followed by an operator: an expression after all (Sinumerik X=10*R1).
    const bool more = equals && p < t.size() && t[p] != ' ';
    if (!more) {
      value = Value::of(sign * v);
      integer_literal = integer;
      pos = p;
      return true;
    }
  }
  integer_literal = false;
  if (pos >= t.size() || (t[pos] == ' ' && !equals))
    return error(column(pos), diag::Code::GcodeBadNumber, "a word without its value");
  return evaluate_at(pos, equals ? Evaluator::Mode::FullToSpace : Evaluator::Mode::Primary, value);
}

bool Interpreter::read_words(std::size_t pos, Block& b) {
  const std::string_view t = text();
  b.line = line_->number;
  b.first_column = column(pos);
  const ParameterStyle style = dialect_.parameters.style;
  while (pos < t.size()) {
    const char c = t[pos];
    if (c == ' ') {
      ++pos;
      continue;
    }
    const std::size_t start = pos;
    if ((c == '#' && style == ParameterStyle::Hash) ||
        (style == ParameterStyle::R && c == 'R' && pos + 1 < t.size() && is_digit(t[pos + 1]) &&
         t.find('=', pos) != std::string_view::npos && [&] {
           std::size_t q = pos + 1;
           while (q < t.size() && is_digit(t[q])) ++q;
           return q < t.size() && t[q] == '=';
         }())) {
      // A parameter assignment: #n = value, #<name> = value, #[expr] = value, Rn = value.
      Assignment a;
      a.column = column(start);
      ++pos;
      if (style == ParameterStyle::Hash && pos < t.size() && t[pos] == '<' &&
          dialect_.parameters.named) {
        const std::size_t close = t.find('>', pos);
        if (close == std::string_view::npos)
          return error(column(pos), diag::Code::GcodeBadParameter,
                       "named parameter not terminated by '>'");
        a.named = true;
        a.name.assign(t.substr(pos + 1, close - pos - 1));
        pos = close + 1;
      } else {
        Value index;
        if (!evaluate_at(pos, Evaluator::Mode::Primary, index)) return false;
        if (index.vacant)
          return error(a.column, diag::Code::GcodeBadParameter, "#<vacant> as a parameter number");
        a.number = index.number;
      }
      while (pos < t.size() && t[pos] == ' ') ++pos;
      if (pos >= t.size() || t[pos] != '=')
        return error(column(pos), diag::Code::GcodeBadParameter,
                     "expected '=' after a parameter at the start of a setting");
      ++pos;
      if (!evaluate_at(pos, Evaluator::Mode::Full, a.value)) return false;
      if (!take_assignment(b, std::move(a))) return false;
      continue;
    }
    // Sinumerik: a DEF variable set among the words (R1=10 DEPTH=-1).
    if ((style == ParameterStyle::R || style == ParameterStyle::Q) && is_letter(c)) {
      std::size_t end = pos;
      while (end < t.size() && (is_letter(t[end]) || is_digit(t[end]) || t[end] == '_')) ++end;
      const std::string_view name = t.substr(pos, end - pos);
      if (end < t.size() && t[end] == '=' && name.size() > 1 && dialect_.word(name) == kNoWord &&
          parameters_.exists_named(name)) {
        Assignment a;
        a.named = true;
        a.name = std::string(name);
        a.column = column(start);
        pos = end + 1;
        if (!evaluate_at(pos, Evaluator::Mode::FullToSpace, a.value)) return false;
        if (!take_assignment(b, std::move(a))) return false;
        continue;
      }
    }
    // A code spelled as a word (Sinumerik CIP, BSPLINE, SUPA, TRANS, DIAMON, G-group keywords).
    if (!dialect_.keywords.empty() && is_letter(c)) {
      bool keyword = false;
      for (const auto& [name, index] : dialect_.keywords) {
        if (!starts_with(t, pos, name)) continue;
        const std::size_t end = pos + name.size();
        if (end < t.size() &&
            (is_letter(t[end]) || is_digit(t[end]) || t[end] == '_' || t[end] == '='))
          continue;
        const CodeSpec& spec = dialect_.codes[static_cast<std::size_t>(index)];
        b.codes.push_back({&spec, 0, false, column(start)});
        if (observer_) observer_->word(name, name, 0, column(start));
        pos = end;
        keyword = true;
        break;
      }
      if (keyword) continue;
    }
    WordId id = kNoWord;
    if (c == '@' && dialect_.polar_radius != kNoWord) id = dialect_.polar_radius;
    if (c == '^' && dialect_.polar_angle != kNoWord) id = dialect_.polar_angle;
    if (!is_letter(c) && id == kNoWord)
      return error(column(pos), diag::Code::GcodeBadCharacter,
                   std::string("bad character '") + c + "' used");
    // A multi-letter word the dialect declares (Sinumerik CR=, TURN=): name then '='.
    std::size_t length = 1;
    if (id == kNoWord && c >= 'A' && c <= 'Z' && ((long_word_initials_ >> (c - 'A')) & 1) != 0) {
      for (std::size_t w = 26; w < dialect_.words.size(); ++w) {
        const std::string& name = dialect_.words[w].name;
        if (name.size() > length && starts_with(t, pos, name) && pos + name.size() < t.size() &&
            t[pos + name.size()] == '=') {
          id = static_cast<WordId>(w);
          length = name.size();
        }
      }
    }
    if (id == kNoWord) {
      id = letter_word(c);
      if (!dialect_.letter_known[id])
        return error(column(pos), diag::Code::GcodeUnknownWord,
                     std::string("unknown word starting with ") + c);
    }
    pos += length;
    bool equals = false;
    if (pos < t.size() && t[pos] == '=' && (dialect_.expressions.address_equals || length > 1)) {
      equals = true;
      ++pos;
    }
    Value v;
    bool integer = false;
    Word::Distance distance = Word::Distance::Modal;
    if (equals && (starts_with(t, pos, "AC(") || starts_with(t, pos, "IC("))) {
      // Sinumerik X=AC(..) / X=IC(..): this one coordinate absolute or incremental.
      distance = t[pos] == 'A' ? Word::Distance::Absolute : Word::Distance::Incremental;
      pos += 3;
      if (!evaluate_at(pos, Evaluator::Mode::Full, v)) return false;
      while (pos < t.size() && t[pos] == ' ') ++pos;
      if (pos >= t.size() || t[pos] != ')')
        return error(column(pos), diag::Code::GcodeBadExpression, "')' missing after AC( / IC(");
      ++pos;
    } else if (equals && pos < t.size() && t[pos] == '"') {
      return error(column(start), diag::Code::GcodeUnsupported,
                   "a word with a text value (tool names T=\"..\")");
    } else if (!read_word_value(pos, v, integer, equals)) {
      return false;
    }
    if (v.vacant) continue;  // FANUC: a word whose value is <vacant> is left out
    const WordSpec& spec = dialect_.words[id];
    const std::uint32_t col = column(start);
    switch (spec.kind) {
      case WordKind::GCode: {
        const double tens = v.number * 10;
        const long long n10 = std::llround(tens);
        if (std::abs(tens - static_cast<double>(n10)) > 1e-6 || n10 < 0)
          return error(col, diag::Code::GcodeUnknownCode,
                       "G code with more than one decimal or negative");
        const CodeSpec* code = dialect_.g_code(static_cast<int>(n10));
        if (!code) {
          char buf[32];
          const int n = std::snprintf(buf, sizeof buf, "G%g", v.number);
          return error(col, diag::Code::GcodeUnknownCode,
                       "unknown G code " + std::string(buf, static_cast<std::size_t>(n)));
        }
        if (v.machine)
          return error(col, diag::Code::GcodeMachineMotion,
                       "a G code chosen by a value only the machine knows");
        b.codes.push_back({code, static_cast<int>(n10), false, col});
        break;
      }
      case WordKind::MCode: {
        const long long n = std::llround(v.number);
        if (std::abs(v.number - static_cast<double>(n)) > 1e-6 || n < 0)
          return error(col, diag::Code::GcodeUnknownCode, "M code that is not a whole number");
        const CodeSpec* code = dialect_.m_code(static_cast<int>(n));
        if (!code)
          return error(col, diag::Code::GcodeUnknownCode, "unknown M code M" + std::to_string(n));
        if (v.machine)
          return error(col, diag::Code::GcodeMachineMotion,
                       "an M code chosen by a value only the machine knows");
        b.codes.push_back({code, static_cast<int>(n), true, col});
        break;
      }
      case WordKind::LineNumber:
        if (b.has_line_number)
          return error(col, diag::Code::GcodeDuplicateWord, "two N words in one block");
        b.has_line_number = true;
        b.line_number = v.number;
        break;
      default:
        if (b.has(id))
          return error(col, diag::Code::GcodeDuplicateWord,
                       "two " + spec.name + " words in one block");
        b.set(id, Word{v.number, col, integer, v.machine, distance});
        break;
    }
    if (observer_) observer_->word(spec.name, t.substr(start, pos - start), v.number, col);
  }
  return true;
}

bool Interpreter::assign(const Assignment& a) {
  if (a.named) {
    for (const auto& prefix : dialect_.parameters.machine_name_prefixes)
      if (a.name.compare(0, prefix.size(), prefix) == 0)
        return error(a.column, diag::Code::GcodeBadParameter,
                     "#<" + a.name + "> is the machine's: it cannot be assigned");
    parameters_.set_named(a.name, a.value);
    return true;
  }
  const auto& rules = dialect_.parameters;
  const bool alarm = rules.alarm != 0 && std::abs(a.number - rules.alarm) < 1e-9;
  const bool stop = rules.stop_message != 0 && std::abs(a.number - rules.stop_message) < 1e-9;
  if (alarm || stop) {
    // FANUC #3000 = n (TEXT): alarm n, the program ends; #3006 = 1 (TEXT): a stop with a
    // message. The text is the block's comment.
    const std::string text =
        line_->comments.empty() ? std::string() : std::string(trim(line_->comments.front().text));
    if (alarm) {
      error(a.column, diag::Code::GcodeAbort,
            "alarm " + number_key(a.value.number) + (text.empty() ? "" : ": " + text));
      done_ = true;
      return false;
    }
    if (!converter_.started()) converter_.start(program_name_);
    converter_.message(text);
    converter_.stop(Action::ProgramStop);
    return true;
  }
  switch (parameters_.set(a.number, a.value)) {
    case ParamStatus::Ok:
      return true;
    case ParamStatus::OutOfRange:
      return error(a.column, diag::Code::GcodeBadParameter, "parameter number out of range");
    case ParamStatus::NotInteger:
      return error(a.column, diag::Code::GcodeBadParameter, "parameter number is not an integer");
    case ParamStatus::ReadOnly:
    case ParamStatus::Undefined:
      return error(a.column, diag::Code::GcodeBadParameter, "parameter is read-only");
  }
  return true;
}

// After the block (LinuxCNC, FANUC) or at once (Sinumerik), as the dialect says.
bool Interpreter::take_assignment(Block& b, Assignment a) {
  if (dialect_.parameters.assign_in_order) return assign(a);
  b.assignments.push_back(std::move(a));
  return true;
}

bool Interpreter::apply_assignments(const Block& b) {
  for (const Assignment& a : b.assignments)
    if (!assign(a)) return false;
  return true;
}

void Interpreter::handle_comments(bool& stop) {
  // Comments that are commands to the controller ((MSG,...), (DEBUG,...), (ABORT,...)) are done
  // here; plain ones stay for the converter (COMMENT calls).
  stop = false;
  plain_comments_.clear();
  for (const Comment& c : line_->comments) {
    const std::string_view body = trim(c.text);
    std::string_view command;
    std::string_view rest;
    for (const auto& [prefix, what] : dialect_.comment_commands) {
      if (body.size() >= prefix.size() && upper_copy(body.substr(0, prefix.size())) == prefix) {
        command = what;
        rest = body.substr(prefix.size());
        break;
      }
    }
    if (command.empty()) {
      plain_comments_.push_back(c);
      continue;
    }
    if (!converter_.started()) converter_.start(program_name_);
    if (command == "message") {
      converter_.message(rest);
    } else if (command == "debug") {
      // #n and #<name> in the text are replaced by their values, as rs274 prints them.
      std::string out;
      const std::string up = upper_copy(rest);
      for (std::size_t i = 0; i < rest.size();) {
        if (rest[i] == '#' && i + 1 < rest.size() &&
            (is_digit(rest[i + 1]) || rest[i + 1] == '<')) {
          std::size_t j = i + 1;
          std::optional<Value> v;
          if (rest[j] == '<') {
            const std::size_t close = up.find('>', j);
            if (close == std::string::npos) break;
            v = parameters_.get_named(std::string_view(up).substr(j + 1, close - j - 1));
            j = close + 1;
          } else {
            while (j < rest.size() && is_digit(rest[j])) ++j;
            double n = 0;
            std::from_chars(rest.data() + i + 1, rest.data() + j, n);
            const ParamRead r = parameters_.get(n);
            if (r.status == ParamStatus::Ok) v = r.value;
          }
          if (v) {
            char buf[64];
            const int n = std::snprintf(buf, sizeof buf, "%f", v->number);
            out.append(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
          } else {
            out += "######";
          }
          i = j;
          continue;
        }
        out += rest[i++];
      }
      converter_.message(out);
    } else if (command == "abort") {
      error(c.column, diag::Code::GcodeAbort, "the program aborts: " + std::string(trim(rest)));
      stop = true;
      done_ = true;
    }
    // "ignore": (PRINT,...), (LOG,...), (PROBEOPEN ...) talk to the operator or a file.
  }
}

void Interpreter::execute_block(Block& b) {
  bool stop = false;
  handle_comments(stop);
  if (stop) return;
  const bool empty = b.present.none() && b.codes.empty() && !b.has_line_number;
  if (empty && plain_comments_.empty()) return;
  if (!empty) executed_any_ = true;
  if (!converter_.started()) converter_.start(program_name_);
  FlowRequest flow;
  if (!converter_.execute(b, plain_comments_, where(), flow)) {
    if (report_.full()) done_ = true;
    return;
  }
  if (mcall_) run_modal_call(b);
  do_flow(flow);
}

void Interpreter::do_flow(const FlowRequest& flow) {
  using Kind = FlowRequest::Kind;
  switch (flow.kind) {
    case Kind::None:
      return;
    case Kind::End:
      done_ = true;
      return;
    case Kind::Call: {
      if (!flow.has_program) {
        error(flow.column, diag::Code::GcodeMissingWord,
              flow.macro ? "G65 without P" : "M98 without P (the program to call)");
        return;
      }
      double number = flow.program;
      long long repeat = flow.repeat;
      if (dialect_.flow.packed_repeat && number > 9999 && !block_.has(letter_word('L'))) {
        repeat = static_cast<long long>(number) / 10000;
        number = static_cast<double>(static_cast<long long>(number) % 10000);
      }
      if (repeat <= 0) return;
      if (flow.local) {
        const Position* n = find_label(position_.source, "N" + number_key(number));
        if (!n) {
          error(flow.column, diag::Code::GcodeMissingProgram,
                "M97: no block N" + number_key(number) + " in this program");
          return;
        }
        const Position target = *n;
        (void)call(position_.source, target, FrameKind::Fanuc, "N" + number_key(number), repeat - 1,
                   false);
        return;
      }
      std::size_t source = 0;
      const auto target = find_fanuc_program(number, source);
      if (!target) {
        error(flow.column, diag::Code::GcodeMissingProgram,
              "subprogram O" + number_key(number) +
                  " is neither in the program nor among the uploaded files");
        return;
      }
      const Block args = block_;  // G65's arguments, before the frame clears the locals
      if (!call(source, *target, flow.macro ? FrameKind::Macro : FrameKind::Fanuc,
                "O" + number_key(number), repeat - 1, flow.macro))
        return;
      if (flow.macro) {
        // FANUC argument specification I: A B C I J K D E F H M Q R S T U V W X Y Z → #1..#26.
        static constexpr std::pair<char, int> kArgs[] = {
            {'A', 1},  {'B', 2},  {'C', 3},  {'I', 4},  {'J', 5},  {'K', 6},  {'D', 7},
            {'E', 8},  {'F', 9},  {'H', 11}, {'M', 13}, {'Q', 17}, {'R', 18}, {'S', 19},
            {'T', 20}, {'U', 21}, {'V', 22}, {'W', 23}, {'X', 24}, {'Y', 25}, {'Z', 26}};
        for (const auto& [letter, number_of] : kArgs) {
          const WordId w = letter_word(letter);
          if (!args.has(w)) continue;
          const Word& word = args.word(w);
          double value = word.value;
          const WordKind kind = dialect_.words[w].kind;
          if (dialect_.integer_literal_increments && word.integer_literal &&
              (kind == WordKind::Axis || kind == WordKind::Length))
            value *= converter_.metric_units() ? dialect_.increment_mm : dialect_.increment_inch;
          (void)parameters_.set(number_of, Value{value, false, word.machine});
        }
      }
      return;
    }
    case Kind::Return:
      if (frames_.size() == 1) {
        // M99 in the main program: the machine starts it again (endlessly); read once.
        warn(flow.column, diag::Code::GcodeIgnored,
             "M99 in the main program repeats it on the machine; read once");
        converter_.stop(Action::ProgramEnd);
        done_ = true;
        return;
      }
      return_from_call(std::nullopt, flow.return_line ? std::optional<std::string>(
                                                            "N" + number_key(*flow.return_line))
                                                      : std::nullopt);
      return;
  }
}

// ---- LinuxCNC O-words ------------------------------------------------------------------------

bool Interpreter::read_o_label(std::string_view t, std::size_t& pos, std::string& label) {
  if (pos >= t.size() || t[pos] != 'O') return false;
  ++pos;
  if (pos < t.size() && t[pos] == '<') {
    const std::size_t close = t.find('>', pos);
    if (close == std::string_view::npos) return false;
    label.assign(t.substr(pos, close - pos + 1));
    pos = close + 1;
    return true;
  }
  if (pos < t.size() && is_digit(t[pos])) {
    std::size_t q = pos;
    while (q < t.size() && is_digit(t[q])) ++q;
    double v = 0;
    std::from_chars(t.data() + pos, t.data() + q, v);
    label = number_key(v);
    pos = q;
    return true;
  }
  if (pos < t.size() && (t[pos] == dialect_.expressions.open || t[pos] == '#')) {
    Value v;
    if (!evaluator_.evaluate(t, pos, Evaluator::Mode::Primary, v)) return false;
    label = number_key(v.number);
    return true;
  }
  return false;
}

bool Interpreter::o_word_statement(std::size_t pos) {
  const std::string_view t = text();
  const std::size_t start = pos;
  std::string label;
  if (!read_o_label(t, pos, label))
    return error(column(start), diag::Code::GcodeBadStatement, "malformed O-word");
  while (pos < t.size() && t[pos] == ' ') ++pos;
  std::size_t kw_end = pos;
  while (kw_end < t.size() && is_letter(t[kw_end])) ++kw_end;
  const std::string keyword(t.substr(pos, kw_end - pos));
  pos = kw_end;
  Frame& frame = frames_.back();
  auto find_loop = [&](std::string_view l) -> Loop* {
    for (auto it = frame.loops.rbegin(); it != frame.loops.rend(); ++it)
      if (it->label == l) return &*it;
    return nullptr;
  };
  auto drop_loop = [&](std::string_view l) {
    for (auto it = frame.loops.rbegin(); it != frame.loops.rend(); ++it)
      if (it->label == l) {
        frame.loops.erase(std::next(it).base());
        return;
      }
  };
  std::string_view found;
  if (keyword.empty()) {
    if (!dialect_.flow.fanuc_subprograms)
      return error(column(start), diag::Code::GcodeBadStatement, "O-word without a keyword");
    if (!executed_any_ && frames_.size() == 1 && !titled_) {
      // The main program's title: O1234 or O<name>.
      titled_ = true;
      if (!line_->comments.empty())
        program_name_ = std::string(trim(line_->comments.front().text));
      else
        program_name_ = "O" + label;
      return true;
    }
    // A FANUC-style subprogram met in sequence: its body runs only when called.
    const std::uint32_t from = line_->number;
    while (!done_ && next_line()) {
      const std::string_view s = line_->text;
      bool m99 = false;
      for (std::size_t i = 0; i + 2 < s.size() + 1 && !m99; ++i) {
        if (s[i] == 'M' && (i == 0 || !is_letter(s[i - 1]))) {
          std::size_t j = i + 1;
          while (j < s.size() && s[j] == '0') ++j;
          m99 = starts_with(s, j, "99") && (j + 2 >= s.size() || !is_digit(s[j + 2]));
        }
      }
      if (m99) return true;
    }
    report_.add(sources_[position_.source].name, diag::Code::GcodeBadFlow, from, 0,
                "subprogram O" + label + " without M99");
    return false;
  }
  auto condition = [&](bool& result) {
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (pos >= t.size() || t[pos] != dialect_.expressions.open)
      return error(column(pos), diag::Code::GcodeBadStatement,
                   "o" + label + " " + keyword + " without its [condition]");
    return evaluate_condition(pos, result);
  };
  if (keyword == "SUB") {
    if (titled_ && executed_any_ && frames_.size() == 1 && !converter_.ended())
      return error(column(start), diag::Code::GcodeBadFlow,
                   "a subroutine definition inside the main program (end it with M2 or M30 first)");
    for (const auto& f : frames_)
      if (f.kind == FrameKind::OWord)
        return error(column(start), diag::Code::GcodeBadFlow, "nested subroutine definition");
    return skip_to({"ENDSUB"}, label, found);
  }
  if (keyword == "ENDSUB" || keyword == "RETURN") {
    std::optional<double> value;
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (pos < t.size() && t[pos] == dialect_.expressions.open) {
      Value v;
      if (!evaluate_at(pos, Evaluator::Mode::Primary, v)) return false;
      value = v.number;
    }
    // ENDSUB names its subroutine; RETURN may carry any label (LinuxCNC writes the label of
    // the IF it stands in).
    if (frames_.size() < 2 || frames_.back().kind != FrameKind::OWord ||
        (keyword == "ENDSUB" && frames_.back().label != label))
      return error(column(start), diag::Code::GcodeBadFlow,
                   "o" + label + " " + keyword + " outside its subroutine");
    return_from_call(value, std::nullopt);
    return true;
  }
  if (keyword == "CALL") {
    std::vector<Value> args;
    while (true) {
      while (pos < t.size() && t[pos] == ' ') ++pos;
      if (pos >= t.size()) break;
      if (t[pos] != dialect_.expressions.open)
        return error(column(pos), diag::Code::GcodeBadStatement,
                     "a call's arguments must be in brackets");
      Value v;
      if (!evaluate_at(pos, Evaluator::Mode::Primary, v)) return false;
      args.push_back(v);
    }
    const std::string key = "o:" + label;
    std::optional<Position> target;
    std::size_t source = 0;
    for (const std::size_t i : {position_.source, std::size_t{0}}) {
      Source& s = sources_[i];
      if (!s.subprograms) index_subprograms(s);
      if (const auto it = s.subprograms->find(key); it != s.subprograms->end()) {
        target = it->second;
        source = i;
        break;
      }
    }
    if (!target) {
      std::string file = label;
      if (file.size() > 1 && file.front() == '<') file = file.substr(1, file.size() - 2);
      if (const auto i = find_file(file)) {
        Source& s = sources_[*i];
        if (!s.subprograms) index_subprograms(s);
        if (const auto it = s.subprograms->find(key); it != s.subprograms->end()) {
          target = it->second;
          source = *i;
        }
      }
    }
    if (!target)
      return error(
          column(start), diag::Code::GcodeMissingProgram,
          "subroutine o" + label + " is neither in the program nor among the uploaded files");
    if (!call(source, *target, FrameKind::OWord, label, 0, true)) return false;
    for (std::size_t i = 0; i < args.size(); ++i)
      (void)parameters_.set(static_cast<double>(i + 1), args[i]);
    return true;
  }
  if (keyword == "IF") {
    bool c = false;
    if (!condition(c)) return false;
    while (!c) {
      if (!skip_to({"ELSEIF", "ELSE", "ENDIF"}, label, found)) return false;
      if (found != "ELSEIF") return true;
      // An ELSEIF: its own condition, read from that line.
      std::size_t p = 0;
      const std::string_view s = line_->text;
      p = s.find("ELSEIF") + 6;
      while (p < s.size() && s[p] == ' ') ++p;
      if (p >= s.size() || s[p] != dialect_.expressions.open)
        return error(column(p), diag::Code::GcodeBadStatement, "elseif without its [condition]");
      if (!evaluate_condition(p, c)) return false;
    }
    return true;
  }
  if (keyword == "ELSEIF" || keyword == "ELSE") return skip_to({"ENDIF"}, label, found);
  if (keyword == "ENDIF") return true;
  if (keyword == "DO") {
    if (frame.loops.size() >= options_.max_call_depth)
      return error(column(start), diag::Code::GcodeNestingLimit, "loops nested too deep");
    drop_loop(label);
    frame.loops.push_back({label,
                           LoopKind::Do,
                           Position{position_.source, cursor_.offset(), position_.line + 1},
                           0,
                           {},
                           -1,
                           0});
    return true;
  }
  if (keyword == "WHILE") {
    Loop* loop = find_loop(label);
    bool c = false;
    if (!condition(c)) return false;
    if (loop && loop->kind == LoopKind::Do) {
      if (c) {
        jump(loop->start);
      } else {
        drop_loop(label);
      }
      return true;
    }
    if (c) {
      if (!loop) {
        if (frame.loops.size() >= options_.max_call_depth)
          return error(column(start), diag::Code::GcodeNestingLimit, "loops nested too deep");
        frame.loops.push_back({label, LoopKind::While, position_, 0, {}, -1, 0});
      }
      return true;
    }
    drop_loop(label);
    return skip_to({"ENDWHILE"}, label, found);
  }
  if (keyword == "ENDWHILE") {
    Loop* loop = find_loop(label);
    if (!loop || loop->kind != LoopKind::While)
      return error(column(start), diag::Code::GcodeBadFlow,
                   "o" + label + " endwhile without while");
    jump(loop->start);
    return true;
  }
  if (keyword == "REPEAT") {
    Value n;
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (pos >= t.size() || !evaluate_at(pos, Evaluator::Mode::Primary, n))
      return pos >= t.size()
                 ? error(column(pos), diag::Code::GcodeBadStatement, "repeat without its [count]")
                 : false;
    drop_loop(label);
    const auto count = static_cast<long long>(std::llround(n.number));
    if (count < 1) return skip_to({"ENDREPEAT"}, label, found);
    if (frame.loops.size() >= options_.max_call_depth)
      return error(column(start), diag::Code::GcodeNestingLimit, "loops nested too deep");
    frame.loops.push_back({label,
                           LoopKind::Repeat,
                           Position{position_.source, cursor_.offset(), position_.line + 1},
                           count,
                           {},
                           -1,
                           0});
    return true;
  }
  if (keyword == "ENDREPEAT") {
    Loop* loop = find_loop(label);
    if (!loop || loop->kind != LoopKind::Repeat)
      return error(column(start), diag::Code::GcodeBadFlow,
                   "o" + label + " endrepeat without repeat");
    if (--loop->remaining > 0) {
      jump(loop->start);
    } else {
      drop_loop(label);
    }
    return true;
  }
  if (keyword == "BREAK" || keyword == "CONTINUE") {
    Loop* loop = find_loop(label);
    if (!loop)
      return error(column(start), diag::Code::GcodeBadFlow,
                   "o" + label + " " + keyword + " outside its loop");
    const LoopKind kind = loop->kind;
    if (keyword == "CONTINUE") {
      if (kind == LoopKind::While) {
        jump(loop->start);
        return true;
      }
      if (kind == LoopKind::Repeat) {
        if (--loop->remaining > 0) {
          jump(loop->start);
          return true;
        }
        drop_loop(label);
        return skip_to({"ENDREPEAT"}, label, found);
      }
      // do ... while: the test at the end decides.
      if (!skip_to({"WHILE"}, label, found)) return false;
      jump(position_);
      return true;
    }
    drop_loop(label);
    if (kind == LoopKind::While) return skip_to({"ENDWHILE"}, label, found);
    if (kind == LoopKind::Repeat) return skip_to({"ENDREPEAT"}, label, found);
    return skip_to({"WHILE"}, label, found);
  }
  return error(column(start), diag::Code::GcodeBadStatement,
               "unknown O-word keyword '" + keyword + "'");
}

// ---- FANUC macro B ---------------------------------------------------------------------------

// Whether a block is one of macro B's statements (IF, WHILE/WH, DO, END, GOTO) rather than words.
bool Interpreter::starts_macro_statement(std::string_view t, std::size_t pos) const {
  for (const std::string_view k : {"IF", "GOTO", "END", "DO"})
    if (starts_with(t, pos, k)) return true;
  for (const std::string& w : dialect_.flow.while_spellings)
    if (starts_with(t, pos, w)) return true;
  return false;
}

bool Interpreter::macro_statement(std::size_t pos, bool& handled) {
  const std::string_view t = text();
  handled = false;
  const char open = dialect_.expressions.open;
  auto keyword_at = [&](std::size_t p, std::string_view k) { return starts_with(t, p, k); };
  const std::size_t start = pos;
  Frame& frame = frames_.back();
  auto goto_label = [&](std::size_t& p) {
    Value n;
    if (!evaluate_at(p, Evaluator::Mode::Primary, n)) return false;
    if (n.machine)
      return error(column(start), diag::Code::GcodeMachineMotion,
                   "a jump to a block chosen by a value only the machine knows");
    const std::string label = "N" + number_key(n.number);
    const Position* target = find_label(position_.source, label);
    if (!target) return error(column(start), diag::Code::GcodeBadFlow, "GOTO: no block " + label);
    frame.loops.erase(
        std::remove_if(frame.loops.begin(), frame.loops.end(),
                       [&](const Loop& l) { return l.start.offset > target->offset; }),
        frame.loops.end());
    jump(*target);
    return true;
  };
  if (keyword_at(pos, "IF") && pos + 2 < t.size() && t[pos + 2] == open) {
    handled = true;
    pos += 2;
    bool c = false;
    if (!evaluate_condition(pos, c)) return false;
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (keyword_at(pos, "GOTO")) {
      pos += 4;
      if (!c) return true;
      return goto_label(pos);
    }
    if (keyword_at(pos, "THEN")) {
      pos += 4;
      if (!c) return true;
      block_.clear();
      if (!read_words(pos, block_)) return false;
      if (!apply_assignments(block_)) return false;
      execute_block(block_);
      return true;
    }
    return error(column(pos), diag::Code::GcodeBadStatement, "IF [..] without GOTO or THEN");
  }
  for (const std::string& w : dialect_.flow.while_spellings) {
    if (!keyword_at(pos, w) || pos + w.size() >= t.size() || t[pos + w.size()] != open) continue;
    handled = true;
    pos += w.size();
    bool c = false;
    if (!evaluate_condition(pos, c)) return false;
    while (pos < t.size() && t[pos] == ' ') ++pos;
    if (!keyword_at(pos, "DO"))
      return error(column(pos), diag::Code::GcodeBadStatement, "WHILE [..] without DO m");
    pos += 2;
    Value m;
    if (!evaluate_at(pos, Evaluator::Mode::Primary, m)) return false;
    const std::string label = "DO" + number_key(m.number);
    auto it = std::find_if(frame.loops.begin(), frame.loops.end(),
                           [&](const Loop& l) { return l.label == label; });
    if (c) {
      if (it == frame.loops.end()) {
        if (frame.loops.size() >= options_.max_call_depth)
          return error(column(start), diag::Code::GcodeNestingLimit, "loops nested too deep");
        frame.loops.push_back({label, LoopKind::While, position_, 0, {}, -1, 0});
      }
      return true;
    }
    if (it != frame.loops.end()) frame.loops.erase(it);
    // Skip to the matching END m.
    const std::uint32_t from = line_->number;
    const std::string end = "END" + number_key(m.number);
    while (!done_ && next_line()) {
      std::string_view s = line_->text;
      std::size_t p = 0;
      if (p < s.size() && s[p] == 'N') {
        ++p;
        while (p < s.size() && is_digit(s[p])) ++p;
      }
      while (p < s.size() && s[p] == ' ') ++p;
      if (starts_with(s, p, end) && (p + end.size() >= s.size() || !is_digit(s[p + end.size()])))
        return true;
    }
    report_.add(sources_[position_.source].name, diag::Code::GcodeBadFlow, from, 0,
                "WHILE .. DO" + number_key(m.number) + " without END" + number_key(m.number));
    return false;
  }
  if (keyword_at(pos, "DO") && pos + 2 < t.size() && (is_digit(t[pos + 2]) || t[pos + 2] == '#')) {
    // DO m alone: a loop without a condition (left with GOTO); END m goes back.
    handled = true;
    pos += 2;
    Value m;
    if (!evaluate_at(pos, Evaluator::Mode::Primary, m)) return false;
    const std::string label = "DO" + number_key(m.number);
    if (std::none_of(frame.loops.begin(), frame.loops.end(),
                     [&](const Loop& l) { return l.label == label; })) {
      if (frame.loops.size() >= options_.max_call_depth)
        return error(column(start), diag::Code::GcodeNestingLimit, "loops nested too deep");
      frame.loops.push_back({label,
                             LoopKind::Loop,
                             Position{position_.source, cursor_.offset(), position_.line + 1},
                             0,
                             {},
                             -1,
                             0});
    }
    return true;
  }
  if (keyword_at(pos, "END") && pos + 3 < t.size() && (is_digit(t[pos + 3]) || t[pos + 3] == '#')) {
    handled = true;
    pos += 3;
    Value m;
    if (!evaluate_at(pos, Evaluator::Mode::Primary, m)) return false;
    const std::string label = "DO" + number_key(m.number);
    for (auto it = frame.loops.rbegin(); it != frame.loops.rend(); ++it) {
      if (it->label == label) {
        jump(it->start);
        return true;
      }
    }
    return error(column(start), diag::Code::GcodeBadFlow,
                 "END" + number_key(m.number) + " without its WHILE .. DO" + number_key(m.number));
  }
  if (keyword_at(pos, "GOTO")) {
    handled = true;
    pos += 4;
    return goto_label(pos);
  }
  return true;
}

// ---- The main loop ---------------------------------------------------------------------------

void Interpreter::step_block() {
  if (line_->block_delete && options_.block_delete) return;
  if (observer_) {
    observer_->begin_block(sources_[position_.source].name, line_->number, line_->raw);
    for (const Comment& c : line_->comments) observer_->comment(c.text, c.column);
  }
  struct End {
    BlockObserver* o;
    ~End() {
      if (o) o->end_block();
    }
  } end{observer_};
  if (line_->has_error) {
    error(line_->error.column, diag::Code::GcodeUnclosedComment,
          line_->error.unclosed_string ? "string not closed on its line"
                                       : "comment not closed on its line");
    return;
  }
  const std::string_view t = line_->text;
  if (dialect_.percent_delimits && !t.empty() && t[0] == '%') {
    if (frames_.size() == 1 && position_.source == 0) {
      if (!percent_seen_ && !executed_any_) {
        percent_seen_ = true;
        return;
      }
      done_ = true;  // a second '%' ends the program
      percent_end_ = true;
    }
    return;
  }
  if (dialect_.syntax == Syntax::Klartext) {
    klartext_line();
    return;
  }
  std::size_t pos = 0;
  while (pos < t.size() && t[pos] == ' ') ++pos;
  // The N word first: a label for jumps, not a statement.
  std::size_t after_n = pos;
  if (after_n < t.size() && t[after_n] == 'N' && after_n + 1 < t.size() &&
      (is_digit(t[after_n + 1]) || t[after_n + 1] == '.')) {
    ++after_n;
    while (after_n < t.size() && (is_digit(t[after_n]) || t[after_n] == '.')) ++after_n;
    while (after_n < t.size() && t[after_n] == ' ') ++after_n;
  }
  if (after_n < t.size()) {
    const char c = t[after_n];
    if (c == 'O' && (dialect_.flow.o_words || dialect_.flow.fanuc_subprograms)) {
      if (dialect_.flow.o_words || (after_n + 1 < t.size() && is_digit(t[after_n + 1]))) {
        if (observer_) observer_->statement("o-word", t.substr(after_n));
        o_word_statement(after_n);
        return;
      }
    }
    // FANUC writes :1234 for O1234; Huazhong %1234 (where '%' does not delimit the program).
    if ((c == ':' || (c == '%' && !dialect_.percent_delimits)) && dialect_.flow.fanuc_subprograms &&
        after_n + 1 < t.size() && is_digit(t[after_n + 1])) {
      scratch_.assign(t);
      scratch_[after_n] = 'O';
      detach_line();
      line_->set_text(scratch_);
      o_word_statement(after_n);
      return;
    }
    bool handled = false;
    if (dialect_.flow.macro_b) {
      if (observer_ && starts_macro_statement(t, after_n))
        observer_->statement("macro", t.substr(after_n));
      macro_statement(after_n, handled);
      if (handled) return;
    }
    if (dialect_.flow.sinumerik) {
      sinumerik_statement(after_n, handled);
      if (handled) return;
    }
  }
  block_.clear();
  if (!read_words(pos, block_)) return;
  if (!apply_assignments(block_)) return;
  execute_block(block_);
}

void Interpreter::end_program() {
  if (!converter_.started()) converter_.start(program_name_);
  if (!converter_.ended() && !cancelled_ && !done_by_error() && !percent_end_ &&
      dialect_.require_program_end) {
    report_.add(sources_[0].name, diag::Code::GcodeNoProgramEnd,
                dialect_.missing_end_is_error ? diag::Severity::Error : diag::Severity::Warning,
                position_.line, 0, "the program ends without its end (M2, M30, %)");
  }
  converter_.finish();
}

bool Interpreter::done_by_error() const {
  return report_.errors() > 0 && done_;
}

void Interpreter::run() {
  while (!done_ && next_line()) step_block();
  end_program();
}

}  // namespace ncpost::gcode::detail
