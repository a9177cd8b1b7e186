#include "ncpost/canon/trace.hpp"

#include <charconv>
#include <cmath>
#include <type_traits>

#include "format.hpp"
#include "ncpost/xmltext/utf8.hpp"

namespace ncpost::canon {
namespace {

using detail::append_integer;

// Length of the valid UTF-8 sequence starting at s[i] (2 to 4 bytes), or 0.
void append_hex_escape(std::string& out, unsigned char c) {
  constexpr char kHex[] = "0123456789ABCDEF";
  out += "\\x";
  out.push_back(kHex[c >> 4]);
  out.push_back(kHex[c & 0x0Fu]);
}

class Printer {
 public:
  explicit Printer(std::string& out) : out_(out) {}

  void operator()(const UseLengthUnits& c) {
    open("USE_LENGTH_UNITS");
    word(name(c.units));
    close();
  }
  void operator()(const SetOriginOffsets& c) {
    open("SET_ORIGIN_OFFSETS");
    number(c.offset.x), number(c.offset.y), number(c.offset.z);
    rotary(c.rotary);
    close();
  }
  void operator()(const SetFeedReference& c) {
    open("SET_FEED_REFERENCE");
    word(name(c.reference));
    close();
  }
  void operator()(const SelectPlane& c) {
    open("SELECT_PLANE");
    word(name(c.plane));
    close();
  }
  void operator()(const StraightTraverse& c) {
    open("STRAIGHT_TRAVERSE");
    pose(c.to);
    close();
  }
  void operator()(const StraightFeed& c) {
    open("STRAIGHT_FEED");
    pose(c.to);
    close();
  }
  void operator()(const ArcFeed& c) {
    if (const auto p = plane_arc(c)) {
      open("ARC_FEED");
      number(p->first_end), number(p->second_end), number(p->first_axis), number(p->second_axis),
          integer(p->rotation), number(p->axis_end_point);
    } else {
      // A tilted-plane arc has no rs274 form; print the stored 3D form under its own name.
      open("ARC_FEED_3D");
      number(c.end.x), number(c.end.y), number(c.end.z);
      number(c.centre.x), number(c.centre.y), number(c.centre.z);
      number(c.normal.i), number(c.normal.j), number(c.normal.k);
      integer(c.turns);
    }
    rotary(c.end.rotary);
    tool_axis(c.end.tool_axis);
    close();
  }
  void operator()(const NurbsFeed& c) {
    open("NURBS_FEED");
    integer(c.degree);
    separate();
    out_ += '[';
    detail::append_control_points(out_, c.points, append_number, ", ", '(', ')');
    out_ += "], [";
    detail::append_values(out_, c.knots, append_number, ", ");
    out_ += ']';
    rotary(c.rotary);
    tool_axis(c.tool_axis);
    close();
  }
  void operator()(const SetFeedRate& c) {
    open("SET_FEED_RATE");
    number(c.rate);
    close();
  }
  void operator()(const SetSpindleSpeed& c) {
    open("SET_SPINDLE_SPEED");
    number(c.rpm);
    close();
  }
  void operator()(const SelectTool& c) {
    open("SELECT_TOOL");
    integer(c.slot);
    close();
  }
  void operator()(const ChangeTool& c) {
    open("CHANGE_TOOL");
    integer(c.slot);
    close();
  }
  void operator()(const UseToolLengthOffset& c) {
    open("USE_TOOL_LENGTH_OFFSET");
    number(c.length);
    close();
  }
  void operator()(const Dwell& c) {
    open("DWELL");
    number(c.seconds);
    close();
  }
  void operator()(const Comment& c) {
    open("COMMENT");
    quoted(c.text);
    close();
  }
  void operator()(const Message& c) {
    open("MESSAGE");
    quoted(c.text);
    close();
  }
  void operator()(const Begin& c) {
    marker(c.scope, "_BEGIN", c.entity);
    // WORKINGSTEP_BEGIN(#10, MACHINING_WORKINGSTEP, "name", block_numbers=off): the output
    // options after the name, only those set.
    if (c.options.empty()) return;
    out_.pop_back();  // the marker's ')'
    for (const auto& entry : kOutputOptions) {
      const Switch s = c.options.get(entry.option);
      if (s == Switch::Unset) continue;
      separate();
      out_ += entry.name;
      out_ += '=';
      out_ += switch_name(s);
    }
    close();
  }
  void operator()(const End& c) { marker(c.scope, "_END", c.entity); }
  void operator()(const Cycle& c) {
    open(name(c.kind));
    number(c.x), number(c.y), number(c.safe_z), number(c.r_z), number(c.bottom_z);
    number(c.feed), number(c.dwell);
    switch (c.kind) {
      case CycleKind::PeckDrill:
        number(c.peck), number(c.peck_retract), number(c.peck_clearance);
        break;
      case CycleKind::Tap:
        number(c.pitch), number(c.spindle_speed);
        word(c.left_hand ? "LEFT_HAND" : "RIGHT_HAND");
        break;
      case CycleKind::Bore:
        word(c.spindle_stop ? "SPINDLE_STOP" : "FEED_OUT");
        break;
      case CycleKind::Drill:
      case CycleKind::Ream:
        break;
    }
    rotary(c.rotary);
    tool_axis(c.tool_axis);
    close();
  }
  // The calls without arguments; a new call with arguments does not compile until handled.
  template <class T>
  requires std::is_empty_v<T>
  void operator()(const T& c) {
    open(name(Call{c}));
    close();
  }

 private:
  void open(std::string_view call_name) {
    out_ += call_name;
    out_ += '(';
    first_ = true;
  }
  void close() { out_ += ')'; }
  void separate() {
    if (!first_) out_ += ", ";
    first_ = false;
  }
  void number(double v) { separate(), append_number(out_, v); }
  void integer(long long v) { separate(), append_integer(out_, v); }
  void word(std::string_view w) { separate(), out_ += w; }
  void quoted(std::string_view text) { separate(), append_quoted(out_, text); }
  void rotary(const std::optional<Rotary>& r) {
    if (r) number(r->a), number(r->b), number(r->c);
  }
  void tool_axis(const std::optional<Direction>& d) {
    if (d) number(d->i), number(d->j), number(d->k);
  }
  void pose(const Pose& p) {
    number(p.x), number(p.y), number(p.z);
    rotary(p.rotary);
    tool_axis(p.tool_axis);
  }
  // WORKINGSTEP_BEGIN(#10, MACHINING_WORKINGSTEP, "name"): `$` for no id or no type; a type
  // that is not an EXPRESS identifier is quoted so that the line still parses.
  void marker(Scope scope, std::string_view suffix, const Entity& e) {
    out_ += name(scope);
    open(suffix);
    separate();
    if (e.id == 0) {
      out_ += '$';
    } else {
      out_ += '#';
      append_integer(out_, e.id);
    }
    if (e.type.empty())
      word("$");
    else if (is_identifier(e.type))
      word(e.type);
    else
      quoted(e.type);
    quoted(e.name);
    close();
  }
  static bool is_identifier(std::string_view s) {
    for (const char ch : s) {
      const bool ok = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') ||
                      (ch >= '0' && ch <= '9') || ch == '_';
      if (!ok) return false;
    }
    return !s.empty() && !(s[0] >= '0' && s[0] <= '9');
  }

  std::string& out_;
  bool first_ = true;
};

}  // namespace

void append_number(std::string& out, double value) {
  // Wide enough for DBL_MAX in fixed notation (309 digits) with 4 decimals and a sign.
  char buffer[330];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, 4);
  std::string_view text(buffer, static_cast<std::size_t>(result.ptr - buffer));
  if (text == "-0.0000") text.remove_prefix(1);
  out += text;
}

void append_quoted(std::string& out, std::string_view text) {
  out += '"';
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      if (c == '"' || c == '\\') out += '\\';
      out.push_back(static_cast<char>(c));
      ++i;
      continue;
    }
    switch (c) {
      case '\n':
        out += "\\n";
        ++i;
        continue;
      case '\r':
        out += "\\r";
        ++i;
        continue;
      case '\t':
        out += "\\t";
        ++i;
        continue;
      default:
        break;
    }
    char32_t cp = 0;
    const std::size_t len = c >= 0x80 ? xmltext::utf8_sequence_length(text, i, cp) : 0;
    if (len == 0) {
      append_hex_escape(out, c);
      ++i;
    } else {
      out.append(text.data() + i, len);
      i += len;
    }
  }
  out += '"';
}

void append_call(std::string& out, const Call& call) {
  Printer printer(out);
  std::visit(printer, call);
}

std::string format_call(const Call& call) {
  std::string out;
  append_call(out, call);
  return out;
}

void TraceWriter::call(const Call& call) {
  line_.clear();
  // "%5d " as NIST and rs274 print the line number.
  char number[24];
  const auto result = std::to_chars(number, number + sizeof number, next_line_++);
  const auto digits = static_cast<std::size_t>(result.ptr - number);
  if (digits < 5) line_.append(5 - digits, ' ');
  line_.append(number, digits);
  line_ += ' ';
  append_call(line_, call);
  line_ += '\n';
  out_(line_);
}

void TraceWriter::write(std::span<const Call> calls) {
  for (const auto& c : calls) call(c);
}

std::string trace(std::span<const Call> calls) {
  std::string out;
  TraceWriter writer([&out](std::string_view line) { out += line; });
  writer.write(calls);
  return out;
}

}  // namespace ncpost::canon
