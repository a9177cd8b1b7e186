// The pure helpers of the specs every feature kind shares (spec.hpp).

#include "spec.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ncpost::stepnc::features {

std::vector<double> levels(double depth, std::optional<double> step) {
  std::size_t n = 1;
  if (step && *step > 0) n = static_cast<std::size_t>(std::ceil(depth / *step - 1e-9));
  n = std::max<std::size_t>(n, 1);
  std::vector<double> out;
  out.reserve(n);
  // Each level from the top, not by accumulation: no drift, and the last is exactly -depth.
  for (std::size_t k = 1; k <= n; ++k)
    out.push_back(k == n ? -depth : -depth * static_cast<double>(k) / static_cast<double>(n));
  return out;
}

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

// NIST's ex1 gives a 20 mm twist drill a tool_tip_half_angle of 31°: read as the angle between
// the cutting edge and the plane normal to the axis (a standard 118° point), as NIST's
// interpreter does. A value of 90° or more cannot be a half angle in either reading; it is taken
// as the whole point angle (the project's bracket example gives its drill 118).
double tip_length(const Tool& tool) {
  if (!tool.tip_half_angle || !(*tool.tip_half_angle > 0) || !(*tool.tip_half_angle < 180))
    return 0;
  const double a = *tool.tip_half_angle * std::numbers::pi / 180.0;
  return *tool.tip_half_angle < 90 ? tool.radius * std::tan(a) : tool.radius / std::tan(a / 2);
}

double point_angle(double tip_half_angle) {
  return tip_half_angle < 90 ? 180 - 2 * tip_half_angle : tip_half_angle;
}

}  // namespace ncpost::stepnc::features
