#include "outline.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "../curves.hpp"
#include "milling.hpp"

namespace ncpost::stepnc::features {
namespace {

using poly::P;

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

}  // namespace

P Element::tangent_at_start() const {
  if (!arc) return (b - a) * (1 / (b - a).length());
  const P r = (a - centre) * (1 / radius);
  return sweep > 0 ? P{-r.y, r.x} : P{r.y, -r.x};
}

P Element::tangent_at_end() const {
  if (!arc) return (b - a) * (1 / (b - a).length());
  const P r = (b - centre) * (1 / radius);
  return sweep > 0 ? P{-r.y, r.x} : P{r.y, -r.x};
}

void reverse(Outline& outline) {
  std::reverse(outline.elements.begin(), outline.elements.end());
  for (Element& e : outline.elements) {
    std::swap(e.a, e.b);
    e.sweep = -e.sweep;
  }
}

std::vector<Corner> corners(const Outline& outline) {
  std::vector<Corner> out;
  const auto& el = outline.elements;
  for (std::size_t i = outline.closed ? 0 : 1; i < el.size(); ++i) {
    const std::size_t b = (i + el.size() - 1) % el.size();
    const Element& before = el[b];
    const P t0 = before.tangent_at_end();
    const P t1 = el[i].tangent_at_start();
    const double turn = std::atan2(t0.cross(t1), t0.dot(t1));
    if (std::abs(turn) > 1e-9) out.push_back({el[i].a, turn, t0, t1, b, i});
  }
  return out;
}

namespace {
int pieces(const Element& e, double tolerance) {
  const double half =
      tolerance < e.radius ? std::acos(1 - tolerance / e.radius) : std::numbers::pi / 2;
  return std::max(1, static_cast<int>(std::min(1e9, std::ceil(std::abs(e.sweep) / (2 * half)))));
}
}  // namespace

std::optional<poly::Chain> tessellate(const Outline& outline, double tolerance, bool material_left,
                                      std::size_t max_points) {
  double count = 0;
  for (const Element& e : outline.elements) count += e.arc ? pieces(e, tolerance) + 1 : 1;
  if (count > static_cast<double>(max_points)) return std::nullopt;
  poly::Chain out;
  out.reserve(static_cast<std::size_t>(count) + 1);
  for (const Element& e : outline.elements) {
    out.push_back(e.a);
    if (!e.arc) continue;
    // Chords inside the circle when the material is outside it, else a polyline of tangents.
    const bool centre_left = e.sweep > 0;
    const bool inscribed = centre_left != material_left;
    const double r = e.radius;
    const int n = pieces(e, tolerance);
    const double step = e.sweep / n;
    const double a0 = angle_of(e.a - e.centre);
    if (inscribed) {
      for (int k = 1; k < n; ++k) {
        const double t = a0 + step * k;
        out.push_back(e.centre + P{std::cos(t), std::sin(t)} * r);
      }
    } else {
      const double rr = r / std::cos(step / 2);
      for (int k = 0; k < n; ++k) {
        const double t = a0 + step * (k + 0.5);
        out.push_back(e.centre + P{std::cos(t), std::sin(t)} * rr);
      }
    }
  }
  if (!outline.closed) out.push_back(outline.elements.back().b);
  return out;
}

namespace legacy {
namespace {

// Reads the curve as elements in the feature's frame (the profile's placement applied).
std::optional<Outline> read_curve(Context& ctx, const Instance& profile, const Instance& curve) {
  detail::Frame frame;
  if (ctx.set(profile, "placement")) {
    const auto f = ctx.g.placement(ctx.g.get(profile, "placement"));
    if (!f) return std::nullopt;
    if (std::abs(f->z.z - 1) > 1e-9 || std::abs(f->origin.z) > 1e-9) {
      ctx.not_implemented(ctx.d(profile) + " placed out of the feature's plane");
      return std::nullopt;
    }
    frame = *f;
  }
  // A list longer than the limit is refused before any of it is read.
  const char* list = ctx.is(&curve, "polyline")          ? "points"
                     : ctx.is(&curve, "composite_curve") ? "segments"
                                                         : nullptr;
  if (list != nullptr) {
    const auto items = ctx.g.get(curve, list);
    if (items && items->is_list() && items->count() > ctx.opt.max_profile_elements + 1) {
      ctx.bad(curve, ctx.d(curve) + " has " + std::to_string(items->count()) +
                         " elements, more than FeatureOptions::max_profile_elements (" +
                         std::to_string(ctx.opt.max_profile_elements) + ")");
      return std::nullopt;
    }
  }
  detail::CurveReader reader(ctx.g, kArcTolerance);
  auto segments = reader.segments(curve);
  if (!segments) return std::nullopt;
  if (segments->size() > ctx.opt.max_profile_elements) {
    ctx.bad(curve, ctx.d(curve) + " has " + std::to_string(segments->size()) +
                       " elements, more than FeatureOptions::max_profile_elements (" +
                       std::to_string(ctx.opt.max_profile_elements) + ")");
    return std::nullopt;
  }
  Outline out;
  out.elements.reserve(segments->size());
  for (const detail::Segment& s : *segments) {
    const Vec3 a = frame.point(s.start);
    const Vec3 b = frame.point(s.end);
    for (const Vec3& p : {a, b}) {
      if (!p.finite() || std::abs(p.x) > poly::kMaxCoordinate ||
          std::abs(p.y) > poly::kMaxCoordinate) {
        ctx.bad(curve, ctx.d(curve) + " has a point beyond " + fmt(poly::kMaxCoordinate) +
                           " mm of the feature's origin");
        return std::nullopt;
      }
      if (std::abs(p.z) > kJoinTolerance) {
        ctx.not_implemented(ctx.d(curve) + ", which leaves the plane of " + ctx.d(profile));
        return std::nullopt;
      }
    }
    Element e;
    e.a = xy(a);
    e.b = xy(b);
    if (s.kind == detail::Segment::Kind::Nurbs) {
      ctx.not_implemented(ctx.d(curve) + " with a B-spline segment as a feature boundary");
      return std::nullopt;
    }
    if (s.kind == detail::Segment::Kind::Arc) {
      const Vec3 n = frame.direction(s.normal);
      if (std::abs(std::abs(n.z) - 1) > 1e-9 || std::abs(s.turns) != 1) {
        ctx.not_implemented(ctx.d(curve) + " with an arc that is not in the profile's plane");
        return std::nullopt;
      }
      e.arc = true;
      e.centre = xy(frame.point(s.centre));
      e.radius = (e.a - e.centre).length();
      const bool ccw = (s.turns > 0) == (n.z > 0);
      double sweep = angle_of(e.b - e.centre) - angle_of(e.a - e.centre);
      if (ccw) {
        while (sweep <= 1e-12) sweep += kTwoPi;
      } else {
        while (sweep >= -1e-12) sweep -= kTwoPi;
      }
      e.sweep = sweep;
      if (!(e.radius > kJoinTolerance)) {
        ctx.bad(curve, ctx.d(curve) + " has an arc of no radius");
        return std::nullopt;
      }
    } else if ((e.b - e.a).length() <= kJoinTolerance / 10) {
      continue;  // a repeated point
    }
    if (!out.elements.empty() && (out.elements.back().b - e.a).length() > kJoinTolerance) {
      ctx.bad(curve, ctx.d(curve) + " is not continuous: a segment starts " +
                         fmt((out.elements.back().b - e.a).length()) +
                         " mm from where the previous one ends");
      return std::nullopt;
    }
    if (!out.elements.empty()) e.a = out.elements.back().b;
    out.elements.push_back(e);
  }
  if (out.elements.empty()) {
    ctx.bad(curve, ctx.d(curve) + " has no extent");
    return std::nullopt;
  }
  return out;
}

std::optional<Outline> ngon(Context& ctx, const Instance& profile) {
  const auto d = ctx.toleranced(profile, "diameter");
  const auto n = ctx.number(profile, "number_of_sides");
  const auto circumscribed = ctx.boolean(profile, "circumscribed_or_across_flats");
  if (!d || !n || !(d->size > 0) || *n < 3 || *n != std::floor(*n) ||
      *n > static_cast<double>(ctx.opt.max_profile_elements)) {
    ctx.bad(profile, ctx.d(profile) +
                         " needs a positive diameter and a whole number of sides "
                         "from 3 to " +
                         std::to_string(ctx.opt.max_profile_elements));
    return std::nullopt;
  }
  const int sides = static_cast<int>(*n);
  // TRUE: the diameter is the circle through the vertices; FALSE: across the flats. The first
  // vertex lies on the profile's x axis.
  const double vertex =
      circumscribed.value_or(true) ? d->size / 2 : d->size / 2 / std::cos(std::numbers::pi / sides);
  if (vertex > poly::kMaxCoordinate) {
    ctx.bad(profile, ctx.d(profile) + " is larger than " + fmt(poly::kMaxCoordinate) + " mm");
    return std::nullopt;
  }
  detail::Frame frame;
  if (ctx.set(profile, "placement")) {
    const auto f = ctx.g.placement(ctx.g.get(profile, "placement"));
    if (!f) return std::nullopt;
    if (std::abs(f->z.z - 1) > 1e-9 || std::abs(f->origin.z) > 1e-9) {
      ctx.not_implemented(ctx.d(profile) + " placed out of the feature's plane");
      return std::nullopt;
    }
    frame = *f;
  }
  Outline out;
  const auto at = [&](int k) {
    const double t = kTwoPi * k / sides;
    return xy(frame.point({vertex * std::cos(t), vertex * std::sin(t), 0}));
  };
  for (int k = 0; k < sides; ++k) {
    Element e;
    e.a = at(k);
    e.b = k + 1 == sides ? out.elements.front().a : at(k + 1);
    out.elements.push_back(e);
  }
  return out;
}

}  // namespace

std::optional<Outline> read_closed_outline(Context& ctx, const Instance& boundary) {
  std::optional<Outline> out;
  if (ctx.is(&boundary, "ngon_closed_profile")) {
    out = ngon(ctx, boundary);
  } else if (ctx.is(&boundary, "general_closed_profile")) {
    const Instance* curve = ctx.ref(boundary, "closed_profile_shape", "bounded_curve");
    if (curve == nullptr) {
      ctx.bad(boundary, ctx.d(boundary) + " has no closed_profile_shape");
      return std::nullopt;
    }
    out = read_curve(ctx, boundary, *curve);
    if (out) {
      const P gap = out->elements.back().b - out->elements.front().a;
      if (gap.length() > kJoinTolerance) {
        ctx.bad(*curve, ctx.d(*curve) + " of " + ctx.d(boundary) + " is not closed: it ends " +
                            fmt(gap.length()) + " mm from its start");
        return std::nullopt;
      }
      out->elements.back().b = out->elements.front().a;
    }
  } else {
    ctx.not_implemented(ctx.d(boundary) + " as a general boundary");
    return std::nullopt;
  }
  if (!out) return std::nullopt;
  out->closed = true;
  // Counter-clockwise, so that the inside is on the left (the sense of a polygon of it decides).
  const auto polygon = tessellate(*out, 0.01, false, ctx.opt.max_polygon_points);
  if (!polygon) {
    ctx.bad(boundary, ctx.d(boundary) + " needs more than FeatureOptions::max_polygon_points (" +
                          std::to_string(ctx.opt.max_polygon_points) + ") polygon points");
    return std::nullopt;
  }
  if (poly::area(*polygon) < 0) reverse(*out);
  return out;
}

std::optional<Outline> read_open_outline(Context& ctx, const Instance& boundary) {
  if (!ctx.is(&boundary, "general_profile")) {
    ctx.not_implemented(ctx.d(boundary) + " as the open boundary of " + ctx.d(ctx.feature()) +
                        " (a GENERAL_PROFILE is)");
    return std::nullopt;
  }
  const Instance* curve = ctx.ref(boundary, "its_profile", "bounded_curve");
  if (curve == nullptr) {
    ctx.bad(boundary, ctx.d(boundary) + " has no its_profile");
    return std::nullopt;
  }
  auto out = read_curve(ctx, boundary, *curve);
  if (!out) return std::nullopt;
  out->closed = false;
  return out;
}

}  // namespace legacy
}  // namespace ncpost::stepnc::features
