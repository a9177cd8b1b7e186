#pragma once
// ROUND_HOLE with the drilling-type operations: a canonical cycle (drill, peck, tap, bore, ream),
// or explicit motions where the operation asks for what no cycle expresses (feed or speed
// changing within the hole, a first peck unlike the others, a dwell between pecks, a retract at
// feed). Coordinates are the hole's: its axis is z, its top z = 0 (docs/features.md).

#include <optional>
#include <vector>

#include "draft.hpp"
#include "region.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;

// A ROUND_HOLE's change_in_diameter: its radius at the top and at the depth plane (both the
// diameter's when it has none). DIAMETER_TAPER gives the final diameter; ANGLE_TAPER the angle
// between wall and axis (positive: narrowing downwards).
struct Taper {
  double top = 0;
  double bottom = 0;
  Subject subject;  // the taper; empty: none
  [[nodiscard]] double smallest() const { return top < bottom ? top : bottom; }
};
// Diagnostics: STEPNC-103 a taper without a positive final diameter, an angle outside (-90, 90)
// or one that closes the hole above its depth.
[[nodiscard]] std::optional<Taper> read_taper(Reader& reader, const p21::Instance& hole,
                                              double diameter, double depth);

// A ROUND_HOLE milled rather than drilled (bottom-and-side or side milling): the circle of its
// diameter cleared as a region, helix down, full circles at each level. Diagnostics (and
// read_region's): STEPNC-101 a conical bottom (a spherical one is read_milled_sphere's);
// STEPNC-103 no diameter or bottom condition.
[[nodiscard]] bool read_milled_hole(Reader& reader, RegionSpec& spec);

// A tapered ROUND_HOLE milled, narrowing downwards: the cylinder of its narrowest diameter
// cleared as a region (`core`), then the cone of its wall in full circles, one per level, each
// at the cone's radius at its own height less the inset (the wall above a level is wider, so no
// circle reaches into it), the levels close enough that the steps they leave on the cone stay
// within FeatureOptions::profile_tolerance.
struct MilledTaperSpec {
  RegionSpec core;
  double top = 0;     // the wall's radius at the top
  double bottom = 0;  // at the depth plane
  double depth = 0;
  std::vector<double> levels;  // of the circles, from the top down
};
// Diagnostics (and read_region's, read_taper's): STEPNC-101 a taper that widens downwards (an
// undercut), a bottom other than flat or through; STEPNC-103 more circles than the motion
// limit.
[[nodiscard]] bool read_milled_taper(Reader& reader, MilledTaperSpec& spec);
// Diagnostics: plan_region's; STEPNC-103 more motions than the motion limit.
[[nodiscard]] bool plan_milled_taper(const MilledTaperSpec& spec, Draft& draft);

// A ROUND_HOLE with a SPHERICAL_HOLE_BOTTOM milled by bottom-and-side milling (a ball end mill,
// or a bull nose whose flat leaves at most FeatureOptions::profile_tolerance at the bottom's
// centre). The sphere of radius R has its lowest point on the depth plane; R is at least the
// hole's radius, so it meets the wall. The cylinder down to where the sphere begins (less
// allowance_bottom) is `core`, cleared as a region; below it the tool's corner circle (the
// ball's centre) keeps on the sphere offset inwards by allowance_bottom + corner radius and
// inside the wall offset by allowance_side + corner radius:
// - `levels`: clearing levels by the axial depth, each a disc of contour-parallel rings from
//   the axis out to the offset sphere at that height, entered by the core's approach (its helix
//   or ramp no larger than the disc, else a plunge along the axis);
// - `rings`: full circles from the top of the sphere down to the bottom, down the wall first
//   where the core stopped above the sphere, then along the sphere's meridian, close enough
//   (scallop_step) that the cusps they leave are at most the profile tolerance.
struct MilledSphereSpec {
  struct Circle {
    double radius = 0;  // of the tool's axis about the hole's
    double z = 0;       // of the tip
  };
  RegionSpec core;
  bool has_core = true;  // false: the sphere reaches the top (within allowance_bottom)
  std::vector<Circle> levels;
  std::vector<Circle> rings;
};
// Diagnostics (and read_region's, read_depth's, read_tool's):
// - STEPNC-101: side milling (the wall alone) of a hole with a spherical bottom.
// - STEPNC-102: a flat end mill (it cannot form the sphere); a tool whose radius is larger than
//   the sphere's less allowance_bottom (both named); a bull nose whose flat leaves more than
//   the profile tolerance at the bottom's centre; a tool wider than the hole.
// - STEPNC-103: a sphere without a radius, or narrower than the hole (it does not close the
//   bottom), or deeper than the hole; more circles than the motion limit.
[[nodiscard]] bool read_milled_sphere(Reader& reader, MilledSphereSpec& spec);
// Diagnostics: plan_region's; STEPNC-103 more motions than the motion limit.
[[nodiscard]] bool plan_milled_sphere(const MilledSphereSpec& spec, Draft& draft);
// Whether the workingstep's feature is a ROUND_HOLE with a SPHERICAL_HOLE_BOTTOM.
[[nodiscard]] bool spherical_bottom(Reader& reader);

// DRILLING_TYPE_STRATEGY: feed and speed as shares of the technology's near the top and near the
// bottom of the hole.
struct DrillingZones {
  double cut_start = 1, feed_start = 1, depth_start = 0;
  double cut_end = 1, feed_end = 1, depth_end = 0;
  [[nodiscard]] bool any() const {
    return (depth_start > 0 && (cut_start != 1 || feed_start != 1)) ||
           (depth_end > 0 && (cut_end != 1 || feed_end != 1));
  }
};

struct HoleSpec {
  Move::CycleKind cycle = Move::CycleKind::Drill;
  double retract_z = 0;  // the R plane, above the top
  double bottom_z = 0;   // where the tool's tip stops
  double feed = 0;       // mm/min
  double dwell = 0;      // seconds at the bottom
  // Peck drilling: each peck's depth, how far the drill backs off between pecks (0: out to the
  // R plane), a first peck of another depth, a dwell after each peck.
  double peck = 0;
  double peck_retract = 0;
  std::optional<double> first_peck;
  double peck_dwell = 0;
  // Rigid tapping: the thread's pitch from feed and speed, the speed in rpm, the tap's hand.
  double pitch = 0;
  double rpm = 0;
  bool left_hand = false;
  bool spindle_stop = false;  // boring: the spindle stops at the bottom
  DrillingZones zones;
  std::optional<double> feed_on_retract;  // a share of the feed; unset: out at rapid
  double spindle = 0;  // the technology's speed (ISO rev/s, signed; 0: unset), for the zones

  // Whether the hole needs explicit motions: what the cycle cannot say.
  [[nodiscard]] bool needs_motions() const {
    return zones.any() || first_peck || peck_dwell != 0 || feed_on_retract;
  }
};

// Where a drill's tip stops in `hole` (a ROUND_HOLE of `depth` whose bottom condition is
// `bottom`), and the check that its cutting edge reaches that deep; thread drilling shares it.
// A through hole: past the depth plane by the tool's point and FeatureOptions::through_clearance;
// a conical bottom: the point below the depth plane (a drill's point angle must be the cone's);
// a blind flat, flat-with-radius or spherical bottom: the tip on the depth plane.
// `pointed`: the tool drills with its point (drills; not reamers, boring bars or taps).
// Diagnostics: STEPNC-101 another bottom condition ("<what_prefix><hole> with <bottom>");
// STEPNC-102 a point angle that is not the cone's; STEPNC-016 a point that leaves a cone in a
// blind bottom another operation has to finish.
[[nodiscard]] std::optional<double> read_drill_bottom(Reader& reader, const p21::Instance& hole,
                                                      const p21::Instance& bottom, double depth,
                                                      const Tool& tool, bool pointed,
                                                      std::string_view what_prefix);
// Diagnostics: STEPNC-102 a cutting edge shorter than the depth the tip goes to.
[[nodiscard]] bool check_drill_edge(Reader& reader, const Tool& tool, double bottom_z,
                                    const p21::Instance& hole);

// Diagnostics (and Reader::read_depth's, read_tool's):
// - STEPNC-101: an operation that is not drilling-type, or one of them the generator does not
//   know; a bottom condition other than through, conical or blind;
//   a test cut or waiting position (boring, reaming); a drilling strategy or feed_on_retract
//   with a tap, reamer or boring cycle.
// - STEPNC-102: a tool larger than the hole (+ tolerance), or than a tapered hole's smallest
//   diameter (a drill makes a cylinder; a note says the taper is left to another operation); a
//   reamer or tap smaller than it
//   (- tolerance); a point angle that is not a conical bottom's; a cutting edge shorter than the
//   depth; a tap whose hand is not the spindle's direction.
// - STEPNC-103: no diameter or bottom condition; no feed rate; a cutting_depth outside the hole;
//   a retract plane not above the hole; a negative dwell; a strategy ratio that is not positive;
//   pecks that are not positive (or a negative retract distance); more pecks than the motion
//   limit; a tap without spindle speed.
// - STEPNC-016: a drill's point leaving a cone in a blind bottom.
[[nodiscard]] bool read_hole(Reader& reader, HoleSpec& spec);

// Diagnostics: STEPNC-103 more motions than the motion limit.
[[nodiscard]] bool plan_hole(const HoleSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
