#pragma once
// SLOT (ISO 14649-10): a profile swept along a course of travel, closed by its end types.
//
// Square-U and rounded-U slots along a straight path with radiused, flat or open ends are
// rounded rectangles (one radius per corner), cleared as regions (region.hpp). Every other
// combination the generator makes is one or more passes of a form tool along the course of
// travel: a cone of the vee's angle, a ball of the partial circle's radius (or smaller balls
// stepped across it within FeatureOptions::profile_tolerance), a ball or an end mill of the
// slot's width along a circle or up a woodruff end. docs/features.md gives the reading of the
// standard behind each choice.

#include <cstddef>
#include <optional>
#include <vector>

#include "draft.hpp"
#include "spec.hpp"

namespace ncpost::stepnc::features {

class Reader;
struct RegionSpec;

// A cone tool must have the vee's angle: at another angle it cuts the walls off by the depth
// times the difference (0.01° over 20 mm: 0.002 mm).
inline constexpr double kAngleMatch = 0.01;

// The course of travel in the feature's xy plane: a line from the placement's origin, or a
// circle (an arc of it) about the origin, starting on the x axis.
struct SlotPath {
  enum class Kind { Line, Arc, Circle } kind = Kind::Line;
  Vec3 dir{1, 0, 0};  // line: unit direction
  double length = 0;  // line: distance; arc, circle: arc length
  double radius = 0;  // arc, circle
  double sweep = 0;   // arc: signed angle (radians, counter-clockwise positive); circle: 2π
};

// A point of a general cross-section: u across the slot (to the left of the travel direction),
// z up, both in mm.
struct SectionPoint {
  double u = 0;
  double z = 0;
};

struct SlotSection {
  enum class Kind { SquareU, RoundedU, Vee, PartialCircular, General } kind = Kind::SquareU;
  double half = 0;                   // U profiles: half the width
  std::optional<Toleranced> fillet;  // square-U: the floor radius
  double angle = 0;                  // vee: the angle between its sides (radians)
  Toleranced radius{};               // vee: bottom radius; partial circle, rounded-U: radius
  double sweep = 0;                  // partial circle: its angle (radians)
  // General (a GENERAL_PROFILE): its curve as a polyline within FeatureOptions::chord_tolerance,
  // u increasing, in the curve's own coordinates (read_section_slot puts its lowest point on
  // the depth plane); the curve, and whether the section is symmetric about the course of travel.
  std::vector<SectionPoint> curve;
  Subject profile_curve;
  bool symmetric = false;
};

struct SlotEnd {
  enum class Kind { Radiused, Flat, Open, Woodruff, Loop } kind = Kind::Radiused;
  Subject subject;   // the end type
  double right = 0;  // flat: corner_radius1, on the right of the travel direction
  double left = 0;   // flat: corner_radius2
  Toleranced woodruff{};
};

// What every slot reader starts from.
struct SlotBasics {
  SlotPath path;
  SlotSection section;
  SlotEnd end[2];
  std::size_t end_count = 0;  // as the file gives them (one item stands for both ends)
  Subject travel;             // course_of_travel
  Subject swept;              // swept_shape
  // The course of travel's own placement in the feature's xy plane (identity when it has none):
  // the slot is read and planned in it, and its moves carried into the feature's frame.
  detail::Frame travel_frame;
  // A square-U or rounded-U slot along a line without woodruff ends: a region.
  [[nodiscard]] bool region() const;
};

// One pass along the course of travel: `offset` to its left and right (a closed ring about it
// when offset > 0) with the tool tip `depth` below the feature's top.
struct SlotPass {
  double offset = 0;
  double depth = 0;
};

// A slot made by a form tool along its course of travel.
struct FormSlotSpec {
  SlotPath path;
  SlotEnd end[2];
  std::vector<SlotPass> passes;  // the finishing passes, from the course of travel outwards
  double depth = 0;              // of the slot
  double tool_radius = 0;
  double ball_radius = 0;      // a ball end mill (0: another tool)
  double stepover = 0;         // stepped passes: their largest spacing on a level above the bottom
  bool ccw = true;             // rings counter-clockwise
  std::vector<double> levels;  // from the top (z = 0) down to the deepest pass
  Entry entry;                 // Plunge or Ramp: down into the material at a radiused end
  Entry exit;                  // Plunge or Ramp: up out of it
  std::optional<double> retract_plane;
  Subject tool;
  Subject feature;
};

// Diagnostics:
// - STEPNC-101: an operation other than bottom-and-side or side milling; a course of travel
//   placed out of the feature's xy plane; a placed swept shape; a path other than linear or
//   circular; a profile other than square-U (vertical walls, one floor radius), rounded-U,
//   symmetric vee or partial circle of at most 180 degrees; an end type the generator does not
//   know.
// - STEPNC-103: no course_of_travel or swept_shape; sizes that are not positive or beyond the
//   length limit; a sweep angle of 0 or a whole turn; a vee angle outside (0, 180) or no tilt;
//   a negative vee radius or corner radius; more than two end conditions; a loop end on an
//   open path, another end on a closed one, no end condition on an open one.
[[nodiscard]] bool read_slot_basics(Reader& reader, SlotBasics& basics);

// A straight square-U or rounded-U slot as a rounded rectangle: radiused ends are half circles
// about the ends of the course of travel, flat ends walls with their own corner radii, open ends
// let the tool run out R + clearance past them. Diagnostics: read_tool's, read_depth's and
// read_region's.
[[nodiscard]] bool read_slot_region(Reader& reader, const SlotBasics& basics, RegionSpec& spec);

// Every other slot: what its profile asks of the tool, and the passes that make it.
// Diagnostics (and read_depth's, read_tool's, read_operation's):
// - STEPNC-101: side milling (the walls are the form tool's); a strategy other than center
//   milling or contour-parallel; flat ends; open ends on an arc; woodruff ends on a vee, on a
//   curved path, shallower than the slot, or square-U ones with a woodruff keyseat mill;
//   stepped passes along a circle or with a woodruff end; a ramp shallower than a woodruff end
//   it comes down; an approach or retract that is not a plunge strategy.
// - STEPNC-102: a tool that is not a cone of the vee's angle (or does not cover its width, or
//   has not its tip radius, or whose edge does not reach its walls); one that is not a ball no
//   larger than a round profile; a tool not of a square-U's width or floor radius along a
//   circle; a square-U woodruff end; a ball larger than a woodruff end; a helix approach or
//   retract; a cutting edge shorter than a level step; one pass asked beyond the axial depth.
// - STEPNC-103: a partial circle that does not reach the top; an overlap outside [0, 1);
//   allowance_bottom that leaves the whole depth; more passes or levels than the motion limit;
//   an approach or retract angle outside (0, 90).
[[nodiscard]] bool read_form_slot(Reader& reader, const SlotBasics& basics, FormSlotSpec& spec);

// A GENERAL_PROFILE swept shape: its curve (POLYLINE, TRIMMED_CURVE, COMPOSITE_CURVE,
// B_SPLINE_CURVE_WITH_KNOTS, BEZIER_CURVE, QUASI_UNIFORM_CURVE; rational ones too) in the
// profile's xy plane, x across the slot to the left of the travel direction and y up, evaluated
// exactly (de Boor) into a polyline within FeatureOptions::chord_tolerance.
// Diagnostics: the curve reader's; STEPNC-103 a curve out of its xy plane, beyond the element
// limit, or without width; STEPNC-101 a curve that turns back across the slot (an undercut:
// not one depth at each point across it).
[[nodiscard]] bool read_general_section(Reader& reader, const p21::Instance& swept, SlotSection& s);

// A slot whose section is a general profile (a polyline, composite curve, B-spline or Bezier
// curve), made by parallel passes along a straight course of travel at offsets across the
// section, each pass's tip as low as the tool (its radius and corner radius, grown by the
// allowance) can go there without crossing the section: the passes are chosen so that what
// they leave on the section stays within FeatureOptions::profile_tolerance. A section symmetric
// about the course of travel is run in rings (half circles about radiused ends, which turn the
// section about the end of the course of travel); any other in straight passes between open
// ends, crossing over the section between them.
struct SectionSlotSpec {
  SlotPath path;
  SlotEnd end[2];
  // Rings: offsets >= 0 from the course of travel outwards (0: the course itself); straight
  // passes: signed offsets from right to left. depth: the tip below the top (> 0).
  std::vector<SlotPass> passes;
  // cross[k]: the height (z, <= 0 or above the top) at which the tool may cross between the
  // course of travel (rings) or pass k - 1 (straight passes) and pass k without touching the
  // section.
  std::vector<double> cross;
  // The passes run at the levels above the deepest, no further apart than the stepover.
  std::vector<std::size_t> rough;
  bool rings = false;
  bool ccw = true;
  double tool_radius = 0;
  std::vector<double> levels;  // from the top (z = 0) down to the deepest pass
  Entry entry;                 // Plunge or Ramp, into the material at a radiused end
  std::optional<double> retract_plane;
  Subject exit_strategy;  // a retract strategy other than along the axis (noted)
  Subject tool;
  Subject feature;
};

// A tool seen across a straight slot: its radius and corner radius, both grown by the allowance
// it leaves on the section (a ball: corner = radius).
struct SectionCutter {
  double radius = 0;
  double corner = 0;
  double allowance = 0;
};

// The lowest tip height (z) of `cutter` centred at offset `v` over a section whose lower side is
// `boundary` (u increasing, z <= 0, the top at z = 0 beyond its ends), without the tool grown by
// the allowance crossing it.
[[nodiscard]] double section_tip(const std::vector<SectionPoint>& boundary,
                                 const SectionCutter& cutter, double v);
// How far the point `p` of the section is from the tool grown by the allowance, its tip at `tip`
// over offset `v` (0 where it touches).
[[nodiscard]] double section_gap(SectionPoint p, const SectionCutter& cutter, double v, double tip);

// Diagnostics (and read_depth's, read_tool's, read_operation's, depth_levels'):
// - STEPNC-101: a path other than linear; ends other than radiused or open; a radiused end on a
//   section that is not symmetric about the course of travel; a strategy other than center
//   milling or contour-parallel; a helix approach.
// - STEPNC-102: a tool that is not a milling cutter with a flat, radiused or ball end; one that
//   cannot reach the section within the profile tolerance somewhere (it names where and by how
//   much: a concave radius smaller than its corner, a section narrower than the tool); one that
//   never gets below the top; a cutting edge shorter than a level step.
// - STEPNC-103: a curve whose ends do not reach the top once its lowest point is on the depth
//   plane; more passes or levels than the motion limit.
[[nodiscard]] bool read_section_slot(Reader& reader, const SlotBasics& basics,
                                     SectionSlotSpec& spec);
// Diagnostics: STEPNC-103 more motions than the motion limit; STEPNC-016 a plunge along the
// axis into the material at a radiused end when no approach is named.
[[nodiscard]] bool plan_section_slot(const SectionSlotSpec& spec, Draft& draft);

// Diagnostics: STEPNC-103 more motions than the motion limit; STEPNC-016 a plunge along the
// axis into the material at a radiused end when no approach is named, a retract ramp that the
// last pass of stepped passes does not need (it ends at the top of its wall).
[[nodiscard]] bool plan_form_slot(const FormSlotSpec& spec, Draft& draft);

}  // namespace ncpost::stepnc::features
