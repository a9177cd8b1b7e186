// How the tool goes down into the material and comes back up (motion.hpp).

#include "motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

double helix_rise_per_turn(const Entry& e) {
  return 2 * std::numbers::pi * e.radius * std::tan(e.angle);
}

}  // namespace

void enter(Draft& draft, const Entry& entry, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z) {
  switch (entry.kind) {
    case Entry::Kind::Plunge:
      draft.feed({p0.x, p0.y, to_z});
      return;
    case Entry::Kind::Helix: {
      // Whole turns about p0, so the helix ends where it began; its descent is at most `angle`.
      const double per_turn = helix_rise_per_turn(entry);
      const int turns = std::max(1, static_cast<int>(std::ceil((from_z - to_z) / per_turn - 1e-9)));
      const Vec3 start = p0 + x * entry.radius + Vec3{0, 0, to_z - p0.z};
      draft.arc(start, {p0.x, p0.y, to_z}, ccw ? turns : -turns);
      draft.feed({p0.x, p0.y, to_z});
      return;
    }
    case Entry::Kind::Ramp: {
      const double drop = ramp_length * std::tan(entry.angle);
      double z = from_z;
      bool out = true;
      Vec3 here{p0.x, p0.y, from_z};
      p0.z = from_z;
      while (z > to_z + kEps) {
        const double share = std::min(1.0, (z - to_z) / drop);
        z = std::max(to_z, z - drop);
        const Vec3 target =
            out ? p0 + ramp_dir * (ramp_length * share) : here - ramp_dir * (ramp_length * share);
        here = {target.x, target.y, z};
        draft.feed(here);
        out = !out;
        if (draft.too_many()) return;
      }
      draft.feed({p0.x, p0.y, to_z});  // back over the last leg at depth
      return;
    }
  }
}

void leave(Draft& draft, const Entry& exit, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z) {
  switch (exit.kind) {
    case Entry::Kind::Plunge:
      draft.feed({p0.x, p0.y, to_z});
      return;
    case Entry::Kind::Helix: {
      // Out to the helix and whole turns up about p0 (the approach's helix, run backwards).
      const double per_turn = helix_rise_per_turn(exit);
      const int turns = std::max(1, static_cast<int>(std::ceil((to_z - from_z) / per_turn - 1e-9)));
      const Vec3 start{p0.x + x.x * exit.radius, p0.y + x.y * exit.radius, from_z};
      draft.feed(start);
      draft.arc({start.x, start.y, to_z}, {p0.x, p0.y, to_z}, ccw ? turns : -turns);
      return;
    }
    case Entry::Kind::Ramp: {
      // Back and forth along the ramp line, rising by at most the angle.
      const double rise = ramp_length * std::tan(exit.angle);
      double z = from_z;
      bool out = true;
      Vec3 here{p0.x, p0.y, from_z};
      while (z < to_z - kEps) {
        const double share = std::min(1.0, (to_z - z) / rise);
        z = std::min(to_z, z + rise);
        const Vec3 target =
            out ? here + ramp_dir * (ramp_length * share) : here - ramp_dir * (ramp_length * share);
        here = {target.x, target.y, z};
        draft.feed(here);
        out = !out;
        if (draft.too_many()) return;
      }
      return;
    }
  }
}

bool entry_too_long(const FeatureOptions& options, const Entry& entry, double ramp_length,
                    double drop) {
  const auto limit = static_cast<double>(options.max_moves);
  if (entry.kind == Entry::Kind::Helix) return drop / helix_rise_per_turn(entry) > limit;
  if (entry.kind == Entry::Kind::Ramp) return drop / (ramp_length * std::tan(entry.angle)) > limit;
  return false;
}

}  // namespace ncpost::stepnc::features
