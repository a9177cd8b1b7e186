// Dispatch from a workingstep to the generator of its feature family, and the readers every
// generator shares (tool, operation parameters, depth).

#include <cmath>

#include "context.hpp"
#include "draft.hpp"
#include "face.hpp"
#include "holes.hpp"
#include "reader.hpp"
#include "step.hpp"
#include "threads.hpp"

namespace ncpost::stepnc::features {
namespace legacy {

std::optional<double> Context::number(const Instance& owner, std::string_view attribute) {
  auto v = g.get(owner, attribute);
  if (!v || v->is_omitted()) return std::nullopt;
  if (v->kind() == p21::ValueKind::Typed) v = m.typed_child(*v);
  if (!v->is_number()) {
    bad(owner, d(owner) + " attribute " + std::string(attribute) + " is not a number");
    return std::nullopt;
  }
  const double x = m.as_real(*v);
  if (!std::isfinite(x)) {
    bad(owner, d(owner) + " attribute " + std::string(attribute) + " is not a finite number");
    return std::nullopt;
  }
  return x;
}

std::optional<Toleranced> Context::toleranced(const Instance& owner, std::string_view attribute) {
  const auto v = g.get(owner, attribute);
  if (!v || v->is_omitted()) return std::nullopt;
  if (!v->is_reference()) {
    if (auto n = number(owner, attribute)) return Toleranced{*n, 0, 0};
    return std::nullopt;
  }
  const Instance* t = g.instance(v, "toleranced_length_measure", &owner, attribute);
  if (t == nullptr) return std::nullopt;
  const auto size = number(*t, "theoretical_size");
  if (!size) {
    bad(*t, d(*t) + " has no theoretical_size");
    return std::nullopt;
  }
  Toleranced out{*size, 0, 0};
  if (const Instance* tol = ref(*t, "implicit_tolerance", "");
      tol != nullptr && g.is_a(*tol, "plus_minus_value")) {
    out.upper = number(*tol, "upper_limit").value_or(0);
    out.lower = number(*tol, "lower_limit").value_or(0);
  }
  return out;
}

std::optional<bool> Context::boolean(const Instance& owner, std::string_view attribute) {
  const auto v = g.get(owner, attribute);
  if (!v || v->is_omitted()) return std::nullopt;
  const auto l = m.as_logical(*v);
  if (!l || *l == p21::Logical::Unknown) return std::nullopt;
  return *l == p21::Logical::True;
}

std::string_view Context::enumeration(const Instance& owner, std::string_view attribute) {
  const auto v = g.get(owner, attribute);
  if (!v || v->kind() != p21::ValueKind::Enumeration) return {};
  return m.enumeration(*v);
}

std::optional<Vec3> Context::direction(const Instance& owner, std::string_view attribute) {
  if (!set(owner, attribute)) return std::nullopt;
  return g.direction(g.get(owner, attribute));
}

std::optional<double> Context::depth() {
  const Instance* plane = ref(feature(), "depth", "elementary_surface");
  if (plane == nullptr) {
    bad(feature(), d(feature()) + " has no depth plane");
    return std::nullopt;
  }
  const auto frame = g.placement(g.get(*plane, "position"));
  if (!frame) return std::nullopt;
  if (std::abs(frame->z.z - 1) > 1e-9) {
    not_implemented(d(*plane) + ", a depth plane not normal to " + d(feature()) + "'s axis");
    return std::nullopt;
  }
  const double depth = -frame->origin.z;
  if (depth > opt.max_length) {
    bad(*plane, d(*plane) + " lies " + fmt(depth) + " below the top of " + d(feature()) +
                    ", beyond the generator's limit of " + fmt(opt.max_length) +
                    " mm (FeatureOptions::max_length)");
    return std::nullopt;
  }
  if (!(depth > 0)) {
    bad(*plane, d(*plane) + " lies at or above the top of " + d(feature()) + " (depth " +
                    std::to_string(depth) + ")");
    return std::nullopt;
  }
  return depth;
}

std::optional<Tool> Context::tool() {
  Tool t;
  t.instance = req.tool;
  t.body = ref(*req.tool, "its_tool_body", "milling_machine_tool_body");
  if (t.body == nullptr) {
    bad(*req.tool, d(*req.tool) + " has no milling tool body, so its size is unknown");
    return std::nullopt;
  }
  const Instance* dim = ref(*t.body, "dimension", "milling_tool_dimension");
  const auto diameter = dim ? number(*dim, "diameter") : std::nullopt;
  if (!diameter || !(*diameter > 0)) {
    bad(*t.body, d(*t.body) + " (tool " + d(*req.tool) + ") has no positive diameter");
    return std::nullopt;
  }
  t.radius = *diameter / 2;
  t.edge_length = number(*dim, "cutting_edge_length");
  t.tip_half_angle = number(*dim, "tool_tip_half_angle");
  t.corner_radius = number(*dim, "edge_radius").value_or(0);
  t.left_hand = enumeration(*t.body, "hand_of_cut") == "LEFT";
  return t;
}

OperationData Context::operation() {
  OperationData o;
  o.retract_plane = number(op(), "retract_plane");
  o.axial = number(op(), "axial_cutting_depth");
  o.radial = number(op(), "radial_cutting_depth");
  o.allowance_side = number(op(), "allowance_side").value_or(0);
  o.allowance_bottom = number(op(), "allowance_bottom").value_or(0);
  o.strategy = ref(op(), "its_machining_strategy", "");
  o.approach = ref(op(), "approach", "approach_retract_strategy");
  o.retract = ref(op(), "retract", "approach_retract_strategy");
  return o;
}

}  // namespace legacy

namespace {

// Each feature kind: its reader fills the spec, its planner draws the path.
bool face(Reader& reader, Draft& draft) {
  FaceSpec spec;
  return read_face(reader, spec) && plan_face(spec, draft);
}

bool hole(Reader& reader, Draft& draft) {
  HoleSpec spec;
  return read_hole(reader, spec) && plan_hole(spec, draft);
}

bool thread_drilling(Reader& reader, Draft& draft) {
  ThreadSpec spec;
  return read_thread_drilling(reader, spec) && plan_thread_drilling(spec, draft);
}

bool step(Reader& reader, Draft& draft) {
  StepSpec spec;
  return read_step(reader, spec) && plan_step(spec, draft);
}

// A kind not yet split into reader and planner.
bool unsplit(bool (*generate)(legacy::Context&), detail::GeometryReader& geometry,
             const Request& request, const FeatureOptions& options, Draft& draft) {
  legacy::Context ctx(geometry, request, options);
  const bool ok = generate(ctx);
  for (const Move& move : ctx.path.moves) draft.add(move);
  return ok;
}

}  // namespace

Path generate(detail::GeometryReader& geometry, const Request& request,
              const FeatureOptions& options) {
  using namespace legacy;
  const Instance& ws = *request.workingstep;
  ModelReport report(geometry, {&ws, geometry.model().type_name(ws)});
  Reader reader(geometry, request, options, report);
  Draft draft(options, report);
  if (request.feature == nullptr) {
    report.not_implemented(reader.name(request.operation) + " without a feature");
    return {};
  }
  const auto old = [&](bool (*generate)(legacy::Context&)) {
    return unsplit(generate, geometry, request, options, draft);
  };
  bool ok = false;
  if (geometry.is_a(*request.operation, "thread_drilling")) {
    ok = thread_drilling(reader, draft);  // on a THREAD feature, which names its hole
  } else if (geometry.is_a(*request.feature, "planar_face")) {
    ok = face(reader, draft);
  } else if (geometry.is_a(*request.feature, "closed_pocket")) {
    ok = old(generate_pocket);
  } else if (geometry.is_a(*request.feature, "open_pocket")) {
    ok = old(generate_open_pocket);
  } else if (geometry.is_a(*request.feature, "general_outside_profile")) {
    ok = old(generate_outside_profile);
  } else if (geometry.is_a(*request.feature, "slot")) {
    ok = old(generate_slot);
  } else if (geometry.is_a(*request.feature, "step")) {
    ok = step(reader, draft);
  } else if (geometry.is_a(*request.feature, "round_hole")) {
    ok = hole(reader, draft);
  } else {
    report.not_implemented(reader.name(request.operation) + " on " + reader.name(request.feature) +
                           " (this feature kind)");
  }
  if (ok && draft.too_many()) ok = draft.limit_reached();
  return std::move(draft).finish(ok);
}

}  // namespace ncpost::stepnc::features
