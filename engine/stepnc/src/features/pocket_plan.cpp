// The round pocket with a half-ball floor: the planner (pocket.hpp).

#include <algorithm>

#include "pocket.hpp"

namespace ncpost::stepnc::features {

bool plan_radiused_pocket(const RadiusedPocketSpec& spec, Draft& draft) {
  const Vec3 axis = spec.axis;
  const double clear = draft.options().clearance;
  const double retract = spec.retract_plane.value_or(clear);
  draft.rapid({axis.x, axis.y, std::max(retract, clear)});
  if (retract > clear) draft.rapid({axis.x, axis.y, clear});
  for (const double z : spec.levels) draft.feed({axis.x, axis.y, z});
  draft.rapid({axis.x, axis.y, std::max(retract, clear)});
  return true;
}

}  // namespace ncpost::stepnc::features
