#pragma once
// Plane regions bounded by lines and circular arcs, and the signed distance to them: the only
// geometry the verifier needs for walls and floors. Deliberately simple (a minimum over the
// boundary's elements, a crossing test on a fine polygon) so it can be trusted by reading it;
// no offsetting, no clipping.

#include <cmath>
#include <numbers>
#include <vector>

namespace ncpost::verify::detail {

struct Vec2 {
  double x = 0;
  double y = 0;
  friend Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
  [[nodiscard]] double dot(Vec2 b) const { return x * b.x + y * b.y; }
  [[nodiscard]] double cross(Vec2 b) const { return x * b.y - y * b.x; }
  // sqrt, not hypot: no overflow at these sizes, and several times faster.
  [[nodiscard]] double length() const { return std::sqrt(x * x + y * y); }
};

inline constexpr double kTwoPi = 2 * std::numbers::pi;

// A boundary element: a line from `a` to `b`, or an arc about `centre` of `radius` from angle
// `start` sweeping `sweep` radians (positive counter-clockwise).
struct Element {
  bool arc = false;
  Vec2 a{}, b{};
  Vec2 centre{};
  double radius = 0;
  double start = 0;
  double sweep = 0;
  [[nodiscard]] double distance(Vec2 p) const;
};

// A closed region. `boundary` need not be ordered; `polygon` (the boundary as a closed polygon,
// arcs split finely) decides inside and outside.
class Region {
 public:
  void add_line(Vec2 a, Vec2 b);
  void add_arc(Vec2 centre, double radius, double start, double sweep);
  void add_polygon_point(Vec2 p) { polygon_.push_back(p); }

  // Positive inside, negative outside: the distance to the nearest boundary element.
  [[nodiscard]] double signed_distance(Vec2 p) const;
  // The distance to the nearest boundary element, unsigned.
  [[nodiscard]] double distance(Vec2 p) const;
  [[nodiscard]] bool inside(Vec2 p) const;
  [[nodiscard]] bool empty() const { return boundary_.empty(); }
  // Bounding box of the boundary.
  [[nodiscard]] Vec2 min() const { return min_; }
  [[nodiscard]] Vec2 max() const { return max_; }

  // The shapes of ISO 14649 profiles, centred (rectangle, circle, n-gon) at `origin`.
  static Region rectangle(Vec2 origin, Vec2 x_axis, double length, double width,
                          double corner_radius);
  // The rectangle spanned from `corner` by the two edge vectors (a planar face's extent).
  static Region parallelogram(Vec2 corner, Vec2 u, Vec2 v);
  static Region circle(Vec2 centre, double radius);

 private:
  void extend(Vec2 p);
  std::vector<Element> boundary_;
  std::vector<Vec2> polygon_;
  Vec2 min_{1e300, 1e300};
  Vec2 max_{-1e300, -1e300};
};

// A raster of square cells over a box, row-major, cell (i, j) centred at
// origin + ((i + 0.5) step, (j + 0.5) step).
struct Grid {
  Vec2 origin{};
  double step = 1;
  int nx = 0;
  int ny = 0;
  [[nodiscard]] std::size_t cells() const {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  }
  [[nodiscard]] Vec2 centre(int i, int j) const {
    return {origin.x + (i + 0.5) * step, origin.y + (j + 0.5) * step};
  }
  [[nodiscard]] std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
  }
};

// Exact Euclidean distance transform (Felzenszwalb & Huttenlocher): for each cell, the distance
// (in cells) to the nearest cell whose `seed` is set; +inf when there is none.
std::vector<float> distance_to_seeds(const Grid& grid, const std::vector<unsigned char>& seed);

// Distance from p to the segment a-b, and the parameter interval of a-b within `radius` of p.
double segment_distance(Vec2 p, Vec2 a, Vec2 b);
// The part [t0, t1] of the segment a + t (b - a), t in [0, 1], within `radius` of p; false when
// there is none.
bool segment_within(Vec2 p, Vec2 a, Vec2 b, double radius, double& t0, double& t1);

}  // namespace ncpost::verify::detail
