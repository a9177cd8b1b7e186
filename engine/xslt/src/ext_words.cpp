// The block-level urn:ncpost:ext functions: a motion's words and a numbered line in one call
// each. They do what a template does with ext:setup-*, ext:format, ext:position, ext:arc-*,
// ext:moved-to, ext:block and ext:line (same arithmetic, same text), but read the motion's
// attributes straight from the context node. A motion template then costs two XPath function
// calls instead of fifteen, which is most of a post's time (docs/xslt-extensions.md, "Words").

#include <charconv>
#include <cmath>
#include <optional>
#include <string>

#include "ext_call.hpp"

namespace ncpost::xslt::detail {
namespace {

// The attributes of a motion element that the words are made of, as number(@name) reads
// them (absent: not present).
struct Motion {
  std::optional<double> x, y, z, a, b, c;      // end point, rotary axes
  std::optional<double> cx, cy, cz, rotation;  // arcs
  const char* plane = nullptr;                 // arcs: "xy", "yz", "xz"
};

Motion read_motion(const xmlNode* node) {
  Motion m;
  if (node == nullptr || node->type != XML_ELEMENT_NODE) return m;
  for (const xmlAttr* a = node->properties; a != nullptr; a = a->next) {
    if (a->children == nullptr || a->children->content == nullptr || a->ns != nullptr) continue;
    const auto* name = reinterpret_cast<const char*>(a->name);
    const xmlChar* text = a->children->content;
    std::optional<double>* slot = nullptr;
    if (name[0] != '\0' && name[1] == '\0') {
      switch (name[0]) {
        case 'x':
          slot = &m.x;
          break;
        case 'y':
          slot = &m.y;
          break;
        case 'z':
          slot = &m.z;
          break;
        case 'a':
          slot = &m.a;
          break;
        case 'b':
          slot = &m.b;
          break;
        case 'c':
          slot = &m.c;
          break;
        default:
          break;
      }
    } else if (name[0] == 'c' && name[2] == '\0' &&
               (name[1] == 'x' || name[1] == 'y' || name[1] == 'z')) {
      slot = name[1] == 'x' ? &m.cx : name[1] == 'y' ? &m.cy : &m.cz;
    } else if (std::string_view(name) == "rotation") {
      slot = &m.rotation;
    } else if (std::string_view(name) == "plane") {
      m.plane = reinterpret_cast<const char*>(text);
    }
    if (slot != nullptr) *slot = xmlXPathStringEvalNumber(text);
  }
  return m;
}

// Appends " <letter><formatted value>"; false (with the call failed) when it cannot.
bool append_word(Call& call, std::string& out, char letter, Quantity quantity, double value) {
  if (!std::isfinite(value)) {
    call.fail(std::string(1, static_cast<char>(std::tolower(letter))) + " is not a finite number");
    return false;
  }
  out += ' ';
  out += letter;
  if (!append_quantity(out, call.config(), Access::program_unit_mm(call.job()), quantity, value)) {
    call.fail(std::string("the value of ") + letter + " is out of range");
    return false;
  }
  return true;
}

// " X.. Y.. Z.." of the end point through the set-up, then " A.. B.. C.." when present: as
// the "xyz" template of ncpost-common.xsl writes them.
bool append_end_point(Call& call, std::string& out, const Motion& m) {
  if (!m.x || !m.y || !m.z) {
    call.fail("the context node is not a motion with x, y and z");
    return false;
  }
  const std::array<double, 3> p{*m.x, *m.y, *m.z};
  for (const double v : p) {
    if (!std::isfinite(v)) {
      call.fail("the end point is not finite");
      return false;
    }
  }
  const SetupTransform& setup = call.config().setup;
  if (!append_word(call, out, 'X', Quantity::Length, setup_axis(setup, 0, p, true)) ||
      !append_word(call, out, 'Y', Quantity::Length, setup_axis(setup, 1, p, true)) ||
      !append_word(call, out, 'Z', Quantity::Length, setup_axis(setup, 2, p, true)))
    return false;
  if (m.a && !append_word(call, out, 'A', Quantity::Angle, *m.a)) return false;
  if (m.b && !append_word(call, out, 'B', Quantity::Angle, *m.b)) return false;
  if (m.c && !append_word(call, out, 'C', Quantity::Angle, *m.c)) return false;
  return true;
}

void record_end_point(Call& call, const Motion& m) {
  Access::position(call.job()) = {*m.x, *m.y, *m.z};
  Access::has_position(call.job()) = true;
}

// ext:motion-words(): the context motion's end point words; it becomes the current position.
void fn_motion_words(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "motion-words", 0, 0);
  if (!call.ok()) return;
  const Motion m = read_motion(x->context != nullptr ? x->context->node : nullptr);
  std::string out;
  out.reserve(48);
  if (!append_end_point(call, out, m)) return;
  record_end_point(call, m);
  call.push_string(out);
}

// The centre as I/J/K offsets from the start (the current position), through the set-up, in
// the arc's plane: I J (xy), J K (yz), I K (xz); as the "arc-ijk" template writes them.
bool append_centre_offsets(Call& call, std::string& out, const Motion& m,
                           const std::array<double, 3>& start) {
  const std::array<double, 3> centre{*m.cx, *m.cy, *m.cz};
  const std::string_view plane = m.plane != nullptr ? m.plane : "";
  const SetupTransform& setup = call.config().setup;
  const char letters[3] = {'I', 'J', 'K'};
  for (int axis = 0; axis < 3; ++axis) {
    const bool used = plane == "yz" ? axis != 0 : plane == "xz" ? axis != 1 : axis != 2;
    if (!used) continue;
    const double offset =
        setup_axis(setup, axis, centre, true) - setup_axis(setup, axis, start, true);
    if (!append_word(call, out, letters[axis], Quantity::Length, offset == 0 ? 0.0 : offset))
      return false;
  }
  return true;
}

// ext:arc-words(form): the context ARC_FEED's end point words, then its centre: form 'r' gives
// FANUC's signed R where R can say it (an arc in the XY plane of less than a full turn), 'ijk'
// (or 'r' elsewhere) I/J/K offsets; then " P<n>" for an arc of n > 1 turns. The end becomes
// the current position. The G2/G3 word and the plane's G17/G18/G19 are the stylesheet's.
void fn_arc_words(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "arc-words", 1, 1);
  if (!call.ok()) return;
  const std::string_view form = call.view(0);
  if (form != "ijk" && form != "r") {
    call.fail("form '" + std::string(form) + "' is not 'ijk' or 'r'");
    return;
  }
  const Motion m = read_motion(x->context != nullptr ? x->context->node : nullptr);
  if (!m.cx || !m.cy || !m.cz || !m.rotation) {
    call.fail("the context node is not an ARC_FEED in a plane (cx, cy, cz, rotation)");
    return;
  }
  if (!std::isfinite(*m.cx) || !std::isfinite(*m.cy) || !std::isfinite(*m.cz)) {
    call.fail("the centre is not finite");
    return;
  }
  const double rotation = *m.rotation;
  if (!(rotation == std::trunc(rotation)) || rotation == 0 || std::abs(rotation) > 1000) {
    call.fail("rotation must be a non-zero whole number, not " + shortest(rotation));
    return;
  }
  if (!Access::has_position(call.job())) {
    call.fail("no position yet: the arc has no start (no motion before it)");
    return;
  }
  const std::array<double, 3> start = Access::position(call.job());
  std::string out;
  out.reserve(80);
  if (!append_end_point(call, out, m)) return;
  const auto turns = static_cast<int>(rotation);
  bool as_r = false;
  if (form == "r" && m.plane != nullptr && std::string_view(m.plane) == "xy" &&
      (turns == 1 || turns == -1)) {
    const PlaneArc arc{start[0], start[1], *m.x, *m.y, *m.cx, *m.cy, turns};
    const std::optional<double> sweep = arc_sweep(arc);
    if (!sweep) {
      call.fail("the start point is on the centre");
      return;
    }
    if (*sweep < 359.999 && *sweep > -359.999) {
      const std::optional<double> r = arc_radius(arc);
      if (!r) {
        call.fail("a zero radius has no R form");
        return;
      }
      if (!append_word(call, out, 'R', Quantity::Length, *r)) return;
      as_r = true;
    }
  }
  if (!as_r && !append_centre_offsets(call, out, m, start)) return;
  if (turns > 1 || turns < -1) {
    out += " P";
    out += std::to_string(std::abs(turns));
  }
  record_end_point(call, m);
  call.push_string(out);
}

// "N<next block number> <argument 0>", checked against the line length, as the result.
void push_numbered(Call& call) {
  char number[24];
  const auto done = std::to_chars(number, number + sizeof number, next_block_number(call.job()));
  const std::string_view text = call.view(0);
  std::string line;
  line.reserve(2 + static_cast<std::size_t>(done.ptr - number) + text.size());
  line += 'N';
  line.append(number, done.ptr);
  line += ' ';
  line += text;
  check_line_length(call, line);
  call.push_string(line);
}

// ext:numbered-line(text): "N<next block number> text", checked against the line length; as
// ext:line(concat('N', ext:block(), ' ', text)).
void fn_numbered_line(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "numbered-line", 1, 1);
  if (!call.ok()) return;
  push_numbered(call);
}

// ext:block-line(text): ext:numbered-line(text) when the profile numbers its blocks
// (block_numbers.numbered), ext:line(text) when it does not.
void fn_block_line(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "block-line", 1, 1);
  if (!call.ok()) return;
  if (!call.config().block.numbered) {
    check_line_length(call, call.view(0));
    call.push_argument(0);
    return;
  }
  push_numbered(call);
}

// ext:block-numbering(): 'yes' when the profile numbers its blocks, else 'no'.
void fn_block_numbering(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "block-numbering", 0, 0);
  if (!call.ok()) return;
  call.push_string(call.config().block.numbered ? "yes" : "no");
}

constexpr Function kWordFunctions[] = {
    {"motion-words", guarded<fn_motion_words>},       {"arc-words", guarded<fn_arc_words>},
    {"numbered-line", guarded<fn_numbered_line>},     {"block-line", guarded<fn_block_line>},
    {"block-numbering", guarded<fn_block_numbering>},
};

}  // namespace

std::span<const Function> word_functions() {
  return kWordFunctions;
}

}  // namespace ncpost::xslt::detail
