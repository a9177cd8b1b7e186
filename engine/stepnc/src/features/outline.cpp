#include "outline.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpost::stepnc::features {
namespace {

using poly::P;

double angle_of(P v) {
  return std::atan2(v.y, v.x);
}

}  // namespace

P Element::tangent_at_start() const {
  if (!arc) return (end - start) * (1 / (end - start).length());
  const P r = (start - centre) * (1 / radius);
  return sweep > 0 ? P{-r.y, r.x} : P{r.y, -r.x};
}

P Element::tangent_at_end() const {
  if (!arc) return (end - start) * (1 / (end - start).length());
  const P r = (end - centre) * (1 / radius);
  return sweep > 0 ? P{-r.y, r.x} : P{r.y, -r.x};
}

void reverse(Outline& outline) {
  std::reverse(outline.elements.begin(), outline.elements.end());
  for (Element& e : outline.elements) {
    std::swap(e.start, e.end);
    e.sweep = -e.sweep;
  }
}

std::vector<Corner> corners(const Outline& outline) {
  std::vector<Corner> out;
  const auto& el = outline.elements;
  for (std::size_t i = outline.closed ? 0 : 1; i < el.size(); ++i) {
    const std::size_t b = (i + el.size() - 1) % el.size();
    const Element& before = el[b];
    const P t0 = before.tangent_at_end();
    const P t1 = el[i].tangent_at_start();
    const double turn = std::atan2(t0.cross(t1), t0.dot(t1));
    if (std::abs(turn) > 1e-9) out.push_back({el[i].start, turn, t0, t1, b, i});
  }
  return out;
}

namespace {
int pieces(const Element& e, double tolerance) {
  const double half =
      tolerance < e.radius ? std::acos(1 - tolerance / e.radius) : std::numbers::pi / 2;
  return std::max(1, static_cast<int>(std::min(1e9, std::ceil(std::abs(e.sweep) / (2 * half)))));
}
}  // namespace

std::optional<poly::Chain> tessellate(const Outline& outline, double tolerance, bool material_left,
                                      std::size_t max_points) {
  double count = 0;
  for (const Element& e : outline.elements) count += e.arc ? pieces(e, tolerance) + 1 : 1;
  if (count > static_cast<double>(max_points)) return std::nullopt;
  poly::Chain out;
  out.reserve(static_cast<std::size_t>(count) + 1);
  for (const Element& e : outline.elements) {
    out.push_back(e.start);
    if (!e.arc) continue;
    // Chords inside the circle when the material is outside it, else a polyline of tangents.
    const bool centre_left = e.sweep > 0;
    const bool inscribed = centre_left != material_left;
    const double r = e.radius;
    const int n = pieces(e, tolerance);
    const double step = e.sweep / n;
    const double a0 = angle_of(e.start - e.centre);
    if (inscribed) {
      for (int k = 1; k < n; ++k) {
        const double t = a0 + step * k;
        out.push_back(e.centre + P{std::cos(t), std::sin(t)} * r);
      }
    } else {
      const double rr = r / std::cos(step / 2);
      for (int k = 0; k < n; ++k) {
        const double t = a0 + step * (k + 0.5);
        out.push_back(e.centre + P{std::cos(t), std::sin(t)} * rr);
      }
    }
  }
  if (!outline.closed) out.push_back(outline.elements.back().end);
  return out;
}

}  // namespace ncpost::stepnc::features
