#pragma once
// Clearing a region whose outline is a rounded rectangle (one radius per corner) or a circle:
// closed pockets with a rectangular or circular profile, and square-U or rounded-U slots along
// a straight course of travel (their ends radiused, flat or open). Contour-parallel rings from
// the centre outwards, or parallel lines with the wall ring after or before them, level by
// level, entered by the approach strategy (docs/features.md).

#include <optional>
#include <vector>

#include "draft.hpp"
#include "shapes.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;

// What a pocket-like feature gives the reader of its region.
struct Region {
  Shape shape;
  bool through = false;
  std::optional<Toleranced> fillet;  // floor radius
  // Corners that lie outside the material (open slot ends), or that the caller has checked
  // itself, need no corner check here.
  bool corners_in_material = true;
  // Only the centre line may be cut (center milling): the tool must fill the width.
  bool centre_only = false;
  // Side milling: only the wall ring at each level (the inside is the bottom operation's).
  bool walls_only = false;
};

struct RegionSpec {
  Shape shape;
  bool centre_only = false;
  bool walls_only = false;
  // Contour-parallel rings (the default), or parallel lines, with a contour ring before or
  // after them for the combined strategies.
  enum class Pattern { Rings, Lines, LinesThenRing, RingThenLines } pattern = Pattern::Rings;
  bool zigzag = true;          // lines back and forth (else one way)
  bool along_x = true;         // lines along the profile's x axis (else y)
  bool lines_up = true;        // lines from -y (-x) to +y (+x)
  bool ccw = true;             // the sense of the rings
  double inset = 0;            // of the outermost ring from the wall: tool radius + allowance_side
  double stepover = 0;         // between rings or lines
  double finish = 0;           // the depth of the last level
  std::vector<double> levels;  // from the top (z = 0) down
  Entry entry;                 // down into the material
  Entry exit;                  // up out of it (Plunge: straight up at rapid)
  std::optional<double> retract_plane;
  Subject tool;
  Subject feature;
};

// Diagnostics (and Reader::read_depth's, read_tool's, read_operation's):
// - STEPNC-101: a strategy other than contour-parallel, bidirectional, unidirectional,
//   bidirectional-contour or contour-bidirectional milling (center milling where only a centre
//   pass can cut); a feed direction oblique to the profile's sides; a line strategy for side
//   milling; an approach or retract that is not a plunge strategy.
// - STEPNC-102: a tool whose corner radius is not the floor fillet; a tool (+ allowance)
//   larger than a corner radius or than the region; one that does not fill the width where only
//   a centre pass can cut; a cutting edge shorter than a level step; one pass asked beyond the
//   axial depth.
// - STEPNC-103: an overlap outside [0, 1); allowance_bottom that leaves the whole depth; more
//   levels than the motion limit; an approach or retract angle outside (0, 90).
// - STEPNC-016: a rotation_direction against the cutmode.
[[nodiscard]] bool read_region(Reader& reader, const Region& region, RegionSpec& spec);
// The same with the depth, tool and operation read already (by a slot's reader).
[[nodiscard]] bool read_region(Reader& reader, const Region& region, double depth, const Tool& tool,
                               const Operation& operation, RegionSpec& spec);

// Diagnostics:
// - STEPNC-102: a helix or ramp (approach or retract) without room in the region.
// - STEPNC-103: more motions than the motion limit.
// - STEPNC-016: a tool that fills the region (it enters along its axis, not by the default helix).
[[nodiscard]] bool plan_region(const RegionSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
