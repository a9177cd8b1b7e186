#pragma once
// Explicit toolpath curves → motion segments in the curve's own coordinates.

#include <optional>
#include <vector>

#include "geometry.hpp"

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

  // The segments of a bounded curve, in its sense; nullopt after reporting why not.
  [[nodiscard]] std::optional<std::vector<Segment>> segments(const p21::Instance& curve,
                                                             int depth = 0);
  // Points of a curve used as a tool-axis curve (POLYLINE of directions as points).
  [[nodiscard]] std::optional<std::vector<Vec3>> polyline_points(const p21::Instance& curve);

 private:
  std::optional<std::vector<Segment>> polyline(const p21::Instance& curve);
  std::optional<std::vector<Segment>> trimmed(const p21::Instance& curve);
  std::optional<std::vector<Segment>> composite(const p21::Instance& curve, int depth);
  std::optional<std::vector<Segment>> bspline(const p21::Instance& curve);
  std::optional<Vec3> trim_point(const p21::Instance& trimmed, std::string_view attribute,
                                 const p21::Instance& basis);

  GeometryReader& geometry_;
  double arc_tolerance_;
};

// The same path travelled backwards.
void reverse(std::vector<Segment>& segments);

}  // namespace ncpost::stepnc::detail
