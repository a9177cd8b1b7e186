#include "ncpost/canon/xml.hpp"

#include <charconv>
#include <cmath>
#include <type_traits>

#include "format.hpp"
#include "ncpost/xmltext/escape.hpp"

namespace ncpost::canon {
namespace {

std::string_view xml_units(Units u) {
  switch (u) {
    case Units::Inches:
      return "inch";
    case Units::Millimetres:
      return "mm";
    case Units::Centimetres:
      return "cm";
  }
  return "mm";
}

std::string_view xml_plane(Plane p) {
  switch (p) {
    case Plane::Xy:
      return "xy";
    case Plane::Yz:
      return "yz";
    case Plane::Xz:
      return "xz";
  }
  return "xy";
}

// The element name without building a Call (which would copy strings and NURBS vectors).
template <class T>
std::string_view element_name(const T& c) {
  if constexpr (std::is_same_v<T, Begin>)
    return marker_name(c.scope, true);
  else if constexpr (std::is_same_v<T, End>)
    return marker_name(c.scope, false);
  else if constexpr (std::is_same_v<T, Cycle>)
    return name(c.kind);
  else if constexpr (std::is_same_v<T, NurbsFeed>)
    return "NURBS_FEED";
  else if constexpr (std::is_same_v<T, Comment>)
    return "COMMENT";
  else if constexpr (std::is_same_v<T, Message>)
    return "MESSAGE";
  else
    return name(Call{c});  // the rest are a few numbers at most
}

// The shortest round-trip text of a number, as append_xml_number writes it, in `buffer`.
std::string_view xml_number(double value, char (&buffer)[32]) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "INF" : "-INF";
  if (value == 0) return "0";  // also -0
  // The shortest round-trip form of a double needs at most 24 characters.
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return {buffer, static_cast<std::size_t>(result.ptr - buffer)};
}

std::string_view xml_integer(long long value, char (&buffer)[32]) {
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return {buffer, static_cast<std::size_t>(result.ptr - buffer)};
}

// The whitespace before an element at `indent`: a newline ends the previous line.
constexpr std::string_view kSpaces = "        ";
std::string_view spaces(int n) {
  return kSpaces.substr(0, static_cast<std::size_t>(n));
}

// Writes one call as one element (a NURBS as an element with children), on its own line.
class ElementWriter {
 public:
  ElementWriter(XmlEvents& out, int indent) : out_(out), indent_(indent) {}

  void operator()(const UseLengthUnits& c) { open(c), text("units", xml_units(c.units)), empty(c); }
  void operator()(const SetOriginOffsets& c) {
    open(c);
    number("x", c.offset.x), number("y", c.offset.y), number("z", c.offset.z);
    rotary(c.rotary);
    empty(c);
  }
  void operator()(const SetFeedReference& c) {
    open(c);
    text("reference", c.reference == FeedReference::Workpiece ? "workpiece" : "xyz");
    empty(c);
  }
  void operator()(const SelectPlane& c) { open(c), text("plane", xml_plane(c.plane)), empty(c); }
  void operator()(const StraightTraverse& c) { open(c), pose(c.to), empty(c); }
  void operator()(const StraightFeed& c) { open(c), pose(c.to), empty(c); }
  void operator()(const ArcFeed& c) {
    open(c);
    number("x", c.end.x), number("y", c.end.y), number("z", c.end.z);
    number("cx", c.centre.x), number("cy", c.centre.y), number("cz", c.centre.z);
    number("ni", c.normal.i), number("nj", c.normal.j), number("nk", c.normal.k);
    integer("turns", c.turns);
    if (const auto p = plane_arc(c)) {
      text("plane", xml_plane(p->plane));
      number("first_end", p->first_end), number("second_end", p->second_end);
      number("first_axis", p->first_axis), number("second_axis", p->second_axis);
      integer("rotation", p->rotation);
      number("axis_end_point", p->axis_end_point);
    }
    rotary(c.end.rotary);
    tool_axis(c.end.tool_axis);
    empty(c);
  }
  void operator()(const NurbsFeed& c) {
    open(c);
    integer("degree", c.degree);
    rotary(c.rotary);
    tool_axis(c.tool_axis);
    const std::string_view inner = spaces(indent_ + 2);
    for (const auto& p : c.points) {
      out_.text("\n"), out_.text(inner);
      out_.start_element("point");
      number("x", p.x), number("y", p.y), number("z", p.z), number("w", p.weight);
      out_.end_element("point");
    }
    for (const double k : c.knots) {
      out_.text("\n"), out_.text(inner);
      out_.start_element("knot");
      number("value", k);
      out_.end_element("knot");
    }
    out_.text("\n"), out_.text(spaces(indent_));
    out_.end_element("NURBS_FEED");
    out_.text("\n");
  }
  void operator()(const SetFeedRate& c) { open(c), number("rate", c.rate), empty(c); }
  void operator()(const SetSpindleSpeed& c) { open(c), number("rpm", c.rpm), empty(c); }
  void operator()(const SelectTool& c) { open(c), integer("slot", c.slot), empty(c); }
  void operator()(const ChangeTool& c) { open(c), integer("slot", c.slot), empty(c); }
  void operator()(const UseToolLengthOffset& c) { open(c), number("length", c.length), empty(c); }
  void operator()(const Dwell& c) { open(c), number("seconds", c.seconds), empty(c); }
  void operator()(const Comment& c) { with_content(c, c.text); }
  void operator()(const Message& c) { with_content(c, c.text); }
  void operator()(const Begin& c) { open(c), entity(c.entity), empty(c); }
  void operator()(const End& c) { open(c), entity(c.entity), empty(c); }
  void operator()(const Cycle& c) {
    open(c);
    detail::cycle_arguments(*this, c);
    rotary(c.rotary);
    tool_axis(c.tool_axis);
    empty(c);
  }
  // The calls without arguments; a new call with arguments does not compile until handled.
  template <class T>
  requires std::is_empty_v<T>
  void operator()(const T& c) { open(c), empty(c); }

  // The attributes of a structure marker (also used for <workingstep>).
  void entity(const Entity& e) {
    if (e.id != 0) integer("id", static_cast<long long>(e.id));
    if (!e.type.empty()) text("type", e.type);
    text("name", e.name);
  }

 private:
  template <class T>
  void open(const T& c) {
    name_ = element_name(c);
    out_.text(spaces(indent_));
    out_.start_element(name_);
  }
  template <class T>
  void empty(const T&) {
    out_.end_element(name_);
    out_.text("\n");
  }
  // Always a text event, also when empty: the text form is then `<COMMENT></COMMENT>`.
  template <class T>
  void with_content(const T& c, std::string_view content) {
    open(c);
    out_.text(content);
    empty(c);
  }

 public:  // what detail::cycle_arguments calls
  void number(std::string_view attribute, double v) {
    char buffer[32];
    out_.attribute(attribute, xml_number(v, buffer));
  }
  void integer(std::string_view attribute, long long v) {
    char buffer[32];
    out_.attribute(attribute, xml_integer(v, buffer));
  }
  void text(std::string_view attribute, std::string_view v) { out_.attribute(attribute, v); }
  void flag(std::string_view attribute, bool v) { text(attribute, v ? "true" : "false"); }
  void rotary(const std::optional<Rotary>& r) {
    if (r) number("a", r->a), number("b", r->b), number("c", r->c);
  }
  void tool_axis(const std::optional<Direction>& d) {
    if (d) number("i", d->i), number("j", d->j), number("k", d->k);
  }
  void pose(const Pose& p) {
    number("x", p.x), number("y", p.y), number("z", p.z);
    rotary(p.rotary);
    tool_axis(p.tool_axis);
  }

 private:
  XmlEvents& out_;
  int indent_;
  std::string_view name_;
};

void open_workingstep(XmlEvents& out, const Begin& b, bool continued) {
  out.text("  ");
  out.start_element("workingstep");
  ElementWriter(out, 0).entity(b.entity);
  if (continued) out.attribute("continued", "true");
  // The output options (output_options.hpp) as block_numbers="off" etc., only those set.
  for (const auto& entry : kOutputOptions)
    if (const Switch s = b.options.get(entry.option); s != Switch::Unset)
      out.attribute(entry.name, switch_name(s));
  out.text("\n");
}

void close_workingstep(XmlEvents& out) {
  out.text("  ");
  out.end_element("workingstep");
  out.text("\n");
}

}  // namespace

void append_xml_number(std::string& out, double value) {
  char buffer[32];
  out += xml_number(value, buffer);
}

void XmlText::start_element(std::string_view name) {
  if (start_tag_open_) out_ += '>';
  out_ += '<';
  out_ += name;
  start_tag_open_ = true;
}

void XmlText::attribute(std::string_view name, std::string_view value) {
  out_ += ' ';
  out_ += name;
  out_ += "=\"";
  xmltext::append_escaped(out_, value, true);
  out_ += '"';
}

void XmlText::text(std::string_view characters) {
  if (start_tag_open_) {
    out_ += '>';
    start_tag_open_ = false;
  }
  xmltext::append_escaped(out_, characters, false);
}

void XmlText::end_element(std::string_view name) {
  if (start_tag_open_) {
    out_ += "/>";
    start_tag_open_ = false;
    return;
  }
  out_ += "</";
  out_ += name;
  out_ += '>';
}

void XmlChunkWriter::append_chunk(std::string& out, const ChunkView& chunk) {
  XmlText text(out);
  append_chunk(text, chunk);
}
void XmlChunkWriter::open(std::string& out, std::uint64_t seq) {
  XmlText text(out);
  open(text, seq);
}
void XmlChunkWriter::append(std::string& out, std::span<const Call> calls) {
  XmlText text(out);
  append(text, calls);
}
void XmlChunkWriter::close(std::string& out) {
  XmlText text(out);
  close(text);
}

void XmlChunkWriter::append_chunk(XmlEvents& out, const ChunkView& chunk, MotionRuns* runs) {
  open(out, chunk.seq);
  append(out, chunk.calls, runs);
  close(out);
}

void XmlChunkWriter::open(XmlEvents& out, std::uint64_t seq) {
  out.start_element("chunk");
  char buffer[32];
  out.attribute("seq", xml_integer(static_cast<long long>(seq), buffer));
  out.text("\n");
  // A workingstep left open by the previous chunk (split at the size limit) goes on here.
  open_here_ = false;
  if (open_workingstep_) {
    open_workingstep(out, *open_workingstep_, true);
    open_here_ = true;
  }
}

void XmlChunkWriter::append(XmlEvents& out, std::span<const Call> calls, MotionRuns* runs) {
  std::size_t run_first = 0;
  std::size_t run_count = 0;
  auto end_run = [&] {
    if (run_count == 0) return;
    char buffer[32];
    out.text(spaces(open_here_ ? 4 : 2));
    out.start_element("motions");
    out.attribute("first", xml_integer(static_cast<long long>(run_first), buffer));
    out.attribute("count", xml_integer(static_cast<long long>(run_count), buffer));
    out.end_element("motions");
    out.text("\n");
    run_count = 0;
  };
  for (const Call& call : calls) {
    if (runs != nullptr) {
      if (const std::optional<std::size_t> index = runs->take(call)) {
        if (run_count == 0) run_first = *index;
        ++run_count;
        continue;
      }
      end_run();
    }
    if (const auto* b = std::get_if<Begin>(&call); b != nullptr && b->scope == Scope::Workingstep) {
      // Workingsteps do not nest; a second begin closes the first so the XML stays well-formed.
      if (open_here_) close_workingstep(out);
      open_workingstep(out, *b, false);
      open_workingstep_ = *b;
      open_here_ = true;
      continue;
    }
    if (const auto* e = std::get_if<End>(&call);
        e != nullptr && e->scope == Scope::Workingstep && open_here_) {
      close_workingstep(out);
      open_workingstep_.reset();
      open_here_ = false;
      continue;
    }
    // Everything else, including a WORKINGSTEP_END without its begin, is an element.
    std::visit(ElementWriter(out, open_here_ ? 4 : 2), call);
  }
  end_run();
}

void XmlChunkWriter::close(XmlEvents& out) {
  if (open_here_) close_workingstep(out);
  open_here_ = false;
  out.end_element("chunk");
  out.text("\n");
}

void XmlChunkSink::chunk(const ChunkView& chunk) {
  text_.clear();
  writer_.append_chunk(text_, chunk);
  out_(chunk.seq, text_);
}

void XmlDocumentWriter::start() {
  if (started_) return;
  started_ = true;
  out_(kXmlPrologue);
}

void XmlDocumentWriter::chunk(const ChunkView& chunk) {
  start();
  text_.clear();
  writer_.append_chunk(text_, chunk);
  out_(text_);
}

void XmlDocumentWriter::finish() {
  if (finished_) return;
  start();
  finished_ = true;
  out_(kXmlEpilogue);
}

std::string to_xml_document(std::span<const Call> calls, ChunkLimits limits) {
  std::string out;
  XmlDocumentWriter document([&out](std::string_view text) { out += text; });
  Chunker chunker(document, limits);
  for (const auto& call : calls) chunker.call(call);
  chunker.finish();
  document.finish();
  return out;
}

}  // namespace ncpost::canon
