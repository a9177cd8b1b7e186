// A ROUND_HOLE with a SPHERICAL_HOLE_BOTTOM milled: the planner (holes.hpp). The cylinder as a
// region; then, from its floor down, a disc of rings at each clearing level (entered by the
// approach about the axis), and last the full circles along the sphere from its top down, each
// reached from the one above by a short feed inside the sphere.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "holes.hpp"
#include "motion.hpp"

namespace ncpost::stepnc::features {

bool plan_milled_sphere(const MilledSphereSpec& spec, Draft& draft) {
  const RegionSpec& core = spec.core;
  if (spec.has_core && !plan_region(core, draft)) return false;
  const double clear = draft.options().clearance;
  const double retract = std::max(core.retract_plane.value_or(clear), clear);
  const Vec3 axis{0, 0, 0};
  const Vec3 x{1, 0, 0};
  const int turn = core.ccw ? 1 : -1;
  const auto circle = [&](double radius, double z) {
    if (radius < 1e-6) return;
    const Vec3 here = draft.here();
    if (std::abs(here.x - radius) + std::abs(here.y) + std::abs(here.z - z) > 1e-9)
      draft.feed({radius, 0, z});
    draft.arc({radius, 0, z}, {0, 0, z}, turn);
  };
  draft.rapid({0, 0, retract});
  double from = clear;
  if (spec.has_core) {
    // Down the axis through the cleared cylinder to its floor.
    from = core.levels.back();
    draft.rapid({0, 0, clear});
    draft.feed({0, 0, from});
  }
  for (const MilledSphereSpec::Circle& level : spec.levels) {
    // Down by the approach about the axis, no wider than the disc; then the rings outwards.
    Entry entry = core.entry;
    double ramp = level.radius;
    if (entry.kind == Entry::Kind::Helix) entry.radius = std::min(entry.radius, level.radius);
    if (entry.kind == Entry::Kind::Ramp && entry.width > 0) ramp = std::min(ramp, entry.width);
    if ((entry.kind == Entry::Kind::Helix && entry.radius < 1e-3) ||
        (entry.kind == Entry::Kind::Ramp && ramp < 1e-3))
      entry.kind = Entry::Kind::Plunge;
    if (entry_too_long(draft.options(), entry, ramp, from - level.z)) return draft.limit_reached();
    if (entry.kind == Entry::Kind::Helix) draft.feed({entry.radius, 0, from});
    enter(draft, entry, axis, x, x, ramp, core.ccw, from, level.z);
    const auto n = static_cast<std::size_t>(std::ceil(level.radius / core.stepover - 1e-9));
    for (std::size_t k = 1; k <= n; ++k)
      circle(level.radius * static_cast<double>(k) / static_cast<double>(n), level.z);
    draft.feed({0, 0, level.z});
    from = level.z;
    if (draft.too_many()) return draft.limit_reached();
  }
  if (!spec.rings.empty()) {
    // Each circle from the one above: in to its radius at the height above, a helix down to
    // it (no steeper than the approach), the circle.
    const Entry& entry = core.entry;
    const double slope = entry.kind == Entry::Kind::Plunge ? 0 : std::tan(entry.angle);
    // The tool is on the axis at the last level (or above the hole): the first circle above it
    // is reached up the cleared axis, one below it like the others, from that height.
    const MilledSphereSpec::Circle start{0, draft.here().z};
    const MilledSphereSpec::Circle* above = nullptr;
    if (spec.rings.front().z >= start.z)
      draft.feed({0, 0, spec.rings.front().z});
    else
      above = &start;
    for (const MilledSphereSpec::Circle& ring : spec.rings) {
      if (above != nullptr) {
        const double drop = above->z - ring.z;
        if (ring.radius < 1e-6) {
          draft.feed({0, 0, ring.z});  // along the sphere, from the circle just above
        } else {
          if (std::abs(ring.radius - above->radius) > 1e-9) draft.feed({ring.radius, 0, above->z});
          const double turn_drop = 2 * std::numbers::pi * ring.radius * slope;
          const double turns = slope > 0 ? std::ceil(drop / turn_drop - 1e-9) : 1;
          if (turns > static_cast<double>(draft.options().max_moves)) return draft.limit_reached();
          const int n = std::max(1, static_cast<int>(turns));
          draft.arc({ring.radius, 0, ring.z}, {0, 0, ring.z}, core.ccw ? n : -n);
        }
      }
      circle(ring.radius, ring.z);
      above = &ring;
      if (draft.too_many()) return draft.limit_reached();
    }
    draft.feed({0, 0, draft.here().z});
  }
  draft.rapid({0, 0, retract});
  return true;
}

}  // namespace ncpost::stepnc::features
