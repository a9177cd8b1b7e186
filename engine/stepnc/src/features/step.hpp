#pragma once
// STEP (ISO 14649-10): a floor at the depth plane between the step's open boundary and its wall,
// cut by passes parallel to the wall that run out of the part past both ends of the open
// boundary (docs/features.md). The schema gives a step no width attribute; it has two
// boundaries:
// - open_boundary, a LINEAR_PATH: the edge where the step is open (the part ends there), from
//   its placement (the feature's origin when unset) along its direction for its distance;
// - wall_boundary, a VEE_PROFILE: the wall's profile; its placement's origin is the vertex of
//   the vee (ISO 10303-214: the profile's placement lies at the connection of its two sides),
//   the foot of the wall. Its first side is the floor (tilt_angle 0: along the profile's x
//   axis), profile_angle the angle from the floor up to the wall, profile_radius the fillet
//   between them.
// The width is the distance between the two.

#include <optional>
#include <vector>

#include "draft.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;

struct StepSpec {
  Vec3 origin{};            // where the open boundary starts
  Vec3 along{1, 0, 0};      // unit direction of the open boundary
  double length = 0;        // of the open boundary
  double width = 0;         // from the open boundary to the foot of the wall: > 0 on the left of
                            // `along`, < 0 on its right
  bool walls_only = false;  // side milling: the pass along the wall alone
  bool one_way = true;      // each pass in the same direction (else back and forth)
  bool forward = true;      // passes along +`along` (the first one, when back and forth)
  double tool_radius = 0;
  double allowance_side = 0;
  double overlap = 0;   // the share of the diameter the first pass reaches past the open boundary
  double stepover = 0;  // between passes
  std::vector<double> levels;           // from the top (z = 0) down
  std::optional<double> retract_plane;  // above the top; else FeatureOptions::clearance
};

// Diagnostics (and Reader::read_depth's, read_tool's, read_operation's):
// - STEPNC-101: an operation other than bottom-and-side or side milling; bosses; an open
//   boundary placed out of the top plane; a tilted wall or one not at 90 degrees to the floor;
//   a strategy other than bidirectional, unidirectional or contour-parallel milling; a feed
//   direction across the wall; an approach or retract that is not a plunge strategy.
// - STEPNC-102: a tool whose corner radius is not the wall's fillet (within its tolerance and
//   the allowance); a cutting edge shorter than a level step; one pass asked beyond the axial
//   depth.
// - STEPNC-103: no open boundary, or one without a positive distance and a direction, beyond the
//   length limit or out of the top plane; no width (no wall_boundary, or no placement of its
//   vee); a wall's foot neither on the floor nor at the top; a width of 0 or beyond the length
//   limit; a wall without profile_angle and tilt_angle; an overlap outside [0, 1);
//   allowance_bottom that leaves the whole depth; more levels than the motion limit.
// - STEPNC-016: a stepover_direction (the passes go from the open boundary to the wall); an
//   approach or retract other than along the tool axis (the passes start and end in the air).
[[nodiscard]] bool read_step(Reader& reader, StepSpec& spec);

// Diagnostics: STEPNC-103 more passes than the motion limit.
[[nodiscard]] bool plan_step(const StepSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
