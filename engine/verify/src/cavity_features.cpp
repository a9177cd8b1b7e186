// The verifier's own reading of the profiled features (cavity.hpp): slots of any profile along
// lines and circles, steps and threads. The readings of the standard are the ones docs/verify.md
// states (ISO 10303-214's vee tilt, a step's wall at its vee's vertex, circles about the
// feature's origin); the code is the verifier's.

#include <algorithm>
#include <cctype>
#include <numbers>

#include "cavity.hpp"
#include "contour.hpp"
#include "model.hpp"

namespace ncpost::verify::detail {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

const p21::Instance* item(const Reader& r, p21::Value v) {
  return v.is_reference() ? r.model().find(v.id()) : nullptr;
}

// Points of a section curve (the verifier's own reading): a POLYLINE, a B-spline (with knots,
// or a BEZIER_CURVE / QUASI_UNIFORM_CURVE with ISO 10303-42's implicit knots; rational too)
// evaluated by de Boor at least every 0.05 mm of its control polygon (and 32 times per control
// point), or lines and circular arcs (contour.hpp) within 0.0005 mm. Empty with the reason when
// it is none of those. The distances to the section are exact to its polyline, so it is kept
// short enough for them to stay fast and fine enough to stay far within the tolerance.
constexpr double kSectionSpacing = 0.05;
constexpr double kSectionChord = 0.0005;

std::vector<Vec2> spline_points(const Reader& r, const p21::Instance& curve, std::string& reason) {
  const auto degree = r.number(curve, "degree");
  std::vector<std::array<double, 4>> points;
  if (const auto list = r.get(curve, "control_points_list"); list && list->is_list())
    for (p21::Value v : r.model().items(*list)) {
      const auto q = r.point(item(r, v));
      if (!q) break;
      points.push_back({q->x, q->y, q->z, 1});
    }
  if (const auto w = r.get(curve, "weights_data"); w && w->is_list()) {
    const auto ws = r.model().items(*w);
    for (std::size_t k = 0; k < ws.size() && k < points.size(); ++k)
      points[k][3] = r.model().as_real(ws[k]);
  }
  const int d = degree ? static_cast<int>(std::clamp(*degree, 0.0, 64.0)) : 0;
  const auto n = static_cast<int>(points.size());
  std::vector<double> knots;
  if (r.is_a(curve, "b_spline_curve_with_knots")) {
    const auto mult = r.get(curve, "knot_multiplicities");
    const auto values = r.get(curve, "knots");
    if (mult && values && mult->is_list() && values->is_list() &&
        mult->count() == values->count()) {
      const auto m = r.model().items(*mult);
      const auto k = r.model().items(*values);
      for (std::size_t i = 0; i < k.size(); ++i)
        for (std::int64_t t = 0; t < r.model().as_integer(m[i]) && t < 64; ++t)
          knots.push_back(r.model().as_real(k[i]));
    }
  } else if (d >= 1 && n > d) {
    // Bezier: segments of d + 1 points sharing their ends (knots 0..segments, d + 1 fold at the
    // ends, d fold inside); quasi-uniform: clamped, one knot per interior point.
    const bool bezier = r.is_a(curve, "bezier_curve");
    const int spans = bezier ? ((n - 1) % d == 0 ? (n - 1) / d : 0) : n - d;
    for (int i = 0; spans > 0 && i <= spans; ++i)
      knots.insert(knots.end(), i == 0 || i == spans ? d + 1 : bezier ? d : 1, i);
  }
  if (d < 1 || n < d + 1 || knots.size() != static_cast<std::size_t>(n + d + 1) ||
      std::any_of(points.begin(), points.end(), [](const auto& p) { return !(p[3] > 0); })) {
    reason = "its general section's curve " + r.type(curve) + " cannot be evaluated";
    return {};
  }
  double polygon = 0;
  for (std::size_t k = 1; k < points.size(); ++k)
    polygon += std::hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
  // At least every kSectionSpacing of the control polygon and 32 times per control point, at
  // most 100,000 times.
  const int count = static_cast<int>(
      std::min(std::max(std::ceil(polygon / kSectionSpacing), 32.0 * n), 100000.0));
  const double u0 = knots[static_cast<std::size_t>(d)];
  const double u1 = knots[static_cast<std::size_t>(n)];
  std::vector<Vec2> out;
  for (int k = 0; k <= count; ++k) {
    const Vec3 p = de_boor(points, knots, d, u0 + (u1 - u0) * k / count);
    if (std::abs(p.z) > 1e-6) {
      reason = "its general section's curve leaves the profile's xy plane";
      return {};
    }
    out.push_back(p.xy());
  }
  return out;
}

std::vector<Vec2> section_points(const Reader& r, const p21::Instance& curve, std::string& reason) {
  if (r.is_a(curve, "b_spline_curve")) return spline_points(r, curve, reason);
  auto pieces = read_curve(r, curve, Frame{}, reason);
  std::vector<Vec2> out;
  if (!pieces) return out;
  for (const Piece2& piece : *pieces) {
    if (out.empty()) out.push_back(piece.a);
    if (!piece.arc) {
      out.push_back(piece.b);
      continue;
    }
    const double from = std::atan2(piece.a.y - piece.centre.y, piece.a.x - piece.centre.x);
    const double step = piece.radius > kSectionChord
                            ? 2 * std::acos(1 - kSectionChord / piece.radius)
                            : std::numbers::pi / 2;
    const int count =
        std::clamp(static_cast<int>(std::ceil(std::abs(piece.sweep) / step)), 1, 100000);
    for (int k = 1; k <= count; ++k) {
      const double a = from + piece.sweep * k / count;
      out.push_back(k == count ? piece.b
                               : piece.centre + Vec2{std::cos(a), std::sin(a)} * piece.radius);
    }
  }
  return out;
}

// The points of a finely sampled curve that keep every dropped point within kSectionChord of
// the chord that replaces it (greedy, a bounded look-ahead): the distances to the section visit
// its pieces, so fewer pieces where it is straight keep them fast.
std::vector<Vec2> simplify(const std::vector<Vec2>& points) {
  if (points.size() < 3) return points;
  std::vector<Vec2> out{points.front()};
  std::size_t from = 0;
  while (from + 1 < points.size()) {
    std::size_t to = from + 1;
    for (std::size_t j = from + 2; j < points.size() && j < from + 400; ++j) {
      bool near = true;
      for (std::size_t k = from + 1; k < j && near; ++k)
        near = segment_distance(points[k], points[from], points[j]) <= kSectionChord;
      if (!near) break;
      to = j;
    }
    out.push_back(points[to]);
    from = to;
  }
  return out;
}

// A GENERAL_PROFILE: x across the slot (to the left of its travel), y up; its lowest point on
// the depth plane, its ends at the top or above (docs/verify.md).
bool general_section(const Reader& r, const p21::Instance& shape, double depth, Cavity& c,
                     Feature& f) {
  const p21::Instance* curve = r.ref(shape, "its_profile");
  if (curve == nullptr) {
    f.reason = "its general section has no curve";
    return false;
  }
  std::vector<Vec2> points = simplify(section_points(r, *curve, f.reason));
  if (points.size() < 2) return false;
  if (points.back().x < points.front().x) std::reverse(points.begin(), points.end());
  double lowest = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (k > 0 && points[k].x < points[k - 1].x - 1e-3) {
      f.reason = "its general section turns back across the slot (an undercut)";
      return false;
    }
    if (k > 0) points[k].x = std::max(points[k].x, points[k - 1].x);
    lowest = std::min(lowest, points[k].y - points.front().y);
  }
  lowest += points.front().y;
  for (Vec2& p : points) p.y += -depth - lowest;
  if (points.front().y < -0.005 || points.back().y < -0.005) {
    f.reason =
        "its general section does not reach the top once its lowest point is on the "
        "depth plane";
    return false;
  }
  // Symmetric: every point's mirror image within 0.005 mm of the curve.
  const auto near_curve = [&](Vec2 m) {
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      if (points[k + 1].x < m.x - 0.01 || points[k].x > m.x + 0.01) continue;
      if (segment_distance(m, points[k], points[k + 1]) <= 0.005) return true;
    }
    return false;
  };
  bool symmetric = true;
  for (std::size_t k = 0; k < points.size() && symmetric; k += 7)
    symmetric = near_curve({-points[k].x, points[k].y});
  c.general(points, symmetric);
  return true;
}

// The swept profile as a section; false with the reason.
bool slot_section(const Reader& r, const p21::Instance& shape, double depth, Cavity& c,
                  Feature& f) {
  if (r.ref(shape, "placement") != nullptr) {
    f.reason = "its swept shape has a placement";
    return false;
  }
  if (r.is_a(shape, "square_u_profile")) {
    const auto width = r.length(shape, "width");
    for (const char* angle : {"first_angle", "second_angle"})
      if (const auto a = r.number(shape, angle); a && std::abs(*a - 90) > 1e-6) {
        f.reason = "its square-U walls are not vertical";
        return false;
      }
    const double r1 = r.length(shape, "first_radius").value_or(0);
    const double r2 = r.length(shape, "second_radius").value_or(0);
    if (!width || *width <= 0 || std::abs(r1 - r2) > 1e-9) {
      f.reason = "its square-U width or floor radii cannot be modelled";
      return false;
    }
    c.square_u(*width / 2, depth, r1);
    return true;
  }
  if (r.is_a(shape, "rounded_u_profile")) {
    const auto width = r.length(shape, "width");
    if (!width || *width <= 0) {
      f.reason = "its rounded-U profile has no width";
      return false;
    }
    c.rounded_u(*width / 2, depth);
    return true;
  }
  if (r.is_a(shape, "vee_profile")) {
    // ISO 10303-214: tilt_angle is the angle between the first side and the profile's x axis,
    // so a vee symmetric about the vertical has 90 - angle / 2.
    const auto angle = r.number(shape, "profile_angle");
    const auto tilt = r.number(shape, "tilt_angle");
    const double radius = r.length(shape, "profile_radius").value_or(0);
    if (!angle || !tilt || *angle <= 0 || *angle >= 180 || radius < 0) {
      f.reason = "its vee has no angle between 0 and 180 degrees";
      return false;
    }
    if (std::abs(*tilt - (90 - *angle / 2)) > 0.01) {
      f.reason = "its vee is tilted to one side";
      return false;
    }
    c.vee(*angle * kDeg, radius, depth);
    return true;
  }
  if (r.is_a(shape, "partial_circular_profile")) {
    const auto radius = r.length(shape, "radius");
    const auto sweep = r.number(shape, "sweep_angle");
    if (!radius || !sweep || *radius <= 0 || *sweep <= 0 || *sweep > 180 + 1e-9 ||
        !c.partial_circle(*radius, *sweep * kDeg, depth)) {
      f.reason = "its partial circle does not reach from the depth plane to the top";
      return false;
    }
    return true;
  }
  if (r.is_a(shape, "general_profile")) return general_section(r, shape, depth, c, f);
  f.reason = "its swept shape " + r.type(shape) + " is not supported";
  return false;
}

}  // namespace

bool read_profiled_slot(const Reader& r, const p21::Instance& feature, Feature& f) {
  const double depth = -f.floor;
  const p21::Instance* travel = r.ref(feature, "course_of_travel");
  const p21::Instance* shape = r.ref(feature, "swept_shape");
  if (travel == nullptr || shape == nullptr || depth <= 0) {
    f.reason = "its course of travel, swept shape or depth cannot be read";
    return false;
  }
  auto cavity = std::make_shared<Cavity>();
  if (!slot_section(r, *shape, depth, *cavity, f)) return false;
  // End types: one item (other than a loop) for both ends, as the generator reads it.
  enum class End { None, Radiused, Open, Woodruff, Loop, Other };
  End ends[2] = {End::None, End::None};
  double woodruff[2] = {0, 0};
  std::size_t count = 0;
  if (const auto list = r.get(feature, "end_conditions"); list && list->is_list()) {
    const auto items = r.model().items(*list);
    count = items.size();
    for (std::size_t k = 0; k < items.size() && k < 2; ++k) {
      const p21::Instance* e = item(r, items[k]);
      if (e == nullptr) continue;
      if (r.is_a(*e, "radiused_slot_end_type")) {
        ends[k] = End::Radiused;
      } else if (r.is_a(*e, "open_slot_end_type")) {
        ends[k] = End::Open;
      } else if (r.is_a(*e, "loop_slot_end_type")) {
        ends[k] = End::Loop;
      } else if (r.is_a(*e, "woodruff_slot_end_type")) {
        ends[k] = End::Woodruff;
        woodruff[k] = r.length(*e, "radius").value_or(0);
      } else {
        ends[k] = End::Other;
      }
    }
    if (items.size() == 1) {
      ends[1] = ends[0];
      woodruff[1] = woodruff[0];
    }
  }
  // A placed course of travel is in f.frame already (model.cpp, place_travel).
  if (cavity->signed_across() && !r.is_a(*travel, "linear_path") &&
      !r.is_a(*travel, "complete_circular_path")) {
    f.reason =
        "its general section is not symmetric and its course of travel is not a line or "
        "a whole circle";
    return false;
  }
  if (r.is_a(*travel, "complete_circular_path")) {
    const auto radius = r.length(*travel, "radius");
    if (!radius || *radius <= 0 || (count > 0 && ends[0] != End::Loop)) {
      f.reason = "its circular course of travel has no radius or ends that are not a loop";
      return false;
    }
    cavity->circle({0, 0}, *radius);
  } else if (r.is_a(*travel, "partial_circular_path")) {
    const auto radius = r.length(*travel, "radius");
    const auto sweep = r.number(*travel, "sweep_angle");
    if (!radius || !sweep || *radius <= 0 || ends[0] != End::Radiused || ends[1] != End::Radiused) {
      f.reason = "its arc of travel has no radius or ends other than radiused";
      return false;
    }
    cavity->arc({0, 0}, *radius, 0, *sweep * kDeg);
  } else if (r.is_a(*travel, "linear_path")) {
    const auto length = r.length(*travel, "distance");
    const auto direction = r.direction(r.ref(*travel, "its_direction"));
    if (!length || !direction || *length <= 0 || std::abs(direction->z) > 1e-9) {
      f.reason = "its course of travel cannot be read";
      return false;
    }
    for (int k = 0; k < 2; ++k) {
      if (ends[k] == End::Radiused && cavity->signed_across()) {
        f.reason = "its general section is not symmetric, so its radiused end is not defined";
        return false;
      }
      if (ends[k] == End::Radiused || ends[k] == End::Open) continue;
      if (ends[k] == End::Woodruff && woodruff[k] + 1e-9 >= depth) continue;
      f.reason = ends[k] == End::Woodruff ? "its woodruff end is less deep than the slot"
                                          : "its ends are not radiused, open or woodruff ends";
      return false;
    }
    const Vec2 d = direction->xy() * (1 / direction->xy().length());
    cavity->segment({0, 0}, d * *length, ends[0] == End::Open, ends[1] == End::Open,
                    ends[0] == End::Woodruff ? woodruff[0] : 0,
                    ends[1] == End::Woodruff ? woodruff[1] : 0);
  } else {
    f.reason = "its course of travel " + r.type(*travel) + " is not supported";
    return false;
  }
  f.cavity = std::move(cavity);
  return true;
}

bool read_step(const Reader& r, const p21::Instance& feature, Feature& f) {
  const double depth = -f.floor;
  const p21::Instance* open = r.ref(feature, "open_boundary");
  const p21::Instance* wall = r.ref(feature, "wall_boundary");
  const auto length = open ? r.length(*open, "distance") : std::nullopt;
  auto along = open ? r.direction(r.ref(*open, "its_direction")) : std::nullopt;
  if (!length || !along || *length <= 0 || depth <= 0) {
    f.reason = "its open boundary or depth cannot be read";
    return false;
  }
  Vec3 origin{};
  if (const p21::Instance* placed = r.ref(*open, "placement")) {
    const auto frame = r.placement(placed);
    if (!frame || std::abs(frame->z.z - 1) > 1e-9) {
      f.reason = "its open boundary's placement cannot be read";
      return false;
    }
    origin = frame->origin;
    along = frame->direction(*along);
  }
  // The wall stands at the vertex of its wall_boundary's vee, whose placement locates it.
  const auto foot = wall ? r.placement(r.ref(*wall, "placement")) : std::nullopt;
  if (!foot) {
    f.reason = "its wall is not located (no wall_boundary with a placement)";
    return false;
  }
  const double angle = r.number(*wall, "profile_angle").value_or(90);
  const double tilt = r.number(*wall, "tilt_angle").value_or(0);
  const double radius = r.length(*wall, "profile_radius").value_or(0);
  if (std::abs(tilt) > 1e-6 || angle < 90 - 1e-9 || angle >= 180 || radius < 0) {
    f.reason = "its wall is tilted or overhangs its floor";
    return false;
  }
  const Vec2 d = along->xy() * (1 / along->xy().length());
  const Vec2 left{-d.y, d.x};
  const double offset = (foot->origin - origin).xy().dot(left);
  if (std::abs(offset) < 1e-6) {
    f.reason = "its wall stands on its open boundary";
    return false;
  }
  const Vec2 into_wall = left * (offset > 0 ? 1 : -1);
  auto cavity = std::make_shared<Cavity>();
  cavity->step(angle * kDeg, radius, depth);
  cavity->line(origin.xy() + into_wall * std::abs(offset), d, into_wall, *length, std::abs(offset));
  f.cavity = std::move(cavity);
  return true;
}

bool read_thread(const Reader& r, const p21::Instance& feature, Feature& f) {
  // The thread's cylinder of its major diameter down its length, then its hole.
  const auto list = r.get(feature, "applied_shape");
  const p21::Instance* hole = nullptr;
  if (list && list->is_list() && list->count() == 1) hole = item(r, r.model().items(*list)[0]);
  const auto major = r.number(feature, "major_diameter");
  if (hole == nullptr || !r.is_a(*hole, "round_hole") || !major || *major <= 0) {
    f.reason = "it is not applied to one ROUND_HOLE or has no major diameter";
    return false;
  }
  const auto own = r.placement(r.ref(feature, "feature_placement"));
  const auto hole_frame = r.placement(r.ref(*hole, "feature_placement"));
  const p21::Instance* plane = r.ref(*hole, "depth");
  const auto hole_depth = plane ? r.placement(r.ref(*plane, "position")) : std::nullopt;
  const auto diameter = r.length(*hole, "diameter");
  if (!own || !hole_frame || !hole_depth || !diameter ||
      (own->origin - hole_frame->origin).length() > 1e-6 ||
      (own->z - hole_frame->z).length() > 1e-9) {
    f.reason = "its hole is not on its axis or cannot be read";
    return false;
  }
  const double length = -f.floor;
  const double depth = -hole_depth->origin.z;
  bool through = false;
  if (const p21::Instance* bottom = r.ref(*hole, "bottom_condition")) {
    through = r.is_a(*bottom, "through_bottom_condition");
    if (!through && !r.is_a(*bottom, "flat_hole_bottom"))
      f.notes.push_back("its hole's " + r.type(*bottom) + " is checked as a flat bottom");
  }
  if (length <= 0 || depth < length - 1e-9 || *diameter >= *major) {
    f.reason = "its length, its hole's depth or its diameters are inconsistent";
    return false;
  }
  auto cavity = std::make_shared<Cavity>();
  cavity->thread(*major / 2, length, *diameter / 2, depth, through);
  cavity->point({0, 0});
  f.cavity = std::move(cavity);
  f.floor = -depth;
  f.through = through;
  f.coverage = false;
  f.notes.push_back(
      "its thread is checked as a cylinder of its major diameter, and the floor "
      "of its hole is not measured for coverage");
  return true;
}

}  // namespace ncpost::verify::detail
