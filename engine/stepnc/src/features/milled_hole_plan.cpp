// A tapered ROUND_HOLE milled: the planner (holes.hpp). The core cylinder as a region, then the
// cone of the wall in full circles from the top down, each entered from the axis at its own
// height and left back to it.

#include "holes.hpp"

namespace ncpost::stepnc::features {

bool plan_milled_taper(const MilledTaperSpec& spec, Draft& draft) {
  if (!plan_region(spec.core, draft)) return false;
  const double clearance = draft.options().clearance;
  const double slope = (spec.top - spec.bottom) / spec.depth;
  draft.rapid({0, 0, clearance});
  for (const double z : spec.levels) {
    const double rho = spec.top + slope * z - spec.core.inset;
    draft.feed({0, 0, z});
    if (rho > 1e-9) {
      draft.feed({rho, 0, z});
      draft.arc({rho, 0, z}, {0, 0, z}, spec.core.ccw ? 1 : -1);
      draft.feed({0, 0, z});
    }
    if (draft.too_many()) return draft.limit_reached();
  }
  draft.rapid({0, 0, clearance});
  return true;
}

}  // namespace ncpost::stepnc::features
