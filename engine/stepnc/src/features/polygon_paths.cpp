// Paths round the polygon rings of general regions (polygon_paths.hpp).

#include "polygon_paths.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ncpost::stepnc::features {
namespace {

using poly::P;
using poly::Ring;

// Arcs fitted back into polygons: at most this many polygon points each (bounded work), radius
// at most this (a longer arc is a line to the control).
constexpr std::size_t kMaxArcPoints = 256;
constexpr double kMaxArcRadius = 1e4;

bool circle_through(P a, P b, P c, P& centre, double& radius) {
  const P ab = b - a;
  const P ac = c - a;
  const double d = 2 * ab.cross(ac);
  if (std::abs(d) < 1e-12) return false;
  const double b2 = ab.dot(ab);
  const double c2 = ac.dot(ac);
  const P rel{(ac.y * b2 - ab.y * c2) / d, (ab.x * c2 - ac.x * b2) / d};
  centre = a + rel;
  radius = rel.length();
  return std::isfinite(radius);
}

}  // namespace

Nearest nearest_on(const Ring& ring, P p) {
  Nearest best{ring.front(), 0, std::numeric_limits<double>::infinity()};
  for (std::size_t e = 0; e < ring.size(); ++e) {
    const P a = ring[e];
    const P b = ring[(e + 1) % ring.size()];
    const P d = b - a;
    const double len2 = d.dot(d);
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const P q = a + d * t;
    const double dist = (q - p).length();
    if (dist < best.distance) best = {q, e, dist};
  }
  return best;
}

std::vector<P> ring_path(const Ring& ring, const Nearest& from, bool ccw) {
  const std::size_t n = ring.size();
  std::vector<P> out{from.point};
  const auto push = [&](P p) {
    if ((p - out.back()).length() > poly::kResolution) out.push_back(p);
  };
  if (ccw) {
    for (std::size_t k = 1; k <= n; ++k) push(ring[(from.edge + k) % n]);
  } else {
    for (std::size_t k = 0; k < n; ++k) push(ring[(from.edge + n - k) % n]);
  }
  push(from.point);
  if (out.size() > 1 && (out.back() - from.point).length() > 0) out.back() = from.point;
  return out;
}

std::vector<PlaneSpan> fit_arcs(const std::vector<P>& pts, double tolerance) {
  std::vector<PlaneSpan> out;
  if (pts.size() < 2) return out;
  const std::size_t last = pts.size() - 1;
  // What does not depend on the candidate circle is computed once: half of each chord.
  std::vector<double> half(last);
  for (std::size_t k = 0; k < last; ++k) half[k] = (pts[k + 1] - pts[k]).length() / 2;
  const double full_turn = 2 * std::numbers::pi - 1e-3;
  std::size_t i = 0;
  while (i < last) {
    std::size_t best = i + 1;
    P best_centre{};
    bool best_ccw = true;
    for (std::size_t j = i + 3; j <= last && j - i <= kMaxArcPoints; ++j) {
      P c;
      double r = 0;
      const std::size_t mid = (i + j) / 2;
      if (!circle_through(pts[i], pts[mid], pts[j], c, r) || r > kMaxArcRadius) break;
      const bool ccw = (pts[mid] - pts[i]).cross(pts[j] - pts[mid]) > 0;
      // Each chord turns by less than a quarter about c, the way of the arc: the dot product
      // positive and the cross product of that sign, which is what atan2 of the two says.
      // atan(t) <= t bounds the sweep from above, so the exact sum of atan2s is needed only
      // when the bound comes near a full turn.
      bool ok = true;
      double bound = 0;
      P u = pts[i] - c;
      double u_length = u.length();
      for (std::size_t k = i; k < j && ok; ++k) {
        const P v = pts[k + 1] - c;
        const double cross = u.cross(v);
        const double dot = u.dot(v);
        ok = std::abs(u_length - r) <= tolerance && dot > 0 && (cross > 0) == ccw &&
             r - std::sqrt(std::max(0.0, r * r - half[k] * half[k])) <= 2 * tolerance;
        bound += std::abs(cross) / dot;
        u = v;
        u_length = v.length();
      }
      if (!ok) break;
      if (bound > full_turn) {
        double sweep = 0;
        for (std::size_t k = i; k < j; ++k) {
          const P a = pts[k] - c;
          const P b = pts[k + 1] - c;
          sweep += std::atan2(a.cross(b), a.dot(b));
        }
        if (std::abs(sweep) > full_turn) break;
      }
      best = j;
      best_centre = c;
      best_ccw = ccw;
    }
    if (best >= i + 3)
      out.push_back({pts[best], true, best_centre, best_ccw});
    else
      out.push_back({pts[i + 1], false, {}, true});
    i = best;
  }
  return out;
}

std::vector<PlaneSpan> spans_of(const PlanePath& path, double fit_tolerance) {
  if (path.fit) return fit_arcs(path.points, fit_tolerance);
  std::vector<PlaneSpan> spans;
  spans.reserve(path.points.size());
  for (std::size_t k = 1; k < path.points.size(); ++k) spans.push_back({path.points[k]});
  return spans;
}

void emit_spans(Draft& draft, const std::vector<PlaneSpan>& spans, double z) {
  for (const PlaneSpan& s : spans) {
    if (s.arc)
      draft.arc(at(s.to, z), at(s.centre, z), s.ccw ? 1 : -1);
    else
      draft.feed(at(s.to, z));
  }
}

}  // namespace ncpost::stepnc::features
