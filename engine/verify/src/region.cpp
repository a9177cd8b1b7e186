#include "region.hpp"

#include <algorithm>
#include <limits>

namespace ncpost::verify::detail {

namespace {

// Polygon points per full circle for the inside test: the sign only matters away from the
// boundary (near it the distance is ~0 either way), so this need not be fine.
constexpr int kPolygonPerCircle = 256;

double normalise(double angle) {
  angle = std::fmod(angle, kTwoPi);
  return angle < 0 ? angle + kTwoPi : angle;
}

}  // namespace

double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double len2 = d.dot(d);
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + d * t - p).length();
}

bool segment_within(Vec2 p, Vec2 a, Vec2 b, double radius, double& t0, double& t1) {
  const Vec2 d = b - a;
  const Vec2 f = a - p;
  const double A = d.dot(d);
  const double C = f.dot(f) - radius * radius;
  if (A < 1e-18) {
    if (C > 0) return false;
    t0 = 0;
    t1 = 1;
    return true;
  }
  const double B = 2 * d.dot(f);
  const double disc = B * B - 4 * A * C;
  if (disc < 0) return false;
  const double root = std::sqrt(disc);
  t0 = std::max(0.0, (-B - root) / (2 * A));
  t1 = std::min(1.0, (-B + root) / (2 * A));
  return t0 <= t1;
}

double Element::distance(Vec2 p) const {
  if (!arc) return segment_distance(p, a, b);
  const Vec2 v = p - centre;
  // Within the sweep: radial distance; outside it: the nearer end point.
  const double from_start = normalise(std::atan2(v.y, v.x) - (sweep >= 0 ? start : start + sweep));
  if (from_start <= std::abs(sweep) || std::abs(sweep) >= kTwoPi - 1e-12)
    return std::abs(v.length() - radius);
  const Vec2 e0 = centre + Vec2{std::cos(start), std::sin(start)} * radius;
  const Vec2 e1 = centre + Vec2{std::cos(start + sweep), std::sin(start + sweep)} * radius;
  return std::min((p - e0).length(), (p - e1).length());
}

void Region::extend(Vec2 p) {
  min_ = {std::min(min_.x, p.x), std::min(min_.y, p.y)};
  max_ = {std::max(max_.x, p.x), std::max(max_.y, p.y)};
}

void Region::add_line(Vec2 a, Vec2 b) {
  Element e;
  e.a = a;
  e.b = b;
  boundary_.push_back(e);
  extend(a);
  extend(b);
}

void Region::add_arc(Vec2 centre, double radius, double start, double sweep) {
  Element e;
  e.arc = true;
  e.centre = centre;
  e.radius = radius;
  e.start = start;
  e.sweep = sweep;
  boundary_.push_back(e);
  const int n =
      std::max(2, static_cast<int>(std::ceil(std::abs(sweep) / kTwoPi * kPolygonPerCircle)));
  for (int k = 0; k <= n; ++k) {
    const double t = start + sweep * k / n;
    extend(centre + Vec2{std::cos(t), std::sin(t)} * radius);
  }
}

bool Region::inside(Vec2 p) const {
  bool in = false;
  const std::size_t n = polygon_.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 a = polygon_[i];
    const Vec2 b = polygon_[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

double Region::distance(Vec2 p) const {
  double d = std::numeric_limits<double>::infinity();
  for (const Element& e : boundary_) d = std::min(d, e.distance(p));
  return d;
}

double Region::signed_distance(Vec2 p) const {
  const double d = distance(p);
  return inside(p) ? d : -d;
}

Region Region::rectangle(Vec2 origin, Vec2 x_axis, double length, double width,
                         double corner_radius) {
  Region r;
  const Vec2 y_axis{-x_axis.y, x_axis.x};
  const double hx = length / 2;
  const double hy = width / 2;
  const double c = std::clamp(corner_radius, 0.0, std::min(hx, hy));
  const auto at = [&](double x, double y) { return origin + x_axis * x + y_axis * y; };
  const double base = std::atan2(x_axis.y, x_axis.x);
  // Counter-clockwise from the middle of the +x side; each corner an arc when c > 0.
  const struct {
    double cx, cy, angle;
  } corners[4] = {{hx - c, hy - c, 0},
                  {-hx + c, hy - c, kTwoPi / 4},
                  {-hx + c, -hy + c, kTwoPi / 2},
                  {hx - c, -hy + c, 3 * kTwoPi / 4}};
  for (int k = 0; k < 4; ++k) {
    const auto& corner = corners[k];
    const auto& next = corners[(k + 1) % 4];
    const Vec2 centre = at(corner.cx, corner.cy);
    const double a0 = base + corner.angle;
    if (c > 0) {
      r.add_arc(centre, c, a0, kTwoPi / 4);
      const int n = 16;
      for (int s = 0; s <= n; ++s) {
        const double t = a0 + kTwoPi / 4 * s / n;
        r.polygon_.push_back(centre + Vec2{std::cos(t), std::sin(t)} * c);
      }
    } else {
      r.polygon_.push_back(centre);
    }
    // The side from this corner's arc end to the next corner's arc start.
    const double a1 = a0 + kTwoPi / 4;
    const Vec2 from = centre + Vec2{std::cos(a1), std::sin(a1)} * c;
    const Vec2 next_centre = at(next.cx, next.cy);
    const Vec2 to = next_centre + Vec2{std::cos(a1), std::sin(a1)} * c;
    if ((to - from).length() > 1e-12) r.add_line(from, to);
  }
  return r;
}

Region Region::parallelogram(Vec2 corner, Vec2 u, Vec2 v) {
  Region r;
  const Vec2 p[4] = {corner, corner + u, corner + u + v, corner + v};
  for (int k = 0; k < 4; ++k) {
    r.add_line(p[k], p[(k + 1) % 4]);
    r.polygon_.push_back(p[k]);
  }
  return r;
}

Region Region::circle(Vec2 centre, double radius) {
  Region r;
  r.add_arc(centre, radius, 0, kTwoPi);
  for (int s = 0; s < kPolygonPerCircle; ++s) {
    const double t = kTwoPi * s / kPolygonPerCircle;
    r.polygon_.push_back(centre + Vec2{std::cos(t), std::sin(t)} * radius);
  }
  return r;
}

namespace {

// One dimension of the squared distance transform (Felzenszwalb & Huttenlocher 2012).
void transform_1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                  std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  constexpr double inf = std::numeric_limits<double>::infinity();
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[static_cast<std::size_t>(q)] == inf) continue;
    while (k >= 0) {
      const int p = v[static_cast<std::size_t>(k)];
      const double s =
          ((f[static_cast<std::size_t>(q)] + q * q) - (f[static_cast<std::size_t>(p)] + p * p)) /
          (2.0 * (q - p));
      if (s <= z[static_cast<std::size_t>(k)]) {
        --k;
      } else {
        break;
      }
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] =
        k == 0 ? -inf
               : ((f[static_cast<std::size_t>(q)] + q * q) -
                  (f[static_cast<std::size_t>(v[static_cast<std::size_t>(k - 1)])] +
                   v[static_cast<std::size_t>(k - 1)] * v[static_cast<std::size_t>(k - 1)])) /
                     (2.0 * (q - v[static_cast<std::size_t>(k - 1)]));
    z[static_cast<std::size_t>(k + 1)] = inf;
  }
  if (k < 0) {
    std::fill(d.begin(), d.end(), inf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(j + 1)] < q) ++j;
    const int p = v[static_cast<std::size_t>(j)];
    d[static_cast<std::size_t>(q)] = (q - p) * (q - p) + f[static_cast<std::size_t>(p)];
  }
}

}  // namespace

std::vector<float> distance_to_seeds(const Grid& grid, const std::vector<unsigned char>& seed) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> squared(grid.cells(), inf);
  const int longest = std::max(grid.nx, grid.ny);
  std::vector<double> f(static_cast<std::size_t>(longest)), d(f.size());
  std::vector<int> v(f.size());
  std::vector<double> z(f.size() + 1);
  // Columns first (seeds → 0), then rows.
  f.resize(static_cast<std::size_t>(grid.ny));
  d.resize(f.size());
  for (int i = 0; i < grid.nx; ++i) {
    for (int j = 0; j < grid.ny; ++j)
      f[static_cast<std::size_t>(j)] = seed[grid.index(i, j)] ? 0.0 : inf;
    transform_1d(f, d, v, z);
    for (int j = 0; j < grid.ny; ++j) squared[grid.index(i, j)] = d[static_cast<std::size_t>(j)];
  }
  f.resize(static_cast<std::size_t>(grid.nx));
  d.resize(f.size());
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) f[static_cast<std::size_t>(i)] = squared[grid.index(i, j)];
    transform_1d(f, d, v, z);
    for (int i = 0; i < grid.nx; ++i) squared[grid.index(i, j)] = d[static_cast<std::size_t>(i)];
  }
  std::vector<float> out(grid.cells());
  for (std::size_t c = 0; c < out.size(); ++c)
    out[c] = squared[c] == inf ? std::numeric_limits<float>::infinity()
                               : static_cast<float>(std::sqrt(squared[c]));
  return out;
}

}  // namespace ncpost::verify::detail
