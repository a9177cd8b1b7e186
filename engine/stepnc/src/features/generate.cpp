// Dispatch from a workingstep to the generator of its feature family, and the readers every
// generator shares (tool, operation parameters, depth).

#include <cmath>

#include "context.hpp"

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

Path generate(detail::GeometryReader& geometry, const Request& request,
              const FeatureOptions& options) {
  using namespace legacy;
  Context ctx(geometry, request, options);
  if (request.feature == nullptr) {
    ctx.not_implemented(ctx.d(request.operation) + " without a feature");
    return {};
  }
  bool ok = false;
  if (geometry.is_a(*request.operation, "thread_drilling")) {
    ok = generate_thread_drilling(ctx);  // on a THREAD feature, which names its hole
  } else if (geometry.is_a(*request.feature, "planar_face")) {
    ok = generate_face(ctx);
  } else if (geometry.is_a(*request.feature, "closed_pocket")) {
    ok = generate_pocket(ctx);
  } else if (geometry.is_a(*request.feature, "open_pocket")) {
    ok = generate_open_pocket(ctx);
  } else if (geometry.is_a(*request.feature, "general_outside_profile")) {
    ok = generate_outside_profile(ctx);
  } else if (geometry.is_a(*request.feature, "slot")) {
    ok = generate_slot(ctx);
  } else if (geometry.is_a(*request.feature, "step")) {
    ok = generate_step(ctx);
  } else if (geometry.is_a(*request.feature, "round_hole")) {
    ok = generate_hole(ctx);
  } else {
    ctx.not_implemented(ctx.d(*request.operation) + " on " + ctx.d(*request.feature) +
                        " (this feature kind)");
  }
  if (ok && ctx.too_many()) ok = ctx.limit_reached();
  ctx.path.ok = ok;
  if (!ok) ctx.path.moves.clear();
  return std::move(ctx.path);
}

}  // namespace ncpost::stepnc::features
