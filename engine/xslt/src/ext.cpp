// The urn:ncpost:ext extension module: functions a profile calls from XPath, with state per
// job. Registered once (initialise) with xsltRegisterExtModule. The functions find the job
// through ctxt->_private, which transform() sets to its run (checked: the run names the
// context). Reference and examples: docs/xslt-extensions.md.

#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>
#include <libxslt/extensions.h>
#include <libxslt/transform.h>
#include <libxslt/variables.h>
#include <libxslt/xsltutils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "ext_call.hpp"
#include "ext_math.hpp"
#include "internal.hpp"

namespace ncpost::xslt::detail {
namespace {

const xmlChar* ns() {
  return reinterpret_cast<const xmlChar*>(kExtNamespace);
}

// Per transform: the run that transform() put in ctxt->_private (null when a transform was
// started some other way; the functions then refuse to work).
struct ExtData {
  TransformRun* run;
};

void* ext_init(xsltTransformContextPtr ctxt, const xmlChar*) {
  auto* run = ctxt != nullptr ? static_cast<TransformRun*>(ctxt->_private) : nullptr;
  if (run != nullptr && run->ctxt != ctxt) run = nullptr;  // not ours
  return new (std::nothrow) ExtData{run};
}

void ext_shutdown(xsltTransformContextPtr, const xmlChar*, void* data) {
  delete static_cast<ExtData*>(data);
}

constexpr std::size_t kMaxPieces = 100000;

std::optional<int> turns_of(Call& call, std::size_t n) {
  const double t = call.number(n, "turns");
  if (!call.ok()) return std::nullopt;
  if (t != std::trunc(t) || t == 0 || std::abs(t) > 1000) {
    call.fail("turns must be a non-zero whole number (positive counter-clockwise), not " +
              shortest(t));
    return std::nullopt;
  }
  return static_cast<int>(t);
}

std::optional<PlaneArc> plane_arc(Call& call, std::size_t sx, std::size_t ex, std::size_t cx,
                                  std::size_t turns) {
  PlaneArc a{call.number(sx, "start-x"),
             call.number(sx + 1, "start-y"),
             call.number(ex, "end-x"),
             call.number(ex + 1, "end-y"),
             call.number(cx, "centre-x"),
             call.number(cx + 1, "centre-y"),
             0};
  const std::optional<int> t = turns_of(call, turns);
  if (!call.ok() || !t) return std::nullopt;
  a.turns = *t;
  return a;
}

// ---- block numbers ----

void fn_block(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "block", 0, 0);
  if (!call.ok()) return;
  call.push_string(std::to_string(next_block_number(call.job())));
}

void fn_block_reset(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "block-reset", 0, 0);
  if (!call.ok()) return;
  Access::next_block(call.job()) = call.config().block.start;
  call.push_string("");
}

// ---- number formatting and units ----

void fn_format(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "format", 2, 2);
  if (!call.ok()) return;
  const std::string_view name = call.view(1);
  const std::optional<Quantity> quantity = quantity_named(name);
  if (!quantity) {
    call.fail("unknown quantity '" + std::string(name) + "' (length, angle, feed, speed or dwell)");
    return;
  }
  const double value = call.number(0, "the value");
  if (!call.ok()) return;
  std::string text;
  if (!append_quantity(text, call.config(), Access::program_unit_mm(call.job()), *quantity,
                       value)) {
    call.fail("the value is out of range");
    return;
  }
  call.push_string(text);
}

void fn_units(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "units", 0, 0);
  if (!call.ok()) return;
  call.push_string(call.config().units == Units::Inch ? "inch" : "mm");
}

void fn_program_units(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "program-units", 1, 1);
  if (!call.ok()) return;
  const std::string_view units = call.view(0);
  double mm = 0;
  if (units == "mm")
    mm = 1.0;
  else if (units == "inch")
    mm = 25.4;
  else if (units == "cm")
    mm = 10.0;
  if (mm == 0) {
    call.fail("unknown units '" + std::string(units) +
              "' (mm, inch or cm, as USE_LENGTH_UNITS/@units)");
    return;
  }
  Access::program_unit_mm(call.job()) = mm;
  call.push_string("");
}

// ---- modal suppression ----

void fn_modal(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "modal", 2, 2);
  if (!call.ok()) return;
  const std::optional<bool> changed = update_modal(call, call.view(0), call.view(1));
  if (!changed) return;
  if (*changed)
    call.push_argument(1);
  else
    call.push_string("");
}

void fn_modal_reset(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "modal-reset", 0, 1);
  if (!call.ok()) return;
  auto& modal = Access::modal(call.job());
  if (call.count() == 0) {
    modal.clear();
  } else {
    const auto found = modal.find(call.string(0));
    if (found != modal.end()) modal.erase(found);
  }
  call.push_string("");
}

// ---- current position ----

void fn_moved_to(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "moved-to", 3, 3);
  if (!call.ok()) return;
  const std::array<double, 3> p{call.number(0, "x"), call.number(1, "y"), call.number(2, "z")};
  if (!call.ok()) return;
  Access::position(call.job()) = p;
  Access::has_position(call.job()) = true;
  call.push_string("");
}

void fn_position(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "position", 1, 1);
  if (!call.ok()) return;
  const std::string_view axis = call.view(0);
  if (axis != "x" && axis != "y" && axis != "z") {
    call.fail("axis '" + std::string(axis) + "' is not x, y or z");
    return;
  }
  if (!Access::has_position(call.job())) {
    call.fail("no position yet: call ext:moved-to(x, y, z) after each motion");
    return;
  }
  call.push_number(Access::position(call.job())[static_cast<std::size_t>(axis[0] - 'x')]);
}

// ---- machine set-up transform ----

template <int Row, bool WithTranslation>
void setup_component(xmlXPathParserContextPtr x, int nargs, const char* name) {
  Call call(x, nargs, name, 3, 3);
  if (!call.ok()) return;
  const std::array<double, 3> p{call.number(0, "x"), call.number(1, "y"), call.number(2, "z")};
  if (!call.ok()) return;
  call.push_number(setup_axis(call.config().setup, Row, p, WithTranslation));
}

void fn_setup_x(xmlXPathParserContextPtr x, int n) {
  setup_component<0, true>(x, n, "setup-x");
}
void fn_setup_y(xmlXPathParserContextPtr x, int n) {
  setup_component<1, true>(x, n, "setup-y");
}
void fn_setup_z(xmlXPathParserContextPtr x, int n) {
  setup_component<2, true>(x, n, "setup-z");
}
void fn_setup_i(xmlXPathParserContextPtr x, int n) {
  setup_component<0, false>(x, n, "setup-i");
}
void fn_setup_j(xmlXPathParserContextPtr x, int n) {
  setup_component<1, false>(x, n, "setup-j");
}
void fn_setup_k(xmlXPathParserContextPtr x, int n) {
  setup_component<2, false>(x, n, "setup-k");
}

// ---- arcs ----

void fn_arc_sweep(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "arc-sweep", 7, 7);
  if (!call.ok()) return;
  const std::optional<PlaneArc> arc = plane_arc(call, 0, 2, 4, 6);
  if (!arc) return;
  const std::optional<double> sweep = arc_sweep(*arc);
  if (!sweep) {
    call.fail("the start point is on the centre");
    return;
  }
  call.push_number(*sweep);
}

void fn_arc_r(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "arc-r", 7, 7);
  if (!call.ok()) return;
  const std::optional<PlaneArc> arc = plane_arc(call, 0, 2, 4, 6);
  if (!arc) return;
  const std::optional<double> r = arc_radius(*arc);
  if (!r) {
    call.fail(
        "a full circle (or more) and a zero radius have no R form; use I, J, K (ext:arc-sweep "
        "tells)");
    return;
  }
  call.push_number(*r);
}

void arc_offset(xmlXPathParserContextPtr x, int nargs, const char* name) {
  Call call(x, nargs, name, 2, 2);
  if (!call.ok()) return;
  const double start = call.number(0, "start");
  const double centre = call.number(1, "centre");
  if (!call.ok()) return;
  const double offset = centre - start;
  call.push_number(offset == 0 ? 0.0 : offset);
}

void fn_arc_i(xmlXPathParserContextPtr x, int n) {
  arc_offset(x, n, "arc-i");
}
void fn_arc_j(xmlXPathParserContextPtr x, int n) {
  arc_offset(x, n, "arc-j");
}
void fn_arc_k(xmlXPathParserContextPtr x, int n) {
  arc_offset(x, n, "arc-k");
}

template <int Component>
void arc_centre_component(xmlXPathParserContextPtr x, int nargs, const char* name) {
  Call call(x, nargs, name, 6, 6);
  if (!call.ok()) return;
  const double sx = call.number(0, "start-x");
  const double sy = call.number(1, "start-y");
  const double ex = call.number(2, "end-x");
  const double ey = call.number(3, "end-y");
  const double r = call.number(4, "r");
  if (!call.ok()) return;
  bool clockwise = false;
  const std::string direction = call.is_string(5) ? call.string(5) : std::string();
  if (direction == "cw" || direction == "CW") {
    clockwise = true;
  } else if (direction == "ccw" || direction == "CCW") {
    clockwise = false;
  } else {
    const double d = call.number(5, "direction");
    if (!call.ok()) return;
    if (d == 0) {
      call.fail("direction is 'cw', 'ccw' or a signed number (negative: clockwise)");
      return;
    }
    clockwise = d < 0;
  }
  const std::optional<std::array<double, 2>> centre = arc_centre(sx, sy, ex, ey, r, clockwise);
  if (!centre) {
    call.fail("no circle of radius " + shortest(std::abs(r)) + " joins the two points");
    return;
  }
  call.push_number((*centre)[Component]);
}

void fn_arc_centre_x(xmlXPathParserContextPtr x, int n) {
  arc_centre_component<0>(x, n, "arc-centre-x");
}
void fn_arc_centre_y(xmlXPathParserContextPtr x, int n) {
  arc_centre_component<1>(x, n, "arc-centre-y");
}

// (sx, sy, sz, ex, ey, ez, cx, cy, turns[, max-sweep])
void arc_split_common(xmlXPathParserContextPtr x, int nargs, bool quadrants) {
  Call call(x, nargs, quadrants ? "arc-split-quadrants" : "arc-split", quadrants ? 9 : 10,
            quadrants ? 9 : 10);
  if (!call.ok()) return;
  PlaneArc arc{call.number(0, "start-x"),
               call.number(1, "start-y"),
               call.number(3, "end-x"),
               call.number(4, "end-y"),
               call.number(6, "centre-x"),
               call.number(7, "centre-y"),
               0};
  const double sz = call.number(2, "start-z");
  const double ez = call.number(5, "end-z");
  const std::optional<int> turns = turns_of(call, 8);
  if (!call.ok() || !turns) return;
  arc.turns = *turns;
  std::optional<std::vector<Point3>> points;
  if (quadrants) {
    points = arc_split_quadrants(arc, sz, ez, kMaxPieces);
  } else {
    const double max_sweep = call.number(9, "max-sweep");
    if (!call.ok()) return;
    if (!(max_sweep > 0)) {
      call.fail("max-sweep must be a positive number of degrees");
      return;
    }
    points = arc_split(arc, sz, ez, max_sweep, kMaxPieces);
  }
  if (!points) {
    call.fail("the arc cannot be split (start on the centre, or more than " +
              std::to_string(kMaxPieces) + " pieces)");
    return;
  }
  call.push_points(*points);
}

void fn_arc_split(xmlXPathParserContextPtr x, int n) {
  arc_split_common(x, n, false);
}
void fn_arc_split_quadrants(xmlXPathParserContextPtr x, int n) {
  arc_split_common(x, n, true);
}

// ---- rotary axes ----

void fn_rotary(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "rotary", 5, 5);
  if (!call.ok()) return;
  const double i = call.number(0, "i");
  const double j = call.number(1, "j");
  const double k = call.number(2, "k");
  if (!call.ok()) return;
  const std::string kinematics = call.string(3);
  const std::string which = call.string(4);
  if (kinematics != "AC" && kinematics != "BC") {
    call.fail("kinematics '" + kinematics + "' is not AC or BC");
    return;
  }
  const char tilt_axis = kinematics[0];
  if (which.size() != 1 || (which[0] != tilt_axis && which[0] != 'C')) {
    call.fail("axis '" + which + "' is not one of " + kinematics);
    return;
  }
  double& last_c = Access::last_c(call.job());
  const std::optional<Rotary> r = rotary_angles(i, j, k, kinematics, last_c);
  if (!r) {
    call.fail("the tool axis (0, 0, 0) has no direction");
    return;
  }
  if (which[0] == 'C') {
    last_c = r->c;
    call.push_number(r->c);
  } else {
    call.push_number(r->tilt);
  }
}

// ---- comments and lines ----

void fn_comment(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "comment", 1, 1);
  if (!call.ok()) return;
  call.push_string(sanitize_comment(call.string(0), call.config().comment));
}

void fn_line(xmlXPathParserContextPtr x, int nargs) {
  Call call(x, nargs, "line", 1, 1);
  if (!call.ok()) return;
  check_line_length(call, call.view(0));
  call.push_argument(0);
}

constexpr Function kFunctions[] = {
    {"block", guarded<fn_block>},
    {"block-reset", guarded<fn_block_reset>},
    {"format", guarded<fn_format>},
    {"units", guarded<fn_units>},
    {"program-units", guarded<fn_program_units>},
    {"modal", guarded<fn_modal>},
    {"modal-reset", guarded<fn_modal_reset>},
    {"moved-to", guarded<fn_moved_to>},
    {"position", guarded<fn_position>},
    {"setup-x", guarded<fn_setup_x>},
    {"setup-y", guarded<fn_setup_y>},
    {"setup-z", guarded<fn_setup_z>},
    {"setup-i", guarded<fn_setup_i>},
    {"setup-j", guarded<fn_setup_j>},
    {"setup-k", guarded<fn_setup_k>},
    {"arc-sweep", guarded<fn_arc_sweep>},
    {"arc-r", guarded<fn_arc_r>},
    {"arc-i", guarded<fn_arc_i>},
    {"arc-j", guarded<fn_arc_j>},
    {"arc-k", guarded<fn_arc_k>},
    {"arc-centre-x", guarded<fn_arc_centre_x>},
    {"arc-centre-y", guarded<fn_arc_centre_y>},
    {"arc-split", guarded<fn_arc_split>},
    {"arc-split-quadrants", guarded<fn_arc_split_quadrants>},
    {"rotary", guarded<fn_rotary>},
    {"comment", guarded<fn_comment>},
    {"line", guarded<fn_line>},
};

}  // namespace

void register_extensions() {
  xsltRegisterExtModule(ns(), ext_init, ext_shutdown);
  for (const Function& f : kFunctions)
    xsltRegisterExtModuleFunction(name_of(f.name), ns(), f.function);
  for (const Function& f : word_functions())
    xsltRegisterExtModuleFunction(name_of(f.name), ns(), f.function);
}

}  // namespace ncpost::xslt::detail

namespace ncpost::xslt {

SetupTransform SetupTransform::from_rotation(std::array<double, 3> axis, double angle_degrees,
                                             std::array<double, 3> translation) {
  SetupTransform s;
  s.translation = translation;
  const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(length > 0)) return s;
  const double ux = axis[0] / length;
  const double uy = axis[1] / length;
  const double uz = axis[2] / length;
  const double a = angle_degrees * std::acos(-1.0) / 180.0;
  // Exact quarter turns stay exact (cos 90 degrees is not 0 in floating point).
  double c = std::cos(a);
  double sn = std::sin(a);
  const double quarters = angle_degrees / 90.0;
  if (quarters == std::round(quarters)) {
    const long q = ((std::lround(quarters) % 4) + 4) % 4;
    c = q == 0 ? 1 : q == 2 ? -1 : 0;
    sn = q == 1 ? 1 : q == 3 ? -1 : 0;
  }
  const double t = 1 - c;
  // R: the active rotation by the angle about the axis (Rodrigues). The machine axes are the
  // program axes turned by R, so a point's machine coordinates are R^T p: the matrix stored
  // is the transpose.
  const std::array<double, 9> r{t * ux * ux + c,       t * ux * uy - sn * uz, t * ux * uz + sn * uy,
                                t * ux * uy + sn * uz, t * uy * uy + c,       t * uy * uz - sn * ux,
                                t * ux * uz - sn * uy, t * uy * uz + sn * ux, t * uz * uz + c};
  s.matrix = {r[0], r[3], r[6], r[1], r[4], r[7], r[2], r[5], r[8]};
  return s;
}

}  // namespace ncpost::xslt
