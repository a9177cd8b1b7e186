#pragma once
// The features whose walls are not vertical or whose floor is not one plane (slots of any
// profile, along lines and circles, with woodruff ends; steps; threads), as the verifier sees
// them: a cross section swept along a spine. At every height the cavity is the set of points
// within the section's half width of the spine, so the distance from a point to the cavity is
// the distance, in the plane across the spine, from (distance to the spine, height) to the
// section; a woodruff end is the section turned about an axis across the slot. Deliberately
// plain geometry, read from the feature by the verifier itself (model.cpp), sharing nothing
// with the generator: see docs/verify.md.

#include <limits>
#include <optional>
#include <vector>

#include "model.hpp"
#include "region.hpp"

namespace ncpost::verify::detail {

class Cavity {
 public:
  enum class Spine { Segment, Arc, Circle, Point, Line };

  // Builders of the section (u across the spine, z up; the top at z = 0). False when the
  // profile does not close (the caller says why).
  void square_u(double half, double depth, double fillet);
  void rounded_u(double radius, double depth);
  bool partial_circle(double radius, double sweep, double depth);
  void vee(double angle, double radius, double depth);
  // A general section: its lower side, u increasing (parts above the top are cut off there).
  // Symmetric, it is measured from the spine as the others; otherwise u is signed (positive to
  // the left of a segment spine) and the spine's ends must be open. The tool is checked on both
  // sides of its axis: the section may rise again towards the spine.
  void general(const std::vector<Vec2>& lower, bool symmetric);
  [[nodiscard]] bool signed_across() const { return across_signed_; }
  // A step's section, u positive into its wall (whose foot is at u = 0), the floor reaching
  // far onto the open side.
  void step(double angle, double radius, double depth);
  // A thread in its hole: radius `major` down to `length`, then the hole's radius down to
  // `depth` (through: far below).
  void thread(double major, double length, double hole, double depth, bool through);
  // A tapered ROUND_HOLE: radius `top` at the top to `bottom` at the depth plane (a cone), then
  // its bottom: flat, a cone of `cone` below the plane, or through (far below).
  void taper(double top, double bottom, double depth, double cone, bool through);
  // A ROUND_HOLE of radius `radius` with a SPHERICAL_HOLE_BOTTOM of radius `sphere` (at least
  // the hole's), its lowest point at `depth`: the wall down to where the sphere meets it, then
  // the sphere.
  void spherical_hole(double radius, double sphere, double depth);

  // The spine in the feature's plane.
  void segment(Vec2 from, Vec2 to, bool open0, bool open1, double woodruff0, double woodruff1);
  void arc(Vec2 centre, double radius, double start, double sweep);
  void circle(Vec2 centre, double radius);
  void point(Vec2 centre);
  // A step: the foot of the wall from `foot` along `along` for `length`, the normal into the
  // wall, the floor `width` wide on the other side.
  void line(Vec2 foot, Vec2 along, Vec2 into_wall, double length, double width);

  // Distance from the spine (signed for a step: positive into the wall).
  [[nodiscard]] double u(Vec2 p) const;
  // Signed distance of a point to the cavity, positive inside; exact outside it.
  [[nodiscard]] double signed_distance(Vec3 p) const;
  // Whether a tool at p (its disc of `radius` about p) may reach a woodruff end, where the
  // cavity is not the same at every distance from the spine.
  [[nodiscard]] bool near_woodruff(Vec2 p, double radius) const;
  // The lowest point of the cavity over p (the top, 0, where there is material up to it).
  [[nodiscard]] double bottom(Vec2 p) const;
  // Whether p is part of the feature's floor (coverage counts it), and a signed distance to
  // that floor's outline in plan (positive inside), for "the tool is over the feature".
  [[nodiscard]] bool on_floor(Vec2 p) const;
  [[nodiscard]] double floor_distance(Vec2 p) const;
  [[nodiscard]] Vec2 min() const;
  [[nodiscard]] Vec2 max() const;
  [[nodiscard]] double floor() const { return floor_; }

  // How far a tool with tip at p and the given outline (ToolShape::outline) reaches into the
  // material or into the allowance (> 0: a gouge of that much), and where (the worst point).
  // For a ball the sphere's part near a woodruff end is its centre's distance to the cavity.
  [[nodiscard]] double violation(Vec3 q, const ToolShape& tool, const std::vector<Vec2>& outline,
                                 double allowance, Vec3* where) const;
  // The outline passed to violation() has changed (a new tool).
  void forget() const { cached_outline_ = nullptr; }

 private:
  [[nodiscard]] double section_floor(double u) const;  // lowest z of the section at u
  // Signed distance to the section, positive inside. Every section is bounded by its lower side
  // below and the top (z = 0) above, so inside is "between the two" (the region's polygon
  // would be slower for the same answer).
  [[nodiscard]] double section_distance(Vec2 p) const;
  [[nodiscard]] double general_distance(Vec2 p) const;  // unsigned, general sections
  // section_distance, but within `allowance` of the top with the walls run on above it (the
  // top is no wall).
  [[nodiscard]] double wall_distance(Vec2 p, double allowance) const;
  [[nodiscard]] double woodruff_distance(Vec3 p, int end, double s, double t) const;

  // The section with its walls run on far above the top: what is added lies above the top (air)
  // even turned about a woodruff axis (which is above the top), so the distance of a ball's
  // centre to it is how far the ball is inside, the top not counting as a wall.
  [[nodiscard]] double open_distance(Vec3 p) const;
  void build_open();

  Region section_;
  Region raised_;
  std::vector<Vec2> lower_;  // the section's lower boundary, by increasing u
  double floor_ = 0;
  double top_ = 0;          // half width at the top (slots), floor width (steps)
  double lo_ = 0, hi_ = 0;  // the section's extent across (general sections; else ±top_)
  bool signed_ = false;
  bool across_signed_ = false;  // an asymmetric general section along a segment
  bool two_sided_ = false;      // a general section: the tool's near side may touch it too
  // The last tool position's answer: along a pass parallel to the spine it does not change.
  mutable double cached_u_ = std::numeric_limits<double>::quiet_NaN();
  mutable double cached_z_ = 0;
  mutable double cached_allowance_ = 0;
  mutable const std::vector<Vec2>* cached_outline_ = nullptr;
  mutable double cached_value_ = 0;
  mutable Vec2 cached_where_{};
  Spine spine_ = Spine::Point;
  Vec2 a_{}, b_{};  // segment ends; arc, circle, point centre in a_
  Vec2 along_{}, normal_{};
  double length_ = 0;
  double radius_ = 0, start_ = 0, sweep_ = 0;
  bool open_[2] = {false, false};
  double woodruff_[2] = {0, 0};
};

// Coverage of a cavity's floor: a height field. For each cell of a raster over the floor, the
// floor's height, the lowest height any swept tool's lower surface reached over it, and the
// lowest height a tool of the smallest shape can reach without crossing the cavity (a
// dilation of the floor by the tool, then an erosion): floor a tool cannot reach is not
// counted; floor left more than the tolerance (measured along the surface's normal) above its
// target height is uncovered.
struct SweptShape {
  Vec3 a, b;  // tool tip, feature frame
  ToolShape tool;
};
struct CavityCoverage {
  double grid = 0;
  bool coarsened = false;
  double reachable_area = 0;
  double unreachable_area = 0;
  double uncovered_fraction = 0;
  std::size_t uncovered = 0;
  Vec3 sample{};  // the uncovered cell nearest the uncovered cells' centroid, on its floor
};
CavityCoverage cover(const Cavity& cavity, const std::vector<SweptShape>& swept,
                     const ToolShape& smallest, double allowance, double tolerance,
                     std::optional<double> grid, double max_work);

}  // namespace ncpost::verify::detail
