#pragma once
// Closed pocket profiles and their inward offsets. Only shapes whose offsets are exact in
// closed form are here (rounded rectangles, circles): an offset is then the same shape with
// smaller sizes, never an approximation that could gouge a wall.

#include <array>
#include <optional>
#include <vector>

#include "draft.hpp"
#include "generator.hpp"

namespace ncpost::stepnc::features {

struct Shape {
  enum class Kind { Rectangle, Circle } kind = Kind::Rectangle;
  double half_length = 0;  // along x (rectangle), or the radius (circle)
  double half_width = 0;   // along y (rectangle), or the radius (circle)
  double corner = 0;       // rectangle corner radius (the smallest, when they differ)
  detail::Frame frame{};   // the profile in the feature's coordinates
  // A rectangle whose corners differ (a slot with mixed or flat ends): counter-clockwise from
  // (+a, +b), i.e. (+a, +b), (-a, +b), (-a, -b), (+a, -b). Unset: every corner is `corner`.
  std::optional<std::array<double, 4>> corners;

  static Shape rectangle(double half_x, double half_y, double corner_radius) {
    return {Kind::Rectangle, half_x, half_y, corner_radius, {}, {}};
  }
  static Shape circle(double radius) { return {Kind::Circle, radius, radius, radius, {}, {}}; }
  [[nodiscard]] double inradius() const {
    return half_length < half_width ? half_length : half_width;
  }
  [[nodiscard]] double corner_at(int k) const {
    return corners ? (*corners)[static_cast<std::size_t>(k)] : corner;
  }
};

// One piece of a closed loop, from the previous piece's end.
struct Span {
  Vec3 to{};
  bool arc = false;
  Vec3 centre{};
  bool ccw = true;
};

struct Loop {
  Vec3 start{};
  std::vector<Span> spans;  // counter-clockwise, ending at `start`
};

// Contour-parallel rings from the centre outwards, in the profile's coordinates (z = 0):
// first the innermost path (a point, or a line from `start` along `axis`, `line_length` long),
// then closed rings, the last at `inset` from the boundary. Neighbouring rings are at most
// `step` apart and evenly spaced.
struct Rings {
  Vec3 start{};
  Vec3 axis{1, 0, 0};
  double line_length = 0;
  std::vector<Loop> loops;
};

[[nodiscard]] Rings contour_rings(const Shape& shape, double inset, double step);

// The boundary offset outwards by `offset` (>= 0): a rounded rectangle grows its corner radius by
// the offset, a circle its radius. Counter-clockwise from the middle of its +x side.
[[nodiscard]] Loop outside_ring(const Shape& shape, double offset);

// Parallel lines across the region left at `inset` from the boundary, along the profile's x axis
// (or y), evenly spaced at most `step` apart, clipped to the region exactly (rounded corners
// and circles included), from the -y (-x) side. Each is (from, to) in the profile's coordinates.
[[nodiscard]] std::vector<std::pair<Vec3, Vec3>> raster(const Shape& shape, double inset,
                                                        double step, bool along_x);

// A loop at height z in the feature's coordinates (`frame` places the profile): a feed to its
// start, then round it counter-clockwise, or clockwise (its spans backwards).
void play_loop(Draft& draft, const Loop& loop, const detail::Frame& frame, bool ccw, double z);

}  // namespace ncpost::stepnc::features
