// From a workingstep to its generated path: the feature kind's reader turns the model into a
// typed spec (reading and checking everything), and its planner turns the spec into motions
// (docs/features.md, "Read, then plan"). Both report through one ModelReport, so diagnostics
// keep the order in which they were found.

#include <string>

#include "draft.hpp"
#include "face.hpp"
#include "general.hpp"
#include "holes.hpp"
#include "outside.hpp"
#include "pocket.hpp"
#include "reader.hpp"
#include "region.hpp"
#include "slot.hpp"
#include "step.hpp"
#include "threads.hpp"

namespace ncpost::stepnc::features {
namespace {

// A kind's reader fills its spec; only then does its planner draw the path.
template <class Spec>
bool read_then_plan(Reader& reader, Draft& draft, bool (*read)(Reader&, Spec&),
                    bool (*plan)(const Spec&, Draft&)) {
  Spec spec;
  return read(reader, spec) && plan(spec, draft);
}

// The same for the readers that go on from what a family's shared reader found.
template <class Spec, class Basics>
bool read_then_plan(Reader& reader, const Basics& basics, Draft& draft,
                    bool (*read)(Reader&, const Basics&, Spec&),
                    bool (*plan)(const Spec&, Draft&)) {
  Spec spec;
  return read(reader, basics, spec) && plan(spec, draft);
}

// A closed pocket: a round one with a half-ball floor, a general profile, or a rectangle or
// circle cleared as a region.
bool closed_pocket(Reader& reader, Draft& draft) {
  PocketBasics basics;
  if (!read_pocket_basics(reader, PocketKind::Closed, basics)) return false;
  if (basics.radiused)
    return read_then_plan(reader, basics, draft, read_radiused_pocket, plan_radiused_pocket);
  if (basics.general)
    return read_then_plan(reader, basics, draft, read_general_pocket, plan_general_pocket);
  return read_then_plan(reader, basics, draft, read_pocket_region, plan_region);
}

bool open_pocket(Reader& reader, Draft& draft) {
  PocketBasics basics;
  return read_pocket_basics(reader, PocketKind::Open, basics) &&
         read_then_plan(reader, basics, draft, read_open_pocket, plan_general_pocket);
}

bool outside_profile(Reader& reader, Draft& draft) {
  OutsideBoundary boundary;
  if (!read_outside_boundary(reader, boundary)) return false;
  if (boundary.general)
    return read_then_plan(reader, boundary, draft, read_general_outside, plan_general_outside);
  return read_then_plan(reader, boundary, draft, read_outside, plan_outside);
}

// A straight U slot is a region; a general section the passes fitted to it; every other slot
// the passes of a form tool. A course of travel
// with its own placement: the slot is planned in it, then its moves carried into the feature's.
bool slot(Reader& reader, Draft& draft) {
  SlotBasics basics;
  if (!read_slot_basics(reader, basics)) return false;
  const std::size_t first = draft.moves().size();
  const bool ok = basics.section.kind == SlotSection::Kind::General
                      ? read_then_plan(reader, basics, draft, read_section_slot, plan_section_slot)
                  : basics.region()
                      ? read_then_plan(reader, basics, draft, read_slot_region, plan_region)
                      : read_then_plan(reader, basics, draft, read_form_slot, plan_form_slot);
  if (ok) draft.place_from(first, basics.travel_frame);
  return ok;
}

// Free-form region milling (a REGION_SURFACE_LIST of B-spline or Bezier surfaces under a
// FREEFORM_OPERATION) needs a 3D toolpath (a parallel projection onto the surfaces) that the
// generator does not make: refused, naming the operation, the region and its surfaces' kinds.
bool freeform(Reader& reader) {
  const Instance& feature = reader.feature();
  std::string surfaces;
  if (const auto list = reader.get(feature, "surface_list"); list && list->is_list()) {
    std::size_t shown = 0;
    const auto items = reader.model().items(*list);
    for (const p21::Value& v : items) {
      if (!v.is_reference() || shown == 3) continue;
      surfaces += (shown++ == 0 ? " (" : ", ") + reader.name(reader.model().find(v.id()));
    }
    if (shown > 0)
      surfaces += items.size() > shown ? ", ... " + std::to_string(items.size()) + " in all)" : ")";
  }
  return reader.report().not_implemented(
      reader.name(reader.operation()) + " on " + reader.name(feature) + surfaces +
      ", free-form region milling (a 3D toolpath over the region's surfaces; give the "
      "workingstep an explicit toolpath),");
}

// The generator of the workingstep's feature kind (thread drilling by its operation: its
// feature is the THREAD, which names its hole).
bool generate_kind(Reader& reader, Draft& draft) {
  const Instance& feature = reader.feature();
  if (reader.is(&reader.operation(), "thread_drilling"))
    return read_then_plan(reader, draft, read_thread_drilling, plan_thread_drilling);
  if (reader.is(&feature, "planar_face"))
    return read_then_plan(reader, draft, read_face, plan_face);
  if (reader.is(&feature, "closed_pocket")) return closed_pocket(reader, draft);
  if (reader.is(&feature, "open_pocket")) return open_pocket(reader, draft);
  if (reader.is(&feature, "general_outside_profile")) return outside_profile(reader, draft);
  if (reader.is(&feature, "slot")) return slot(reader, draft);
  if (reader.is(&feature, "step")) return read_then_plan(reader, draft, read_step, plan_step);
  if (reader.is(&feature, "round_hole")) {
    // Milled (bottom-and-side or side milling: helix down, circles round), else drilled.
    if (reader.is(&reader.operation(), "bottom_and_side_milling") ||
        reader.is(&reader.operation(), "side_milling")) {
      if (reader.set(feature, "change_in_diameter"))
        return read_then_plan(reader, draft, read_milled_taper, plan_milled_taper);
      if (spherical_bottom(reader))
        return read_then_plan(reader, draft, read_milled_sphere, plan_milled_sphere);
      return read_then_plan(reader, draft, read_milled_hole, plan_region);
    }
    return read_then_plan(reader, draft, read_hole, plan_hole);
  }
  if (reader.is(&reader.operation(), "freeform_operation") || reader.is(&feature, "region"))
    return freeform(reader);
  return reader.report().not_implemented(reader.name(reader.operation()) + " on " +
                                         reader.name(feature) + " (this feature kind)");
}

}  // namespace

Path generate(detail::GeometryReader& geometry, const Request& request,
              const FeatureOptions& options) {
  const Instance& ws = *request.workingstep;
  ModelReport report(geometry, {&ws, geometry.model().type_name(ws)});
  Reader reader(geometry, request, options, report);
  Draft draft(options, report);
  if (request.feature == nullptr) {
    report.not_implemented(reader.name(request.operation) + " without a feature");
    return {};
  }
  bool ok = generate_kind(reader, draft);
  if (ok && draft.too_many()) ok = draft.limit_reached();
  return std::move(draft).finish(ok);
}

}  // namespace ncpost::stepnc::features
