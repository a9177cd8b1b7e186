#include "polygons.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <polyclipping/clipper.hpp>

namespace ncpost::stepnc::features::poly {
namespace {

namespace cl = ClipperLib;

constexpr double kScale = 1 / kResolution;

cl::IntPoint to_int(P p) {
  return {static_cast<cl::cInt>(std::llround(p.x * kScale)),
          static_cast<cl::cInt>(std::llround(p.y * kScale))};
}
P to_mm(const cl::IntPoint& p) {
  return {static_cast<double>(p.X) / kScale, static_cast<double>(p.Y) / kScale};
}
cl::Path to_path(const std::vector<P>& points) {
  cl::Path out;
  out.reserve(points.size());
  for (const P& p : points) out.push_back(to_int(p));
  return out;
}
std::vector<P> to_points(const cl::Path& path) {
  std::vector<P> out;
  out.reserve(path.size());
  for (const auto& p : path) out.push_back(to_mm(p));
  return out;
}
cl::Paths to_paths(const Areas& areas) {
  cl::Paths out;
  for (const Area& a : areas) {
    out.push_back(to_path(a.outer));
    for (const Ring& h : a.holes) out.push_back(to_path(h));
  }
  return out;
}

// The tree's outer contours with their holes. Walked with an explicit stack (Clipper's own
// GetNext recurses once per nesting level).
Areas to_areas(const cl::PolyTree& tree) {
  Areas out;
  std::vector<const cl::PolyNode*> outers(tree.Childs.begin(), tree.Childs.end());
  while (!outers.empty()) {
    const cl::PolyNode* node = outers.back();
    outers.pop_back();
    if (node->IsOpen() || node->Contour.size() < 3) continue;
    Area a;
    a.outer = to_points(node->Contour);
    for (const cl::PolyNode* hole : node->Childs) {
      if (hole->Contour.size() >= 3) a.holes.push_back(to_points(hole->Contour));
      outers.insert(outers.end(), hole->Childs.begin(), hole->Childs.end());
    }
    out.push_back(std::move(a));
  }
  return out;
}

std::optional<Areas> boolean(const Areas& a, const Areas& b, cl::ClipType type) {
  try {
    cl::Clipper c;
    c.AddPaths(to_paths(a), cl::ptSubject, true);
    c.AddPaths(to_paths(b), cl::ptClip, true);
    cl::PolyTree tree;
    if (!c.Execute(type, tree, cl::pftNonZero, cl::pftNonZero)) return std::nullopt;
    return to_areas(tree);
  } catch (...) {
    return std::nullopt;
  }
}

double segment_distance(P p, P a, P b) {
  const P d = b - a;
  const double len2 = d.dot(d);
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + d * t - p).length();
}

// Douglas-Peucker on a closed ring, with an explicit stack.
Ring simplify_ring(const Ring& ring, double tolerance) {
  const std::size_t n = ring.size();
  if (n < 4) return ring;
  // Split at the first point and the point farthest from it.
  std::size_t far = 0;
  for (std::size_t i = 1; i < n; ++i)
    if ((ring[i] - ring[0]).length() > (ring[far] - ring[0]).length()) far = i;
  std::vector<bool> keep(n + 1, false);
  keep[0] = keep[far] = keep[n] = true;
  const auto at = [&](std::size_t i) { return ring[i % n]; };
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, far}, {far, n}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    double worst = -1;
    std::size_t at_worst = a;
    for (std::size_t i = a + 1; i < b; ++i) {
      const double d = segment_distance(at(i), at(a), at(b));
      if (d > worst) {
        worst = d;
        at_worst = i;
      }
    }
    if (worst > tolerance) {
      keep[at_worst] = true;
      stack.push_back({a, at_worst});
      stack.push_back({at_worst, b});
    }
  }
  Ring out;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) out.push_back(ring[i]);
  return out.size() >= 3 ? out : ring;
}

}  // namespace

Areas simplified(const Areas& areas, double tolerance) {
  Areas out;
  for (const Area& a : areas) {
    Area s{simplify_ring(a.outer, tolerance), {}};
    for (const Ring& h : a.holes) s.holes.push_back(simplify_ring(h, tolerance));
    out.push_back(std::move(s));
  }
  return out;
}

double P::length() const {
  return std::hypot(x, y);
}

double area(const Ring& ring) {
  double twice = 0;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    twice += ring[j].x * ring[i].y - ring[i].x * ring[j].y;
  return twice / 2;
}

double area(const Areas& areas) {
  double total = 0;
  for (const Area& a : areas) {
    total += area(a.outer);
    for (const Ring& h : a.holes) total += area(h);
  }
  return total;
}

bool contains(const Area& a, P p) {
  const cl::IntPoint q = to_int(p);
  if (cl::PointInPolygon(q, to_path(a.outer)) == 0) return false;
  return std::none_of(a.holes.begin(), a.holes.end(),
                      [&](const Ring& h) { return cl::PointInPolygon(q, to_path(h)) == 1; });
}

bool contains(const Areas& areas, P p) {
  return std::any_of(areas.begin(), areas.end(), [&](const Area& a) { return contains(a, p); });
}

double distance_to_boundary(const Areas& areas, P p) {
  double best = std::numeric_limits<double>::infinity();
  const auto ring = [&](const Ring& r) {
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
      best = std::min(best, segment_distance(p, r[j], r[i]));
  };
  for (const Area& a : areas) {
    ring(a.outer);
    for (const Ring& h : a.holes) ring(h);
  }
  return best;
}

bool simple(const Ring& ring) {
  if (ring.size() < 3) return false;
  try {
    // A simple ring is its own union: one polygon of the same area. Crossing or touching edges
    // split it into several, or change the area (a part wound twice, a bow tie's halves).
    const cl::Path path = to_path(ring);
    const double expected = std::abs(cl::Area(path));
    if (!(expected > 0)) return false;
    cl::Paths out;
    cl::SimplifyPolygon(path, out, cl::pftNonZero);
    if (out.size() != 1) return false;
    cl::Paths even;
    cl::SimplifyPolygon(path, even, cl::pftEvenOdd);
    if (even.size() != 1) return false;
    const double got = std::abs(cl::Area(out.front()));
    return std::abs(got - expected) <= 1e-9 * expected + 1 &&
           std::abs(std::abs(cl::Area(even.front())) - expected) <= 1e-9 * expected + 1;
  } catch (...) {
    return false;
  }
}

std::optional<Areas> Polygons::offset(const Areas& region, double delta) const {
  try {
    cl::ClipperOffset o;
    o.ArcTolerance = arc_tolerance_ * kScale;
    o.AddPaths(to_paths(region), cl::jtRound, cl::etClosedPolygon);
    cl::PolyTree tree;
    o.Execute(tree, delta * kScale);
    return to_areas(tree);
  } catch (...) {
    return std::nullopt;
  }
}

std::optional<Areas> Polygons::unite(const Areas& a, const Areas& b) const {
  return boolean(a, b, cl::ctUnion);
}
std::optional<Areas> Polygons::difference(const Areas& a, const Areas& b) const {
  return boolean(a, b, cl::ctDifference);
}
std::optional<Areas> Polygons::intersection(const Areas& a, const Areas& b) const {
  return boolean(a, b, cl::ctIntersection);
}

std::optional<Areas> Polygons::sweep(const std::vector<Ring>& rings,
                                     const std::vector<Chain>& chains, double radius) const {
  try {
    cl::ClipperOffset o;
    o.ArcTolerance = arc_tolerance_ * kScale;
    for (const Ring& r : rings) o.AddPath(to_path(r), cl::jtRound, cl::etClosedLine);
    for (const Chain& c : chains) {
      cl::Path path = to_path(c);
      // A chain of one point (or a zero-length one) still sweeps a disc.
      if (path.size() == 1) path.push_back(path.front());
      o.AddPath(path, cl::jtRound, cl::etOpenRound);
    }
    cl::PolyTree tree;
    o.Execute(tree, radius * kScale);
    return to_areas(tree);
  } catch (...) {
    return std::nullopt;
  }
}

std::optional<std::vector<Chain>> Polygons::clip(const std::vector<Chain>& chains,
                                                 const Areas& region) const {
  try {
    cl::Clipper c;
    for (const Chain& chain : chains)
      if (chain.size() >= 2) c.AddPath(to_path(chain), cl::ptSubject, false);
    c.AddPaths(to_paths(region), cl::ptClip, true);
    cl::PolyTree tree;
    if (!c.Execute(cl::ctIntersection, tree, cl::pftNonZero, cl::pftNonZero)) return std::nullopt;
    cl::Paths open;
    cl::OpenPathsFromPolyTree(tree, open);
    std::vector<Chain> out;
    for (const cl::Path& path : open) {
      if (path.size() < 2) continue;
      Chain piece = to_points(path);
      out.push_back(std::move(piece));
    }
    return out;
  } catch (...) {
    return std::nullopt;
  }
}

bool Polygons::segment_inside(P a, P b, const Areas& region) const {
  const double length = (b - a).length();
  if (length < kResolution) return contains(region, a);
  const auto pieces = clip({{a, b}}, region);
  if (!pieces || pieces->size() != 1) return false;
  const Chain& piece = pieces->front();
  return std::abs((piece.back() - piece.front()).length() - length) <= 2 * kResolution;
}

}  // namespace ncpost::stepnc::features::poly
