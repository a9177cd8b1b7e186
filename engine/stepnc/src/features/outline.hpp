#pragma once
// General profiles (GENERAL_CLOSED_PROFILE, NGON_CLOSED_PROFILE, GENERAL_PROFILE) as exact
// lines and circular arcs in the feature's xy plane, their corners, and their polygons for
// offsetting, tessellated on the material side so that an offset of the polygon never comes
// closer to the material than the same offset of the exact outline (docs/features.md).

#include <optional>
#include <string>
#include <vector>

#include "generator.hpp"
#include "polygons.hpp"
#include "report.hpp"

namespace ncpost::stepnc::features {

struct Element {
  poly::P start, end;  // where it starts and ends
  bool arc = false;    // else a line
  poly::P centre{};    // arcs
  double radius = 0;   // arcs
  double sweep = 0;    // arcs: signed angle from a to b about the centre (positive CCW)
  [[nodiscard]] poly::P tangent_at_start() const;
  [[nodiscard]] poly::P tangent_at_end() const;
};

struct Outline {
  std::vector<Element> elements;  // each starting where the previous ends
  bool closed = true;             // the last ends where the first starts
};

// A corner of an outline where the tangent turns (a polyline vertex, a line meeting an arc at
// an angle): `turn` is the signed turning angle in radians (positive: to the left).
struct Corner {
  poly::P at;
  double turn = 0;
  poly::P in, out;                    // unit tangents arriving and leaving
  std::size_t before = 0, after = 0;  // the elements that meet there
};

// A point of the plane for a message: "(x, y)".
[[nodiscard]] inline std::string at_text(poly::P p) {
  return "(" + fmt(p.x) + ", " + fmt(p.y) + ")";
}

// The margin by which every region of tool centres is kept inside the exact one: the round
// joins' chords (chord_tolerance), the arcs fitted back (three times that), Clipper's grid.
[[nodiscard]] inline double region_margin(const FeatureOptions& options) {
  return 5 * options.chord_tolerance + 4 * poly::kResolution;
}

// Reverses the sense of travel.
void reverse(Outline& outline);
// Where consecutive elements meet at an angle (closed outlines: the closing vertex too).
std::vector<Corner> corners(const Outline& outline);

// The outline as a polygon whose chords or tangent polylines deviate at most `tolerance` from
// each arc, always on the side away from the material: `material_left` says which side of the
// direction of travel the material is on. nullopt when it would have more than `max_points`.
std::optional<poly::Chain> tessellate(const Outline& outline, double tolerance, bool material_left,
                                      std::size_t max_points);

}  // namespace ncpost::stepnc::features
