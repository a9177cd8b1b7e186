#pragma once
// Explicit toolpath curves → motion segments in the curve's own coordinates. Shared by the
// ISO 14649 and the AP238 AIM interpreters (see geometry.hpp).

#include <optional>
#include <vector>

#include "ncpost/stepnc/geometry.hpp"

namespace ncpost::stepnc::detail {

struct Segment {
  enum class Kind : std::uint8_t { Line, Arc, Nurbs };
  Kind kind = Kind::Line;
  Vec3 start{};
  Vec3 end{};
  // Arcs and helices: a point on the axis, the axis (unit), and the signed turn count about it
  // (positive counter-clockwise seen from the axis tip; |turns| - 1 full turns, as rs274 counts).
  Vec3 centre{};
  Vec3 normal{0, 0, 1};
  int turns = 1;
  // NURBS: control points (x, y, z) with weights, knots expanded by multiplicity.
  int degree = 0;
  std::vector<Vec3> control_points;
  std::vector<double> weights;
  std::vector<double> knots;
  // Tool axis at the end of the segment, when the toolpath carries one.
  std::optional<Vec3> tool_axis;
};

class CurveReader {
 public:
  CurveReader(GeometryReader& geometry, double arc_tolerance)
      : geometry_(geometry), arc_tolerance_(arc_tolerance) {}

  // The units of the curves read next (AP238 curves carry their representation context's
  // units; ISO 14649 curves are in mm and radians, the defaults): lengths are scaled to mm, and
  // circle trim parameters are angles of `radians_per_unit` radians.
  void set_units(double mm_per_unit, double radians_per_unit) {
    mm_per_unit_ = mm_per_unit;
    radians_per_unit_ = radians_per_unit;
  }

  // The segments of a bounded curve, in its sense, in mm; nullopt after reporting why not.
  [[nodiscard]] std::optional<std::vector<Segment>> segments(const p21::Instance& curve);
  // Points of a curve used as a tool-axis curve (POLYLINE of directions as points).
  [[nodiscard]] std::optional<std::vector<Vec3>> polyline_points(const p21::Instance& curve);
  // A tool-axis curve on a path: one axis vector per point of a polyline path, set as each
  // segment's tool_axis. False (nothing changed) for any other combination, which the caller
  // reports as not implemented.
  [[nodiscard]] bool apply_tool_axis(std::vector<Segment>& segments,
                                     const p21::Instance& axis_curve);

 private:
  std::optional<std::vector<Segment>> curve_segments(const p21::Instance& curve, int depth);
  std::optional<std::vector<Segment>> polyline(const p21::Instance& curve);
  std::optional<std::vector<Segment>> trimmed(const p21::Instance& curve);
  std::optional<std::vector<Segment>> composite(const p21::Instance& curve, int depth);
  std::optional<std::vector<Segment>> bspline(const p21::Instance& curve);
  std::optional<Vec3> trim_point(const p21::Instance& trimmed, std::string_view attribute,
                                 const p21::Instance& basis);

  GeometryReader& geometry_;
  double arc_tolerance_;  // mm
  double mm_per_unit_ = 1;
  double radians_per_unit_ = 1;
};

// The same path travelled backwards.
void reverse(std::vector<Segment>& segments);
// Positions (ends, arc centres, control points) multiplied by `factor`; directions, weights and
// knots unchanged.
void scale(std::vector<Segment>& segments, double factor);

}  // namespace ncpost::stepnc::detail
