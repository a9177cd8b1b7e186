// THREAD_DRILLING: the planner (threads.hpp). Down the axis to the bottom, back up to the bottom
// of the thread, out to the thread, a helix up to the top with the thread's pitch (whole and
// part turns: counter-clockwise seen from above for a right-hand thread), back to the axis and
// out at rapid.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "threads.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

bool plan_thread_drilling(const ThreadSpec& spec, Draft& draft) {
  const double turns = spec.length / spec.pitch;
  if (turns > static_cast<double>(draft.options().max_moves)) return draft.limit_reached();
  const double whole = std::floor(turns + 1e-9);
  const double rest = turns - whole;
  const double end_angle = 2 * std::numbers::pi * rest * (spec.right ? 1 : -1);
  int n = static_cast<int>(whole);
  if (rest > 1e-9) n += 1;
  n = std::max(n, 1);

  const double offset = spec.offset;
  draft.rapid({0, 0, spec.retract_z});
  draft.feed({0, 0, spec.bottom_z});
  if (spec.dwell > 0) draft.add({Move::Kind::Dwell, {}, {}, 1, spec.dwell});
  if (spec.bottom_z < -spec.length - kEps) draft.feed({0, 0, -spec.length});
  draft.feed({offset, 0, -spec.length});
  draft.arc({offset * std::cos(end_angle), offset * std::sin(end_angle), 0}, {0, 0, 0},
            spec.right ? n : -n);
  draft.feed({0, 0, 0});
  draft.rapid({0, 0, spec.retract_z});
  return true;
}

}  // namespace ncpost::stepnc::features
