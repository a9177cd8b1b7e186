// GENERAL_OUTSIDE_PROFILE: the planners (outside.hpp). Each level starts and ends at a lead-in
// point in the air beyond the ring, where the tool goes down and up at feed.

#include <algorithm>

#include "outside.hpp"
#include "polygon_paths.hpp"

namespace ncpost::stepnc::features {

bool plan_outside(const OutsideSpec& spec, Draft& draft) {
  const Loop ring = outside_ring(spec.shape, spec.offset);
  const double clear = draft.options().clearance;
  const double retract = spec.retract_plane.value_or(clear);
  const Vec3 lead_local = ring.start + Vec3{spec.tool_radius + clear, 0, 0};
  const auto at = [&](Vec3 p, double z) { return spec.shape.frame.point({p.x, p.y, z}); };
  draft.rapid(at(lead_local, std::max(retract, clear)));
  if (retract > clear) draft.rapid(at(lead_local, clear));
  for (const double zz : spec.levels) {
    draft.feed(at(lead_local, zz));
    play_loop(draft, ring, spec.shape.frame, spec.ccw, zz);
    draft.feed(at(lead_local, zz));
    if (draft.too_many()) return draft.limit_reached();
  }
  draft.rapid(at(lead_local, std::max(retract, clear)));
  return true;
}

// The lead-in point lies beyond the ring's rightmost point along +x, where nothing of the part
// can be.
bool plan_general_outside(const GeneralOutsideSpec& spec, Draft& draft) {
  const FeatureOptions& options = draft.options();
  const poly::Ring& ring = spec.ring;
  if (static_cast<double>(ring.size() + 4) * static_cast<double>(spec.levels.size()) >
      static_cast<double>(options.max_moves))
    return draft.limit_reached();
  std::size_t right = 0;
  for (std::size_t k = 1; k < ring.size(); ++k)
    if (ring[k].x > ring[right].x) right = k;
  const Nearest start{ring[right], right, 0};
  const poly::P lead = ring[right] + poly::P{spec.tool_radius + options.clearance, 0};
  const std::vector<PlaneSpan> spans =
      spans_of({ring_path(ring, start, spec.ccw), true}, options.chord_tolerance);
  const double clear = options.clearance;
  const double retract = spec.retract_plane.value_or(clear);
  draft.rapid(at(lead, std::max(retract, clear)));
  if (retract > clear) draft.rapid(at(lead, clear));
  for (const double z : spec.levels) {
    draft.feed(at(lead, z));
    draft.feed(at(ring[right], z));
    emit_spans(draft, spans, z);
    draft.feed(at(lead, z));
    if (draft.too_many()) return draft.limit_reached();
  }
  draft.rapid(at(lead, std::max(retract, clear)));
  return true;
}

}  // namespace ncpost::stepnc::features
