// The material that orthogonal_radius adds in a general pocket's sharp corners (profile_read.hpp).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "profile_read.hpp"

namespace ncpost::stepnc::features {
namespace {

using poly::Area;
using poly::Areas;
using poly::P;
using poly::Ring;

constexpr double kEps = 1e-9;

// Points of the arc about `c` of radius `r` from angle `from` through `sweep`, after its start
// and up to its end, no chord further than `tolerance` from it.
void append_arc(Ring& ring, P c, double r, double from, double sweep, double tolerance) {
  const double step = r > tolerance ? 2 * std::acos(1 - tolerance / r) : std::numbers::pi / 2;
  const int n = std::clamp(static_cast<int>(std::ceil(std::abs(sweep) / step)), 1, 1 << 16);
  for (int k = 1; k <= n; ++k) {
    const double a = from + sweep * k / n;
    ring.push_back(c + P{std::cos(a), std::sin(a)} * r);
  }
}

double angle_of(P v) {
  return std::atan2(v.y, v.x);
}

// Where a point at `rho` to the left of element `e` may be: a line or a circle.
struct Carrier {
  bool circle = false;
  P point, dir;  // line
  P centre;      // circle
  double radius = 0;
};

std::optional<Carrier> offset_carrier(const Element& e, double rho) {
  Carrier c;
  if (!e.arc) {
    c.dir = (e.end - e.start) * (1 / (e.end - e.start).length());
    c.point = e.start + P{-c.dir.y, c.dir.x} * rho;
    return c;
  }
  c.circle = true;
  c.centre = e.centre;
  c.radius = e.sweep > 0 ? e.radius - rho : e.radius + rho;
  if (!(c.radius > kEps)) return std::nullopt;
  return c;
}

std::vector<P> intersections(const Carrier& a, const Carrier& b) {
  std::vector<P> out;
  if (!a.circle && !b.circle) {
    const double den = a.dir.cross(b.dir);
    if (std::abs(den) < 1e-12) return out;
    out.push_back(a.point + a.dir * ((b.point - a.point).cross(b.dir) / den));
    return out;
  }
  if (a.circle && b.circle) {
    const P d = b.centre - a.centre;
    const double l = d.length();
    if (l < 1e-12 || l > a.radius + b.radius || l < std::abs(a.radius - b.radius)) return out;
    const double x = (l * l + a.radius * a.radius - b.radius * b.radius) / (2 * l);
    const double h = std::sqrt(std::max(0.0, a.radius * a.radius - x * x));
    const P u = d * (1 / l);
    const P m = a.centre + u * x;
    out.push_back(m + P{-u.y, u.x} * h);
    out.push_back(m - P{-u.y, u.x} * h);
    return out;
  }
  const Carrier& line = a.circle ? b : a;
  const Carrier& circle = a.circle ? a : b;
  const P f = line.point - circle.centre;
  const double bb = f.dot(line.dir);
  const double cc = f.dot(f) - circle.radius * circle.radius;
  const double disc = bb * bb - cc;
  if (disc < 0) return out;
  for (const double s : {-bb - std::sqrt(disc), -bb + std::sqrt(disc)})
    out.push_back(line.point + line.dir * s);
  return out;
}

// The foot of `p` on the element, and whether it lies within the element.
bool foot_on(const Element& e, P p, P& foot) {
  if (!e.arc) {
    const P d = e.end - e.start;
    const double t = (p - e.start).dot(d) / d.dot(d);
    foot = e.start + d * t;
    return t >= -1e-9 && t <= 1 + 1e-9;
  }
  const P r = p - e.centre;
  foot = e.centre + r * (e.radius / r.length());
  double from_start = angle_of(foot - e.centre) - angle_of(e.start - e.centre);
  if (e.sweep < 0) from_start = -from_start;
  from_start = std::fmod(from_start + 4 * std::numbers::pi, 2 * std::numbers::pi);
  return from_start <= std::abs(e.sweep) + 1e-9;
}

}  // namespace

// The material that ISO 14649's orthogonal_radius adds in the pocket's sharp corners (those
// turning away from the material, where the tool cannot reach): the part of each corner beyond
// a fillet arc of that radius tangent to both sides. Each polygon covers its fillet's material:
// the fillet's chords lie on the pocket side, and the sides' arcs are followed to within the
// chord tolerance. A fillet that the sides are too short for, or too curved, is taken tangent
// to the sides' directions at the corner, which keeps more material.
std::optional<Areas> fillet_material(Reader& reader, const Outline& outline, double rho, double d) {
  const FeatureOptions& opt = reader.options();
  Areas out;
  if (!(rho > 0)) return out;
  const double tol = opt.chord_tolerance;
  // How much of each straight side the fillets at its two ends take.
  std::vector<double> taken(outline.elements.size(), 0);
  for (const Corner& c : corners(outline)) {
    if (c.turn <= 0 || d * (1 / std::cos(std::min(c.turn, 3.1) / 2) - 1) <= opt.corner_tolerance)
      continue;
    const double half = (std::numbers::pi - c.turn) / 2;  // half the angle inside the corner
    if (half < 1e-6) continue;
    const Element& ea = outline.elements[c.before];
    const Element& eb = outline.elements[c.after];
    // Tangent to the sides' directions: the fallback, and the guess that picks the fillet.
    const P bisector = (c.out - c.in) * (1 / (c.out - c.in).length());
    P centre = c.at + bisector * (rho / std::sin(half));
    P t1 = c.at - c.in * (rho / std::tan(half));
    P t2 = c.at + c.out * (rho / std::tan(half));
    bool exact = false;
    const auto ca = offset_carrier(ea, rho);
    const auto cb = offset_carrier(eb, rho);
    if (ca && cb) {
      double best = std::numeric_limits<double>::infinity();
      for (const P& q : intersections(*ca, *cb)) {
        P f1;
        P f2;
        if ((q - centre).length() < best && foot_on(ea, q, f1) && foot_on(eb, q, f2)) {
          best = (q - centre).length();
          centre = q;
          t1 = f1;
          t2 = f2;
          exact = true;
        }
      }
    }
    for (const auto& [index, tangent] : {std::pair{c.before, t1}, std::pair{c.after, t2}}) {
      const Element& side = outline.elements[index];
      if (side.arc) continue;
      taken[index] += (tangent - c.at).length();
      if (taken[index] > (side.end - side.start).length() + 1e-6) {
        reader.report().bad(reader.subject(reader.feature()),
                            reader.name(reader.feature()) + " orthogonal_radius " + fmt(rho) +
                                " does not fit the side from " + at_text(side.start) + " to " +
                                at_text(side.end) + " between its corners");
        return std::nullopt;
      }
    }
    Ring ring{c.at};
    // Back along the side that arrives, to the first tangent point.
    if (exact && ea.arc) {
      const double from = angle_of(c.at - ea.centre);
      double sweep = angle_of(t1 - ea.centre) - from;
      while (ea.sweep > 0 ? sweep > 0 : sweep < 0)
        sweep += ea.sweep > 0 ? -2 * std::numbers::pi : 2 * std::numbers::pi;
      append_arc(ring, ea.centre, ea.radius, from, sweep, tol);
    } else {
      ring.push_back(t1);
    }
    const double a0 = angle_of(t1 - centre);
    double sweep = angle_of(t2 - centre) - a0;
    while (sweep > std::numbers::pi) sweep -= 2 * std::numbers::pi;
    while (sweep < -std::numbers::pi) sweep += 2 * std::numbers::pi;
    append_arc(ring, centre, rho, a0, sweep, tol);
    // Back along the side that leaves, to the corner.
    if (exact && eb.arc) {
      const double from = angle_of(t2 - eb.centre);
      double back = angle_of(c.at - eb.centre) - from;
      while (eb.sweep > 0 ? back > 0 : back < 0)
        back += eb.sweep > 0 ? -2 * std::numbers::pi : 2 * std::numbers::pi;
      append_arc(ring, eb.centre, eb.radius, from, back, tol);
      ring.pop_back();  // the corner itself is the first point
    }
    if (poly::area(ring) < 0) std::reverse(ring.begin(), ring.end());
    out.push_back({std::move(ring), {}});
  }
  return out;
}

}  // namespace ncpost::stepnc::features
