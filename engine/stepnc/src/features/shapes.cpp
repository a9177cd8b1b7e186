#include "shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ncpost::stepnc::features {
namespace {

constexpr double kTiny = 1e-9;

// A rounded rectangle centred at the origin, counter-clockwise from the middle of its +x side;
// r[k] is the radius of corner k, counter-clockwise from (+a, +b).
Loop rounded_rectangle(double a, double b, std::array<double, 4> r) {
  for (double& c : r) c = std::clamp(c, 0.0, std::min(a, b));
  Loop loop;
  loop.start = {a, 0, 0};
  Vec3 at = loop.start;
  const auto line = [&](Vec3 to) {
    if ((to - at).length() > kTiny) loop.spans.push_back({to, false, {}, true});
    at = to;
  };
  const auto corner = [&](Vec3 to, Vec3 centre, double radius) {
    if (radius > kTiny) loop.spans.push_back({to, true, centre, true});
    at = to;
  };
  line({a, b - r[0], 0});
  corner({a - r[0], b, 0}, {a - r[0], b - r[0], 0}, r[0]);
  line({-a + r[1], b, 0});
  corner({-a, b - r[1], 0}, {-a + r[1], b - r[1], 0}, r[1]);
  line({-a, -b + r[2], 0});
  corner({-a + r[2], -b, 0}, {-a + r[2], -b + r[2], 0}, r[2]);
  line({a - r[3], -b, 0});
  corner({a, -b + r[3], 0}, {a - r[3], -b + r[3], 0}, r[3]);
  line(loop.start);
  return loop;
}

std::array<double, 4> corner_radii(const Shape& shape, double offset) {
  std::array<double, 4> r{};
  for (int k = 0; k < 4; ++k)
    r[static_cast<std::size_t>(k)] = std::max(0.0, shape.corner_at(k) + offset);
  return r;
}

Loop full_circle(double radius) {
  Loop loop;
  loop.start = {radius, 0, 0};
  loop.spans.push_back({loop.start, true, {0, 0, 0}, true});
  return loop;
}

}  // namespace

Loop outside_ring(const Shape& shape, double offset) {
  if (shape.kind == Shape::Kind::Circle) return full_circle(shape.half_length + offset);
  return rounded_rectangle(shape.half_length + offset, shape.half_width + offset,
                           corner_radii(shape, offset));
}

Rings contour_rings(const Shape& shape, double inset, double step) {
  Rings out;
  const double a_out = shape.half_length - inset;
  const double b_out = shape.half_width - inset;
  const double room = std::max(0.0, std::min(a_out, b_out));
  const std::size_t n = room <= kTiny ? 0 : static_cast<std::size_t>(std::ceil(room / step - 1e-9));
  const double s = n == 0 ? 0 : room / static_cast<double>(n);
  // Innermost: what is left of the region when it has been offset by `room`.
  const double a_in = std::max(0.0, a_out - room);
  const double b_in = std::max(0.0, b_out - room);
  if (a_in >= b_in) {
    out.start = {-a_in, 0, 0};
    out.axis = {1, 0, 0};
    out.line_length = 2 * a_in;
  } else {
    out.start = {0, -b_in, 0};
    out.axis = {0, 1, 0};
    out.line_length = 2 * b_in;
  }
  for (std::size_t k = 1; k <= n; ++k) {
    // Each ring from the outermost inwards by whole steps: no drift, the last exactly at inset.
    const double in = static_cast<double>(n - k) * s;
    if (shape.kind == Shape::Kind::Circle)
      out.loops.push_back(full_circle(a_out - in));
    else
      out.loops.push_back(
          rounded_rectangle(a_out - in, b_out - in, corner_radii(shape, -inset - in)));
  }
  return out;
}

std::vector<std::pair<Vec3, Vec3>> raster(const Shape& shape, double inset, double step,
                                          bool along_x) {
  const double a_out = std::max(0.0, shape.half_length - inset);
  const double b_out = std::max(0.0, shape.half_width - inset);
  const double along = along_x ? a_out : b_out;  // half extent along the lines
  const double across = along_x ? b_out : a_out;
  // The corner radius of the region at each corner (counter-clockwise from (+a, +b)).
  std::array<double, 4> rho = corner_radii(shape, -inset);
  for (double& c : rho) c = std::clamp(c, 0.0, std::min(a_out, b_out));
  const std::size_t n =
      across <= kTiny ? 0 : static_cast<std::size_t>(std::ceil(2 * across / step - 1e-9));
  std::vector<std::pair<Vec3, Vec3>> lines;
  lines.reserve(n + 1);
  // Inside the straight sides a line spans the full length; in a corner it ends on the arc.
  const auto reach = [&](double v, double r) {
    const double into_corner = std::abs(v) - (across - r);
    return into_corner > 0 ? along - r + std::sqrt(std::max(0.0, r * r - into_corner * into_corner))
                           : along;
  };
  for (std::size_t k = 0; k <= n; ++k) {
    const double v =
        n == 0 ? 0 : -across + 2 * across * static_cast<double>(k) / static_cast<double>(n);
    // The corners at the line's + and - ends.
    const double r_plus = along_x ? rho[v >= 0 ? 0 : 3] : rho[v >= 0 ? 0 : 1];
    const double r_minus = along_x ? rho[v >= 0 ? 1 : 2] : rho[v >= 0 ? 3 : 2];
    const double hi = reach(v, r_plus);
    const double lo = reach(v, r_minus);
    if (along_x)
      lines.push_back({{-lo, v, 0}, {hi, v, 0}});
    else
      lines.push_back({{v, -lo, 0}, {v, hi, 0}});
  }
  return lines;
}
void play_loop(Draft& draft, const Loop& loop, const detail::Frame& frame, bool ccw, double z) {
  const auto at = [&](Vec3 p) { return frame.point({p.x, p.y, z}); };
  draft.feed(at(loop.start));
  if (ccw) {
    for (const Span& s : loop.spans) {
      if (s.arc)
        draft.arc(at(s.to), at(s.centre), 1);
      else
        draft.feed(at(s.to));
    }
    return;
  }
  // Backwards: span i runs from the end of span i-1 (the start for the first) to its end.
  for (std::size_t i = loop.spans.size(); i-- > 0;) {
    const Vec3 to = i == 0 ? loop.start : loop.spans[i - 1].to;
    const Span& s = loop.spans[i];
    if (s.arc)
      draft.arc(at(to), at(s.centre), -1);
    else
      draft.feed(at(to));
  }
}

}  // namespace ncpost::stepnc::features
