// General profiles: CLOSED_POCKET bounded by a GENERAL_CLOSED_PROFILE (polyline, composite curve
// of lines and arcs) or an NGON_CLOSED_PROFILE, OPEN_POCKET, and GENERAL_OUTSIDE_PROFILE with
// such a boundary. The region the tool centre may use is built with polygon offsets (Clipper,
// polygons.hpp), always a little inside the exact one; the rings and lines are cut from it and
// checked to cover it before any motion is made (docs/features.md, "General profiles").

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>

#include "milling.hpp"
#include "outline.hpp"
#include "polygons.hpp"

namespace ncpost::stepnc::features::legacy {
namespace {

using poly::Area;
using poly::Areas;
using poly::Chain;
using poly::P;
using poly::Ring;

constexpr double kEps = 1e-9;
// Coverage is retried with one more ring this many times before the pocket is refused.
constexpr int kCoverageTries = 5;
// Vertices of a ring (or points of a line) tried as the place to go down into material.
constexpr std::size_t kSiteSamples = 64;
// Arcs fitted back into polygons: at most this many polygon points each (bounded work), radius
// at most this (a longer arc is a line to the control).
constexpr std::size_t kMaxArcPoints = 256;
constexpr double kMaxArcRadius = 1e4;

std::string at_text(P p) {
  return "(" + fmt(p.x) + ", " + fmt(p.y) + ")";
}

// ---- arcs fitted back into polygons -------------------------------------------------------

struct Span2 {
  P to;
  bool arc = false;
  P centre{};
  bool ccw = true;
};

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

// The path through `pts` as lines and arcs: a run of at least four points within `tolerance` of
// one circle, whose chords' sagittas are at most twice that (round joins are made with chords
// of sagitta `tolerance`), is one arc: the arc is within 3 × `tolerance` of the polygon. The
// polygons of round joins and of offset arcs are such runs, so their offsets come out as the arcs
// they are.
std::vector<Span2> fit_arcs(const std::vector<P>& pts, double tolerance) {
  std::vector<Span2> out;
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

// ---- rings ----------------------------------------------------------------------------------

struct Nearest {
  P point;
  std::size_t edge = 0;  // the point lies on ring[edge] → ring[edge + 1]
  double distance = 0;
};

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

// Round the ring from a point on it and back to that point, in the sense asked (the ring itself
// is counter-clockwise).
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

// ---- the plan: where the tool goes down, and what it cuts from there without lifting ----------

struct Site {
  Entry::Kind kind = Entry::Kind::Plunge;
  P centre;          // of the helix, or where the tool plunges
  double helix = 0;  // helix radius
  P ramp_from, ramp_to;
  P start;                     // where the paths begin after the entry
  bool straight_down = false;  // re-entry of one-way lines without a named approach
  [[nodiscard]] P entry_point() const {
    if (straight_down) return start;
    if (kind == Entry::Kind::Helix) return centre + P{helix, 0};
    if (kind == Entry::Kind::Ramp) return ramp_from;
    return centre;
  }
};

struct Path2 {
  std::vector<P> points;
  bool fit = false;  // rings: arcs may be fitted back
};

struct Group {
  Site site;
  std::vector<Path2> paths;  // each reached from the previous one by a feed inside the region
};

class Planner {
 public:
  // `centres` is `source` shrunk by `base`: inner rings are shrunk from `source` at once, so
  // that a round join about one of its corners stays one arc.
  // Shrunk by `rho` or more, `source` and `sharp` (its corners not filleted) give the same
  // region, and `sharp` has far fewer points: its polygon's arcs do not fold over.
  Planner(Context& ctx, const Tool& tool, const OperationData& o, const Entry& entry,
          const Areas& centres, const Areas& source, const Areas& sharp, double rho, double base,
          double margin)
      : ctx_(ctx),
        tool_(tool),
        approach_(o.approach),
        entry_(entry),
        centres_(centres),
        source_(source),
        sharp_(sharp),
        rho_(rho),
        base_(base),
        margin_(margin),
        polygons_(ctx.opt.chord_tolerance),
        checks_(ctx.opt.corner_tolerance / 5) {}

  // A site among sampled points: the helix where there is most room, a ramp along a segment.
  bool site(const std::vector<P>& candidates, const std::vector<std::pair<P, P>>& ramps,
            const std::function<P(P)>& start_after, Site& out) {
    out = Site{};
    out.kind = entry_.kind;
    if (entry_.kind == Entry::Kind::Ramp) {
      double best = -1;
      for (const auto& [a, b] : ramps) {
        const double l = (b - a).length();
        if (l > best) {
          best = l;
          out.ramp_from = a;
          out.ramp_to = b;
        }
      }
      // Round the innermost ring the edges are short: a line from the sampled point with most
      // room, as long as that room, stays inside the region too and is often much longer (a
      // ramp's legs are its length; short legs make hundreds of them).
      const P along = best > 0 ? (out.ramp_to - out.ramp_from) * (1 / best) : P{1, 0};
      const std::size_t every = std::max<std::size_t>(1, candidates.size() / kSiteSamples);
      for (std::size_t k = 0; k < candidates.size(); k += every) {
        const double r = poly::distance_to_boundary(centres_, candidates[k]) - margin_;
        if (r > best) {
          best = r;
          out.ramp_from = candidates[k];
          out.ramp_to = candidates[k] + along * r;
        }
      }
      double length = best;
      if (entry_.width > 0) length = std::min(length, entry_.width);
      if (!(length >= 1e-3))
        return ctx_.unfit(*approach_, ctx_.d(*approach_) + ": no room for a ramp of " +
                                          ctx_.d(*tool_.instance) + " in " +
                                          ctx_.d(ctx_.feature()));
      out.ramp_to = out.ramp_from + (out.ramp_to - out.ramp_from) * (length / best);
      out.centre = out.ramp_from;
      out.start = out.ramp_from;
      return true;
    }
    double room = -1;
    std::size_t step = std::max<std::size_t>(1, candidates.size() / kSiteSamples);
    for (std::size_t k = 0; k < candidates.size(); k += step) {
      const double r = poly::distance_to_boundary(centres_, candidates[k]);
      if (r > room) {
        room = r;
        out.centre = candidates[k];
      }
    }
    out.start = start_after(out.centre);
    if (entry_.kind == Entry::Kind::Plunge) return true;
    room = std::max(0.0, room - margin_);
    out.helix = entry_.radius;
    if (out.helix > room + kEps) {
      if (entry_.explicit_entry)
        return ctx_.unfit(*approach_, ctx_.d(*approach_) + " radius " + fmt(entry_.radius) +
                                          " leaves no room for " + ctx_.d(*tool_.instance) +
                                          " in " + ctx_.d(ctx_.feature()) + " (at most " +
                                          fmt(room) + " at " + at_text(out.centre) + ")");
      out.helix = room;
    }
    if (out.helix < 1e-3) {
      if (entry_.explicit_entry)
        return ctx_.unfit(*approach_, ctx_.d(*approach_) + ": " + ctx_.d(*tool_.instance) +
                                          " fills " + ctx_.d(ctx_.feature()) + " at " +
                                          at_text(out.centre) + ", no room for a helix");
      out.kind = Entry::Kind::Plunge;
      if (!plunge_noted_)
        ctx_.note(ctx_.feature(), ctx_.d(*tool_.instance) + " fills " + ctx_.d(ctx_.feature()) +
                                      " at " + at_text(out.centre) +
                                      "; it enters along its axis, as there is no room for a "
                                      "helix");
      plunge_noted_ = true;
    }
    return true;
  }

  // Contour-parallel rings from the innermost outwards, `step` apart at most; nullopt with a
  // diagnostic when they cannot be made.
  std::optional<std::vector<Group>> rings(double step, bool ccw, bool walls_only);
  // Parallel lines along `u`, clipped to the region, then (or first) the ring round each part.
  // `left`: the lines follow each other to the left of `u` (else to the right).
  std::optional<std::vector<Group>> lines(double step, P u, bool left, bool zigzag, bool ring_first,
                                          bool ccw);

 private:
  // The largest distance from the region's boundary that a point of it has.
  std::optional<double> inradius();
  bool covered(const std::vector<Ring>& rings, const std::vector<Chain>& chains);
  // Rings that are the boundaries of nested regions (`levels`, from the outermost) cover all of
  // the outermost when, in each, what is further than the tool radius from its boundary lies
  // within the tool radius of the next one: a test on each region, not on the union of all
  // the swept bands (which costs far more).
  bool rings_cover(const std::vector<Areas>& levels, const std::vector<double>& insets);
  // `source` shrunk by `base` + `inset`.
  std::optional<Areas> shrunk(double inset, bool for_check = false) {
    const double by = base_ + inset;
    return (for_check ? checks_ : polygons_).offset(by >= rho_ ? sharp_ : source_, -by);
  }

  Context& ctx_;
  const Tool& tool_;
  const Instance* approach_;  // set whenever entry_.explicit_entry
  const Entry& entry_;
  const Areas& centres_;
  const Areas& source_;
  const Areas& sharp_;
  double rho_;
  double base_;
  double margin_;
  poly::Polygons polygons_;
  // For tests that only need to be right within a share of the corner tolerance, whose
  // round joins need fewer points: both shrinks and grows err towards "not covered".
  poly::Polygons checks_;
  bool plunge_noted_ = false;
};

std::optional<double> Planner::inradius() {
  // On a simplified outline (within `coarse` either way): the answer only spaces the rings,
  // and the innermost ring is put `coarse` further out, so that it is never empty.
  const double coarse = std::min(0.02 * tool_.radius, 0.1);
  const Areas outline = poly::simplified(centres_, coarse);
  double lo = 0;
  double hi = 0;
  for (const Area& a : centres_) {
    P mn = a.outer.front();
    P mx = mn;
    for (const P& p : a.outer) {
      mn = {std::min(mn.x, p.x), std::min(mn.y, p.y)};
      mx = {std::max(mx.x, p.x), std::max(mx.y, p.y)};
    }
    hi = std::max(hi, std::min(mx.x - mn.x, mx.y - mn.y) / 2);
  }
  for (int k = 0; k < 64 && hi - lo > coarse; ++k) {
    const double mid = (lo + hi) / 2;
    const auto e = checks_.offset(outline, -mid);
    if (!e) return std::nullopt;
    (e->empty() ? hi : lo) = mid;
  }
  return std::max(0.0, lo - 2 * coarse);
}

bool Planner::covered(const std::vector<Ring>& rings, const std::vector<Chain>& chains) {
  // What the tool sweeps must include the whole region its centre may use: then it includes
  // the floor within the tool radius of it, all the floor the tool can reach.
  const auto swept = polygons_.sweep(rings, chains, tool_.radius);
  if (!swept) return false;
  const auto left = polygons_.difference(centres_, *swept);
  if (!left) return false;
  const auto significant = polygons_.offset(*left, -ctx_.opt.corner_tolerance / 2);
  return significant && significant->empty();
}

bool Planner::rings_cover(const std::vector<Areas>& levels, const std::vector<double>& insets) {
  for (std::size_t k = 0; k < levels.size(); ++k) {
    // Further than the tool radius from ring k: the source shrunk that much more, less the
    // islands that ring k does not go round (slivers left out of the plan).
    const auto deeper = shrunk(insets[k] + tool_.radius, true);
    const auto far = deeper ? checks_.intersection(*deeper, levels[k]) : std::nullopt;
    if (!far) return false;
    Areas rest = *far;
    if (!rest.empty() && k + 1 < levels.size()) {
      // On a simplified copy, grown that much less: still inside the exact grown region.
      const double e = ctx_.opt.corner_tolerance / 5;
      const auto near = checks_.offset(poly::simplified(levels[k + 1], e), tool_.radius - e);
      const auto left = near ? checks_.difference(rest, *near) : std::nullopt;
      if (!left) return false;
      rest = *left;
    }
    if (rest.empty()) continue;
    const auto significant = checks_.offset(rest, -ctx_.opt.corner_tolerance / 2);
    if (!significant || !significant->empty()) return false;
  }
  return true;
}

std::optional<std::vector<Group>> Planner::rings(double step0, bool ccw, bool walls_only) {
  const auto room = inradius();
  if (!room) return std::nullopt;
  if (*room / step0 > static_cast<double>(ctx_.opt.max_moves)) {
    ctx_.limit_reached();
    return std::nullopt;
  }
  auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(*room / step0 - 1e-9)));
  for (int attempt = 0; attempt < kCoverageTries; ++attempt, ++n) {
    const double s = *room / static_cast<double>(n);
    // Rings at whole steps from the outermost, and the innermost just short of the centre.
    struct Node {
      Ring ring;
      std::size_t level = 0;
      std::ptrdiff_t parent = -1;
      std::vector<std::size_t> children;
    };
    std::vector<Node> nodes;
    std::vector<double> insets;
    std::size_t points = 0;
    for (std::size_t k = 0; k <= n; ++k) {
      const double inset = k < n ? static_cast<double>(k) * s : *room - std::min(0.05 * s, 0.01);
      insets.push_back(inset);
      std::optional<Areas> level = k == 0 ? std::optional<Areas>(centres_) : shrunk(inset);
      if (!level) return std::nullopt;
      for (Area& a : *level) {
        if (!a.holes.empty()) {
          ctx_.not_implemented(ctx_.d(ctx_.feature()) + ": its offset at " + fmt(inset) +
                               " mm encloses an island");
          return std::nullopt;
        }
        Node node{std::move(a.outer), k, -1, {}};
        points += node.ring.size();
        if (k > 0) {
          for (std::size_t i = nodes.size(); i-- > 0;) {
            if (nodes[i].level + 1 != k) continue;
            if (poly::contains(Area{nodes[i].ring, {}}, node.ring.front())) {
              node.parent = static_cast<std::ptrdiff_t>(i);
              break;
            }
          }
          if (node.parent < 0) continue;  // a sliver outside its level's rings: nothing to cut
        }
        nodes.push_back(std::move(node));
        if (nodes.back().parent >= 0)
          nodes[static_cast<std::size_t>(nodes.back().parent)].children.push_back(nodes.size() - 1);
      }
      if (points > ctx_.opt.max_moves) {
        ctx_.limit_reached();
        return std::nullopt;
      }
    }
    std::vector<Areas> levels(n + 1);
    for (const Node& node : nodes) levels[node.level].push_back(Area{node.ring, {}});
    if (!walls_only && !rings_cover(levels, insets)) continue;

    // Post-order from each outermost ring: a branch's innermost ring first, each ring entered
    // from the one inside it by the shortest feed (it stays between the two rings).
    std::vector<Group> groups;
    const auto deepest_leaf = [&](std::size_t i) {
      while (!nodes[i].children.empty()) i = nodes[i].children.front();
      return i;
    };
    for (std::size_t root = 0; root < nodes.size(); ++root) {
      if (nodes[root].parent >= 0) continue;
      std::vector<std::size_t> order;
      std::vector<std::pair<std::size_t, std::size_t>> stack{{root, 0}};
      while (!stack.empty()) {
        auto& [i, next] = stack.back();
        if (next < nodes[i].children.size()) {
          const std::size_t child = nodes[i].children[next++];
          stack.push_back({child, 0});
        } else {
          order.push_back(i);
          stack.pop_back();
        }
      }
      if (walls_only) order = {root};
      const std::size_t first_leaf = deepest_leaf(root);
      P here{};
      for (std::size_t k = 0; k < order.size(); ++k) {
        const Node& node = nodes[order[k]];
        const bool leaf = node.children.empty();
        bool jump = k == 0;
        if (!jump && leaf) {
          const Nearest to = nearest_on(node.ring, here);
          jump = !polygons_.segment_inside(here, to.point, centres_);
        }
        if (jump) {
          const Ring& site_ring = k == 0 ? nodes[first_leaf].ring : node.ring;
          std::vector<std::pair<P, P>> edges;
          for (std::size_t e = 0; e < site_ring.size(); ++e)
            edges.emplace_back(site_ring[e], site_ring[(e + 1) % site_ring.size()]);
          Group g;
          if (!site(
                  site_ring, edges, [](P p) { return p; }, g.site))
            return std::nullopt;
          groups.push_back(std::move(g));
          here = groups.back().site.start;
        }
        const Nearest from = nearest_on(node.ring, here);
        groups.back().paths.push_back({ring_path(node.ring, from, ccw), true});
        here = from.point;
      }
    }
    return groups;
  }
  ctx_.not_implemented(ctx_.d(ctx_.op()) + " on " + ctx_.d(ctx_.feature()) +
                       ": contour-parallel rings that cover its floor could not be made");
  return std::nullopt;
}

std::optional<std::vector<Group>> Planner::lines(double step, P u, bool left, bool zigzag,
                                                 bool ring_first, bool ccw) {
  const P v{-u.y, u.x};
  std::vector<Group> groups;
  for (const Area& area : centres_) {
    if (!area.holes.empty()) {
      ctx_.not_implemented(ctx_.d(ctx_.feature()) + ": a region with an island");
      return std::nullopt;
    }
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    for (const P& p : area.outer) {
      u0 = std::min(u0, p.dot(u));
      u1 = std::max(u1, p.dot(u));
      v0 = std::min(v0, p.dot(v));
      v1 = std::max(v1, p.dot(v));
    }
    if ((v1 - v0) / step > static_cast<double>(ctx_.opt.max_moves)) {
      ctx_.limit_reached();
      return std::nullopt;
    }
    const auto n = static_cast<std::size_t>(std::ceil((v1 - v0) / step - 1e-9));
    std::vector<Chain> chords;
    for (std::size_t k = 0; k <= n; ++k) {
      const double vv =
          n == 0 ? (v0 + v1) / 2 : v0 + (v1 - v0) * static_cast<double>(k) / static_cast<double>(n);
      chords.push_back({u * (u0 - 1) + v * vv, u * (u1 + 1) + v * vv});
    }
    auto pieces = polygons_.clip(chords, Areas{area});
    if (!pieces) return std::nullopt;
    // Along u, ordered line by line (stepping along v), then along u.
    struct Piece {
      P a, b;
      double v, u;
    };
    std::vector<Piece> sorted;
    for (Chain& c : *pieces) {
      P a = c.front();
      P b = c.back();
      if ((b - a).dot(u) < 0) std::swap(a, b);
      if ((b - a).length() < poly::kResolution) continue;
      sorted.push_back({a, b, a.dot(v), a.dot(u)});
    }
    if (sorted.empty()) {
      // Too small for a line: the ring alone.
      Group g;
      if (!site(
              area.outer, {}, [](P p) { return p; }, g.site))
        return std::nullopt;
      const Nearest from = nearest_on(area.outer, g.site.start);
      g.paths.push_back({ring_path(area.outer, from, ccw), true});
      groups.push_back(std::move(g));
      continue;
    }
    const double line_gap = n == 0 ? 1 : (v1 - v0) / static_cast<double>(n);
    const auto line_of = [&](const Piece& x) {
      const double k = std::round((x.v - v0) / line_gap);
      return left ? k : -k;
    };
    std::sort(sorted.begin(), sorted.end(), [&](const Piece& x, const Piece& y) {
      const double kx = line_of(x);
      const double ky = line_of(y);
      return kx != ky ? kx < ky : x.u < y.u;
    });
    if (zigzag) {
      // Every other line backwards (its pieces in reverse order too).
      std::size_t i = 0;
      bool backwards = false;
      while (i < sorted.size()) {
        std::size_t j = i;
        const double k = line_of(sorted[i]);
        while (j < sorted.size() && line_of(sorted[j]) == k) ++j;
        if (backwards) {
          std::reverse(sorted.begin() + static_cast<std::ptrdiff_t>(i),
                       sorted.begin() + static_cast<std::ptrdiff_t>(j));
          for (std::size_t m = i; m < j; ++m) std::swap(sorted[m].a, sorted[m].b);
        }
        backwards = !backwards;
        i = j;
      }
    }
    std::vector<Chain> chains;
    for (const Piece& p : sorted) chains.push_back({p.a, p.b});
    if (!covered({area.outer}, chains)) {
      ctx_.not_implemented(ctx_.d(ctx_.op()) + " on " + ctx_.d(ctx_.feature()) +
                           ": its lines and wall ring leave floor uncut");
      return std::nullopt;
    }
    const auto new_group = [&](const Piece& p, bool straight_down) -> bool {
      std::vector<P> along;
      for (int k = 0; k <= 16; ++k) along.push_back(p.a + (p.b - p.a) * (k / 16.0));
      Group g;
      if (!site(
              along, {{p.a, p.b}}, [&](P) { return p.a; }, g.site))
        return false;
      g.site.straight_down = straight_down;
      groups.push_back(std::move(g));
      return true;
    };
    P here{};
    for (std::size_t k = 0; k < sorted.size(); ++k) {
      const Piece& p = sorted[k];
      const bool linked = k > 0 && zigzag && polygons_.segment_inside(here, p.a, centres_);
      if (k == 0 || !linked) {
        // One-way lines without a named approach go straight down at each line start, as the
        // rectangular raster does; a named approach is used at every entry.
        if (!new_group(p, k > 0 && !zigzag && !entry_.explicit_entry)) return std::nullopt;
        if (k == 0 && ring_first) {
          const Nearest from = nearest_on(area.outer, p.a);
          groups.back().paths.push_back({ring_path(area.outer, from, ccw), true});
        }
      }
      groups.back().paths.push_back({{p.a, p.b}, false});
      here = p.b;
    }
    if (!ring_first) {
      const Nearest from = nearest_on(area.outer, here);
      groups.back().paths.push_back({ring_path(area.outer, from, ccw), true});
    }
  }
  return groups;
}

// ---- playing a plan ----------------------------------------------------------------------------

// The margin by which every centre region is kept inside the exact one: the round joins' chords
// (chord_tolerance), the arcs fitted back (three times that), Clipper's grid.
double margin(const Context& ctx) {
  return 5 * ctx.opt.chord_tolerance + 4 * poly::kResolution;
}

struct Play {
  Context& ctx;
  const Entry& entry;
  // The operation's retract strategy (null: straight up) and what it asks for.
  const Instance* retract_strategy;
  const Entry& exit;
  const Areas& centres;
  std::vector<double> levels;
  double clear = 0;
  double retract = 0;
  bool ccw = true;
  double fit_tolerance = 0;
};

Vec3 at(P p, double z) {
  return {p.x, p.y, z};
}

// A path as the spans it is played as: its points as feeds, or, for rings, with arcs fitted back.
// Computed once per path, not per level: the fitting is most of what playing a ring costs.
std::vector<Span2> spans_of(const Path2& path, double fit_tolerance) {
  if (path.fit) return fit_arcs(path.points, fit_tolerance);
  std::vector<Span2> spans;
  spans.reserve(path.points.size());
  for (std::size_t k = 1; k < path.points.size(); ++k) spans.push_back({path.points[k]});
  return spans;
}

void emit_spans(Context& ctx, const std::vector<Span2>& spans, double z) {
  for (const Span2& s : spans) {
    if (s.arc)
      ctx.arc(at(s.to, z), at(s.centre, z), s.ccw ? 1 : -1);
    else
      ctx.feed(at(s.to, z));
  }
}

// The operation's retract strategy from the floor at `z`: back across the machined floor to
// where the last approach came down, and up the way it came (a helix about the same centre, a
// ramp along the same line), as rectangular pockets do. `here` becomes where the tool ends.
// False after reporting a retract that does not fit or cannot be made here.
bool leave_pocket(const Play& p, const Site& site, const poly::Polygons& polygons, double z,
                  P& here) {
  Context& ctx = p.ctx;
  const Instance& strategy = *p.retract_strategy;
  const std::string what = ctx.d(strategy) + " as the retract from " + ctx.d(ctx.feature());
  if (p.exit.kind == Entry::Kind::Ramp && site.kind != Entry::Kind::Ramp)
    return ctx.not_implemented(what +
                               " after an approach that is not a ramp (the ramp out "
                               "follows the approach's ramp line)");
  const P from = site.kind == Entry::Kind::Ramp ? site.ramp_from : site.centre;
  if ((from - here).length() > kEps && !polygons.segment_inside(here, from, p.centres))
    return ctx.not_implemented(what + ": no straight way across the floor from " + at_text(here) +
                               " back to where the approach came down, " + at_text(from));
  Entry exit = p.exit;
  Vec3 ramp_dir{1, 0, 0};
  double length = 0;
  if (exit.kind == Entry::Kind::Ramp) {
    const P d = site.ramp_to - site.ramp_from;
    length = d.length();
    if (length > 0) ramp_dir = {d.x / length, d.y / length, 0};
    if (exit.width > 0) length = std::min(length, exit.width);
    if (length < 1e-3) return ctx.unfit(strategy, what + ": no room for a ramp");
  } else {
    const double room = poly::distance_to_boundary(p.centres, from) - margin(ctx);
    if (exit.radius > room + kEps || exit.radius < 1e-3)
      return ctx.unfit(strategy, what + ": a helix of radius " + fmt(exit.radius) +
                                     " does not fit at " + at_text(from) + " (room " +
                                     fmt(std::max(0.0, room)) + ")");
  }
  if (entry_too_long(ctx, exit, length, p.clear - z)) return ctx.limit_reached();
  ctx.feed(at(from, z));
  leave(ctx, exit, at(from, z), {1, 0, 0}, ramp_dir, length, p.ccw, z, p.clear);
  const Vec3 end = ctx.path.moves.back().to;
  here = {end.x, end.y};
  return true;
}

bool play(const Play& p, const std::vector<Group>& groups) {
  Context& ctx = p.ctx;
  const poly::Polygons polygons(ctx.opt.chord_tolerance);
  std::size_t count = 0;
  for (const Group& g : groups)
    for (const Path2& path : g.paths) count += path.points.size() + 8;
  if (static_cast<double>(count) * static_cast<double>(p.levels.size()) >
      static_cast<double>(ctx.opt.max_moves))
    return ctx.limit_reached();
  std::vector<std::vector<std::vector<Span2>>> spans(groups.size());
  for (std::size_t gi = 0; gi < groups.size(); ++gi)
    for (const Path2& path : groups[gi].paths) spans[gi].push_back(spans_of(path, p.fit_tolerance));
  double from_z = p.clear;
  P here{};
  bool started = false;
  for (const double z : p.levels) {
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      const Site& site = groups[gi].site;
      const P e = site.entry_point();
      if (!started) {
        ctx.rapid(at(e, std::max(p.retract, p.clear)));
        if (p.retract > p.clear) ctx.rapid(at(e, p.clear));
        started = true;
      } else if (gi == 0 && polygons.segment_inside(here, e, p.centres)) {
        // Across the floor just machined, to where the next level starts.
        ctx.feed(at(e, from_z));
      } else {
        // Up above the feature's top, across, and down at feed through what is machined.
        ctx.rapid(at(here, p.clear));
        ctx.rapid(at(e, p.clear));
        if (from_z < p.clear) ctx.feed(at(e, from_z));
      }
      if (site.straight_down) {
        ctx.feed(at(site.start, z));
      } else {
        Entry entry = p.entry;
        entry.kind = site.kind;
        entry.radius = site.helix;
        const P dir = site.ramp_to - site.ramp_from;
        const double length = dir.length();
        const Vec3 ramp_dir = length > 0 ? Vec3{dir.x / length, dir.y / length, 0} : Vec3{1, 0, 0};
        if (entry_too_long(ctx, entry, length, from_z - z)) return ctx.limit_reached();
        enter(ctx, entry, at(site.kind == Entry::Kind::Ramp ? site.ramp_from : site.centre, z),
              {1, 0, 0}, ramp_dir, length, p.ccw, from_z, z);
        const P end = site.kind == Entry::Kind::Ramp ? site.ramp_from : site.centre;
        if ((site.start - end).length() > kEps) ctx.feed(at(site.start, z));
      }
      here = site.start;
      for (std::size_t pi = 0; pi < groups[gi].paths.size(); ++pi) {
        const Path2& path = groups[gi].paths[pi];
        if ((path.points.front() - here).length() > kEps) ctx.feed(at(path.points.front(), z));
        emit_spans(ctx, spans[gi][pi], z);
        here = path.points.back();
      }
      if (ctx.too_many()) return ctx.limit_reached();
    }
    from_z = z;
  }
  if (p.retract_strategy != nullptr && p.exit.kind != Entry::Kind::Plunge &&
      !leave_pocket(p, groups.back().site, polygons, from_z, here))
    return false;
  ctx.rapid(at(here, std::max(p.retract, p.clear)));
  return true;
}

// ---- pockets ------------------------------------------------------------------------------------

bool corner_checks(Context& ctx, const Outline& outline, const Tool& tool, const OperationData& o,
                   double corner_radius, bool material_outside) {
  const double d = tool.radius + o.allowance_side;
  const std::string who = ctx.d(*tool.instance) + " radius " + fmt(tool.radius) + " + allowance " +
                          fmt(o.allowance_side) + " of " + ctx.d(ctx.op());
  // A corner turning towards the material is one the tool must fit into.
  const double sign = material_outside ? 1 : -1;
  for (const Corner& c : corners(outline)) {
    if (sign * c.turn <= 0) continue;
    const double left = d * (1 / std::cos(std::min(std::abs(c.turn), 3.1) / 2) - 1);
    if (left <= ctx.opt.corner_tolerance || corner_radius + kEps >= d) continue;
    return ctx.unfit(*tool.instance, who + " > corner radius " + fmt(corner_radius) + " of " +
                                         ctx.d(ctx.feature()) + " at " + at_text(c.at));
  }
  for (const Element& e : outline.elements) {
    if (!e.arc || sign * e.sweep <= 0 || e.radius + kEps >= d ||
        std::max(e.radius, corner_radius) + kEps >= d)
      continue;
    const double mid = std::atan2((e.a - e.centre).y, (e.a - e.centre).x) + e.sweep / 2;
    return ctx.unfit(*tool.instance,
                     who + " > arc radius " + fmt(e.radius) + " of " + ctx.d(ctx.feature()) +
                         " at " + at_text(e.centre + P{std::cos(mid), std::sin(mid)} * e.radius));
  }
  return true;
}

// What a general pocket (closed or open) hands to the common machining.
struct PocketRegion {
  Areas centres;  // where the tool centre may go
  Areas source;   // what `centres` is shrunk from (by `base`)
  Areas sharp;    // `source` without its corner fillets, of radius `rho`
  double rho = 0;
  double base = 0;
  Areas floor;  // what it must reach (the floor inset by the side allowance)
  bool through = false;
  std::optional<Toleranced> fillet;
};

bool machine_pocket(Context& ctx, const Tool& tool, const OperationData& o, PocketRegion& region,
                    double depth) {
  const Instance& f = ctx.feature();
  // Checks only: within a fifth of the corner tolerance, erring towards "not reached".
  const double e = ctx.opt.corner_tolerance / 5;
  const poly::Polygons polygons(e);
  if (region.centres.empty())
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " diameter " + fmt(2 * tool.radius) +
                                         " + allowances does not fit " + ctx.d(f));
  // Everything of the floor within the tool radius of the centre region: nothing narrower
  // than the tool (a neck between two walls) may be left.
  const auto reach = polygons.offset(poly::simplified(region.centres, e), tool.radius - e);
  const auto missed = reach ? polygons.difference(region.floor, *reach) : std::nullopt;
  const auto missed_much =
      missed ? polygons.offset(*missed, -ctx.opt.chord_tolerance) : std::nullopt;
  if (!missed_much) return ctx.bad(f, ctx.d(f) + ": its outline cannot be offset");
  if (!missed_much->empty())
    return ctx.unfit(*tool.instance, ctx.d(*tool.instance) + " diameter " + fmt(2 * tool.radius) +
                                         " + allowance " + fmt(o.allowance_side) + " of " +
                                         ctx.d(ctx.op()) + " does not reach all of " + ctx.d(f) +
                                         ": a part near " +
                                         at_text(missed_much->front().outer.front()) +
                                         " is narrower than the tool");

  const bool walls_only = ctx.is(&ctx.op(), "side_milling");
  enum class Pattern { Rings, LinesThenRing, RingThenLines } pattern = Pattern::Rings;
  bool zigzag = true;
  bool left = true;
  P u{1, 0};
  if (o.strategy != nullptr && !ctx.is(o.strategy, "contour_parallel")) {
    if (ctx.is(o.strategy, "bidirectional_milling") ||
        ctx.is(o.strategy, "bidirectional_contour")) {
      pattern = Pattern::LinesThenRing;
    } else if (ctx.is(o.strategy, "unidirectional_milling")) {
      pattern = Pattern::LinesThenRing;
      zigzag = false;
    } else if (ctx.is(o.strategy, "contour_bidirectional")) {
      pattern = Pattern::RingThenLines;
    } else {
      return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f));
    }
    if (walls_only)
      return ctx.not_implemented(ctx.d(*o.strategy) + " for " + ctx.d(ctx.op()) + " on " +
                                 ctx.d(f));
    if (const auto dir = ctx.direction(*o.strategy, "feed_direction")) {
      if (std::abs(dir->z) > 1e-9)
        return ctx.bad(*o.strategy, ctx.d(*o.strategy) + " feed_direction is not in the pocket");
      u = P{dir->x, dir->y} * (1 / std::hypot(dir->x, dir->y));
    }
    // Lines follow each other to the left of the feed direction, or to the right when asked.
    left = ctx.enumeration(*o.strategy, "stepover_direction") != "RIGHT";
  }
  const bool ccw = rings_ccw(ctx, o, true);
  double overlap = 0;
  double step = stepover(ctx, tool, o, overlap);
  if (!check_overlap(ctx, o, overlap)) return false;
  step = std::min(step, kSharpCornerStep * tool.radius);
  if (region.fillet && !check_fillet(ctx, tool, o, *region.fillet)) return false;

  const double finish = depth - (region.through ? -ctx.opt.through_clearance : o.allowance_bottom);
  if (!(finish > 0))
    return ctx.bad(ctx.op(), ctx.d(ctx.op()) + " leaves the whole depth of " + ctx.d(f));
  const auto z_levels = depth_levels(ctx, o, finish);
  if (!z_levels || !check_edge(ctx, tool, *z_levels)) return false;
  Entry entry;
  if (!read_entry(ctx, o, tool, entry)) return false;
  Entry exit;
  if (!read_exit(ctx, o, entry, exit)) return false;

  Planner planner(ctx, tool, o, entry, region.centres, region.source, region.sharp, region.rho,
                  region.base, margin(ctx));
  std::optional<std::vector<Group>> groups;
  if (pattern == Pattern::Rings) {
    groups = planner.rings(step, ccw, walls_only);
  } else {
    groups = planner.lines(step, u, left, zigzag, pattern == Pattern::RingThenLines, ccw);
  }
  if (!groups) return false;
  if (groups->empty()) return ctx.bad(f, ctx.d(f) + ": nothing to machine");
  Play p{ctx,
         entry,
         o.retract,
         exit,
         region.centres,
         *z_levels,
         ctx.opt.clearance,
         o.retract_plane.value_or(ctx.opt.clearance),
         ccw,
         ctx.opt.chord_tolerance};
  return play(p, *groups);
}

// The outline's polygon on the side away from the material, checked simple.
std::optional<Ring> polygon_of(Context& ctx, const Instance& at, const Outline& outline,
                               bool material_left) {
  auto ring =
      tessellate(outline, ctx.opt.chord_tolerance, material_left, ctx.opt.max_polygon_points);
  if (!ring) {
    ctx.bad(at, ctx.d(at) + " needs more than FeatureOptions::max_polygon_points (" +
                    std::to_string(ctx.opt.max_polygon_points) + ") polygon points");
    return std::nullopt;
  }
  if (!poly::simple(*ring)) {
    ctx.bad(at, ctx.d(at) + " crosses itself or encloses no area");
    return std::nullopt;
  }
  return ring;
}

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
    c.dir = (e.b - e.a) * (1 / (e.b - e.a).length());
    c.point = e.a + P{-c.dir.y, c.dir.x} * rho;
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
    const P d = e.b - e.a;
    const double t = (p - e.a).dot(d) / d.dot(d);
    foot = e.a + d * t;
    return t >= -1e-9 && t <= 1 + 1e-9;
  }
  const P r = p - e.centre;
  foot = e.centre + r * (e.radius / r.length());
  double from_start = angle_of(foot - e.centre) - angle_of(e.a - e.centre);
  if (e.sweep < 0) from_start = -from_start;
  from_start = std::fmod(from_start + 4 * std::numbers::pi, 2 * std::numbers::pi);
  return from_start <= std::abs(e.sweep) + 1e-9;
}

// The material that ISO 14649's orthogonal_radius adds in the pocket's sharp corners (those
// turning away from the material, where the tool cannot reach): the part of each corner beyond
// a fillet arc of that radius tangent to both sides. Each polygon covers its fillet's material:
// the fillet's chords lie on the pocket side, and the sides' arcs are followed to within the
// chord tolerance. A fillet that the sides are too short for, or too curved, is taken tangent
// to the sides' directions at the corner, which keeps more material.
std::optional<Areas> fillet_material(Context& ctx, const Outline& outline, double rho, double d) {
  const FeatureOptions& opt = ctx.opt;
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
      if (taken[index] > (side.b - side.a).length() + 1e-6) {
        ctx.bad(ctx.feature(), ctx.d(ctx.feature()) + " orthogonal_radius " + fmt(rho) +
                                   " does not fit the side from " + at_text(side.a) + " to " +
                                   at_text(side.b) + " between its corners");
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

}  // namespace

bool general_pocket(Context& ctx, const Instance& boundary, bool through,
                    std::optional<Toleranced> fillet) {
  const Instance& f = ctx.feature();
  const auto outline = read_closed_outline(ctx, boundary);
  if (!outline) return false;
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  const auto corner = ctx.toleranced(f, "orthogonal_radius");
  const double rho = corner ? corner->size : 0;
  if (!corner_checks(ctx, *outline, *tool, o, rho, true)) return false;
  const auto ring = polygon_of(ctx, boundary, *outline, false);
  if (!ring) return false;
  const poly::Polygons polygons(ctx.opt.chord_tolerance);
  const double d = tool->radius + o.allowance_side;
  const auto fillets = fillet_material(ctx, *outline, rho, d);
  if (!fillets) return false;
  const auto pocket = polygons.difference(Areas{Area{*ring, {}}}, *fillets);
  const auto centres = pocket ? polygons.offset(*pocket, -(d + margin(ctx))) : std::nullopt;
  const auto floor = pocket ? polygons.offset(*pocket, -(o.allowance_side + 2 * margin(ctx) +
                                                         ctx.opt.corner_tolerance))
                            : std::nullopt;
  if (!centres || !floor) return ctx.bad(f, ctx.d(f) + ": its outline cannot be offset");
  PocketRegion region{*centres, *pocket, Areas{Area{*ring, {}}}, rho, d + margin(ctx), *floor,
                      through,  fillet};
  return machine_pocket(ctx, *tool, o, region, *depth);
}

bool generate_open_pocket(Context& ctx) {
  const Instance& f = ctx.feature();
  if (!ctx.is(&ctx.op(), "bottom_and_side_milling") && !ctx.is(&ctx.op(), "side_milling"))
    return ctx.not_implemented(ctx.d(ctx.op()) + " on " + ctx.d(f) +
                               " (pockets take bottom-and-side or side milling)");
  if (const auto bosses = ctx.g.get(f, "its_boss"); bosses && bosses->is_list() && bosses->count())
    return ctx.not_implemented(ctx.d(f) + " with bosses (islands)");
  if (const auto slope = ctx.number(f, "slope"); slope && std::abs(*slope) > kEps)
    return ctx.not_implemented(ctx.d(f) + " with sloped walls");
  const Instance* bottom = ctx.ref(f, "bottom_condition", "pocket_bottom_condition");
  if (bottom == nullptr) return ctx.bad(f, ctx.d(f) + " has no bottom_condition");
  const bool through = ctx.is(bottom, "through_pocket_bottom_condition");
  if (!through && !ctx.is(bottom, "planar_pocket_bottom_condition"))
    return ctx.not_implemented(ctx.d(f) + " with " + ctx.d(*bottom));
  const Instance* boundary = ctx.ref(f, "open_boundary", "open_profile");
  if (boundary == nullptr) return ctx.bad(f, ctx.d(f) + " has no open_boundary");
  if (const Instance* wall = ctx.ref(f, "wall_boundary", "open_profile"))
    ctx.note(*wall, ctx.d(*wall) + " is for information only (ISO 14649-10): " + ctx.d(f) +
                        " is open along the straight line between the ends of " + ctx.d(*boundary));
  auto walls = read_open_outline(ctx, *boundary);
  if (!walls) return false;
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  const double d = tool->radius + o.allowance_side;
  const double m = margin(ctx);
  const poly::Polygons polygons(ctx.opt.chord_tolerance);

  // The pocket: the walls closed by the straight open side, counter-clockwise.
  const auto closed_polygon = [&]() -> std::optional<Ring> {
    return tessellate(*walls, ctx.opt.chord_tolerance, false, ctx.opt.max_polygon_points);
  };
  auto ring = closed_polygon();
  if (ring && poly::area(*ring) < 0) {
    reverse(*walls);
    ring = closed_polygon();
  }
  if (!ring) return ctx.bad(*boundary, ctx.d(*boundary) + " needs too many polygon points");
  if (!poly::simple(*ring))
    return ctx.bad(*boundary, ctx.d(*boundary) + " and its open side cross or enclose no area");
  const P a = walls->elements.back().b;  // the open side runs from a to b
  const P b = walls->elements.front().a;
  if ((b - a).length() < 1e-3)
    return ctx.bad(*boundary, ctx.d(*boundary) + " is closed: " + ctx.d(f) + " has no open side");
  const auto corner = ctx.toleranced(f, "orthogonal_radius");
  const double rho = corner ? corner->size : 0;
  if (!corner_checks(ctx, *walls, *tool, o, rho, true)) return false;

  // Beyond the open side the tool may run out by R + clearance: the centre region reaches that
  // far past it, and keeps d from the walls, which go on along the open side's line past its
  // ends (the part's face there, whose material the tool must not cut either).
  const P along = (b - a) * (1 / (b - a).length());
  const P out{along.y, -along.x};
  const double run = tool->radius + ctx.opt.clearance;
  const double reach = run + d;
  const Ring beyond{a - along * reach, b + along * reach, b + along * reach + out * run,
                    a - along * reach + out * run};
  auto walls_chain = tessellate(*walls, ctx.opt.chord_tolerance, false, ctx.opt.max_polygon_points);
  if (!walls_chain) return ctx.bad(*boundary, ctx.d(*boundary) + " needs too many polygon points");
  walls_chain->insert(walls_chain->begin(), b + along * (reach + d + 1));
  walls_chain->push_back(a - along * (reach + d + 1));
  const auto fillet_areas = fillet_material(ctx, *walls, rho, d);
  if (!fillet_areas) return false;
  const Areas& fillets = *fillet_areas;
  const auto united = polygons.unite(Areas{Area{*ring, {}}}, Areas{Area{beyond, {}}});
  const auto open = united ? polygons.difference(*united, fillets) : std::nullopt;
  const auto band = polygons.sweep({}, {*walls_chain}, d + m + ctx.opt.chord_tolerance);
  const auto fillet_band = polygons.offset(fillets, d + m + ctx.opt.chord_tolerance);
  const auto keep_off = band && fillet_band ? polygons.unite(*band, *fillet_band) : std::nullopt;
  const auto centres = open && keep_off ? polygons.difference(*open, *keep_off) : std::nullopt;
  const auto inset =
      open ? polygons.offset(*open, -(o.allowance_side + 2 * m + ctx.opt.corner_tolerance))
           : std::nullopt;
  const auto floor = inset ? polygons.intersection(*inset, Areas{Area{*ring, {}}}) : std::nullopt;
  if (!centres || !floor) return ctx.bad(f, ctx.d(f) + ": its outline cannot be offset");
  PocketRegion region{*centres, *centres, *centres, 0,
                      0,        *floor,   through,  ctx.toleranced(f, "planar_radius")};
  return machine_pocket(ctx, *tool, o, region, *depth);
}

bool general_outside_profile(Context& ctx, const Instance& boundary) {
  const Instance& f = ctx.feature();
  const auto outline = read_closed_outline(ctx, boundary);
  if (!outline) return false;
  const auto depth = ctx.depth();
  const auto tool = ctx.tool();
  if (!depth || !tool) return false;
  const OperationData o = ctx.operation();
  if (o.strategy != nullptr && !ctx.is(o.strategy, "contour_parallel"))
    return ctx.not_implemented(ctx.d(*o.strategy) + " on " + ctx.d(f));
  if (o.approach != nullptr && !ctx.is(o.approach, "plunge_strategy"))
    return ctx.not_implemented(ctx.d(*o.approach) + " as the approach of " + ctx.d(ctx.op()));
  if (!corner_checks(ctx, *outline, *tool, o, 0, false)) return false;
  const auto part = polygon_of(ctx, boundary, *outline, true);
  if (!part) return false;
  const poly::Polygons polygons(ctx.opt.chord_tolerance);
  const auto grown =
      polygons.offset(Areas{Area{*part, {}}}, tool->radius + o.allowance_side + margin(ctx));
  if (!grown || grown->size() != 1) return ctx.bad(f, ctx.d(f) + ": its outline cannot be offset");
  if (!grown->front().holes.empty())
    return ctx.unfit(*tool->instance, ctx.d(*tool->instance) + " diameter " +
                                          fmt(2 * tool->radius) + " + allowance " +
                                          fmt(o.allowance_side) + " of " + ctx.d(ctx.op()) +
                                          " does not fit into a bay of " + ctx.d(f) + " near " +
                                          at_text(grown->front().holes.front().front()));
  const Ring& ring = grown->front().outer;
  const bool ccw = rings_ccw(ctx, o, false);
  const auto z_levels = depth_levels(ctx, o, *depth);
  if (!z_levels || !check_edge(ctx, *tool, *z_levels)) return false;
  if (static_cast<double>(ring.size() + 4) * static_cast<double>(z_levels->size()) >
      static_cast<double>(ctx.opt.max_moves))
    return ctx.limit_reached();
  // Each level starts and ends at a lead-in point clear of the ring on the +x side of its
  // rightmost point: nothing of the part lies that way.
  std::size_t right = 0;
  for (std::size_t k = 1; k < ring.size(); ++k)
    if (ring[k].x > ring[right].x) right = k;
  const Nearest start{ring[right], right, 0};
  const P lead = ring[right] + P{tool->radius + ctx.opt.clearance, 0};
  const std::vector<Span2> spans =
      spans_of({ring_path(ring, start, ccw), true}, ctx.opt.chord_tolerance);
  const double clear = ctx.opt.clearance;
  const double retract = o.retract_plane.value_or(clear);
  ctx.rapid(at(lead, std::max(retract, clear)));
  if (retract > clear) ctx.rapid(at(lead, clear));
  for (const double z : *z_levels) {
    ctx.feed(at(lead, z));
    ctx.feed(at(ring[right], z));
    emit_spans(ctx, spans, z);
    ctx.feed(at(lead, z));
    if (ctx.too_many()) return ctx.limit_reached();
  }
  ctx.rapid(at(lead, std::max(retract, clear)));
  return true;
}

}  // namespace ncpost::stepnc::features::legacy
