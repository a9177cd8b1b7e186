#include <algorithm>
#include <array>
#include <cmath>

#include "ncpost/render/render.hpp"

namespace ncpost::render {
namespace {

using H = std::array<double, 4>;  // w·x, w·y, w·z, w

double distance_to_segment(const canon::Point& p, const canon::Point& a, const canon::Point& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  const double len2 = dx * dx + dy * dy + dz * dz;
  double t = 0;
  if (len2 > 0)
    t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy + (p.z - a.z) * dz) / len2, 0.0, 1.0);
  const double qx = a.x + t * dx - p.x, qy = a.y + t * dy - p.y, qz = a.z + t * dz - p.z;
  return std::sqrt(qx * qx + qy * qy + qz * qz);
}

// Appends the end points of pieces within `tolerance` of the curve from u0 to u1. False when the
// curve cannot be followed: a deviation that is not a number (geometry so large that distances
// overflow), or more pieces than kMaxNurbsPoints.
bool subdivide(const canon::NurbsFeed& n, double u0, const canon::Point& p0, double u1,
               const canon::Point& p1, double tolerance, int depth,
               std::vector<canon::Point>& out) {
  const double um = 0.5 * (u0 + u1);
  const canon::Point pm = nurbs_point(n, um);
  // Also look at the quarter points: an S-shaped piece can pass through the chord's midpoint.
  const canon::Point pa = nurbs_point(n, 0.5 * (u0 + um));
  const canon::Point pb = nurbs_point(n, 0.5 * (um + u1));
  const double dev = std::max({distance_to_segment(pm, p0, p1), distance_to_segment(pa, p0, p1),
                               distance_to_segment(pb, p0, p1)});
  if (!std::isfinite(dev) || !std::isfinite(p1.x) || !std::isfinite(p1.y) || !std::isfinite(p1.z))
    return false;
  if (depth >= 24 || dev <= tolerance) {
    if (out.size() >= kMaxNurbsPoints) return false;
    out.push_back(p1);
    return true;
  }
  return subdivide(n, u0, p0, um, pm, tolerance, depth + 1, out) &&
         subdivide(n, um, pm, u1, p1, tolerance, depth + 1, out);
}

}  // namespace

canon::Point nurbs_point(const canon::NurbsFeed& n, double u) {
  const int p = n.degree;
  const auto& U = n.knots;
  const int count = static_cast<int>(n.points.size());
  // The knot span k with U[k] <= u < U[k+1], clamped to the last non-empty span.
  int k = p;
  for (int i = p; i < count; ++i)
    if (U[static_cast<std::size_t>(i)] <= u &&
        U[static_cast<std::size_t>(i)] < U[static_cast<std::size_t>(i) + 1])
      k = i;
  std::vector<H> d(static_cast<std::size_t>(p) + 1);
  for (int j = 0; j <= p; ++j) {
    const auto& cp = n.points[static_cast<std::size_t>(j + k - p)];
    d[static_cast<std::size_t>(j)] = {cp.x * cp.weight, cp.y * cp.weight, cp.z * cp.weight,
                                      cp.weight};
  }
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const double lo = U[static_cast<std::size_t>(j + k - p)];
      const double hi = U[static_cast<std::size_t>(j + 1 + k - r)];
      const double alpha = hi > lo ? (u - lo) / (hi - lo) : 0.0;
      auto& dj = d[static_cast<std::size_t>(j)];
      const auto& dm = d[static_cast<std::size_t>(j) - 1];
      for (std::size_t c = 0; c < 4; ++c) dj[c] = (1 - alpha) * dm[c] + alpha * dj[c];
    }
  const H& h = d[static_cast<std::size_t>(p)];
  return {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
}

std::vector<canon::Point> linearize(const canon::NurbsFeed& n, double tolerance) {
  std::vector<canon::Point> out;
  if (!canon::valid(n) || n.points.size() < 2) return out;
  const auto p = static_cast<std::size_t>(n.degree);
  const auto& U = n.knots;
  const std::size_t last = n.points.size();  // U[last] is the end of the domain
  for (std::size_t i = p; i < last; ++i) {
    if (!(U[i] < U[i + 1])) continue;
    // Four pieces per knot span to start with, then halves until within tolerance.
    constexpr int kStart = 4;
    double u0 = U[i];
    canon::Point p0 = nurbs_point(n, u0);
    for (int s = 1; s <= kStart; ++s) {
      const double u1 = s == kStart ? U[i + 1] : U[i] + (U[i + 1] - U[i]) * s / kStart;
      const canon::Point p1 = nurbs_point(n, u1);
      if (!subdivide(n, u0, p0, u1, p1, tolerance, 0, out)) return {};
      u0 = u1;
      p0 = p1;
    }
  }
  // The curve is clamped: end exactly on the last control point.
  if (!out.empty()) {
    const auto& e = n.points.back();
    out.back() = {e.x, e.y, e.z};
  }
  return out;
}

}  // namespace ncpost::render
