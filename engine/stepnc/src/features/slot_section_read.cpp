// SLOT whose swept shape is a GENERAL_PROFILE: the section's curve, evaluated exactly, and the
// reader that fits a tool's passes to it (slot.hpp). The geometry is the tool's silhouette
// across a straight slot: turning about a vertical axis, its lowest point at each distance ρ
// from its axis is on its profile (flat to radius − corner, then the corner's quarter circle),
// and a slot that is a straight extrusion of its section (or a section turned about a vertical
// axis, at a radiused end) meets the tool first in that silhouette's plane. Growing the tool by
// the allowance grows both radii by it.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "curves.hpp"
#include "milling_read.hpp"
#include "reader.hpp"
#include "slot.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Bisections of a curve's parameter interval at most: 2^-30 of a span is below any tolerance.
constexpr int kMaxSplits = 30;
// Offsets at most on the grid across a general section: FeatureOptions::profile_tolerance apart
// up to a section (with the tool's reach on both sides) 500 mm wide, further apart beyond, so
// that the work stays bounded.
constexpr std::size_t kMaxOffsets = 100'000;

// De Boor's algorithm in homogeneous coordinates: the point at parameter t of a clamped
// (rational) B-spline whose knots are expanded by multiplicity.
Vec3 de_boor(const detail::Segment& s, double t) {
  const int p = s.degree;
  const auto n = static_cast<int>(s.control_points.size()) - 1;
  int k = p;
  while (k < n && s.knots[static_cast<std::size_t>(k + 1)] <= t) ++k;
  std::array<std::array<double, 4>, 65> d{};
  for (int j = 0; j <= p; ++j) {
    const auto i = static_cast<std::size_t>(j + k - p);
    const Vec3 q = s.control_points[i];
    const double w = s.weights[i];
    d[static_cast<std::size_t>(j)] = {q.x * w, q.y * w, q.z * w, w};
  }
  for (int r = 1; r <= p; ++r)
    for (int j = p; j >= r; --j) {
      const double lo = s.knots[static_cast<std::size_t>(j + k - p)];
      const double hi = s.knots[static_cast<std::size_t>(j + 1 + k - r)];
      const double a = hi > lo ? (t - lo) / (hi - lo) : 0;
      auto& to = d[static_cast<std::size_t>(j)];
      const auto& from = d[static_cast<std::size_t>(j - 1)];
      for (std::size_t m = 0; m < 4; ++m) to[m] = (1 - a) * from[m] + a * to[m];
    }
  const auto& h = d[static_cast<std::size_t>(p)];
  return {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
}

double chord_distance(Vec3 p, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  const double l2 = ab.dot(ab);
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0;
  return (p - (a + ab * t)).length();
}

// A NURBS segment as points: each knot span split in halves until the curve's midpoint and
// quarter points are within `tolerance` of the chord. Appends all but the first point.
bool sample_nurbs(const detail::Segment& s, double tolerance, std::size_t limit,
                  std::vector<Vec3>& out) {
  struct Piece {
    double t0, t1;
    Vec3 a, b;
    int depth;
  };
  const auto n = s.control_points.size();
  if (s.degree < 1 || s.degree > 64 || s.weights.size() != n ||
      s.knots.size() != n + static_cast<std::size_t>(s.degree) + 1)
    return false;
  for (double w : s.weights)
    if (!(w > 0)) return false;
  const double first = s.knots[static_cast<std::size_t>(s.degree)];
  const double last = s.knots[n];
  std::vector<Piece> stack;
  for (std::size_t i = n; i-- > static_cast<std::size_t>(s.degree);) {
    const double t0 = s.knots[i];
    const double t1 = s.knots[i + 1];
    if (!(t1 > t0) || t0 < first || t1 > last) continue;
    stack.push_back({t0, t1, de_boor(s, t0), de_boor(s, t1), 0});
  }
  while (!stack.empty()) {
    const Piece piece = stack.back();
    stack.pop_back();
    const double tm = (piece.t0 + piece.t1) / 2;
    const Vec3 m = de_boor(s, tm);
    const Vec3 q1 = de_boor(s, (piece.t0 + tm) / 2);
    const Vec3 q3 = de_boor(s, (tm + piece.t1) / 2);
    const double off =
        std::max({chord_distance(m, piece.a, piece.b), chord_distance(q1, piece.a, piece.b),
                  chord_distance(q3, piece.a, piece.b)});
    if (off > tolerance && piece.depth < kMaxSplits) {
      stack.push_back({tm, piece.t1, m, piece.b, piece.depth + 1});
      stack.push_back({piece.t0, tm, piece.a, m, piece.depth + 1});
      continue;
    }
    out.push_back(piece.b);
    if (out.size() > limit) return false;
  }
  return true;
}

// An arc segment (a trimmed circle in the profile's plane) as chords within `tolerance`.
void sample_arc(const detail::Segment& s, double tolerance, std::vector<Vec3>& out) {
  const Vec3 n = s.normal * (1 / std::max(s.normal.length(), 1e-12));
  const Vec3 r0 = s.start - s.centre;
  const double radius = (r0 - n * r0.dot(n)).length();
  const Vec3 e1 = (r0 - n * r0.dot(n)) * (1 / std::max(radius, 1e-12));
  const Vec3 e2 = n.cross(e1);
  const Vec3 r1 = s.end - s.centre;
  double sweep = std::atan2(r1.dot(e2), r1.dot(e1));
  if (s.turns > 0 && sweep <= kEps) sweep += 2 * std::numbers::pi;
  if (s.turns < 0 && sweep >= -kEps) sweep -= 2 * std::numbers::pi;
  const double step =
      radius > tolerance ? 2 * std::acos(1 - tolerance / radius) : std::numbers::pi / 2;
  const int count = std::clamp(static_cast<int>(std::ceil(std::abs(sweep) / step)), 1, 100000);
  for (int k = 1; k <= count; ++k) {
    const double a = sweep * k / count;
    out.push_back(k == count ? s.end
                             : s.centre + n * r0.dot(n) + e1 * (radius * std::cos(a)) +
                                   e2 * (radius * std::sin(a)));
  }
}

// The z of the polyline `b` (u increasing) at u: the lowest where it is vertical.
double interpolate(SectionPoint p, SectionPoint q, double u) {
  if (q.u - p.u < 1e-12) return std::max(p.z, q.z);
  return p.z + (q.z - p.z) * (std::clamp(u, p.u, q.u) - p.u) / (q.u - p.u);
}

}  // namespace

bool read_general_section(Reader& reader, const Instance& swept, SlotSection& s) {
  Report& report = reader.report();
  const Instance* curve = reader.ref(swept, "its_profile", "bounded_curve");
  if (curve == nullptr)
    return report.bad(reader.subject(swept), reader.name(swept) + " has no its_profile");
  const FeatureOptions& options = reader.options();
  detail::CurveReader curves(reader.geometry(), options.chord_tolerance);
  const auto segments = curves.segments(*curve);
  if (!segments) return false;
  const Subject named = reader.subject(*curve);
  std::vector<Vec3> points;
  for (const detail::Segment& seg : *segments) {
    if (points.empty()) points.push_back(seg.start);
    switch (seg.kind) {
      case detail::Segment::Kind::Line:
        points.push_back(seg.end);
        break;
      case detail::Segment::Kind::Arc:
        sample_arc(seg, options.chord_tolerance, points);
        break;
      case detail::Segment::Kind::Nurbs:
        if (!sample_nurbs(seg, options.chord_tolerance, options.max_polygon_points, points))
          return report.bad(named, named.name() + " cannot be evaluated within " +
                                       fmt(options.chord_tolerance) + " mm in " +
                                       std::to_string(options.max_polygon_points) + " points");
        break;
    }
    if (points.size() > options.max_polygon_points)
      return report.bad(named, named.name() + " needs more than " +
                                   std::to_string(options.max_polygon_points) + " points within " +
                                   fmt(options.chord_tolerance) + " mm");
  }
  for (const Vec3& p : points)
    if (!p.finite() || std::abs(p.z) > options.chord_tolerance)
      return report.bad(named, named.name() + ", the section of " + reader.name(reader.feature()) +
                                   ", leaves its xy plane (a point at z " + fmt(p.z) + ")");
  // One depth at each point across: u never turns back (vertical pieces are walls).
  if (points.size() >= 2 && points.back().x < points.front().x)
    std::reverse(points.begin(), points.end());
  std::vector<SectionPoint> section;
  for (const Vec3& p : points) {
    if (!section.empty() && p.x < section.back().u - options.chord_tolerance)
      return report.not_implemented(
          reader.name(reader.feature()) + " with " + reader.name(swept) + " whose its_profile " +
          named.name() + " turns back across the slot at x " + fmt(section.back().u) + ", y " +
          fmt(section.back().z) +
          " (an undercut: a tool turning about the vertical makes one depth at each point "
          "across a slot)");
    section.push_back({std::max(p.x, section.empty() ? p.x : section.back().u), p.y});
  }
  if (section.size() < 2 || !(section.back().u - section.front().u > options.chord_tolerance))
    return report.bad(named, named.name() + ", the section of " + reader.name(reader.feature()) +
                                 ", has no width across the slot");
  if (!reader.size_ok(*curve, section.back().u - section.front().u, "width")) return false;
  s.kind = SlotSection::Kind::General;
  s.profile_curve = named;
  s.curve = std::move(section);
  // Symmetric about the course of travel: each point's mirror image lies on the curve.
  const auto& c = s.curve;
  const auto on_curve = [&](SectionPoint m) {
    auto it = std::lower_bound(c.begin(), c.end(), m.u - options.chord_tolerance,
                               [](const SectionPoint& p, double u) { return p.u < u; });
    if (it != c.begin()) --it;
    for (; it + 1 != c.end() && it->u <= m.u + options.chord_tolerance; ++it) {
      const Vec3 a{it->u, it->z, 0};
      const Vec3 b{(it + 1)->u, (it + 1)->z, 0};
      if (chord_distance({m.u, m.z, 0}, a, b) <= options.profile_tolerance) return true;
    }
    return false;
  };
  s.symmetric = std::all_of(c.begin(), c.end(), [&](const SectionPoint& p) {
    return on_curve({-p.u, p.z});
  });
  return true;
}

double section_tip(const std::vector<SectionPoint>& boundary, const SectionCutter& cutter,
                   double v) {
  const double flat = std::max(0.0, cutter.radius - cutter.corner);
  const double c = cutter.corner + cutter.allowance;
  const double reach = flat + c;
  // The lowest height of the corner circles' centres (their line): above every point of the
  // section within reach, and of the top beyond its ends.
  double centre = -kInf;
  const auto raise = [&](double u, double z) {
    const double d = std::abs(u - v) - flat;
    if (d > c + 1e-12) return;
    centre = std::max(centre, z + (d <= 0 ? c : std::sqrt(std::max(0.0, c * c - d * d))));
  };
  if (boundary.empty()) return 0;
  raise(std::clamp(v, boundary.back().u, kInf), 0);
  raise(std::clamp(v, -kInf, boundary.front().u), 0);
  auto it = std::lower_bound(boundary.begin(), boundary.end(), v - reach,
                             [](const SectionPoint& p, double u) { return p.u < u; });
  if (it != boundary.begin()) --it;
  for (; it + 1 != boundary.end() && it->u <= v + reach; ++it) {
    const SectionPoint p = *it;
    const SectionPoint q = *(it + 1);
    if (q.u - p.u < 1e-12) {
      raise(p.u, std::max(p.z, q.z));
      continue;
    }
    const double slope = (q.z - p.z) / (q.u - p.u);
    // On a line the height is concave in u: its top is at an end, at the edge of the flat, or
    // where the corner circle is tangent to it.
    const double tangent = c > 0 ? slope * c / std::sqrt(1 + slope * slope) : 0;
    for (const double u : {p.u, q.u, v - flat, v + flat, v - flat + tangent, v + flat + tangent}) {
      if (u < p.u || u > q.u) continue;
      raise(u, interpolate(p, q, u));
    }
  }
  return centre - cutter.corner;
}

double section_gap(SectionPoint p, const SectionCutter& cutter, double v, double tip) {
  const double flat = std::max(0.0, cutter.radius - cutter.corner);
  const double c = cutter.corner + cutter.allowance;
  const double dx = std::max(0.0, std::abs(p.u - v) - flat);
  const double dy = std::max(0.0, tip + cutter.corner - p.z);
  return std::max(0.0, std::sqrt(dx * dx + dy * dy) - c);
}

}  // namespace ncpost::stepnc::features

namespace ncpost::stepnc::features {
namespace {

// What the generator asks of a general section's slot before fitting passes to it.
bool check_section_slot(Reader& reader, const SlotBasics& basics, const Tool& tool,
                        const Operation& operation) {
  Report& report = reader.report();
  const auto f = [&] { return reader.name(reader.feature()); };
  const auto swept = [&] { return basics.swept.name(); };
  const bool circle = basics.path.kind == SlotPath::Kind::Circle;
  if (basics.path.kind != SlotPath::Kind::Line && !circle)
    return report.not_implemented(f() + " with " + swept() + " along " + basics.travel.name() +
                                  " (a general section is generated along a linear path or a "
                                  "complete circle)");
  if (circle && operation.approach && !reader.is(operation.approach, "plunge_toolaxis"))
    return report.not_implemented(operation.approach.name() + " into " + f() + " with " + swept() +
                                  " along " + basics.travel.name() +
                                  " (the tool goes down along its axis there)");
  for (const SlotEnd& e : basics.end) {
    if (circle) break;  // a loop (read_slot_basics)
    if (e.kind != SlotEnd::Kind::Radiused && e.kind != SlotEnd::Kind::Open)
      return report.not_implemented(
          f() + " with " + swept() + " and the end " + e.subject.name() +
          " (a general section is generated between radiused and open ends)");
    if (e.kind == SlotEnd::Kind::Radiused && !basics.section.symmetric)
      return report.not_implemented(
          f() + "'s radiused end " + e.subject.name() + " with " + swept() + ", whose curve " +
          basics.section.profile_curve.name() +
          " is not symmetric about the course of travel (a radiused end turns the section "
          "about the end of the course of travel, which only a symmetric section defines)");
  }
  if (operation.allowance_side < 0 || operation.allowance_bottom < 0)
    return report.bad(operation.subject,
                      operation.subject.name() + " leaves a negative allowance (" +
                          fmt(operation.allowance_side) + " on the sides, " +
                          fmt(operation.allowance_bottom) + " at the bottom) on " + f());
  if (reader.is(&reader.operation(), "side_milling"))
    return report.not_implemented(operation.subject.name() + " on " + f() + " with " + swept() +
                                  " (its walls and bottom are one surface, made by "
                                  "bottom-and-side milling)");
  if (operation.strategy && !reader.is(operation.strategy, "center_milling") &&
      !reader.is(operation.strategy, "contour_parallel"))
    return report.not_implemented(operation.strategy.name() + " on " + f() + ", which " +
                                  tool.subject.name() +
                                  " machines in passes along its course of travel");
  const bool end_mill = reader.is(tool.body, "endmill") || reader.is(tool.body, "facemill");
  if (!end_mill || reader.is(tool.body, "tapered_endmill") || tool.tip_half_angle)
    return report.unfit(tool.subject, tool.subject.name() +
                                          " is not an end mill with a flat, "
                                          "radiused or ball end; " +
                                          f() + "'s general section " +
                                          basics.section.profile_curve.name() +
                                          " is made by one turning about the vertical");
  return true;
}

// The section's lower side clipped at the top (z <= 0), u increasing.
std::vector<SectionPoint> below_top(const std::vector<SectionPoint>& curve) {
  std::vector<SectionPoint> out;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const SectionPoint p = curve[i];
    if (i > 0) {
      const SectionPoint q = curve[i - 1];
      if ((q.z > 0) != (p.z > 0) && std::abs(p.z - q.z) > 1e-15) {
        const double t = q.z / (q.z - p.z);
        out.push_back({q.u + (p.u - q.u) * t, 0});
      }
    }
    out.push_back({p.u, std::min(p.z, 0.0)});
  }
  return out;
}

// The points of the section at which what the passes leave is measured: its vertices, and
// points along its pieces no further apart than `spacing`.
std::vector<SectionPoint> probes(const std::vector<SectionPoint>& boundary, double spacing) {
  std::vector<SectionPoint> out;
  for (std::size_t i = 0; i + 1 < boundary.size(); ++i) {
    const SectionPoint p = boundary[i];
    const SectionPoint q = boundary[i + 1];
    const double length = std::hypot(q.u - p.u, q.z - p.z);
    const auto n = static_cast<std::size_t>(std::ceil(length / spacing));
    for (std::size_t k = 0; k < std::max<std::size_t>(n, 1); ++k) {
      const double t = n == 0 ? 0 : static_cast<double>(k) / static_cast<double>(n);
      const SectionPoint s{p.u + (q.u - p.u) * t, p.z + (q.z - p.z) * t};
      if (s.z < 0) out.push_back(s);
    }
  }
  if (!boundary.empty() && boundary.back().z < 0) out.push_back(boundary.back());
  return out;
}

// The offsets a tool may take (a grid `step` apart; rings: from the course of travel out) with
// its tip there, and for each probe the grid offset that comes nearest to it and how near.
struct Fit {
  std::vector<double> v;
  std::vector<double> tip;
  std::vector<SectionPoint> probe;
  std::vector<std::size_t> best;
  double worst = 0;  // the largest gap no offset closes, at probe worst_probe
  std::size_t worst_probe = 0;
  std::size_t count = 0;  // offsets 0 … count
  double from = 0;
  double spacing = 0;
  [[nodiscard]] std::size_t index(double u) const {
    return static_cast<std::size_t>(
        std::clamp((u - from) / spacing, 0.0, static_cast<double>(count)));
  }
};

// What pass `i` (and its mirror image for rings) leaves at probe p.
double left_at(const Fit& fit, const SectionCutter& cutter, bool rings, SectionPoint p,
               std::size_t i) {
  double g = section_gap(p, cutter, fit.v[i], fit.tip[i]);
  if (rings) g = std::min(g, section_gap(p, cutter, -fit.v[i], fit.tip[i]));
  return std::min(g, -p.z);
}

// The grid of offsets `tol` apart from `from` to `to`, the tip at each, and the nearest any of
// them comes to each probe: what no set of passes can do better.
Fit fit_offsets(const std::vector<SectionPoint>& boundary, const SectionCutter& cutter, bool rings,
                double from, double to, double tol) {
  Fit fit;
  const double reach = cutter.radius + cutter.allowance;
  // Offsets `tol` apart, or kMaxOffsets across a section too wide for that.
  fit.count = static_cast<std::size_t>(
      std::min(std::ceil((to - from) / tol), static_cast<double>(kMaxOffsets)));
  fit.from = from;
  fit.spacing = (to - from) / static_cast<double>(fit.count);
  for (std::size_t i = 0; i <= fit.count; ++i) {
    const double v = from + fit.spacing * static_cast<double>(i);
    fit.v.push_back(v);
    fit.tip.push_back(section_tip(boundary, cutter, v));
  }
  fit.probe = probes(boundary, std::max(tol, fit.spacing));
  if (rings) std::erase_if(fit.probe, [](const SectionPoint& p) { return p.u < -1e-12; });
  for (std::size_t k = 0; k < fit.probe.size(); ++k) {
    const SectionPoint p = fit.probe[k];
    double g = kInf;
    std::size_t at = 0;
    for (std::size_t i = fit.index(p.u - reach - fit.spacing);
         i <= fit.index(p.u + reach + fit.spacing); ++i) {
      if (!(fit.tip[i] < 0)) continue;
      const double gi = left_at(fit, cutter, rings, p, i);
      if (gi < g) {
        g = gi;
        at = i;
      }
    }
    g = std::min(g, -p.z);
    fit.best.push_back(at);
    if (g > fit.worst) {
      fit.worst = g;
      fit.worst_probe = k;
    }
  }
  return fit;
}

// The passes: from the first offset where the tool cuts, each as far from the last as leaves
// no more than `tol` on the probes between them; then any probe still left more gets the pass
// nearest to it. Nullopt beyond `limit` passes.
std::optional<std::vector<std::size_t>> choose_passes(const Fit& fit, const SectionCutter& cutter,
                                                      bool rings, double tol, std::size_t limit) {
  std::vector<std::size_t> order(fit.probe.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return fit.best[a] < fit.best[b]; });
  const auto covered = [&](std::size_t i, std::size_t j) {
    auto it = std::lower_bound(order.begin(), order.end(), i,
                               [&](std::size_t k, std::size_t b) { return fit.best[k] < b; });
    for (; it != order.end() && fit.best[*it] <= j; ++it) {
      const SectionPoint p = fit.probe[*it];
      if (std::min(left_at(fit, cutter, rings, p, i), left_at(fit, cutter, rings, p, j)) > tol)
        return false;
    }
    return true;
  };
  std::vector<std::size_t> chosen;
  std::size_t i = 0;
  // From the first offset where the tool cuts deeper than the tolerance (above, what is left
  // is within it anyway; the last round adds a pass if not).
  while (i < fit.count && !(fit.tip[i] < -tol)) ++i;
  std::size_t last = fit.count;
  while (last > i && !(fit.tip[last] < -tol)) --last;
  chosen.push_back(i);
  const auto window =
      static_cast<std::size_t>(std::ceil(2 * (cutter.radius + cutter.allowance) / fit.spacing)) + 2;
  while (i < last) {
    std::size_t next = i;
    for (std::size_t j = i + 1; j <= std::min(last, i + window); ++j) {
      if (!(fit.tip[j] < 0)) continue;
      if (covered(i, j)) {
        next = j;
      } else if (next != i) {
        break;
      }
    }
    if (next == i)
      for (next = i + 1; next < last && !(fit.tip[next] < 0);) ++next;
    chosen.push_back(next);
    i = next;
    if (chosen.size() > limit) return std::nullopt;
  }
  for (std::size_t round = 0;; ++round) {
    std::vector<std::size_t> missing;
    for (std::size_t k = 0; k < fit.probe.size(); ++k) {
      double g = kInf;
      for (const std::size_t c : chosen)
        g = std::min(g, left_at(fit, cutter, rings, fit.probe[k], c));
      if (g > tol) missing.push_back(fit.best[k]);
    }
    if (missing.empty()) break;
    if (round > 100) return std::nullopt;
    chosen.insert(chosen.end(), missing.begin(), missing.end());
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
  }
  return chosen;
}

// The passes, and the height at which the tool crosses to each: the tip of a tool whose flat
// spans both offsets (rings: the course of travel and the pass). Returns the deepest tip's depth.
double add_passes(const Fit& fit, const std::vector<std::size_t>& chosen,
                  const std::vector<SectionPoint>& boundary, const SectionCutter& cutter,
                  bool rings, SectionSlotSpec& spec) {
  double deepest = 0;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const double v = fit.v[chosen[k]];
    const double tip = fit.tip[chosen[k]];
    spec.passes.push_back({std::abs(v) < 1e-9 ? 0.0 : v, -tip});
    deepest = std::max(deepest, -tip);
    const double a = rings ? -v : k == 0 ? v : fit.v[chosen[k - 1]];
    SectionCutter span = cutter;
    span.radius += (v - a) / 2;
    spec.cross.push_back(section_tip(boundary, span, (a + v) / 2));
  }
  return deepest;
}

}  // namespace

bool read_section_slot(Reader& reader, const SlotBasics& basics, SectionSlotSpec& spec) {
  Report& report = reader.report();
  const FeatureOptions& options = reader.options();
  const auto f = [&] { return reader.name(reader.feature()); };
  const auto depth = reader.read_depth();
  const auto tool = reader.read_tool();
  if (!depth || !tool) return false;
  const Operation operation = reader.read_operation();
  if (!check_section_slot(reader, basics, *tool, operation)) return false;
  const SlotSection& section = basics.section;
  const Subject& curve = section.profile_curve;
  // The curve's lowest point on the depth plane; its ends must reach the top.
  double lowest = kInf;
  for (const SectionPoint& p : section.curve) lowest = std::min(lowest, p.z);
  const double shift = -*depth - lowest;
  std::vector<SectionPoint> shifted = section.curve;
  for (SectionPoint& p : shifted) p.z += shift;
  for (const SectionPoint& end : {shifted.front(), shifted.back()})
    if (end.z < -options.profile_tolerance)
      return report.bad(curve, curve.name() + ", the section of " + f() + ", ends " + fmt(-end.z) +
                                   " below the top at x " + fmt(end.u) +
                                   " once its lowest point is on the depth plane, " + fmt(*depth) +
                                   " below the top");
  if (std::abs(shift) > options.chord_tolerance)
    report.note(curve, curve.name() + ": the lowest point of the section of " + f() + " (y " +
                           fmt(lowest) + ") is put on its depth plane, " + fmt(*depth) +
                           " below the top");
  const std::vector<SectionPoint> boundary = below_top(shifted);
  const bool circle = basics.path.kind == SlotPath::Kind::Circle;
  const bool rings = !circle && section.symmetric &&
                     (basics.end[0].kind == SlotEnd::Kind::Radiused ||
                      basics.end[1].kind == SlotEnd::Kind::Radiused);
  SectionCutter cutter{tool->radius,
                       reader.is(tool->body, "ball_endmill")
                           ? tool->radius
                           : std::clamp(tool->corner_radius, 0.0, tool->radius),
                       std::max(operation.allowance_side, operation.allowance_bottom)};
  const double tol = options.profile_tolerance;
  const double reach = cutter.radius + cutter.allowance;
  const double from = rings ? 0 : boundary.front().u - reach;
  const double to = boundary.back().u + reach;
  // Round a circle the section's left (inner) side and the tool must stay clear of its centre.
  if (circle && !(basics.path.radius - to > 0))
    return report.bad(curve, curve.name() + ", the section of " + f() + ", reaches " + fmt(to) +
                                 " to the left of " + basics.travel.name() + " with " +
                                 tool->subject.name() + ", beyond the centre of its radius " +
                                 fmt(basics.path.radius));
  const Fit fit = fit_offsets(boundary, cutter, rings, from, to, tol);
  const auto shape = [&] {
    return tool->subject.name() + " (radius " + fmt(cutter.radius) + ", corner radius " +
           fmt(cutter.corner) +
           (cutter.allowance > 0 ? ", grown by the allowance " + fmt(cutter.allowance) : "") + ")";
  };
  if (std::none_of(fit.tip.begin(), fit.tip.end(), [](double t) { return t < 0; }))
    return report.unfit(tool->subject, shape() + " never gets below the top of " + f() +
                                           ": its section " + curve.name() +
                                           " is narrower than the tool");
  if (fit.worst > tol) {
    const SectionPoint p = fit.probe[fit.worst_probe];
    return report.unfit(tool->subject,
                        shape() + " cannot reach the section " + curve.name() + " of " + f() +
                            ": it stays " + fmt(fit.worst) + " off it at x " + fmt(p.u) + ", y " +
                            fmt(p.z - shift) +
                            " (a part of the section narrower or tighter than the tool)");
  }
  const auto chosen = choose_passes(fit, cutter, rings, tol, options.max_moves);
  if (!chosen) return report.limit_reached(options.max_moves);
  const double deepest = add_passes(fit, *chosen, boundary, cutter, rings, spec);
  if (static_cast<double>(spec.passes.size()) * 10 > static_cast<double>(options.max_moves))
    return report.limit_reached(options.max_moves);
  // The passes of the levels above the deepest: the stepover apart at most.
  double overlap = 0;
  const double step = stepover(reader, *tool, operation, overlap);
  if (!check_overlap(reader, operation, overlap)) return false;
  spec.rough.push_back(0);
  for (std::size_t k = 1; k < spec.passes.size(); ++k) {
    const bool last_one = k + 1 == spec.passes.size();
    if (last_one || spec.passes[k + 1].offset - spec.passes[spec.rough.back()].offset > step)
      spec.rough.push_back(k);
  }
  auto levels = depth_levels(reader, operation, deepest);
  if (!levels || !check_edge(reader, *tool, *levels)) return false;
  if (static_cast<double>(levels->size()) * static_cast<double>(spec.passes.size()) * 10 >
      static_cast<double>(options.max_moves))
    return report.limit_reached(options.max_moves);
  spec.levels = std::move(*levels);
  spec.path = basics.path;
  spec.end[0] = basics.end[0];
  spec.end[1] = basics.end[1];
  spec.rings = rings;
  spec.ccw = rings_ccw(reader, operation, true, false);
  spec.tool_radius = tool->radius;
  spec.entry.kind = Entry::Kind::Plunge;
  if (operation.approach) {
    if (!read_plunge(reader, *operation.approach.instance, "approach into", spec.entry))
      return false;
    if (spec.entry.kind == Entry::Kind::Helix)
      return report.unfit(operation.approach,
                          operation.approach.name() + ": " + tool->subject.name() + " machines " +
                              f() +
                              " in passes along its course of travel; there is no room "
                              "for a helix");
  }
  if (operation.retract && !reader.is(operation.retract, "plunge_toolaxis"))
    spec.exit_strategy = operation.retract;
  spec.retract_plane = operation.retract_plane;
  spec.tool = tool->subject;
  spec.feature = reader.subject(reader.feature());
  return true;
}

}  // namespace ncpost::stepnc::features
