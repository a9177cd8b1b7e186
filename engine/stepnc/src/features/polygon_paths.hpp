#pragma once
// Paths round the polygon rings of general regions, as the tool plays them: the nearest point
// of a ring, the way round it from there, the arcs fitted back into its polygon, and the spans
// at a height. Shared by the planners of general pockets and outside profiles.

#include <vector>

#include "draft.hpp"
#include "polygons.hpp"

namespace ncpost::stepnc::features {

// One piece of a path in the plane: a line or an arc (about `centre`) to `to`.
struct PlaneSpan {
  poly::P to;
  bool arc = false;
  poly::P centre{};
  bool ccw = true;
};

// A path the tool follows at one height: a ring (closed, back to its first point) or a line.
struct PlanePath {
  std::vector<poly::P> points;
  bool fit = false;  // rings: arcs may be fitted back
};

struct Nearest {
  poly::P point;
  std::size_t edge = 0;  // the point lies on ring[edge] → ring[edge + 1]
  double distance = 0;
};

[[nodiscard]] Nearest nearest_on(const poly::Ring& ring, poly::P p);
// Round the ring from a point on it and back to that point, in the sense asked (the ring itself
// is counter-clockwise).
[[nodiscard]] std::vector<poly::P> ring_path(const poly::Ring& ring, const Nearest& from, bool ccw);

// The path through `points` as lines and arcs: a run of at least four points within `tolerance`
// of one circle, whose chords' sagittas are at most twice that (round joins are made with chords
// of sagitta `tolerance`), is one arc: the arc is within 3 × `tolerance` of the polygon.
[[nodiscard]] std::vector<PlaneSpan> fit_arcs(const std::vector<poly::P>& points, double tolerance);
// A path as the spans it is played as: its points as feeds, or, for rings, with arcs fitted
// back. Computed once per path, not per level: the fitting is most of what playing a ring costs.
[[nodiscard]] std::vector<PlaneSpan> spans_of(const PlanePath& path, double fit_tolerance);
// The spans at height z (arcs about the feature's z axis).
void emit_spans(Draft& draft, const std::vector<PlaneSpan>& spans, double z);

[[nodiscard]] inline Vec3 at(poly::P p, double z) {
  return {p.x, p.y, z};
}

}  // namespace ncpost::stepnc::features
