// Pockets with general profiles: the planner (general.hpp). Rings or lines are cut from the
// region the tool centre may use and checked to cover it before any motion is made; each group
// of paths starts where the tool goes down (its site) and is cut from there without lifting.

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "general.hpp"
#include "motion.hpp"
#include "outline.hpp"
#include "polygon_paths.hpp"

namespace ncpost::stepnc::features {
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

struct Group {
  Site site;
  std::vector<PlanePath> paths;  // each reached from the previous one by a feed inside the region
};

// A ring of the contour-parallel plan and its place in the tree of nested rings: a region that
// splits into islands as it shrinks has one branch per island.
struct RingNode {
  Ring ring;
  std::size_t level = 0;
  std::ptrdiff_t parent = -1;
  std::vector<std::size_t> children;
};

// One piece of a line clipped to the region, from a to b along the feed direction; v and u
// are where it starts across and along.
struct Piece {
  P from, to;
  double across, along;
};

class Planner {
 public:
  // `centres` is `source` shrunk by `base`: inner rings are shrunk from `source` at once, so
  // that a round join about one of its corners stays one arc.
  // Shrunk by `rho` or more, `source` and `sharp` (its corners not filleted) give the same
  // region, and `sharp` has far fewer points: its polygon's arcs do not fold over.
  Planner(const GeneralPocketSpec& spec, Draft& draft)
      : draft_(draft),
        options_(draft.options()),
        spec_(spec),
        entry_(spec.entry),
        centres_(spec.region.centres),
        source_(spec.region.source),
        sharp_(spec.region.sharp),
        rho_(spec.region.rho),
        base_(spec.region.base),
        margin_(region_margin(draft.options())),
        polygons_(draft.options().chord_tolerance),
        checks_(draft.options().corner_tolerance / 5) {}

  // Contour-parallel rings from the innermost outwards, `step` apart at most; nullopt with a
  // diagnostic when they cannot be made.
  std::optional<std::vector<Group>> rings(double step, bool ccw, bool walls_only);
  // Parallel lines along `u`, clipped to the region, then (or first) the ring round each part.
  // `left`: the lines follow each other to the left of `u` (else to the right).
  std::optional<std::vector<Group>> lines(double step, P u, bool left, bool zigzag, bool ring_first,
                                          bool ccw);

 private:
  // A site among sampled points: the helix where there is most room, a ramp along a segment.
  bool site(const std::vector<P>& candidates, const std::vector<std::pair<P, P>>& ramps,
            const std::function<P(P)>& start_after, Site& out);
  bool ramp_site(const std::vector<P>& candidates, const std::vector<std::pair<P, P>>& ramps,
                 Site& out);
  bool helix_site(const std::vector<P>& candidates, const std::function<P(P)>& start_after,
                  Site& out);
  // The largest distance from the region's boundary that a point of it has.
  std::optional<double> inradius();
  bool covered(const std::vector<Ring>& rings, const std::vector<Chain>& chains);
  // Rings that are the boundaries of nested regions (`levels`, from the outermost) cover all of
  // the outermost when, in each, what is further than the tool radius from its boundary lies
  // within the tool radius of the next one: a test on each region, not on the union of all
  // the swept bands (which costs far more).
  bool rings_cover(const std::vector<Areas>& levels, const std::vector<double>& insets);
  // The tree of n + 1 rings at whole steps of room / n from the outermost, the innermost just
  // short of the centre; `insets` receives each level's inset. nullopt when they cannot be made
  // (after reporting an island or the motion limit).
  std::optional<std::vector<RingNode>> ring_tree(std::size_t n, double room,
                                                 std::vector<double>& insets);
  // Post-order from each outermost ring: a branch's innermost ring first, each ring entered
  // from the one inside it by the shortest feed (it stays between the two rings).
  std::optional<std::vector<Group>> ring_groups(const std::vector<RingNode>& nodes, bool ccw,
                                                bool walls_only);
  // The lines across one area, sorted line by line; empty when it is too small for a line.
  std::optional<std::vector<Piece>> line_pieces(const Area& area, double step, P u, bool left,
                                                bool zigzag);
  // The groups of one area's lines and its wall ring.
  bool line_groups(const Area& area, const std::vector<Piece>& pieces, bool zigzag, bool ring_first,
                   bool ccw, std::vector<Group>& groups);
  // `source` shrunk by `base` + `inset`.
  std::optional<Areas> shrunk(double inset, bool for_check = false) {
    const double by = base_ + inset;
    return (for_check ? checks_ : polygons_).offset(by >= rho_ ? sharp_ : source_, -by);
  }

  Draft& draft_;
  const FeatureOptions& options_;
  const GeneralPocketSpec& spec_;
  const Entry& entry_;  // its strategy is set whenever it is explicit_entry
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

bool Planner::site(const std::vector<P>& candidates, const std::vector<std::pair<P, P>>& ramps,
                   const std::function<P(P)>& start_after, Site& out) {
  out = Site{};
  out.kind = entry_.kind;
  if (entry_.kind == Entry::Kind::Ramp) return ramp_site(candidates, ramps, out);
  return helix_site(candidates, start_after, out);
}

bool Planner::ramp_site(const std::vector<P>& candidates, const std::vector<std::pair<P, P>>& ramps,
                        Site& out) {
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
    return draft_.report().unfit(
        entry_.strategy, entry_.strategy.name() + ": no room for a ramp of " + spec_.tool.name() +
                             " in " + spec_.feature.name());
  out.ramp_to = out.ramp_from + (out.ramp_to - out.ramp_from) * (length / best);
  out.centre = out.ramp_from;
  out.start = out.ramp_from;
  return true;
}

bool Planner::helix_site(const std::vector<P>& candidates, const std::function<P(P)>& start_after,
                         Site& out) {
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
  Report& report = draft_.report();
  const Subject& approach = entry_.strategy;
  if (out.helix > room + kEps) {
    if (entry_.explicit_entry)
      return report.unfit(approach, approach.name() + " radius " + fmt(entry_.radius) +
                                        " leaves no room for " + spec_.tool.name() + " in " +
                                        spec_.feature.name() + " (at most " + fmt(room) + " at " +
                                        at_text(out.centre) + ")");
    out.helix = room;
  }
  if (out.helix < 1e-3) {
    if (entry_.explicit_entry)
      return report.unfit(approach, approach.name() + ": " + spec_.tool.name() + " fills " +
                                        spec_.feature.name() + " at " + at_text(out.centre) +
                                        ", no room for a helix");
    out.kind = Entry::Kind::Plunge;
    if (!plunge_noted_)
      report.note(spec_.feature, spec_.tool.name() + " fills " + spec_.feature.name() + " at " +
                                     at_text(out.centre) +
                                     "; it enters along its axis, as there is no room for a "
                                     "helix");
    plunge_noted_ = true;
  }
  return true;
}

std::optional<double> Planner::inradius() {
  // On a simplified outline (within `coarse` either way): the answer only spaces the rings,
  // and the innermost ring is put `coarse` further out, so that it is never empty.
  const double coarse = std::min(0.02 * spec_.tool_radius, 0.1);
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
  const auto swept = polygons_.sweep(rings, chains, spec_.tool_radius);
  if (!swept) return false;
  const auto left = polygons_.difference(centres_, *swept);
  if (!left) return false;
  const auto significant = polygons_.offset(*left, -options_.corner_tolerance / 2);
  return significant && significant->empty();
}

bool Planner::rings_cover(const std::vector<Areas>& levels, const std::vector<double>& insets) {
  for (std::size_t k = 0; k < levels.size(); ++k) {
    // Further than the tool radius from ring k: the source shrunk that much more, less the
    // islands that ring k does not go round (slivers left out of the plan).
    const auto deeper = shrunk(insets[k] + spec_.tool_radius, true);
    const auto far = deeper ? checks_.intersection(*deeper, levels[k]) : std::nullopt;
    if (!far) return false;
    Areas rest = *far;
    if (!rest.empty() && k + 1 < levels.size()) {
      // On a simplified copy, grown that much less: still inside the exact grown region.
      const double e = options_.corner_tolerance / 5;
      const auto near = checks_.offset(poly::simplified(levels[k + 1], e), spec_.tool_radius - e);
      const auto left = near ? checks_.difference(rest, *near) : std::nullopt;
      if (!left) return false;
      rest = *left;
    }
    if (rest.empty()) continue;
    const auto significant = checks_.offset(rest, -options_.corner_tolerance / 2);
    if (!significant || !significant->empty()) return false;
  }
  return true;
}

std::optional<std::vector<RingNode>> Planner::ring_tree(std::size_t n, double room,
                                                        std::vector<double>& insets) {
  const double s = room / static_cast<double>(n);
  std::vector<RingNode> nodes;
  std::size_t points = 0;
  for (std::size_t k = 0; k <= n; ++k) {
    const double inset = k < n ? static_cast<double>(k) * s : room - std::min(0.05 * s, 0.01);
    insets.push_back(inset);
    std::optional<Areas> level = k == 0 ? std::optional<Areas>(centres_) : shrunk(inset);
    if (!level) return std::nullopt;
    for (Area& a : *level) {
      if (!a.holes.empty()) {
        draft_.report().not_implemented(spec_.feature.name() + ": its offset at " + fmt(inset) +
                                        " mm encloses an island");
        return std::nullopt;
      }
      RingNode node{std::move(a.outer), k, -1, {}};
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
    if (points > options_.max_moves) {
      draft_.limit_reached();
      return std::nullopt;
    }
  }
  return nodes;
}

std::optional<std::vector<Group>> Planner::ring_groups(const std::vector<RingNode>& nodes, bool ccw,
                                                       bool walls_only) {
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
      const RingNode& node = nodes[order[k]];
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

std::optional<std::vector<Group>> Planner::rings(double step0, bool ccw, bool walls_only) {
  const auto room = inradius();
  if (!room) return std::nullopt;
  if (*room / step0 > static_cast<double>(options_.max_moves)) {
    draft_.limit_reached();
    return std::nullopt;
  }
  auto n = static_cast<std::size_t>(std::max(1.0, std::ceil(*room / step0 - 1e-9)));
  for (int attempt = 0; attempt < kCoverageTries; ++attempt, ++n) {
    std::vector<double> insets;
    const auto nodes = ring_tree(n, *room, insets);
    if (!nodes) return std::nullopt;
    std::vector<Areas> levels(n + 1);
    for (const RingNode& node : *nodes) levels[node.level].push_back(Area{node.ring, {}});
    if (!walls_only && !rings_cover(levels, insets)) continue;
    return ring_groups(*nodes, ccw, walls_only);
  }
  draft_.report().not_implemented(
      spec_.operation.name() + " on " + spec_.feature.name() +
      ": contour-parallel rings that cover its floor could not be made");
  return std::nullopt;
}

std::optional<std::vector<Piece>> Planner::line_pieces(const Area& area, double step, P u,
                                                       bool left, bool zigzag) {
  const P v{-u.y, u.x};
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const P& p : area.outer) {
    u0 = std::min(u0, p.dot(u));
    u1 = std::max(u1, p.dot(u));
    v0 = std::min(v0, p.dot(v));
    v1 = std::max(v1, p.dot(v));
  }
  if ((v1 - v0) / step > static_cast<double>(options_.max_moves)) {
    draft_.limit_reached();
    return std::nullopt;
  }
  const auto n = static_cast<std::size_t>(std::ceil((v1 - v0) / step - 1e-9));
  std::vector<Chain> chords;
  for (std::size_t k = 0; k <= n; ++k) {
    const double vv =
        n == 0 ? (v0 + v1) / 2 : v0 + (v1 - v0) * static_cast<double>(k) / static_cast<double>(n);
    chords.push_back({u * (u0 - 1) + v * vv, u * (u1 + 1) + v * vv});
  }
  auto clipped = polygons_.clip(chords, Areas{area});
  if (!clipped) return std::nullopt;
  // Along u, ordered line by line (stepping along v), then along u.
  std::vector<Piece> sorted;
  for (Chain& c : *clipped) {
    P a = c.front();
    P b = c.back();
    if ((b - a).dot(u) < 0) std::swap(a, b);
    if ((b - a).length() < poly::kResolution) continue;
    sorted.push_back({a, b, a.dot(v), a.dot(u)});
  }
  const double line_gap = n == 0 ? 1 : (v1 - v0) / static_cast<double>(n);
  const auto line_of = [&](const Piece& x) {
    const double k = std::round((x.across - v0) / line_gap);
    return left ? k : -k;
  };
  std::sort(sorted.begin(), sorted.end(), [&](const Piece& x, const Piece& y) {
    const double kx = line_of(x);
    const double ky = line_of(y);
    return kx != ky ? kx < ky : x.along < y.along;
  });
  if (!zigzag) return sorted;
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
      for (std::size_t m = i; m < j; ++m) std::swap(sorted[m].from, sorted[m].to);
    }
    backwards = !backwards;
    i = j;
  }
  return sorted;
}

bool Planner::line_groups(const Area& area, const std::vector<Piece>& pieces, bool zigzag,
                          bool ring_first, bool ccw, std::vector<Group>& groups) {
  std::vector<Chain> chains;
  for (const Piece& p : pieces) chains.push_back({p.from, p.to});
  if (!covered({area.outer}, chains))
    return draft_.report().not_implemented(spec_.operation.name() + " on " + spec_.feature.name() +
                                           ": its lines and wall ring leave floor uncut");
  const auto new_group = [&](const Piece& p, bool straight_down) -> bool {
    std::vector<P> along;
    for (int k = 0; k <= 16; ++k) along.push_back(p.from + (p.to - p.from) * (k / 16.0));
    Group g;
    if (!site(
            along, {{p.from, p.to}}, [&](P) { return p.from; }, g.site))
      return false;
    g.site.straight_down = straight_down;
    groups.push_back(std::move(g));
    return true;
  };
  P here{};
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& p = pieces[k];
    const bool linked = k > 0 && zigzag && polygons_.segment_inside(here, p.from, centres_);
    if (k == 0 || !linked) {
      // One-way lines without a named approach go straight down at each line start, as the
      // rectangular raster does; a named approach is used at every entry.
      if (!new_group(p, k > 0 && !zigzag && !entry_.explicit_entry)) return false;
      if (k == 0 && ring_first) {
        const Nearest from = nearest_on(area.outer, p.from);
        groups.back().paths.push_back({ring_path(area.outer, from, ccw), true});
      }
    }
    groups.back().paths.push_back({{p.from, p.to}, false});
    here = p.to;
  }
  if (!ring_first) {
    const Nearest from = nearest_on(area.outer, here);
    groups.back().paths.push_back({ring_path(area.outer, from, ccw), true});
  }
  return true;
}

std::optional<std::vector<Group>> Planner::lines(double step, P u, bool left, bool zigzag,
                                                 bool ring_first, bool ccw) {
  std::vector<Group> groups;
  for (const Area& area : centres_) {
    if (!area.holes.empty()) {
      draft_.report().not_implemented(spec_.feature.name() + ": a region with an island");
      return std::nullopt;
    }
    const auto pieces = line_pieces(area, step, u, left, zigzag);
    if (!pieces) return std::nullopt;
    if (pieces->empty()) {
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
    if (!line_groups(area, *pieces, zigzag, ring_first, ccw, groups)) return std::nullopt;
  }
  return groups;
}

// ---- playing a plan ----------------------------------------------------------------------------

// The operation's retract strategy from the floor at `z`: back across the machined floor to
// where the last approach came down, and up the way it came (a helix about the same centre, a
// ramp along the same line), as rectangular pockets do. `here` becomes where the tool ends.
// False after reporting a retract that does not fit or cannot be made here.
bool leave_pocket(const GeneralPocketSpec& spec, Draft& draft, const Site& site,
                  const poly::Polygons& polygons, double z, P& here) {
  Report& report = draft.report();
  const Subject& strategy = spec.exit.strategy;
  const double clear = draft.options().clearance;
  const Areas& centres = spec.region.centres;
  const std::string what = strategy.name() + " as the retract from " + spec.feature.name();
  if (spec.exit.kind == Entry::Kind::Ramp && site.kind != Entry::Kind::Ramp)
    return report.not_implemented(what +
                                  " after an approach that is not a ramp (the ramp out "
                                  "follows the approach's ramp line)");
  const P from = site.kind == Entry::Kind::Ramp ? site.ramp_from : site.centre;
  if ((from - here).length() > kEps && !polygons.segment_inside(here, from, centres))
    return report.not_implemented(what + ": no straight way across the floor from " +
                                  at_text(here) + " back to where the approach came down, " +
                                  at_text(from));
  const Entry& exit = spec.exit;
  Vec3 ramp_dir{1, 0, 0};
  double length = 0;
  if (exit.kind == Entry::Kind::Ramp) {
    const P d = site.ramp_to - site.ramp_from;
    length = d.length();
    if (length > 0) ramp_dir = {d.x / length, d.y / length, 0};
    if (exit.width > 0) length = std::min(length, exit.width);
    if (length < 1e-3) return report.unfit(strategy, what + ": no room for a ramp");
  } else {
    const double room = poly::distance_to_boundary(centres, from) - region_margin(draft.options());
    if (exit.radius > room + kEps || exit.radius < 1e-3)
      return report.unfit(strategy, what + ": a helix of radius " + fmt(exit.radius) +
                                        " does not fit at " + at_text(from) + " (room " +
                                        fmt(std::max(0.0, room)) + ")");
  }
  if (entry_too_long(draft.options(), exit, length, clear - z)) return draft.limit_reached();
  draft.feed(at(from, z));
  leave(draft, exit, at(from, z), {1, 0, 0}, ramp_dir, length, spec.ccw, z, clear);
  const Vec3 end = draft.here();
  here = {end.x, end.y};
  return true;
}

// Down at a group's site to `z`: straight (one-way lines), or the approach at its site.
// False after the motion limit.
bool enter_site(const GeneralPocketSpec& spec, Draft& draft, const Site& site, double from_z,
                double z) {
  if (site.straight_down) {
    draft.feed(at(site.start, z));
    return true;
  }
  Entry entry = spec.entry;
  entry.kind = site.kind;
  entry.radius = site.helix;
  const P dir = site.ramp_to - site.ramp_from;
  const double length = dir.length();
  const Vec3 ramp_dir = length > 0 ? Vec3{dir.x / length, dir.y / length, 0} : Vec3{1, 0, 0};
  if (entry_too_long(draft.options(), entry, length, from_z - z)) return draft.limit_reached();
  enter(draft, entry, at(site.kind == Entry::Kind::Ramp ? site.ramp_from : site.centre, z),
        {1, 0, 0}, ramp_dir, length, spec.ccw, from_z, z);
  const P end = site.kind == Entry::Kind::Ramp ? site.ramp_from : site.centre;
  if ((site.start - end).length() > kEps) draft.feed(at(site.start, z));
  return true;
}

bool play(const GeneralPocketSpec& spec, Draft& draft, const std::vector<Group>& groups) {
  const FeatureOptions& options = draft.options();
  const poly::Polygons polygons(options.chord_tolerance);
  const double clear = options.clearance;
  const double retract = spec.retract_plane.value_or(clear);
  std::size_t count = 0;
  for (const Group& g : groups)
    for (const PlanePath& path : g.paths) count += path.points.size() + 8;
  if (static_cast<double>(count) * static_cast<double>(spec.levels.size()) >
      static_cast<double>(options.max_moves))
    return draft.limit_reached();
  std::vector<std::vector<std::vector<PlaneSpan>>> spans(groups.size());
  for (std::size_t gi = 0; gi < groups.size(); ++gi)
    for (const PlanePath& path : groups[gi].paths)
      spans[gi].push_back(spans_of(path, options.chord_tolerance));
  double from_z = clear;
  P here{};
  bool started = false;
  for (const double z : spec.levels) {
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      const Site& site = groups[gi].site;
      const P e = site.entry_point();
      if (!started) {
        draft.rapid(at(e, std::max(retract, clear)));
        if (retract > clear) draft.rapid(at(e, clear));
        started = true;
      } else if (gi == 0 && polygons.segment_inside(here, e, spec.region.centres)) {
        // Across the floor just machined, to where the next level starts.
        draft.feed(at(e, from_z));
      } else {
        // Up above the feature's top, across, and down at feed through what is machined.
        draft.rapid(at(here, clear));
        draft.rapid(at(e, clear));
        if (from_z < clear) draft.feed(at(e, from_z));
      }
      if (!enter_site(spec, draft, site, from_z, z)) return false;
      here = site.start;
      for (std::size_t pi = 0; pi < groups[gi].paths.size(); ++pi) {
        const PlanePath& path = groups[gi].paths[pi];
        if ((path.points.front() - here).length() > kEps) draft.feed(at(path.points.front(), z));
        emit_spans(draft, spans[gi][pi], z);
        here = path.points.back();
      }
      if (draft.too_many()) return draft.limit_reached();
    }
    from_z = z;
  }
  if (spec.exit.strategy && spec.exit.kind != Entry::Kind::Plunge &&
      !leave_pocket(spec, draft, groups.back().site, polygons, from_z, here))
    return false;
  draft.rapid(at(here, std::max(retract, clear)));
  return true;
}

}  // namespace

bool plan_general_pocket(const GeneralPocketSpec& spec, Draft& draft) {
  Planner planner(spec, draft);
  using Pattern = GeneralPocketSpec::Pattern;
  const auto groups = spec.pattern == Pattern::Rings
                          ? planner.rings(spec.stepover, spec.ccw, spec.walls_only)
                          : planner.lines(spec.stepover, spec.feed, spec.left, spec.zigzag,
                                          spec.pattern == Pattern::RingThenLines, spec.ccw);
  if (!groups) return false;
  if (groups->empty())
    return draft.report().bad(spec.feature, spec.feature.name() + ": nothing to machine");
  return play(spec, draft, *groups);
}

}  // namespace ncpost::stepnc::features
