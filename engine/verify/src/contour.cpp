#include "contour.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ncpost::verify::detail {
namespace {

// Composite curves nested deeper than this are not read (bounded recursion).
constexpr int kMaxNesting = 8;
// mm: pieces that end this far apart do not join.
constexpr double kJoin = 1e-3;
// Polygon points per full turn of an arc (for the inside test only; distances are exact).
constexpr int kPerTurn = 256;

double angle(Vec2 v) {
  return std::atan2(v.y, v.x);
}
Vec2 unit(Vec2 v) {
  return v * (1 / v.length());
}
Vec2 left(Vec2 v) {
  return {-v.y, v.x};
}
Vec2 on_circle(Vec2 c, double r, double a) {
  return c + Vec2{std::cos(a), std::sin(a)} * r;
}

// The direction of travel at the start and at the end of a piece.
Vec2 start_direction(const Piece2& p) {
  if (!p.arc) return unit(p.b - p.a);
  const Vec2 radial = unit(p.a - p.centre);
  return p.sweep > 0 ? left(radial) : left(radial) * -1;
}
Vec2 end_direction(const Piece2& p) {
  if (!p.arc) return unit(p.b - p.a);
  const Vec2 radial = unit(p.b - p.centre);
  return p.sweep > 0 ? left(radial) : left(radial) * -1;
}

bool read_into(const Reader& r, const p21::Instance& curve, const Frame& local, int depth,
               std::vector<Piece2>& out, std::string& reason) {
  const p21::Model& m = r.model();
  const auto point = [&](const p21::Instance* p) -> std::optional<Vec3> {
    const auto q = r.point(p);
    if (!q) return std::nullopt;
    return local.point(*q);
  };
  const auto planar = [&](const Vec3& p) {
    if (std::abs(p.z) <= kJoin) return true;
    reason = "its profile leaves the feature's plane";
    return false;
  };
  if (r.is_a(curve, "polyline")) {
    const auto list = r.get(curve, "points");
    if (!list || !list->is_list() || list->count() < 2) {
      reason = "its polyline has fewer than 2 points";
      return false;
    }
    std::optional<Vec3> previous;
    for (p21::Value v : m.items(*list)) {
      const auto p = v.is_reference() ? point(m.find(v.id())) : std::nullopt;
      if (!p || !planar(*p)) {
        if (reason.empty()) reason = "a point of its polyline cannot be read";
        return false;
      }
      if (previous && (p->xy() - previous->xy()).length() > 1e-9)
        out.push_back({false, previous->xy(), p->xy(), {}, 0, 0});
      previous = p;
    }
    return true;
  }
  if (r.is_a(curve, "trimmed_curve")) {
    const p21::Instance* basis = r.ref(curve, "basis_curve");
    const auto trim = [&](std::string_view name) -> std::optional<Vec3> {
      const auto set = r.get(curve, name);
      if (!set || !set->is_list()) return std::nullopt;
      for (p21::Value v : m.items(*set))
        if (v.is_reference()) return point(m.find(v.id()));
      return std::nullopt;
    };
    const auto a = trim("trim_1");
    const auto b = trim("trim_2");
    if (basis == nullptr || !a || !b) {
      reason = "a trimmed curve of its profile is not trimmed by points";
      return false;
    }
    if (!planar(*a) || !planar(*b)) return false;
    const auto sense = r.get(curve, "sense_agreement");
    const bool agrees = !sense || r.model().as_logical(*sense) != p21::Logical::False;
    if (r.is_a(*basis, "line")) {
      out.push_back({false, a->xy(), b->xy(), {}, 0, 0});  // from trim_1 to trim_2 either way
      return true;
    }
    if (!r.is_a(*basis, "circle")) {
      reason = "its profile trims a " + r.type(*basis) + " (lines and circles are read)";
      return false;
    }
    const auto frame = r.placement(r.ref(*basis, "position"));
    const auto radius = r.number(*basis, "radius");
    if (!frame || !radius || *radius <= 0) {
      reason = "a circle of its profile cannot be read";
      return false;
    }
    const Frame circle = local.then(*frame);
    if (std::abs(std::abs(circle.z.z) - 1) > 1e-9) {
      reason = "an arc of its profile is not in the feature's plane";
      return false;
    }
    // Counter-clockwise about the circle's axis when the senses agree; seen from +z.
    const bool ccw = agrees == (circle.z.z > 0);
    Piece2 p{true, a->xy(), b->xy(), circle.origin.xy(), *radius, 0};
    double sweep = angle(p.b - p.centre) - angle(p.a - p.centre);
    if (ccw) {
      while (sweep <= 1e-12) sweep += kTwoPi;
    } else {
      while (sweep >= -1e-12) sweep -= kTwoPi;
    }
    p.sweep = sweep;
    if (std::abs((p.a - p.centre).length() - p.radius) > kJoin ||
        std::abs((p.b - p.centre).length() - p.radius) > kJoin) {
      reason = "an arc of its profile does not end on its circle";
      return false;
    }
    out.push_back(p);
    return true;
  }
  if (r.is_a(curve, "composite_curve")) {
    if (depth >= kMaxNesting) {
      reason = "its composite curve nests deeper than " + std::to_string(kMaxNesting);
      return false;
    }
    const auto list = r.get(curve, "segments");
    if (!list || !list->is_list()) {
      reason = "its composite curve has no segments";
      return false;
    }
    for (p21::Value v : m.items(*list)) {
      const p21::Instance* seg = v.is_reference() ? m.find(v.id()) : nullptr;
      const p21::Instance* parent = seg ? r.ref(*seg, "parent_curve") : nullptr;
      if (parent == nullptr) {
        reason = "a segment of its composite curve cannot be read";
        return false;
      }
      std::vector<Piece2> part;
      if (!read_into(r, *parent, local, depth + 1, part, reason)) return false;
      const auto same = r.get(*seg, "same_sense");
      if (same && r.model().as_logical(*same) == p21::Logical::False) {
        std::reverse(part.begin(), part.end());
        for (Piece2& p : part) {
          std::swap(p.a, p.b);
          p.sweep = -p.sweep;
        }
      }
      out.insert(out.end(), part.begin(), part.end());
    }
    return true;
  }
  reason = "its profile is a " + r.type(curve) +
           " (polylines, trimmed lines and circles and "
           "composite curves of them are read)";
  return false;
}

void add_piece(Region& region, const Piece2& p) {
  if (!p.arc) {
    region.add_line(p.a, p.b);
    region.add_polygon_point(p.a);
    return;
  }
  const double a0 = angle(p.a - p.centre);
  region.add_arc(p.centre, p.radius, a0, p.sweep);
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(p.sweep) / kTwoPi * kPerTurn)));
  for (int k = 0; k < n; ++k)
    region.add_polygon_point(on_circle(p.centre, p.radius, a0 + p.sweep * k / n));
}

// Where a point `radius` to the left of the piece may lie: a line (point, direction) or a
// circle (centre, radius).
struct Track {
  bool circle = false;
  Vec2 point{}, direction{};
  Vec2 centre{};
  double radius = 0;
};

std::optional<Track> inside_track(const Piece2& p, double radius) {
  Track t;
  if (!p.arc) {
    t.direction = unit(p.b - p.a);
    t.point = p.a + left(t.direction) * radius;
    return t;
  }
  t.circle = true;
  t.centre = p.centre;
  t.radius = p.sweep > 0 ? p.radius - radius : p.radius + radius;
  if (t.radius <= 1e-9) return std::nullopt;
  return t;
}

std::vector<Vec2> meet(const Track& s, const Track& t) {
  std::vector<Vec2> out;
  if (!s.circle && !t.circle) {
    const double den = s.direction.cross(t.direction);
    if (std::abs(den) > 1e-12)
      out.push_back(s.point + s.direction * ((t.point - s.point).cross(t.direction) / den));
    return out;
  }
  if (s.circle && t.circle) {
    const Vec2 d = t.centre - s.centre;
    const double l = d.length();
    if (l < 1e-12) return out;
    const double x = (l * l + s.radius * s.radius - t.radius * t.radius) / (2 * l);
    const double h2 = s.radius * s.radius - x * x;
    if (h2 < 0) return out;
    const Vec2 base = s.centre + unit(d) * x;
    out.push_back(base + left(unit(d)) * std::sqrt(h2));
    out.push_back(base - left(unit(d)) * std::sqrt(h2));
    return out;
  }
  const Track& line = s.circle ? t : s;
  const Track& circle = s.circle ? s : t;
  const Vec2 f = line.point - circle.centre;
  const double half_b = f.dot(line.direction);
  const double disc = half_b * half_b - (f.dot(f) - circle.radius * circle.radius);
  if (disc < 0) return out;
  out.push_back(line.point + line.direction * (-half_b - std::sqrt(disc)));
  out.push_back(line.point + line.direction * (-half_b + std::sqrt(disc)));
  return out;
}

// The nearest point of the piece's carrier (line or circle) to q.
Vec2 foot(const Piece2& p, Vec2 q) {
  if (!p.arc) {
    const Vec2 d = p.b - p.a;
    return p.a + d * ((q - p.a).dot(d) / d.dot(d));
  }
  return p.centre + unit(q - p.centre) * p.radius;
}

// The piece from `from` (on it) to its end, or from its start to `to`.
Piece2 trimmed_start(const Piece2& p, Vec2 from) {
  Piece2 out = p;
  out.a = from;
  if (p.arc) {
    double rest = angle(p.b - p.centre) - angle(from - p.centre);
    if (p.sweep > 0) {
      while (rest < 0) rest += kTwoPi;
    } else {
      while (rest > 0) rest -= kTwoPi;
    }
    out.sweep = rest;
  }
  return out;
}
Piece2 trimmed_end(const Piece2& p, Vec2 to) {
  Piece2 out = p;
  out.b = to;
  if (p.arc) {
    double part = angle(to - p.centre) - angle(p.a - p.centre);
    if (p.sweep > 0) {
      while (part < 0) part += kTwoPi;
    } else {
      while (part > 0) part -= kTwoPi;
    }
    out.sweep = part;
  }
  return out;
}

}  // namespace

std::optional<std::vector<Piece2>> read_curve(const Reader& r, const p21::Instance& curve,
                                              const Frame& local, std::string& reason) {
  std::vector<Piece2> raw;
  if (!read_into(r, curve, local, 0, raw, reason)) return std::nullopt;
  std::vector<Piece2> out;
  for (Piece2& p : raw) {
    if (!p.arc && (p.b - p.a).length() < 1e-9) continue;
    if (!out.empty()) {
      if ((out.back().b - p.a).length() > kJoin) {
        reason = "the pieces of its profile do not join";
        return std::nullopt;
      }
      p.a = out.back().b;
    }
    out.push_back(p);
  }
  if (out.empty()) {
    reason = "its profile has no extent";
    return std::nullopt;
  }
  return out;
}

void make_counter_clockwise(std::vector<Piece2>& chain) {
  // Twice the signed area: the chain's chords and, for arcs, their segments.
  double twice = 0;
  for (const Piece2& p : chain) {
    twice += p.a.cross(p.b);
    if (p.arc) twice += p.radius * p.radius * (p.sweep - std::sin(p.sweep));
  }
  twice += chain.back().b.cross(chain.front().a);
  if (twice >= 0) return;
  std::reverse(chain.begin(), chain.end());
  for (Piece2& p : chain) {
    std::swap(p.a, p.b);
    p.sweep = -p.sweep;
  }
}

std::vector<Piece2> with_fillets(const std::vector<Piece2>& chain, double radius, bool closed) {
  if (!(radius > 0) || chain.size() < 2) return chain;
  const std::size_t n = chain.size();
  std::vector<Piece2> pieces = chain;
  // For each corner (piece i - 1 meets piece i): the fillet, if it turns left and fits.
  std::vector<std::optional<Piece2>> fillet(n);
  for (std::size_t i = closed ? 0 : 1; i < n; ++i) {
    Piece2& before = pieces[(i + n - 1) % n];
    Piece2& after = pieces[i];
    const Vec2 din = end_direction(before);
    const Vec2 dout = start_direction(after);
    if (din.cross(dout) <= 1e-9) continue;  // straight on or turning right
    const auto s = inside_track(before, radius);
    const auto t = inside_track(after, radius);
    if (!s || !t) continue;
    const Vec2 corner = after.a;
    std::optional<Vec2> best;
    for (const Vec2& c : meet(*s, *t)) {
      // The fillet's centre lies inside the corner, near it.
      if (best && (c - corner).length() >= (*best - corner).length()) continue;
      if ((c - corner).dot(dout - din) <= 0) continue;
      best = c;
    }
    if (!best) continue;
    const Vec2 t1 = foot(before, *best);
    const Vec2 t2 = foot(after, *best);
    Piece2 arc{true, t1, t2, *best, radius, 0};
    double sweep = angle(t2 - *best) - angle(t1 - *best);
    while (sweep > kTwoPi / 2) sweep -= kTwoPi;
    while (sweep < -kTwoPi / 2) sweep += kTwoPi;
    arc.sweep = sweep;
    before = trimmed_end(before, t1);
    after = trimmed_start(after, t2);
    fillet[i] = arc;
  }
  std::vector<Piece2> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (fillet[i]) out.push_back(*fillet[i]);
    out.push_back(pieces[i]);
  }
  return out;
}

Region region_of(const std::vector<Piece2>& closed) {
  Region region;
  for (const Piece2& p : closed) add_piece(region, p);
  if ((closed.back().b - closed.front().a).length() > 1e-9)
    add_piece(region, {false, closed.back().b, closed.front().a, {}, 0, 0});
  return region;
}

Region open_walls_region(const std::vector<Piece2>& walls, double far) {
  // The walls run from b0 to a1; the open side from a1 back to b0, with the pocket on its left.
  const Vec2 start = walls.front().a;
  const Vec2 end = walls.back().b;
  const Vec2 along = unit(start - end);
  const Vec2 out{along.y, -along.x};
  Region region;
  for (const Piece2& p : walls) add_piece(region, p);
  const Vec2 p1 = end - along * far;
  const Vec2 p2 = p1 + out * far;
  const Vec2 p3 = start + along * far + out * far;
  const Vec2 p4 = start + along * far;
  for (const auto& [a, b] : {std::pair{end, p1}, std::pair{p1, p2}, std::pair{p2, p3},
                             std::pair{p3, p4}, std::pair{p4, start}}) {
    region.add_line(a, b);
    region.add_polygon_point(a);
  }
  return region;
}

}  // namespace ncpost::verify::detail
