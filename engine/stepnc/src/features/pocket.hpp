#pragma once
// CLOSED_POCKET and OPEN_POCKET: what they have in common, read once (bottom-and-side or side
// milling, no bosses, vertical walls, a planar, through or radiused bottom, a boundary), and
// the kinds of closed pocket besides the general ones (general.hpp): a rectangular or circular
// profile, cleared as a region (region.hpp), and the round pocket whose floor is the half ball
// of its radius (docs/features.md).

#include <optional>
#include <vector>

#include "draft.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;
struct RegionSpec;

enum class PocketKind { Closed, Open };

// What the readers of every pocket start from.
struct PocketBasics {
  const p21::Instance* boundary = nullptr;  // feature_boundary (closed), open_boundary (open)
  const p21::Instance* bottom = nullptr;    // its bottom_condition
  bool through = false;
  bool radiused = false;    // a RADIUSED_POCKET_BOTTOM_CONDITION (closed pockets only)
  bool general = false;     // a closed pocket bounded by a general or n-gon profile
  bool walls_only = false;  // side milling: the wall ring alone
};

// Diagnostics:
// - STEPNC-101: an operation other than bottom-and-side or side milling; bosses (islands);
//   sloped walls; a bottom condition other than planar, through or (closed pockets) radiused.
// - STEPNC-103: no bottom_condition; no feature_boundary (closed) or open_boundary (open).
// - STEPNC-016: an open pocket's wall_boundary, which is for information only.
[[nodiscard]] bool read_pocket_basics(Reader& reader, PocketKind kind, PocketBasics& basics);

// A closed pocket with a RECTANGULAR_CLOSED_PROFILE or CIRCULAR_CLOSED_PROFILE: its region
// (orthogonal_radius at the corners, planar_radius on the floor). Diagnostics: read_closed_
// profile's and read_region's.
[[nodiscard]] bool read_pocket_region(Reader& reader, const PocketBasics& basics, RegionSpec& spec);

// A round pocket whose floor is the lower half of a ball of the pocket's radius, on its axis:
// a ball end mill of that radius straight down the axis, level by level.
struct RadiusedPocketSpec {
  Vec3 axis{};  // where the axis meets the top
  std::vector<double> levels;
  std::optional<double> retract_plane;
};

// Diagnostics (and read_depth's, read_tool's, read_closed_profile's):
// - STEPNC-101: a boundary that is not a circle; another sphere (3D surface finishing).
// - STEPNC-102: a tool that is not a ball end mill of that radius; an allowance_side it cannot
//   leave; an approach other than along the axis; a cutting edge shorter than a level step.
// - STEPNC-103: no centre or radius of the sphere; a lowest point off the depth plane;
//   allowance_bottom that leaves the whole depth; more levels than the motion limit.
[[nodiscard]] bool read_radiused_pocket(Reader& reader, const PocketBasics& basics,
                                        RadiusedPocketSpec& spec);
[[nodiscard]] bool plan_radiused_pocket(const RadiusedPocketSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
