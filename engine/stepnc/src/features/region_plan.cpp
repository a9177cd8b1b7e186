// Clearing a rounded-rectangle or circular region: the planner (region.hpp).

#include <algorithm>
#include <cmath>

#include "motion.hpp"
#include "region.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;
constexpr double kTiny = 1e-9;

using Pattern = RegionSpec::Pattern;

// The rings at height z in the feature's coordinates, from the innermost start (where the tool
// is), each ring entered from the previous one by a straight feed inside the region.
void play_rings(Draft& draft, const Rings& rings, const detail::Frame& frame, bool ccw, double z) {
  if (rings.line_length > kTiny) {
    const Vec3 end = rings.start + rings.axis * rings.line_length;
    draft.feed(frame.point({end.x, end.y, z}));
  }
  for (const Loop& loop : rings.loops) play_loop(draft, loop, frame, ccw, z);
}

// The paths of every level: the rings, or the lines (whose entry is at the centre) and the
// outermost ring of the combined strategies. False after the motion limit.
bool paths(const RegionSpec& spec, double room, Draft& draft, Rings& rings,
           std::vector<std::pair<Vec3, Vec3>>& lines, Pattern& pattern) {
  const Shape& shape = spec.shape;
  const std::size_t max_moves = draft.options().max_moves;
  // Counted before anything is built: a hostile stepover must not allocate its way out.
  if (room / spec.stepover > static_cast<double>(max_moves)) return draft.limit_reached();
  pattern = spec.pattern;
  if (pattern == Pattern::Rings) {
    rings = contour_rings(shape, spec.inset, spec.stepover);
    if (spec.walls_only && !spec.centre_only) {
      // The wall ring alone, entered from the centre across the pocket the bottom operation
      // cleared (or, if it did not, by a cut no deeper than the level).
      rings.line_length = 0;
      if (rings.loops.size() > 1) rings.loops.erase(rings.loops.begin(), rings.loops.end() - 1);
    }
  } else {
    if (2 * shape.inradius() / spec.stepover > static_cast<double>(max_moves))
      return draft.limit_reached();
    lines = raster(shape, spec.inset, spec.stepover, spec.along_x);
    if (!spec.lines_up) std::reverse(lines.begin(), lines.end());
    rings.start = {0, 0, 0};
    // One-way lines have no move along the wall between their ends, which leaves a cusp there,
    // and zigzag lines join their ends by chords, which cut across rounded corners (and
    // circles) of the region: the wall ring clears both, as in the combined strategy.
    bool rounded = shape.kind == Shape::Kind::Circle;
    for (int k = 0; k < 4; ++k) rounded = rounded || shape.corner_at(k) > spec.inset + kEps;
    if (pattern == Pattern::Lines && (!spec.zigzag || rounded)) pattern = Pattern::LinesThenRing;
    if (pattern != Pattern::Lines) {
      const Rings outer = contour_rings(shape, spec.inset, spec.stepover);
      if (!outer.loops.empty()) rings.loops.push_back(outer.loops.back());
    }
  }
  if ((rings.loops.size() + lines.size()) * spec.levels.size() > max_moves)
    return draft.limit_reached();
  return true;
}

// Where the approach and the retract go: a helix about the start, or a ramp along the innermost
// path, as the room allows. False after reporting one that does not fit.
bool fit_entries(const RegionSpec& spec, double room, const Rings& rings, Draft& draft,
                 Entry& entry, double& ramp_length, double& exit_length) {
  Report& report = draft.report();
  const auto tool = [&] { return spec.tool.name(); };
  const auto f = [&] { return spec.feature.name(); };
  const Subject& approach = spec.entry.strategy;
  ramp_length = std::max(rings.line_length, room);
  if (entry.kind == Entry::Kind::Helix) {
    if (entry.radius > room + kEps) {
      if (entry.explicit_entry)
        return report.unfit(approach, approach.name() + " radius " + fmt(entry.radius) +
                                          " leaves no room for " + tool() + " in " + f() +
                                          " (at most " + fmt(room) + ")");
      entry.radius = room;
    }
    if (entry.radius < 1e-3) {
      if (entry.explicit_entry)
        return report.unfit(
            approach, approach.name() + ": " + tool() + " fills " + f() + ", no room for a helix");
      entry.kind = Entry::Kind::Plunge;
      report.note(spec.feature, tool() + " fills " + f() +
                                    " across; it enters along its axis, as there is no room for "
                                    "a helix");
    }
  } else if (entry.kind == Entry::Kind::Ramp) {
    if (entry.width > 0) ramp_length = std::min(ramp_length, entry.width);
    if (ramp_length < 1e-3)
      return report.unfit(approach,
                          approach.name() + ": no room for a ramp of " + tool() + " in " + f());
  }
  // The retract needs the same room as an approach of its kind.
  const Entry& exit = spec.exit;
  const Subject& retract = exit.strategy;
  exit_length = std::max(rings.line_length, room);
  if (exit.kind == Entry::Kind::Helix && (exit.radius > room + kEps || exit.radius < 1e-3))
    return report.unfit(retract, retract.name() + " radius " + fmt(exit.radius) + " does not fit " +
                                     tool() + " in " + f() + " (room " + fmt(room) + ")");
  if (exit.kind == Entry::Kind::Ramp) {
    if (exit.width > 0) exit_length = std::min(exit_length, exit.width);
    if (exit_length < 1e-3)
      return report.unfit(retract,
                          retract.name() + ": no room for a ramp of " + tool() + " in " + f());
  }
  return true;
}

// The lines of one level (and the wall ring after them), from where the entry left the tool.
void play_lines(Draft& draft, const RegionSpec& spec, Pattern pattern, const Rings& rings,
                const std::vector<std::pair<Vec3, Vec3>>& lines, bool ccw, double zz) {
  const detail::Frame& frame = spec.shape.frame;
  const auto at = [&](Vec3 p) { return frame.point({p.x, p.y, zz}); };
  // Back above the feature's top: between two lines the material near the wall is not yet cut
  // at every height, so a rapid lower down could run into it.
  const double lift = draft.options().clearance;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const bool reverse = spec.zigzag && k % 2 == 1;
    const Vec3 a = at(reverse ? lines[k].second : lines[k].first);
    const Vec3 b = at(reverse ? lines[k].first : lines[k].second);
    if (!spec.zigzag && k > 0) {
      // One way only: up, back at rapid, down at feed.
      const Vec3 here = draft.here();
      draft.rapid({here.x, here.y, lift});
      draft.rapid({a.x, a.y, lift});
    }
    draft.feed(a);
    draft.feed(b);
  }
  if (pattern == Pattern::LinesThenRing) {
    Rings ring = rings;
    ring.line_length = 0;
    play_rings(draft, ring, frame, ccw, zz);
  }
}

}  // namespace

bool plan_region(const RegionSpec& spec, Draft& draft) {
  const Shape& shape = spec.shape;
  const FeatureOptions& options = draft.options();
  const double room = std::max(0.0, shape.inradius() - spec.inset);
  Rings rings;
  std::vector<std::pair<Vec3, Vec3>> lines;
  Pattern pattern = spec.pattern;
  if (!paths(spec, room, draft, rings, lines, pattern)) return false;
  Entry entry = spec.entry;
  double ramp_length = 0;
  double exit_length = 0;
  if (!fit_entries(spec, room, rings, draft, entry, ramp_length, exit_length)) return false;
  const Entry& exit = spec.exit;
  const bool ccw = spec.ccw;
  const double clear = options.clearance;
  const double retract = spec.retract_plane.value_or(clear);
  if (entry_too_long(options, entry, ramp_length, clear + spec.finish) ||
      entry_too_long(options, exit, exit_length, clear + spec.finish))
    return draft.limit_reached();
  const Vec3 p0f = shape.frame.point(rings.start);
  const Vec3 x_axis = shape.frame.x;
  const Vec3 ramp_dir = shape.frame.direction(rings.axis);
  const Vec3 entry_start = entry.kind == Entry::Kind::Helix ? p0f + x_axis * entry.radius : p0f;
  draft.rapid({entry_start.x, entry_start.y, std::max(retract, clear)});
  if (retract > clear) draft.rapid({entry_start.x, entry_start.y, clear});
  double from_z = clear;
  for (const double zz : spec.levels) {
    if (from_z < clear) draft.feed({entry_start.x, entry_start.y, from_z});
    enter(draft, entry, p0f, x_axis, ramp_dir, ramp_length, ccw, from_z, zz);
    if (pattern == Pattern::Rings || pattern == Pattern::RingThenLines)
      play_rings(draft, rings, shape.frame, ccw, zz);
    if (pattern != Pattern::Rings) play_lines(draft, spec, pattern, rings, lines, ccw, zz);
    if (draft.too_many()) return draft.limit_reached();
    from_z = zz;
  }
  if (exit.kind != Entry::Kind::Plunge) {
    // Back across the cleared floor to where the approach came down, and up the same way.
    draft.feed({p0f.x, p0f.y, from_z});
    leave(draft, exit, p0f, x_axis, ramp_dir, exit_length, ccw, from_z, clear);
  }
  const Vec3 end = draft.here();
  if (end.z < std::max(retract, clear) - kEps)
    draft.rapid({end.x, end.y, std::max(retract, clear)});
  return true;
}

}  // namespace ncpost::stepnc::features
