#pragma once
// Plane polygons for the feature generator: offsets (round joins), boolean operations and the
// clipping of open lines, on top of Clipper 1 (libpolyclipping). This file and polygons.cpp are
// the only ones that see Clipper: coordinates cross into its integer grid here (1e-4 mm) and its
// exceptions end here, as an empty optional. See docs/features.md ("General profiles").

#include <optional>
#include <utility>
#include <vector>

namespace ncpost::stepnc::features::poly {

struct P {
  double x = 0;
  double y = 0;
  friend P operator+(P a, P b) { return {a.x + b.x, a.y + b.y}; }
  friend P operator-(P a, P b) { return {a.x - b.x, a.y - b.y}; }
  friend P operator*(P a, double s) { return {a.x * s, a.y * s}; }
  [[nodiscard]] double dot(P b) const { return x * b.x + y * b.y; }
  [[nodiscard]] double cross(P b) const { return x * b.y - y * b.x; }
  [[nodiscard]] double length() const;
};

// A closed polygon: the last point connects back to the first (not repeated).
using Ring = std::vector<P>;
// An open polyline.
using Chain = std::vector<P>;

// One connected piece of a region: its outer boundary counter-clockwise, its holes clockwise.
struct Area {
  Ring outer;
  std::vector<Ring> holes;
};
using Areas = std::vector<Area>;

// Every coordinate handed to the functions below must be within this many mm of the origin
// (checked where profiles are read): Clipper's fast integer range at the 1e-4 mm grid.
inline constexpr double kMaxCoordinate = 1e5;
// mm per Clipper unit: what a coordinate may move by when it crosses into Clipper.
inline constexpr double kResolution = 1e-4;

// Signed area (counter-clockwise positive) of a ring, and the total of a region.
[[nodiscard]] double area(const Ring& ring);
[[nodiscard]] double area(const Areas& areas);
// Inside the outer boundary and outside every hole (the boundary counts as inside).
[[nodiscard]] bool contains(const Area& area, P p);
[[nodiscard]] bool contains(const Areas& areas, P p);
// The shortest distance from p to any edge of the region's boundaries.
[[nodiscard]] double distance_to_boundary(const Areas& areas, P p);
// The ring has no two edges that cross or touch other than neighbours at their shared vertex,
// and encloses a positive area.
[[nodiscard]] bool simple(const Ring& ring);

// The region with its boundaries simplified (Douglas-Peucker): no point moves more than
// `tolerance`, either way; far fewer points where arcs were finely split.
[[nodiscard]] Areas simplified(const Areas& areas, double tolerance);

// All operations return nullopt when Clipper refuses (a coordinate out of range, memory).
class Polygons {
 public:
  // `arc_tolerance`: the largest distance (mm) between a round join's polygon and its arc.
  explicit Polygons(double arc_tolerance) : arc_tolerance_(arc_tolerance) {}

  // The region grown (delta > 0) or shrunk (delta < 0) by |delta|, with round joins. The join
  // polygons have their vertices on the exact arc, so their chords lie inside it: callers add
  // the arc tolerance to a shrink that must not come closer than |delta| to the old boundary.
  [[nodiscard]] std::optional<Areas> offset(const Areas& region, double delta) const;
  [[nodiscard]] std::optional<Areas> unite(const Areas& a, const Areas& b) const;
  [[nodiscard]] std::optional<Areas> difference(const Areas& a, const Areas& b) const;
  [[nodiscard]] std::optional<Areas> intersection(const Areas& a, const Areas& b) const;
  // The region swept by a disc of `radius` along closed rings and open chains.
  [[nodiscard]] std::optional<Areas> sweep(const std::vector<Ring>& rings,
                                           const std::vector<Chain>& chains, double radius) const;
  // The parts of the open chains inside the region (Clipper may return a piece reversed).
  [[nodiscard]] std::optional<std::vector<Chain>> clip(const std::vector<Chain>& chains,
                                                       const Areas& region) const;
  // The straight segment a-b lies in the region (within the coordinate grid).
  [[nodiscard]] bool segment_inside(P a, P b, const Areas& region) const;

 private:
  double arc_tolerance_;
};

}  // namespace ncpost::stepnc::features::poly
