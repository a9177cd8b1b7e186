#pragma once
// Pockets with general profiles: a CLOSED_POCKET bounded by a GENERAL_CLOSED_PROFILE (polyline,
// composite curve of lines and arcs) or an NGON_CLOSED_PROFILE, and an OPEN_POCKET whose
// open_boundary is a GENERAL_PROFILE (its walls). The reader turns the profile into the region
// the tool centre may use, built with polygon offsets (Clipper, polygons.hpp) always a little
// inside the exact one, and checks that the tool reaches all of the floor from it; the planner
// cuts rings or lines from that region, checks that they cover it, chooses where the tool goes
// down, and plays them level by level (docs/features.md, "General profiles").

#include <optional>
#include <vector>

#include "draft.hpp"
#include "polygons.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;
struct PocketBasics;

// The regions of a general pocket.
struct GeneralRegion {
  poly::Areas centres;  // where the tool centre may go
  poly::Areas source;   // what `centres` is shrunk from (by `base`)
  poly::Areas sharp;    // `source` without its corner fillets, of radius `rho`
  double rho = 0;
  double base = 0;
};

struct GeneralPocketSpec {
  GeneralRegion region;
  // Contour-parallel rings (the default), or parallel lines along `feed` followed or preceded
  // by the ring round each part of the region.
  enum class Pattern { Rings, LinesThenRing, RingThenLines } pattern = Pattern::Rings;
  bool zigzag = true;          // lines back and forth (else one way)
  bool left = true;            // lines follow each other to the left of `feed`
  poly::P feed{1, 0};          // unit direction of the lines
  bool walls_only = false;     // side milling: the wall ring alone
  bool ccw = true;             // the sense of the rings
  double stepover = 0;         // between rings or lines
  std::vector<double> levels;  // from the top (z = 0) down
  Entry entry;                 // down into the material
  Entry exit;                  // up out of it (Plunge: straight up at rapid)
  std::optional<double> retract_plane;
  Subject tool;
  double tool_radius = 0;
  Subject operation;
  Subject feature;
};

// Diagnostics (and Reader::read_depth's, read_tool's, read_operation's, read_closed_outline's):
// - STEPNC-101: a strategy other than contour-parallel, bidirectional, unidirectional,
//   bidirectional-contour or contour-bidirectional milling; a line strategy for side milling;
//   an approach or retract that is not a plunge strategy.
// - STEPNC-102: a corner or arc the tool does not fit (corner_checks); a tool that does not fit
//   the pocket, or leaves a part of its floor narrower than itself; one whose corner radius is
//   not the floor fillet; a cutting edge shorter than a level step; one pass asked beyond the
//   axial depth.
// - STEPNC-103: a polygon that crosses itself or has too many points; orthogonal_radius fillets
//   that do not fit a side; an outline that cannot be offset; a feed direction out of the
//   pocket's plane; an overlap outside [0, 1); allowance_bottom that leaves the whole depth;
//   more levels than the motion limit; an approach angle outside (0, 90).
// - STEPNC-016: a rotation_direction against the cutmode.
[[nodiscard]] bool read_general_pocket(Reader& reader, const PocketBasics& basics,
                                       GeneralPocketSpec& spec);
// An open pocket (read_general_pocket's diagnostics): beyond the straight line between the
// walls' ends is air, into which the tool may run by R + clearance; the line's continuation past
// them is the part's face. Diagnostics besides: STEPNC-103 walls that, with their open side,
// cross or enclose no area, or that close (no open side).
[[nodiscard]] bool read_open_pocket(Reader& reader, const PocketBasics& basics,
                                    GeneralPocketSpec& spec);

// Diagnostics:
// - STEPNC-101: a region whose offset encloses an island; rings or lines that leave floor uncut
//   (five attempts); a ramp retract after an approach that is not a ramp; no straight way back
//   across the floor to where the approach came down.
// - STEPNC-102: a helix or ramp (approach or retract) that does not fit where it goes down.
// - STEPNC-103: nothing to machine; more motions than the motion limit.
// - STEPNC-016: a tool that fills the pocket where it goes down (it enters along its axis).
// Should Clipper refuse an offset of the regions the reader built (their coordinates are
// bounded, so it should not), the planner returns false without a diagnostic, as the
// generator always has.
[[nodiscard]] bool plan_general_pocket(const GeneralPocketSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
