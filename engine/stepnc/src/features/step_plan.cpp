// STEP: the planner (step.hpp). Across (t, from the open boundary towards the wall): the last
// pass R + allowance off the wall, the first with the tool reaching the overlap past the open
// boundary, evenly between, none further apart than the stepover; along: each from R +
// clearance before the step's start to as far past its end. Between passes that do not join
// beyond the open end the tool goes up, over and down outside the part, as faces do.

#include <algorithm>
#include <cmath>

#include "step.hpp"

namespace ncpost::stepnc::features {

bool plan_step(const StepSpec& spec, Draft& draft) {
  const FeatureOptions& options = draft.options();
  const std::vector<double>& z_levels = spec.levels;
  const double r = spec.tool_radius;
  const double width = std::abs(spec.width);
  const double t_wall = width - r - spec.allowance_side;
  const double t_first = std::min(t_wall, r - spec.overlap * 2 * r);
  if ((t_wall - t_first) / spec.stepover > static_cast<double>(options.max_moves) ||
      (t_wall - t_first) / spec.stepover * static_cast<double>(z_levels.size()) >
          static_cast<double>(options.max_moves))
    return draft.limit_reached();
  std::vector<double> across;
  const auto n = static_cast<std::size_t>(std::ceil((t_wall - t_first) / spec.stepover - 1e-9));
  for (std::size_t k = 0; k <= n; ++k)
    across.push_back(n == 0 ? t_wall
                            : t_first + (t_wall - t_first) * static_cast<double>(k) /
                                            static_cast<double>(n));
  if (spec.walls_only) across.erase(across.begin(), across.end() - 1);

  const Vec3 left = Vec3{0, 0, 1}.cross(spec.along);
  const double wall_side = spec.width > 0 ? 1 : -1;  // the wall is to the left of +along when > 0
  const double run = r + options.clearance;
  const double s0 = -run;
  const double s1 = spec.length + run;
  const auto at = [&](double s, double t, double z) {
    return spec.origin + spec.along * s + left * (t * wall_side) + Vec3{0, 0, z};
  };
  const double clear = options.clearance;
  const double retract = spec.retract_plane.value_or(clear);
  bool first = true;
  for (const double z : z_levels) {
    for (std::size_t k = 0; k < across.size(); ++k) {
      const bool fwd = spec.one_way ? spec.forward : (k % 2 == 0) == spec.forward;
      const double from = fwd ? s0 : s1;
      const double to = fwd ? s1 : s0;
      if (first) {
        draft.rapid(at(from, across[k], std::max(retract, clear)));
        if (retract > clear) draft.rapid(at(from, across[k], clear));
        draft.feed(at(from, across[k], z));
        first = false;
      } else if (k == 0 || spec.one_way) {
        // Up, over (outside the part) and down at feed, as faces do between levels.
        const Vec3 here = draft.here();
        draft.rapid({here.x, here.y, clear});
        draft.rapid(at(from, across[k], clear));
        draft.feed(at(from, across[k], z));
      } else {
        draft.feed(at(from, across[k], z));  // step over beyond the open end
      }
      draft.feed(at(to, across[k], z));
    }
    if (draft.too_many()) return draft.limit_reached();
  }
  const Vec3 end = draft.here();
  draft.rapid({end.x, end.y, std::max(retract, clear)});
  return true;
}

}  // namespace ncpost::stepnc::features
