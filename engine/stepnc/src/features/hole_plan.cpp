// ROUND_HOLE: the planner (holes.hpp). One canned cycle, or the motions it stands for with what
// it cannot say: the strategy's zones at their feed and speed, a first peck of its own depth, a
// dwell after each peck, the way out at a share of the feed.

#include <algorithm>

#include "holes.hpp"

namespace ncpost::stepnc::features {
namespace {

constexpr double kEps = 1e-9;

// The zone of a height (0 near the top, 1 between, 2 near the bottom), each with its feed and
// speed, set only when the zone changes.
class Zones {
 public:
  Zones(const HoleSpec& spec, Draft& draft)
      : spec_(spec),
        draft_(draft),
        z_start_(std::max(spec.bottom_z, -spec.zones.depth_start)),
        z_end_(std::min(0.0, spec.bottom_z + spec.zones.depth_end)) {}

  // Down from `from` to `to`, split at the zone borders so each piece runs at its zone's feed
  // and speed.
  void feed_to(double from, double to) {
    for (const double border : {z_start_, z_end_}) {
      if (border < from - kEps && border > to + kEps) {
        enter(zone(from - kEps));
        draft_.feed({0, 0, border});
        from = border;
      }
    }
    enter(zone(from - kEps));
    draft_.feed({0, 0, to});
  }

 private:
  [[nodiscard]] int zone(double z) const {
    return z > z_start_ + kEps ? 0 : z > z_end_ + kEps ? 1 : 2;
  }
  void enter(int zone) {
    if (zone == current_) return;
    const DrillingZones& s = spec_.zones;
    draft_.add({Move::Kind::FeedRate,
                {},
                {},
                1,
                spec_.feed * (zone == 0   ? s.feed_start
                              : zone == 2 ? s.feed_end
                                          : 1)});
    if (spec_.spindle != 0)
      draft_.add({Move::Kind::Spindle,
                  {},
                  {},
                  1,
                  spec_.spindle * (zone == 0   ? s.cut_start
                                   : zone == 2 ? s.cut_end
                                               : 1)});
    current_ = zone;
  }

  const HoleSpec& spec_;
  Draft& draft_;
  double z_start_;
  double z_end_;
  int current_ = -1;
};

Move cycle_of(const HoleSpec& spec) {
  Move cycle{Move::Kind::Cycle, {0, 0, spec.retract_z}};
  cycle.cycle = spec.cycle;
  cycle.bottom = spec.bottom_z;
  cycle.feed = spec.feed;
  cycle.dwell = spec.dwell;
  cycle.peck = spec.peck;
  cycle.peck_retract = spec.peck_retract;
  cycle.pitch = spec.pitch;
  cycle.rpm = spec.rpm;
  cycle.left_hand = spec.left_hand;
  cycle.spindle_stop = spec.spindle_stop;
  return cycle;
}

}  // namespace

bool plan_hole(const HoleSpec& spec, Draft& draft) {
  if (!spec.needs_motions()) {
    draft.add(cycle_of(spec));
    return true;
  }
  const double r_z = spec.retract_z;
  draft.rapid({0, 0, r_z});
  Zones zones(spec, draft);
  if (spec.cycle == Move::CycleKind::Drill) {
    zones.feed_to(r_z, spec.bottom_z);
  } else {
    double at = r_z;
    double target = std::max(spec.bottom_z, -spec.first_peck.value_or(spec.peck));
    for (;;) {
      zones.feed_to(at, target);
      if (target <= spec.bottom_z + kEps) break;
      if (spec.peck_dwell > 0) draft.add({Move::Kind::Dwell, {}, {}, 1, spec.peck_dwell});
      at = target + spec.peck_retract;
      if (spec.peck_retract > 0)
        draft.rapid({0, 0, at});
      else
        draft.rapid({0, 0, at = r_z});
      target = std::max(spec.bottom_z, target - spec.peck);
      if (draft.too_many()) return draft.limit_reached();
    }
  }
  const auto set_feed = [&](double v) { draft.add({Move::Kind::FeedRate, {}, {}, 1, v}); };
  if (spec.dwell > 0) draft.add({Move::Kind::Dwell, {}, {}, 1, spec.dwell});
  set_feed(spec.feed);
  if (spec.spindle != 0) draft.add({Move::Kind::Spindle, {}, {}, 1, spec.spindle});
  if (spec.feed_on_retract && *spec.feed_on_retract > 0) {
    set_feed(spec.feed * *spec.feed_on_retract);
    draft.feed({0, 0, r_z});
    set_feed(spec.feed);
  } else {
    draft.rapid({0, 0, r_z});
  }
  return true;
}

}  // namespace ncpost::stepnc::features
