// The pure helpers of the specs every feature kind shares (spec.hpp).

#include "spec.hpp"

#include <algorithm>
#include <cmath>

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

}  // namespace ncpost::stepnc::features
