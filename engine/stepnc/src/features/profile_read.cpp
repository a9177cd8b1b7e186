// The readers of feature profiles (profile_read.hpp).

#include "profile_read.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../curves.hpp"
#include "implicit.hpp"
#include "milling_read.hpp"

namespace ncpost::stepnc::features {
namespace {

using poly::P;

constexpr double kEps = 1e-9;
constexpr double kTwoPi = 2 * std::numbers::pi;
// How far apart (mm) the end of one element and the start of the next may be: P21 files round
// coordinates, and a trimmed curve's end points are written separately from its neighbours'.
constexpr double kJoinTolerance = 1e-3;
// Arcs whose end points are off their circle by more than this are refused (STEPNC-012).
constexpr double kArcTolerance = 1e-3;

P xy(Vec3 v) {
  return {v.x, v.y};
}

double angle_of(P v) {
  return std::atan2(v.y, v.x);
}

// A list longer than the limit is refused before any of it is read.
bool check_element_count(Reader& reader, const Instance& curve, std::size_t count) {
  const std::size_t limit = reader.options().max_profile_elements;
  if (count <= limit) return true;
  return reader.report().bad(reader.subject(curve),
                             reader.name(curve) + " has " + std::to_string(count) +
                                 " elements, more than FeatureOptions::max_profile_elements (" +
                                 std::to_string(limit) + ")");
}

// One segment of a curve as an element of the outline, in the feature's frame; nullopt after
// reporting (a point too far out or out of the plane, a B-spline, an arc out of the plane or of
// no radius); an element with `a == b` for a repeated point.
std::optional<Element> element_of(Reader& reader, const Instance& profile, const Instance& curve,
                                  const detail::Frame& frame, const detail::Segment& s) {
  Report& report = reader.report();
  const Vec3 a = frame.point(s.start);
  const Vec3 b = frame.point(s.end);
  for (const Vec3& p : {a, b}) {
    if (!p.finite() || std::abs(p.x) > poly::kMaxCoordinate ||
        std::abs(p.y) > poly::kMaxCoordinate) {
      report.bad(reader.subject(curve), reader.name(curve) + " has a point beyond " +
                                            fmt(poly::kMaxCoordinate) +
                                            " mm of the feature's origin");
      return std::nullopt;
    }
    if (std::abs(p.z) > kJoinTolerance) {
      report.not_implemented(reader.name(curve) + ", which leaves the plane of " +
                             reader.name(profile));
      return std::nullopt;
    }
  }
  Element e;
  e.start = xy(a);
  e.end = xy(b);
  if (s.kind == detail::Segment::Kind::Nurbs) {
    report.not_implemented(reader.name(curve) + " with a B-spline segment as a feature boundary");
    return std::nullopt;
  }
  if (s.kind != detail::Segment::Kind::Arc) return e;
  const Vec3 n = frame.direction(s.normal);
  if (std::abs(std::abs(n.z) - 1) > 1e-9 || std::abs(s.turns) != 1) {
    report.not_implemented(reader.name(curve) + " with an arc that is not in the profile's plane");
    return std::nullopt;
  }
  e.arc = true;
  e.centre = xy(frame.point(s.centre));
  e.radius = (e.start - e.centre).length();
  const bool ccw = (s.turns > 0) == (n.z > 0);
  double sweep = angle_of(e.end - e.centre) - angle_of(e.start - e.centre);
  if (ccw) {
    while (sweep <= 1e-12) sweep += kTwoPi;
  } else {
    while (sweep >= -1e-12) sweep -= kTwoPi;
  }
  e.sweep = sweep;
  if (!(e.radius > kJoinTolerance)) {
    report.bad(reader.subject(curve), reader.name(curve) + " has an arc of no radius");
    return std::nullopt;
  }
  return e;
}

// Reads the curve as elements in the feature's frame (the profile's placement applied).
std::optional<Outline> read_curve(Reader& reader, const Instance& profile, const Instance& curve) {
  detail::Frame frame;
  if (!read_profile_placement(reader, profile, "feature's", frame)) return std::nullopt;
  const char* list = reader.is(&curve, "polyline")          ? "points"
                     : reader.is(&curve, "composite_curve") ? "segments"
                                                            : nullptr;
  if (list != nullptr) {
    const auto items = reader.get(curve, list);
    // One more than the limit: a closed polyline repeats its first point.
    if (items && items->is_list() && items->count() > reader.options().max_profile_elements + 1 &&
        !check_element_count(reader, curve, items->count()))
      return std::nullopt;
  }
  detail::CurveReader curves(reader.geometry(), kArcTolerance);
  auto segments = curves.segments(curve);
  if (!segments || !check_element_count(reader, curve, segments->size())) return std::nullopt;
  Outline out;
  out.elements.reserve(segments->size());
  for (const detail::Segment& s : *segments) {
    auto e = element_of(reader, profile, curve, frame, s);
    if (!e) return std::nullopt;
    if (!e->arc && (e->end - e->start).length() <= kJoinTolerance / 10)
      continue;  // a repeated point
    if (!out.elements.empty() && (out.elements.back().end - e->start).length() > kJoinTolerance) {
      reader.report().bad(reader.subject(curve),
                          reader.name(curve) + " is not continuous: a segment starts " +
                              fmt((out.elements.back().end - e->start).length()) +
                              " mm from where the previous one ends");
      return std::nullopt;
    }
    if (!out.elements.empty()) e->start = out.elements.back().end;
    out.elements.push_back(*e);
  }
  if (out.elements.empty()) {
    reader.report().bad(reader.subject(curve), reader.name(curve) + " has no extent");
    return std::nullopt;
  }
  return out;
}

std::optional<Outline> ngon(Reader& reader, const Instance& profile) {
  const auto d = reader.toleranced(profile, "diameter");
  const auto n = reader.number(profile, "number_of_sides");
  const auto circumscribed = reader.boolean(profile, "circumscribed_or_across_flats");
  const std::size_t limit = reader.options().max_profile_elements;
  if (!d || !n || !(d->size > 0) || *n < 3 || *n != std::floor(*n) ||
      *n > static_cast<double>(limit)) {
    reader.report().bad(reader.subject(profile),
                        reader.name(profile) +
                            " needs a positive diameter and a whole number of sides "
                            "from 3 to " +
                            std::to_string(limit));
    return std::nullopt;
  }
  const int sides = static_cast<int>(*n);
  // TRUE: the diameter is the circle through the vertices; FALSE: across the flats. The first
  // vertex lies on the profile's x axis.
  const double vertex =
      circumscribed.value_or(true) ? d->size / 2 : d->size / 2 / std::cos(std::numbers::pi / sides);
  if (vertex > poly::kMaxCoordinate) {
    reader.report().bad(reader.subject(profile), reader.name(profile) + " is larger than " +
                                                     fmt(poly::kMaxCoordinate) + " mm");
    return std::nullopt;
  }
  detail::Frame frame;
  if (!read_profile_placement(reader, profile, "feature's", frame)) return std::nullopt;
  Outline out;
  const auto at = [&](int k) {
    const double t = kTwoPi * k / sides;
    return xy(frame.point({vertex * std::cos(t), vertex * std::sin(t), 0}));
  };
  for (int k = 0; k < sides; ++k) {
    Element e;
    e.start = at(k);
    e.end = k + 1 == sides ? out.elements.front().start : at(k + 1);
    out.elements.push_back(e);
  }
  return out;
}

// A general closed profile's curve, which must end where it starts.
std::optional<Outline> general_closed(Reader& reader, const Instance& boundary) {
  const Instance* curve = reader.ref(boundary, "closed_profile_shape", "bounded_curve");
  if (curve == nullptr) {
    reader.report().bad(reader.subject(boundary),
                        reader.name(boundary) + " has no closed_profile_shape");
    return std::nullopt;
  }
  auto out = read_curve(reader, boundary, *curve);
  if (!out) return std::nullopt;
  const P gap = out->elements.back().end - out->elements.front().start;
  if (gap.length() > kJoinTolerance && close_implicitly(reader, boundary, *curve, gap.length())) {
    Element closing;
    closing.start = out->elements.back().end;
    closing.end = out->elements.front().start;
    out->elements.push_back(closing);
  } else if (gap.length() > kJoinTolerance) {
    reader.report().bad(reader.subject(*curve),
                        reader.name(*curve) + " of " + reader.name(boundary) +
                            " is not closed: it ends " + fmt(gap.length()) + " mm from its start");
    return std::nullopt;
  }
  out->elements.back().end = out->elements.front().start;
  return out;
}

}  // namespace

bool read_profile_placement(Reader& reader, const Instance& profile, std::string_view plane,
                            detail::Frame& frame) {
  if (!reader.set(profile, "placement")) return true;
  const auto placed = reader.placement(profile, "placement");
  if (!placed) return false;
  if (std::abs(placed->z.z - 1) > 1e-9 || std::abs(placed->origin.z) > kEps)
    return reader.report().not_implemented(reader.name(profile) + " placed out of the " +
                                           std::string(plane) + " plane");
  frame = *placed;
  return true;
}

bool read_closed_profile(Reader& reader, const Instance& boundary, double corner,
                         std::string_view plane, Shape& shape) {
  Report& report = reader.report();
  const Instance& f = reader.feature();
  if (reader.is(&boundary, "rectangular_closed_profile")) {
    const auto w = reader.toleranced(boundary, "profile_width");
    const auto l = reader.toleranced(boundary, "profile_length");
    if (!w || !l || !(w->size > 0) || !(l->size > 0))
      return report.bad(reader.subject(boundary),
                        reader.name(boundary) + " needs a positive width and length");
    // Length along the profile's x axis, width along y: as NIST's ex1/ex1E pair places it.
    shape = Shape::rectangle(l->size / 2, w->size / 2, corner);
    if (shape.corner > std::min(shape.half_length, shape.half_width) + kEps)
      return report.bad(reader.subject(f),
                        reader.name(f) + " orthogonal_radius " + fmt(shape.corner) +
                            " is more than half the width of " + reader.name(boundary));
  } else if (reader.is(&boundary, "circular_closed_profile")) {
    const auto dia = reader.toleranced(boundary, "diameter");
    if (!dia || !(dia->size > 0))
      return report.bad(reader.subject(boundary),
                        reader.name(boundary) + " needs a positive diameter");
    shape = Shape::circle(dia->size / 2);
  } else {
    return report.not_implemented(reader.name(f) + " bounded by " + reader.name(boundary));
  }
  return read_profile_placement(reader, boundary, plane, shape.frame);
}

std::optional<Outline> read_closed_outline(Reader& reader, const Instance& boundary) {
  std::optional<Outline> out;
  if (reader.is(&boundary, "ngon_closed_profile")) {
    out = ngon(reader, boundary);
  } else if (reader.is(&boundary, "general_closed_profile")) {
    out = general_closed(reader, boundary);
  } else {
    reader.report().not_implemented(reader.name(boundary) + " as a general boundary");
    return std::nullopt;
  }
  if (!out) return std::nullopt;
  out->closed = true;
  // Counter-clockwise, so that the inside is on the left (the sense of a polygon of it decides).
  const auto polygon = tessellate(*out, 0.01, false, reader.options().max_polygon_points);
  if (!polygon) {
    reader.report().bad(
        reader.subject(boundary),
        reader.name(boundary) + " needs more than FeatureOptions::max_polygon_points (" +
            std::to_string(reader.options().max_polygon_points) + ") polygon points");
    return std::nullopt;
  }
  if (poly::area(*polygon) < 0) reverse(*out);
  return out;
}

std::optional<Outline> read_open_outline(Reader& reader, const Instance& boundary) {
  if (!reader.is(&boundary, "general_profile")) {
    reader.report().not_implemented(reader.name(boundary) + " as the open boundary of " +
                                    reader.name(reader.feature()) + " (a GENERAL_PROFILE is)");
    return std::nullopt;
  }
  const Instance* curve = reader.ref(boundary, "its_profile", "bounded_curve");
  if (curve == nullptr) {
    reader.report().bad(reader.subject(boundary), reader.name(boundary) + " has no its_profile");
    return std::nullopt;
  }
  auto out = read_curve(reader, boundary, *curve);
  if (!out) return std::nullopt;
  out->closed = false;
  return out;
}

bool corner_checks(Reader& reader, const Outline& outline, const Tool& tool,
                   const Operation& operation, double corner_radius, bool material_outside) {
  const double d = tool.radius + operation.allowance_side;
  const auto who = [&] {
    return tool.subject.name() + " radius " + fmt(tool.radius) + " + allowance " +
           fmt(operation.allowance_side) + " of " + operation.subject.name();
  };
  const auto feature = [&] { return reader.name(reader.feature()); };
  // A corner turning towards the material is one the tool must fit into.
  const double sign = material_outside ? 1 : -1;
  // Roughing leaves the stock it cannot reach in corners tighter than the tool for the
  // finishing pass: a warning with the largest stock left, once per feature (the first such
  // corner named).
  const bool rough = roughing(reader);
  std::string first;
  double stock = 0;
  const auto tight = [&](const std::string& what, double left) {
    if (!rough) return reader.report().unfit(tool.subject, what);
    if (first.empty()) first = what;
    stock = std::max(stock, left);
    return true;
  };
  for (const Corner& c : corners(outline)) {
    if (sign * c.turn <= 0) continue;
    const double secant = 1 / std::cos(std::min(std::abs(c.turn), 3.1) / 2) - 1;
    const double left = d * secant;
    if (left <= reader.options().corner_tolerance || corner_radius + kEps >= d) continue;
    if (!tight(who() + " > corner radius " + fmt(corner_radius) + " of " + feature() + " at " +
                   at_text(c.at),
               (d - corner_radius) * secant))
      return false;
  }
  for (const Element& e : outline.elements) {
    if (!e.arc || sign * e.sweep <= 0 || e.radius + kEps >= d ||
        std::max(e.radius, corner_radius) + kEps >= d)
      continue;
    const double mid = std::atan2((e.start - e.centre).y, (e.start - e.centre).x) + e.sweep / 2;
    // An arc of the outline itself (not a corner's fillet) that the tool cannot follow: the
    // outline the part must have, which roughing too may not leave unmachined in general.
    return reader.report().unfit(
        tool.subject, who() + " > arc radius " + fmt(e.radius) + " of " + feature() + " at " +
                          at_text(e.centre + P{std::cos(mid), std::sin(mid)} * e.radius));
  }
  if (!first.empty())
    reader.report().stock_left(tool.subject, first + ": the roughing pass leaves up to " +
                                                 fmt(stock) +
                                                 " mm more stock there for the finishing pass");
  return true;
}

std::optional<poly::Ring> polygon_of(Reader& reader, const Instance& at, const Outline& outline,
                                     bool material_left) {
  const FeatureOptions& options = reader.options();
  auto ring =
      tessellate(outline, options.chord_tolerance, material_left, options.max_polygon_points);
  if (!ring) {
    reader.report().bad(reader.subject(at),
                        reader.name(at) + " needs more than FeatureOptions::max_polygon_points (" +
                            std::to_string(options.max_polygon_points) + ") polygon points");
    return std::nullopt;
  }
  if (!poly::simple(*ring)) {
    reader.report().bad(reader.subject(at),
                        reader.name(at) + " crosses itself or encloses no area");
    return std::nullopt;
  }
  return ring;
}

}  // namespace ncpost::stepnc::features
