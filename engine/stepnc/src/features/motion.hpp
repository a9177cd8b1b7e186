#pragma once
// What the 2.5D milling planners share: how the tool goes down into the material at a
// pattern's start and comes back up, as its Entry (spec.hpp) says.

#include "draft.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

// Down from `from_z` to `to_z` at p0. `x` is the profile's x axis: the helix starts at
// p0 + radius · x, where the caller put the tool; a ramp runs back and forth along `ramp_dir`
// for `ramp_length`.
void enter(Draft& draft, const Entry& entry, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);
// The mirror of `enter`: up from `from_z` to `to_z`, the tool being at p0 (a helix first feeds
// out to p0 + radius · x).
void leave(Draft& draft, const Entry& exit, Vec3 p0, Vec3 x, Vec3 ramp_dir, double ramp_length,
           bool ccw, double from_z, double to_z);
// A helix over `drop` needs more turns, or a ramp more legs, than the motion limit allows.
[[nodiscard]] bool entry_too_long(const FeatureOptions& options, const Entry& entry,
                                  double ramp_length, double drop);

}  // namespace ncpost::stepnc::features
