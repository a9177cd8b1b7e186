// The block-level urn:ncpost:ext functions: a motion's words, a block line, and a whole run
// of motion blocks, in one call each. They do what a template does with ext:setup-*,
// ext:format, ext:position, ext:arc-*, ext:moved-to, ext:modal, ext:block and ext:line (same
// arithmetic, same text), but read the motion from the context node's attributes, or, for a
// run, from the job's memory. The motion templates are most of a post's time, and each XPath
// function call costs libxslt thousands of instructions (docs/xslt-extensions.md, "Words").

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ext_call.hpp"

namespace ncpost::xslt::detail {
namespace {

// A motion as the word functions need it, whether read from an element or from a run.
struct MotionValues {
  std::array<double, 3> end{};
  std::optional<double> a, b, c;  // rotary axes
  // Arcs only.
  std::array<double, 3> centre{};
  std::string_view plane;  // "xy", "yz", "xz"
  int rotation = 0;        // signed turns about the plane's normal
};

// An attribute's number, read exactly (std::from_chars rounds correctly, so the canonical
// XML's shortest round-trip numbers give back the very doubles of the canonical calls, as a
// run has them); what it cannot read as a whole goes through XPath's number().
double number_of(const xmlChar* text) {
  const auto* s = reinterpret_cast<const char*>(text);
  const std::size_t length = std::strlen(s);
  double value = 0;
  const auto done = std::from_chars(s, s + length, value);
  if (done.ec == std::errc() && done.ptr == s + length) return value;
  return xmlXPathStringEvalNumber(text);
}

// The attributes of a motion element (absent: not present).
struct MotionAttributes {
  std::optional<double> x, y, z, a, b, c;      // end point, rotary axes
  std::optional<double> cx, cy, cz, rotation;  // arcs
  const char* plane = nullptr;                 // arcs: "xy", "yz", "xz"
};

MotionAttributes read_attributes(const xmlNode* node) {
  MotionAttributes m;
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
    if (slot != nullptr) *slot = number_of(text);
  }
  return m;
}

std::optional<MotionValues> motion_of(Call& call, const MotionAttributes& m) {
  if (!m.x || !m.y || !m.z) {
    call.fail("the context node is not a motion with x, y and z");
    return std::nullopt;
  }
  MotionValues v;
  v.end = {*m.x, *m.y, *m.z};
  v.a = m.a, v.b = m.b, v.c = m.c;
  return v;
}

std::optional<MotionValues> arc_of(Call& call, const MotionAttributes& m) {
  std::optional<MotionValues> v = motion_of(call, m);
  if (!v) return std::nullopt;
  if (!m.cx || !m.cy || !m.cz || !m.rotation || m.plane == nullptr) {
    call.fail("the context node is not an ARC_FEED in a plane (cx, cy, cz, rotation, plane)");
    return std::nullopt;
  }
  const double rotation = *m.rotation;
  if (!(rotation == std::trunc(rotation)) || rotation == 0 || std::abs(rotation) > 1000) {
    call.fail("rotation must be a non-zero whole number, not " + shortest(rotation));
    return std::nullopt;
  }
  v->centre = {*m.cx, *m.cy, *m.cz};
  v->plane = m.plane;
  v->rotation = static_cast<int>(rotation);
  return v;
}

MotionValues motion_of(const RunMotion& r) {
  MotionValues v;
  v.end = {r.x, r.y, r.z};
  if (r.has_rotary) v.a = r.a, v.b = r.b, v.c = r.c;
  if (r.kind == RunMotion::Kind::Arc) {
    v.centre = {r.cx, r.cy, r.cz};
    v.plane = r.plane == RunMotion::Plane::Yz   ? "yz"
              : r.plane == RunMotion::Plane::Xz ? "xz"
                                                : "xy";
    v.rotation = r.rotation;
  }
  return v;
}

// Appends " <letter><formatted value>"; false (with the call failed) when it cannot.
bool append_word(Call& call, std::string& out, char letter, Quantity quantity, double value) {
  if (!std::isfinite(value)) {
    call.fail(std::string(1, static_cast<char>(std::tolower(letter))) + " is not a finite number");
    return false;
  }
  const ScaledQuantity scaled =
      scale_quantity(call.config(), Access::program_unit_mm(call.job()), quantity, value);
  if (!std::isfinite(scaled.value)) {
    call.fail(std::string("the value of ") + letter + " is out of range");
    return false;
  }
  // One append per word: this runs for every coordinate of every block.
  char word[2 + kNumberRoom];
  word[0] = ' ';
  word[1] = letter;
  const char* end = write_number(word + 2, scaled.value, *scaled.format);
  out.append(word, static_cast<std::size_t>(end - word));  // (pointer, length): no replace()
  return true;
}

// " X.. Y.. Z.." of the end point through the set-up, then " A.. B.. C.." when present (those
// of JobConfig::rotary_axes): as the "xyz" template of ncpost-common.xsl writes them.
bool append_end_point(Call& call, std::string& out, const MotionValues& m) {
  for (const double v : m.end) {
    if (!std::isfinite(v)) {
      call.fail("the end point is not finite");
      return false;
    }
  }
  const SetupTransform& setup = call.config().setup;
  if (!append_word(call, out, 'X', Quantity::Length, setup_axis(setup, 0, m.end, true)) ||
      !append_word(call, out, 'Y', Quantity::Length, setup_axis(setup, 1, m.end, true)) ||
      !append_word(call, out, 'Z', Quantity::Length, setup_axis(setup, 2, m.end, true)))
    return false;
  const std::array<bool, 3>& axes = call.config().rotary_axes;
  if (m.a && axes[0] && !append_word(call, out, 'A', Quantity::Angle, *m.a)) return false;
  if (m.b && axes[1] && !append_word(call, out, 'B', Quantity::Angle, *m.b)) return false;
  if (m.c && axes[2] && !append_word(call, out, 'C', Quantity::Angle, *m.c)) return false;
  return true;
}

void record_end_point(Call& call, const MotionValues& m) {
  Access::position(call.job()) = m.end;
  Access::has_position(call.job()) = true;
}

// The centre as I/J/K offsets from the start, through the set-up, in the arc's plane: I J
// (xy), J K (yz), I K (xz); as the "arc-ijk" template writes them.
bool append_centre_offsets(Call& call, std::string& out, const MotionValues& m,
                           const std::array<double, 3>& start) {
  const SetupTransform& setup = call.config().setup;
  const char letters[3] = {'I', 'J', 'K'};
  for (int axis = 0; axis < 3; ++axis) {
    const bool used = m.plane == "yz" ? axis != 0 : m.plane == "xz" ? axis != 1 : axis != 2;
    if (!used) continue;
    const double offset =
        setup_axis(setup, axis, m.centre, true) - setup_axis(setup, axis, start, true);
    if (!append_word(call, out, letters[axis], Quantity::Length, offset == 0 ? 0.0 : offset))
      return false;
  }
  return true;
}

// The value a word of `quantity` shows once written (rounded to the profile's format), in the
// canonical program's units.
double as_written(Call& call, Quantity quantity, double value) {
  const ScaledQuantity scaled =
      scale_quantity(call.config(), Access::program_unit_mm(call.job()), quantity, value);
  if (!std::isfinite(scaled.value) || scaled.value == 0 || value == 0) return value;
  char digits[kNumberRoom + 1];
  char* end = write_number(digits, scaled.value, *scaled.format);
  *end = '\0';
  const double shown = std::strtod(digits, nullptr);
  return std::isfinite(shown) ? shown * (value / scaled.value) : value;
}

// Near a half circle the centre an R word implies moves far when R and the end points are
// rounded (it sits sqrt(R^2 - (chord/2)^2) off the chord: 0.11 mm for a 25 mm half circle and
// R to 3 decimals). R is written only when the centre a controller computes from the written
// words stays within this of the true one; I/J/K otherwise.
constexpr double kRCentreTolerance = 0.001;  // mm

bool r_keeps_centre(Call& call, const PlaneArc& arc, double r) {
  const auto shown = [&](double v) { return as_written(call, Quantity::Length, v); };
  const auto centre = arc_centre(shown(arc.sx), shown(arc.sy), shown(arc.ex), shown(arc.ey),
                                 shown(r), arc.turns < 0);
  return centre && std::hypot((*centre)[0] - arc.cx, (*centre)[1] - arc.cy) <= kRCentreTolerance;
}

// The words of an arc (see ext:arc-words) appended to `out`; the end becomes the position.
bool append_arc(Call& call, std::string& out, std::string_view form, const MotionValues& m) {
  for (const double v : m.centre) {
    if (!std::isfinite(v)) {
      call.fail("the centre is not finite");
      return false;
    }
  }
  if (!Access::has_position(call.job())) {
    call.fail("no position yet: the arc has no start (no motion before it)");
    return false;
  }
  const std::array<double, 3> start = Access::position(call.job());
  if (!append_end_point(call, out, m)) return false;
  bool as_r = false;
  if (form == "r" && m.plane == "xy" && (m.rotation == 1 || m.rotation == -1)) {
    const PlaneArc arc{start[0],    start[1],    m.end[0],  m.end[1],
                       m.centre[0], m.centre[1], m.rotation};
    const std::optional<double> sweep = arc_sweep(arc);
    if (!sweep) {
      call.fail("the start point is on the centre");
      return false;
    }
    if (*sweep < 359.999 && *sweep > -359.999) {
      const std::optional<double> r = arc_radius(arc);
      if (!r) {
        call.fail("a zero radius has no R form");
        return false;
      }
      if (r_keeps_centre(call, arc, *r)) {
        if (!append_word(call, out, 'R', Quantity::Length, *r)) return false;
        as_r = true;
      }
    }
  }
  if (!as_r && !append_centre_offsets(call, out, m, start)) return false;
  if (m.rotation > 1 || m.rotation < -1) {
    out += " P";
    out += std::to_string(std::abs(m.rotation));
  }
  record_end_point(call, m);
  return true;
}

bool valid_form(Call& call, std::string_view form) {
  if (form == "ijk" || form == "r") return true;
  call.fail("form '" + std::string(form) + "' is not 'ijk' or 'r'");
  return false;
}

const xmlNode* context_node(xmlXPathParserContextPtr x) {
  return x->context != nullptr ? x->context->node : nullptr;
}

// Whether blocks written at `node` carry N numbers: the block_numbers="on|off" of the enclosing
// <workingstep> (an output option the shop's operation-name rules selected; canon/
// output_options.hpp) when it has one, else the profile's block_numbers.numbered. Looked up
// from the context node, so a batch of chunks in one transform numbers each workingstep as its
// own options say.
bool numbered_at(Call& call, const xmlNode* node) {
  for (; node != nullptr; node = node->parent) {
    if (node->type != XML_ELEMENT_NODE ||
        std::string_view(reinterpret_cast<const char*>(node->name)) != "workingstep")
      continue;
    for (const xmlAttr* a = node->properties; a != nullptr; a = a->next) {
      if (a->children == nullptr || a->children->content == nullptr ||
          std::string_view(reinterpret_cast<const char*>(a->name)) != "block_numbers")
        continue;
      return std::string_view(reinterpret_cast<const char*>(a->children->content)) == "on";
    }
    break;
  }
  return call.config().block.numbered;
}

// ext:motion-words(): the context motion's end point words; it becomes the current position.
void fn_motion_words(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "motion-words", 0, 0);
  if (!call.ok()) return;
  const std::optional<MotionValues> m = motion_of(call, read_attributes(context_node(x)));
  if (!m) return;
  std::string out;
  out.reserve(48);
  if (!append_end_point(call, out, *m)) return;
  record_end_point(call, *m);
  call.push_string(out);
}

// ext:arc-words(form): the context ARC_FEED's end point words, then its centre: form 'r' gives
// FANUC's signed R where R can say it (an arc in the XY plane of less than a full turn), 'ijk'
// (or 'r' elsewhere) I/J/K offsets; then " P<n>" for an arc of n > 1 turns. The end becomes
// the current position. The G2/G3 word and the plane's G17/G18/G19 are the stylesheet's.
void fn_arc_words(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "arc-words", 1, 1);
  if (!call.ok()) return;
  const std::string_view form = call.view(0);
  if (!valid_form(call, form)) return;
  const std::optional<MotionValues> m = arc_of(call, read_attributes(context_node(x)));
  if (!m) return;
  std::string out;
  out.reserve(80);
  if (!append_arc(call, out, form, *m)) return;
  call.push_string(out);
}

// ext:block-line(text): "N<next> text" when the profile numbers its blocks
// (block_numbers.numbered, or the enclosing workingstep's block_numbers option: numbered_at),
// `text` when it does not; checked against the line length.
void fn_block_line(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "block-line", 1, 1);
  if (!call.ok()) return;
  if (!numbered_at(call, context_node(x))) {
    check_line_length(call, call.view(0));
    call.push_argument(0);
    return;
  }
  std::string line;
  append_block_line(call, line, call.view(0), true);
  call.push_string(line);
}

// ext:numbered-line(text): "N<next> text", checked; ext:line(concat('N', ext:block(), ' ', text)).
void fn_numbered_line(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "numbered-line", 1, 1);
  if (!call.ok()) return;
  std::string line;
  append_block_line(call, line, call.view(0), true);
  call.push_string(line);
}

// ext:block-numbering(): 'yes' when blocks at the context node carry N numbers (numbered_at),
// else 'no'.
void fn_block_numbering(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "block-numbering", 0, 0);
  if (!call.ok()) return;
  call.push_string(numbered_at(call, context_node(x)) ? "yes" : "no");
}

// ext:motion-run(traverse, feed, cw, ccw, form): the blocks of the run of motions that the
// context <motions first=".." count=".."/> element stands for, each ended by a newline:
//   traverse / feed:  block-line(concat(word, motion-words()))
//   arc:              block-line(G17/G19/G18) when the plane's modal word changed, then
//                     block-line(concat(cw or ccw, arc-words(form)))
// exactly what ncpost-common.xsl's STRAIGHT_TRAVERSE, STRAIGHT_FEED and ARC_FEED templates
// write for the same motions as elements. Each motion may be rendered once.
void fn_motion_run(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "motion-run", 5, 5);
  if (!call.ok()) return;
  const std::string_view traverse = call.view(0), feed = call.view(1), cw = call.view(2),
                         ccw = call.view(3), form = call.view(4);
  if (!valid_form(call, form)) return;
  const xmlNode* node = context_node(x);
  std::optional<double> first, count;
  if (node != nullptr && node->type == XML_ELEMENT_NODE &&
      std::string_view(reinterpret_cast<const char*>(node->name)) == "motions") {
    for (const xmlAttr* a = node->properties; a != nullptr; a = a->next) {
      if (a->children == nullptr || a->children->content == nullptr) continue;
      const std::string_view name(reinterpret_cast<const char*>(a->name));
      if (name == "first") first = number_of(a->children->content);
      if (name == "count") count = number_of(a->children->content);
    }
  }
  const std::span<const RunMotion> motions = Access::run_motions(call.job());
  std::vector<std::uint8_t>& rendered = Access::run_rendered(call.job());
  if (!first || !count || !(*first >= 0) || !(*count >= 1) || *first != std::trunc(*first) ||
      *count != std::trunc(*count) || *first + *count > static_cast<double>(motions.size())) {
    call.fail("the context node is not a <motions first=\"..\" count=\"..\"/> of this document");
    return;
  }
  const auto begin = static_cast<std::size_t>(*first);
  const auto end = begin + static_cast<std::size_t>(*count);
  const bool numbered = numbered_at(call, node);
  std::string out;
  out.reserve((end - begin) * 40);
  for (std::size_t i = begin; i < end; ++i) {
    if (rendered[i] != 0) {
      call.fail("motion " + std::to_string(i) + " of the run was rendered before");
      return;
    }
    rendered[i] = 1;
    const RunMotion& r = motions[i];
    const MotionValues m = motion_of(r);
    if (r.kind == RunMotion::Kind::Arc) {
      const char* plane_word = r.plane == RunMotion::Plane::Yz   ? "G19"
                               : r.plane == RunMotion::Plane::Xz ? "G18"
                                                                 : "G17";
      const std::optional<bool> changed = update_modal(call, "plane", plane_word);
      if (!changed) return;
      if (*changed) {
        append_block_line(call, out, plane_word, numbered);
        out += '\n';
      }
    }
    // The block is written in place: its words go straight after its N word.
    const std::size_t line = begin_block_line(call, out, numbered);
    if (r.kind == RunMotion::Kind::Arc) {
      out += r.rotation > 0 ? ccw : cw;
      if (!append_arc(call, out, form, m)) return;
    } else {
      out += r.kind == RunMotion::Kind::Traverse ? traverse : feed;
      if (!append_end_point(call, out, m)) return;
      record_end_point(call, m);
    }
    end_block_line(call, out, line);
    out += '\n';
  }
  call.push_string(out);
}

constexpr Function kWordFunctions[] = {
    {"motion-words", guarded<fn_motion_words>},       {"arc-words", guarded<fn_arc_words>},
    {"block-line", guarded<fn_block_line>},           {"numbered-line", guarded<fn_numbered_line>},
    {"block-numbering", guarded<fn_block_numbering>}, {"motion-run", guarded<fn_motion_run>},
};

}  // namespace

std::span<const Function> word_functions() {
  return kWordFunctions;
}

}  // namespace ncpost::xslt::detail
