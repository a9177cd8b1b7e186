#include "curves.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpost::stepnc::detail {
namespace {

constexpr int kMaxCurveNesting = 16;
constexpr double kTwoPi = 2 * std::numbers::pi;

// Angle of `p` around an axis, measured in the plane normal to `axis` from `reference`.
double angle_about(Vec3 p, Vec3 centre, Vec3 axis, Vec3 reference) {
  const Vec3 d = p - centre;
  const Vec3 in_plane = d - axis * d.dot(axis);
  const Vec3 other = axis.cross(reference);
  return std::atan2(in_plane.dot(other), in_plane.dot(reference));
}

double radial_distance(Vec3 p, Vec3 centre, Vec3 axis) {
  const Vec3 d = p - centre;
  return (d - axis * d.dot(axis)).length();
}

}  // namespace

void reverse(std::vector<Segment>& segments) {
  std::reverse(segments.begin(), segments.end());
  for (Segment& s : segments) {
    std::swap(s.start, s.end);
    if (s.kind == Segment::Kind::Arc) s.turns = -s.turns;
    if (s.kind == Segment::Kind::Nurbs) {
      std::reverse(s.control_points.begin(), s.control_points.end());
      std::reverse(s.weights.begin(), s.weights.end());
      const double sum = s.knots.front() + s.knots.back();
      std::reverse(s.knots.begin(), s.knots.end());
      for (double& k : s.knots) k = sum - k;
    }
  }
}

void scale(std::vector<Segment>& segments, double factor) {
  if (factor == 1) return;
  for (Segment& s : segments) {
    s.start = s.start * factor;
    s.end = s.end * factor;
    s.centre = s.centre * factor;
    for (Vec3& p : s.control_points) p = p * factor;
  }
}

std::optional<std::vector<Segment>> CurveReader::segments(const p21::Instance& curve) {
  auto out = curve_segments(curve, 0);
  if (out) scale(*out, mm_per_unit_);
  return out;
}

bool CurveReader::apply_tool_axis(std::vector<Segment>& segments, const p21::Instance& axis_curve) {
  const auto axes =
      geometry_.is_a(axis_curve, "polyline") ? polyline_points(axis_curve) : std::nullopt;
  if (!axes || axes->size() != segments.size() + 1 ||
      std::any_of(segments.begin(), segments.end(),
                  [](const Segment& s) { return s.kind != Segment::Kind::Line; }))
    return false;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Vec3 d = (*axes)[i + 1];
    segments[i].tool_axis = d * (1.0 / std::max(d.length(), 1e-12));
  }
  return true;
}

std::optional<std::vector<Segment>> CurveReader::curve_segments(const p21::Instance& curve,
                                                                int depth) {
  if (depth > kMaxCurveNesting) {
    geometry_.error(diag::Code::StepncBadGeometry, curve,
                    describe(geometry_.model(), curve) + " nests curves deeper than " +
                        std::to_string(kMaxCurveNesting));
    return std::nullopt;
  }
  if (geometry_.is_a(curve, "polyline")) return polyline(curve);
  if (geometry_.is_a(curve, "trimmed_curve")) return trimmed(curve);
  if (geometry_.is_a(curve, "composite_curve")) return composite(curve, depth);
  if (geometry_.is_a(curve, "b_spline_curve_with_knots") || geometry_.is_a(curve, "bezier_curve") ||
      geometry_.is_a(curve, "quasi_uniform_curve"))
    return bspline(curve);
  geometry_.error(diag::Code::StepncNotImplemented, curve,
                  describe(geometry_.model(), curve) +
                      " as a toolpath curve is not implemented (POLYLINE, TRIMMED_CURVE, "
                      "COMPOSITE_CURVE, B_SPLINE_CURVE_WITH_KNOTS, BEZIER_CURVE and "
                      "QUASI_UNIFORM_CURVE are)");
  return std::nullopt;
}

std::optional<std::vector<Vec3>> CurveReader::polyline_points(const p21::Instance& curve) {
  const auto list = geometry_.attributes().get(curve, "points");
  if (!list || !list->is_list()) return std::nullopt;
  std::vector<Vec3> points;
  for (p21::Value v : geometry_.model().items(*list)) {
    auto p = geometry_.point(v);
    if (!p) return std::nullopt;
    points.push_back(*p);
  }
  return points;
}

std::optional<std::vector<Segment>> CurveReader::polyline(const p21::Instance& curve) {
  auto points = polyline_points(curve);
  if (!points || points->size() < 2) {
    geometry_.error(diag::Code::StepncBadGeometry, curve,
                    describe(geometry_.model(), curve) + " needs at least two points");
    return std::nullopt;
  }
  std::vector<Segment> out;
  for (std::size_t i = 1; i < points->size(); ++i) {
    Segment s;
    s.start = (*points)[i - 1];
    s.end = (*points)[i];
    out.push_back(s);
  }
  return out;
}

// A trimming point: a CARTESIAN_POINT, or a PARAMETER_VALUE on the basis curve. When both are
// given, master_representation chooses (ISO 10303-42).
std::optional<Vec3> CurveReader::trim_point(const p21::Instance& trimmed,
                                            std::string_view attribute,
                                            const p21::Instance& basis) {
  const p21::Model& m = geometry_.model();
  const auto set = geometry_.get(trimmed, attribute);
  if (!set || !set->is_list() || set->count() == 0) {
    geometry_.error(diag::Code::StepncBadAttribute, trimmed,
                    describe(m, trimmed) + " attribute " + std::string(attribute) + " is empty");
    return std::nullopt;
  }
  std::optional<p21::Value> point_value;
  std::optional<double> parameter;
  for (p21::Value v : m.items(*set)) {
    if (v.is_reference()) point_value = v;
    if (v.kind() == p21::ValueKind::Typed && m.typed_child(v).is_number())
      parameter = m.as_real(m.typed_child(v));
  }
  const auto master = geometry_.get(trimmed, "master_representation");
  const bool prefer_parameter = master && master->kind() == p21::ValueKind::Enumeration &&
                                m.enumeration(*master) == "PARAMETER";
  if (point_value && (!parameter || !prefer_parameter)) return geometry_.point(point_value);
  if (!parameter) {
    geometry_.error(diag::Code::StepncBadAttribute, trimmed,
                    describe(m, trimmed) + " attribute " + std::string(attribute) +
                        " holds neither a point nor a parameter");
    return std::nullopt;
  }
  if (geometry_.is_a(basis, "line")) {
    const auto origin = geometry_.point(geometry_.get(basis, "pnt"));
    const p21::Instance* vector =
        geometry_.instance(geometry_.get(basis, "dir"), "vector", &basis, "dir");
    if (!origin || vector == nullptr) return std::nullopt;
    const auto direction = geometry_.direction(geometry_.get(*vector, "orientation"));
    const auto magnitude = geometry_.number(*vector, "magnitude");
    if (!direction || !magnitude) return std::nullopt;
    return *origin + *direction * (*parameter * *magnitude);
  }
  if (geometry_.is_a(basis, "circle")) {
    const auto frame = geometry_.placement(geometry_.get(basis, "position"));
    const auto radius = geometry_.number(basis, "radius");
    if (!frame || !radius) return std::nullopt;
    // ISO 10303-42 circle parameter: the angle, in the context's plane angle unit (radians for
    // ISO 14649, which has no unit context).
    const double angle = *parameter * radians_per_unit_;
    return frame->point({*radius * std::cos(angle), *radius * std::sin(angle), 0});
  }
  geometry_.error(diag::Code::StepncNotImplemented, trimmed,
                  describe(m, trimmed) + " trimmed by parameter on " + describe(m, basis) +
                      " is not implemented (by point it is)");
  return std::nullopt;
}

std::optional<std::vector<Segment>> CurveReader::trimmed(const p21::Instance& curve) {
  const p21::Model& m = geometry_.model();
  const p21::Instance* basis =
      geometry_.instance(geometry_.get(curve, "basis_curve"), "curve", &curve, "basis_curve");
  if (basis == nullptr) return std::nullopt;
  const auto start = trim_point(curve, "trim_1", *basis);
  const auto end = trim_point(curve, "trim_2", *basis);
  if (!start || !end) return std::nullopt;
  const auto sense = geometry_.get(curve, "sense_agreement");
  const bool agrees = !sense || m.as_logical(*sense) != p21::Logical::False;

  Segment s;
  s.start = *start;
  s.end = *end;
  if (geometry_.is_a(*basis, "line")) return std::vector<Segment>{s};

  const bool helix = geometry_.is_a(*basis, "helix");
  if (!helix && !geometry_.is_a(*basis, "circle")) {
    geometry_.error(diag::Code::StepncNotImplemented, curve,
                    describe(m, curve) + " trims " + describe(m, *basis) +
                        ", which is not implemented (LINE, CIRCLE and HELIX are)");
    return std::nullopt;
  }
  const auto frame = geometry_.placement(geometry_.get(*basis, "position"));
  const auto radius = geometry_.number(*basis, "radius");
  if (!frame || !radius) return std::nullopt;
  for (const auto& [p, which] : {std::pair{*start, "start"}, std::pair{*end, "end"}}) {
    const double r = radial_distance(p, frame->origin, frame->z);
    if (std::abs(r - *radius) * mm_per_unit_ > arc_tolerance_) {
      geometry_.error(diag::Code::StepncArcMismatch, curve,
                      describe(m, curve) + ": the " + which + " point is " + std::to_string(r) +
                          " from the axis of " + describe(m, *basis) + ", whose radius is " +
                          std::to_string(*radius));
      return std::nullopt;
    }
  }
  s.kind = Segment::Kind::Arc;
  s.centre = frame->origin;
  s.normal = frame->z;
  // Sense agreement: counter-clockwise about the placement axis, else clockwise.
  const int direction = agrees ? 1 : -1;
  const double a0 = angle_about(*start, frame->origin, frame->z, frame->x);
  const double a1 = angle_about(*end, frame->origin, frame->z, frame->x);
  double sweep = direction > 0 ? a1 - a0 : a0 - a1;  // in the direction of travel, [0, 2π)
  sweep = std::fmod(sweep + 2 * kTwoPi, kTwoPi);
  if (!helix) {
    const double rise = (*end - *start).dot(frame->z);
    if (std::abs(rise) * mm_per_unit_ > arc_tolerance_) {
      geometry_.error(diag::Code::StepncArcMismatch, curve,
                      describe(m, curve) + ": the end points of a circular arc differ by " +
                          std::to_string(rise) + " along its axis");
      return std::nullopt;
    }
    s.turns = direction;  // a closed circle (start == end) is one full turn, as in rs274
    return std::vector<Segment>{s};
  }
  const auto pitch = geometry_.number(*basis, "pitch");
  if (!pitch || std::abs(*pitch) < 1e-9) {
    geometry_.error(diag::Code::StepncBadGeometry, *basis, describe(m, *basis) + " has no pitch");
    return std::nullopt;
  }
  // The helix rises |pitch| per turn; its angular travel must end where the end point is.
  // rs274 counts |turns| - 1 full turns before the last, partial one; when the end is at the
  // start's angle that last part is itself a full turn.
  const double rise = std::abs((*end - *start).dot(frame->z));
  const double total = kTwoPi * rise / std::abs(*pitch);
  const double partial = sweep < 1e-9 ? kTwoPi : sweep;
  const double full_turns = std::floor((total - partial) / kTwoPi + 0.5);
  const double mismatch = std::abs(full_turns * kTwoPi + partial - total) * *radius;
  if (mismatch * mm_per_unit_ > std::max(arc_tolerance_, 1e-3 * total * *radius * mm_per_unit_)) {
    geometry_.error(diag::Code::StepncArcMismatch, curve,
                    describe(m, curve) + ": a rise of " + std::to_string(rise) + " at pitch " +
                        std::to_string(*pitch) + " does not end at the end point's angle on " +
                        describe(m, *basis));
    return std::nullopt;
  }
  s.turns = direction * (static_cast<int>(std::max(0.0, full_turns)) + 1);
  return std::vector<Segment>{s};
}

std::optional<std::vector<Segment>> CurveReader::composite(const p21::Instance& curve, int depth) {
  const p21::Model& m = geometry_.model();
  const auto list = geometry_.get(curve, "segments");
  if (!list || !list->is_list()) return std::nullopt;
  std::vector<Segment> out;
  for (p21::Value v : m.items(*list)) {
    const p21::Instance* seg = geometry_.instance(v, "composite_curve_segment", &curve, "segments");
    if (seg == nullptr) return std::nullopt;
    const p21::Instance* parent =
        geometry_.instance(geometry_.get(*seg, "parent_curve"), "curve", seg, "parent_curve");
    if (parent == nullptr) return std::nullopt;
    auto part = curve_segments(*parent, depth + 1);
    if (!part) return std::nullopt;
    const auto same = geometry_.get(*seg, "same_sense");
    if (same && m.as_logical(*same) == p21::Logical::False) reverse(*part);
    out.insert(out.end(), part->begin(), part->end());
  }
  return out;
}

namespace {

// ISO 10303-42's implicit knots of a B_SPLINE_CURVE subtype without a knot list (n control
// points of degree d): a BEZIER_CURVE is piecewise Bézier, knots 0 … (n − 1) / d with
// multiplicity d + 1 at the ends and d inside; a QUASI_UNIFORM_CURVE is clamped uniform, knots
// 0 … n − d with multiplicity d + 1 at the ends and 1 inside. Empty when n does not fit.
std::vector<double> implicit_knots(bool bezier, int d, std::size_t n) {
  std::vector<double> knots;
  const auto count = static_cast<std::int64_t>(n);
  if (d < 1 || count < d + 1 || count > 100000 || (bezier && (count - 1) % d != 0)) return knots;
  const std::int64_t last = bezier ? (count - 1) / d : count - d;
  for (std::int64_t i = 0; i <= last; ++i) {
    const std::int64_t times = i == 0 || i == last ? d + 1 : bezier ? d : 1;
    for (std::int64_t r = 0; r < times; ++r) knots.push_back(static_cast<double>(i));
  }
  return knots;
}

}  // namespace

std::optional<std::vector<Segment>> CurveReader::bspline(const p21::Instance& curve) {
  const p21::Model& m = geometry_.model();
  Segment s;
  s.kind = Segment::Kind::Nurbs;
  const bool explicit_knots = geometry_.is_a(curve, "b_spline_curve_with_knots");
  const auto degree = geometry_.get(curve, "degree");
  const auto points = geometry_.get(curve, "control_points_list");
  if (!degree || !points || !points->is_list()) {
    geometry_.error(diag::Code::StepncBadAttribute, curve,
                    describe(m, curve) + " lacks its degree, control points or knots");
    return std::nullopt;
  }
  s.degree = static_cast<int>(std::clamp<std::int64_t>(m.as_integer(*degree), -1, 64));
  for (p21::Value v : m.items(*points)) {
    auto p = geometry_.point(v);
    if (!p) return std::nullopt;
    s.control_points.push_back(*p);
  }
  if (explicit_knots) {
    const auto multiplicities = geometry_.get(curve, "knot_multiplicities");
    const auto knots = geometry_.get(curve, "knots");
    if (!multiplicities || !knots || !multiplicities->is_list() || !knots->is_list() ||
        multiplicities->count() != knots->count()) {
      geometry_.error(diag::Code::StepncBadAttribute, curve,
                      describe(m, curve) + " lacks its degree, control points or knots");
      return std::nullopt;
    }
    const auto mult = m.items(*multiplicities);
    const auto k = m.items(*knots);
    for (std::size_t i = 0; i < k.size(); ++i)
      for (std::int64_t r = 0; r < m.as_integer(mult[i]) && r < 64; ++r)
        s.knots.push_back(m.as_real(k[i]));
  } else {
    s.knots =
        implicit_knots(geometry_.is_a(curve, "bezier_curve"), s.degree, s.control_points.size());
    if (s.knots.empty()) {
      geometry_.error(
          diag::Code::StepncBadGeometry, curve,
          describe(m, curve) + ": " + std::to_string(s.control_points.size()) +
              " control points do not make a curve of degree " + std::to_string(s.degree) +
              (geometry_.is_a(curve, "bezier_curve") ? " (a Bezier curve has degree × segments + 1)"
                                                     : " (at least degree + 1)"));
      return std::nullopt;
    }
  }
  s.weights.assign(s.control_points.size(), 1.0);
  if (const auto w = geometry_.get(curve, "weights_data"); w && w->is_list()) {
    const auto ws = m.items(*w);
    if (ws.size() != s.control_points.size()) {
      geometry_.error(diag::Code::StepncBadGeometry, curve,
                      describe(m, curve) + " has " + std::to_string(ws.size()) + " weights for " +
                          std::to_string(s.control_points.size()) + " control points");
      return std::nullopt;
    }
    for (std::size_t i = 0; i < ws.size(); ++i) s.weights[i] = m.as_real(ws[i]);
  }
  if (s.degree < 1 ||
      s.knots.size() != s.control_points.size() + static_cast<std::size_t>(s.degree) + 1) {
    geometry_.error(diag::Code::StepncBadGeometry, curve,
                    describe(m, curve) + ": " + std::to_string(s.knots.size()) + " knots for " +
                        std::to_string(s.control_points.size()) + " control points of degree " +
                        std::to_string(s.degree) + " (expected points + degree + 1)");
    return std::nullopt;
  }
  s.start = s.control_points.front();
  s.end = s.control_points.back();
  return std::vector<Segment>{s};
}

}  // namespace ncpost::stepnc::detail
