#pragma once
// What the specs of every feature kind share (docs/features.md, "Read, then plan").

#include <optional>
#include <vector>

namespace ncpost::stepnc::features {

// Equal depth levels from 0 down to -depth, none deeper than `step` (one level when no step).
[[nodiscard]] std::vector<double> levels(double depth, std::optional<double> step);

}  // namespace ncpost::stepnc::features
