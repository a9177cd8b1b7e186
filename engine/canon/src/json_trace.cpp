#include "ncpost/canon/json_trace.hpp"

#include <cmath>
#include <type_traits>

#include "format.hpp"
#include "ncpost/canon/output_options.hpp"
#include "ncpost/xmltext/utf8.hpp"

namespace ncpost::canon {
namespace {

using detail::append_integer;

// Writes one call's members after {"n": N, "call": "NAME". Names follow canon.rng's attributes.
class JsonPrinter {
 public:
  explicit JsonPrinter(std::string& out) : out_(out) {}

  void operator()(const UseLengthUnits& c) { text("units", name(c.units)); }
  void operator()(const SetOriginOffsets& c) {
    point(c.offset.x, c.offset.y, c.offset.z);
    rotary(c.rotary);
  }
  void operator()(const SetFeedReference& c) { text("reference", name(c.reference)); }
  void operator()(const SelectPlane& c) { text("plane", name(c.plane)); }
  void operator()(const StraightTraverse& c) { pose(c.to); }
  void operator()(const StraightFeed& c) { pose(c.to); }
  // Always the 3D form (end, centre, normal, turns): a reader needs no selected plane.
  void operator()(const ArcFeed& c) {
    pose(c.end);
    triple("centre", c.centre.x, c.centre.y, c.centre.z);
    triple("normal", c.normal.i, c.normal.j, c.normal.k);
    integer("turns", c.turns);
  }
  void operator()(const NurbsFeed& c) {
    integer("degree", c.degree);
    key("points");
    out_ += '[';
    detail::append_control_points(out_, c.points, append_json_number, ",", '[', ']');
    out_ += ']';
    key("knots");
    out_ += '[';
    detail::append_values(out_, c.knots, append_json_number, ",");
    out_ += ']';
    rotary(c.rotary);
    tool_axis(c.tool_axis);
  }
  void operator()(const SetFeedRate& c) { number("rate", c.rate); }
  void operator()(const SetSpindleSpeed& c) { number("rpm", c.rpm); }
  void operator()(const SelectTool& c) { integer("slot", c.slot); }
  void operator()(const ChangeTool& c) { integer("slot", c.slot); }
  void operator()(const UseToolLengthOffset& c) { number("length", c.length); }
  void operator()(const Dwell& c) { number("seconds", c.seconds); }
  void operator()(const Comment& c) { text("text", c.text); }
  void operator()(const Message& c) { text("text", c.text); }
  void operator()(const Begin& c) {
    entity(c.entity);
    // A workingstep's output options, as in the text trace: only those set.
    if (c.options.empty()) return;
    key("options");
    out_ += '{';
    bool first = true;
    for (const auto& entry : kOutputOptions) {
      const Switch s = c.options.get(entry.option);
      if (s == Switch::Unset) continue;
      if (!first) out_ += ',';
      first = false;
      append_json_string(out_, entry.name);
      out_ += ':';
      append_json_string(out_, switch_name(s));
    }
    out_ += '}';
  }
  void operator()(const End& c) { entity(c.entity); }
  void operator()(const Cycle& c) {
    detail::cycle_arguments(*this, c);
    rotary(c.rotary);
    tool_axis(c.tool_axis);
  }
  // The calls without arguments; a new call with arguments does not compile until handled.
  template <class T>
  requires std::is_empty_v<T>
  void operator()(const T&) {}

 private:
  void key(std::string_view k) {
    out_ += ",\"";
    out_ += k;
    out_ += "\":";
  }

 public:  // what detail::cycle_arguments calls
  void number(std::string_view k, double v) { key(k), append_json_number(out_, v); }
  void integer(std::string_view k, long long v) { key(k), append_integer(out_, v); }
  void flag(std::string_view k, bool v) { key(k), out_ += v ? "true" : "false"; }
  void text(std::string_view k, std::string_view v) { key(k), append_json_string(out_, v); }

 private:
  void point(double x, double y, double z) { number("x", x), number("y", y), number("z", z); }
  void triple(std::string_view k, double a, double b, double c) {
    key(k);
    out_ += '[';
    append_json_number(out_, a), out_ += ',';
    append_json_number(out_, b), out_ += ',';
    append_json_number(out_, c);
    out_ += ']';
  }
  void rotary(const std::optional<Rotary>& r) {
    if (r) number("a", r->a), number("b", r->b), number("c", r->c);
  }
  void tool_axis(const std::optional<Direction>& d) {
    if (d) number("i", d->i), number("j", d->j), number("k", d->k);
  }
  void pose(const Pose& p) {
    point(p.x, p.y, p.z);
    rotary(p.rotary);
    tool_axis(p.tool_axis);
  }
  // The marker's entity: id and type null when there is none.
  void entity(const Entity& e) {
    key("id");
    if (e.id == 0)
      out_ += "null";
    else
      append_integer(out_, e.id);
    key("type");
    if (e.type.empty())
      out_ += "null";
    else
      append_json_string(out_, e.type);
    text("name", e.name);
  }

  std::string& out_;
};

}  // namespace

void append_json_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  append_number(out, value);
}

void append_json_string(std::string& out, std::string_view text) {
  constexpr char kHex[] = "0123456789abcdef";
  out += '"';
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x80) {
      if (c == '"' || c == '\\') out += '\\';
      out.push_back(static_cast<char>(c));
      ++i;
      continue;
    }
    if (c < 0x20) {
      // \b \t \n \f \r by name (0x08 to 0x0D but 0x0B), the rest as \u00XX.
      constexpr char kNamed[] = "btnvfr";  // 0x0B (v) is not named in JSON
      if (c >= '\b' && c <= '\r' && c != 0x0B) {
        out += '\\';
        out += kNamed[c - '\b'];
      } else {
        out += "\\u00";
        out.push_back(kHex[c >> 4]);
        out.push_back(kHex[c & 0x0Fu]);
      }
      ++i;
      continue;
    }
    char32_t cp = 0;
    const std::size_t len = xmltext::utf8_sequence_length(text, i, cp);
    if (len == 0) {
      out += "\\ufffd";
      ++i;
    } else {
      out.append(text.data() + i, len);
      i += len;
    }
  }
  out += '"';
}

void append_json_call(std::string& out, const Call& call, std::uint64_t line) {
  out += "{\"n\":";
  append_integer(out, line);
  out += ",\"call\":\"";
  out += name(call);
  out += '"';
  JsonPrinter printer(out);
  std::visit(printer, call);
  out += '}';
}

JsonTraceWriter::JsonTraceWriter(TextSink out, JsonLayout layout, std::string header_members)
    : out_(std::move(out)), layout_(layout), header_members_(std::move(header_members)) {}

void JsonTraceWriter::header() {
  header_written_ = true;
  line_ = "{\"format\":\"ncpost-trace\",\"version\":1";
  if (!header_members_.empty()) {
    line_ += ',';
    line_ += header_members_;
  }
  line_ += layout_ == JsonLayout::Lines ? "}\n" : ",\"calls\":[\n";
  out_(line_);
}

void JsonTraceWriter::call(const Call& call) {
  if (finished_) return;
  const bool first = !header_written_;
  if (first) header();
  line_.clear();
  if (layout_ == JsonLayout::Document && next_line_ > 1) line_ += ",\n";
  append_json_call(line_, call, next_line_++);
  if (layout_ == JsonLayout::Lines) line_ += '\n';
  out_(line_);
}

void JsonTraceWriter::finish(std::string_view end_members) {
  if (finished_) return;
  if (!header_written_) header();
  finished_ = true;
  line_.clear();
  if (layout_ == JsonLayout::Lines) {
    line_ += "{\"end\":true";
  } else {
    line_ += next_line_ > 1 ? "\n]" : "]";
  }
  if (!end_members.empty()) {
    line_ += ',';
    line_ += end_members;
  }
  line_ += "}\n";
  out_(line_);
}

}  // namespace ncpost::canon
