// The reading every feature reader shares (reader.hpp).

#include "reader.hpp"

#include <cmath>

#include "implicit.hpp"

namespace ncpost::stepnc::features {

void ModelReport::add(Finding finding) {
  const Instance* at = finding.at.instance ? finding.at.instance : workingstep().instance;
  geometry_.error(finding.code, *at, std::move(finding.message));
}

Reader::Reader(detail::GeometryReader& geometry, const Request& request,
               const FeatureOptions& options, Report& report)
    : geometry_(geometry),
      model_(geometry.model()),
      request_(request),
      options_(options),
      report_(report) {}

Subject Reader::subject(const Instance& instance) const {
  return {&instance, model_.type_name(instance)};
}

Subject Reader::subject(const Instance* instance) const {
  return instance ? subject(*instance) : Subject{};
}

std::string Reader::name(const Instance& instance) const {
  return subject(instance).name();
}

std::string Reader::name(const Instance* instance) const {
  return subject(instance).name();
}

bool Reader::is(const Instance* instance, std::string_view entity) {
  return instance != nullptr && geometry_.is_a(*instance, entity);
}

bool Reader::set(const Instance& owner, std::string_view attribute) {
  const auto v = geometry_.get(owner, attribute);
  return v && !v->is_omitted();
}

bool Reader::has_items(const Instance& owner, std::string_view attribute) {
  const auto v = geometry_.get(owner, attribute);
  return v && v->is_list() && v->count() > 0;
}

std::optional<p21::Value> Reader::get(const Instance& owner, std::string_view attribute) {
  return geometry_.get(owner, attribute);
}

const Instance* Reader::ref(const Instance& owner, std::string_view attribute,
                            std::string_view type) {
  if (!set(owner, attribute)) return nullptr;
  return geometry_.instance(geometry_.get(owner, attribute), type, &owner, attribute);
}

// A tolerant check (express::ValidateOptions::tolerant) lets '$' through where the schema
// requires a value; a reader that would otherwise take its default for it says so, as an error.
bool Reader::required_omitted(const Instance& owner, std::string_view attribute,
                              const std::optional<p21::Value>& value) {
  if (!value || !value->is_omitted()) return false;
  const express::Entity* entity = geometry_.attributes().entity(owner);
  if (entity == nullptr) return false;
  const auto index = entity->attribute_index(attribute);
  if (!index || entity->attributes[*index].optional) return false;
  return !report_.bad(subject(owner), name(owner) + " attribute " + std::string(attribute) +
                                          " is '$', but ISO 14649 requires it and the toolpath "
                                          "depends on it: nothing is assumed in its place");
}

std::optional<double> Reader::number(const Instance& owner, std::string_view attribute) {
  auto v = geometry_.get(owner, attribute);
  if (required_omitted(owner, attribute, v) || !v || v->is_omitted()) return std::nullopt;
  if (v->kind() == p21::ValueKind::Typed) v = model_.typed_child(*v);
  if (!v->is_number()) {
    report_.bad(subject(owner),
                name(owner) + " attribute " + std::string(attribute) + " is not a number");
    return std::nullopt;
  }
  const double x = model_.as_real(*v);
  if (!std::isfinite(x)) {
    report_.bad(subject(owner),
                name(owner) + " attribute " + std::string(attribute) + " is not a finite number");
    return std::nullopt;
  }
  return x;
}

std::optional<Toleranced> Reader::toleranced(const Instance& owner, std::string_view attribute) {
  const auto v = geometry_.get(owner, attribute);
  if (!v || v->is_omitted()) return std::nullopt;
  if (!v->is_reference()) {
    if (auto n = number(owner, attribute)) return Toleranced{*n, 0, 0};
    return std::nullopt;
  }
  const Instance* measure = geometry_.instance(v, "toleranced_length_measure", &owner, attribute);
  if (measure == nullptr) return std::nullopt;
  const auto size = number(*measure, "theoretical_size");
  if (!size) {
    report_.bad(subject(*measure), name(*measure) + " has no theoretical_size");
    return std::nullopt;
  }
  Toleranced out{*size, 0, 0};
  if (const Instance* tolerance = ref(*measure, "implicit_tolerance", "");
      tolerance != nullptr && geometry_.is_a(*tolerance, "plus_minus_value")) {
    out.upper = number(*tolerance, "upper_limit").value_or(0);
    out.lower = number(*tolerance, "lower_limit").value_or(0);
  }
  return out;
}

std::optional<bool> Reader::boolean(const Instance& owner, std::string_view attribute) {
  const auto v = geometry_.get(owner, attribute);
  if (required_omitted(owner, attribute, v) || !v || v->is_omitted()) return std::nullopt;
  const auto logical = model_.as_logical(*v);
  if (!logical || *logical == p21::Logical::Unknown) return std::nullopt;
  return *logical == p21::Logical::True;
}

std::string_view Reader::enumeration(const Instance& owner, std::string_view attribute) {
  const auto v = geometry_.get(owner, attribute);
  if (required_omitted(owner, attribute, v) || !v || v->kind() != p21::ValueKind::Enumeration)
    return {};
  return model_.enumeration(*v);
}

std::string Reader::text(const Instance& owner, std::string_view attribute) {
  const auto v = geometry_.get(owner, attribute);
  if (!v || v->kind() != p21::ValueKind::String) return {};
  return model_.as_string(*v);
}

std::optional<Vec3> Reader::direction(const Instance& owner, std::string_view attribute) {
  if (!set(owner, attribute)) return std::nullopt;
  return geometry_.direction(geometry_.get(owner, attribute));
}

std::optional<detail::Frame> Reader::placement(const Instance& owner, std::string_view attribute) {
  return geometry_.placement(geometry_.get(owner, attribute));
}

std::optional<Vec3> Reader::point(const Instance& owner, std::string_view attribute) {
  return geometry_.point(geometry_.get(owner, attribute));
}

bool Reader::size_ok(const Instance& at, double value, std::string_view what) {
  if (std::abs(value) <= options_.max_length) return true;
  return report_.bad(subject(at), name(at) + " " + std::string(what) + " " + fmt(value) +
                                      " is beyond the generator's limit of " +
                                      fmt(options_.max_length) +
                                      " mm (FeatureOptions::max_length)");
}

// Diagnostics: STEPNC-101 a depth plane not normal to the feature's axis; STEPNC-103 no depth
// plane, one at or above the top, or one deeper than FeatureOptions::max_length; and the
// geometry reader's for a bad placement.
std::optional<double> Reader::read_depth() {
  const Instance& f = feature();
  const Instance* plane = ref(f, "depth", "elementary_surface");
  if (plane == nullptr) {
    // A through hole's depth, when the tolerant mode takes it from the workpiece (implicit.hpp).
    if (std::optional<double> through; implicit_through_depth(*this, through)) return through;
    report_.bad(subject(f), name(f) + " has no depth plane");
    return std::nullopt;
  }
  const auto frame = placement(*plane, "position");
  if (!frame) return std::nullopt;
  if (std::abs(frame->z.z - 1) > 1e-9) {
    report_.not_implemented(name(*plane) + ", a depth plane not normal to " + name(f) + "'s axis");
    return std::nullopt;
  }
  const double depth = -frame->origin.z;
  if (depth > options_.max_length) {
    report_.bad(subject(*plane), name(*plane) + " lies " + fmt(depth) + " below the top of " +
                                     name(f) + ", beyond the generator's limit of " +
                                     fmt(options_.max_length) + " mm (FeatureOptions::max_length)");
    return std::nullopt;
  }
  if (!(depth > 0)) {
    report_.bad(subject(*plane), name(*plane) + " lies at or above the top of " + name(f) +
                                     " (depth " + std::to_string(depth) + ")");
    return std::nullopt;
  }
  return depth;
}

// Diagnostics: STEPNC-103 a tool without a milling tool body or a positive diameter, or a
// dimension that is not a number.
std::optional<Tool> Reader::read_tool() {
  const Instance& tool = *request_.tool;
  Tool out;
  out.subject = subject(tool);
  const Instance* body = ref(tool, "its_tool_body", "milling_machine_tool_body");
  if (body == nullptr) {
    report_.bad(out.subject, name(tool) + " has no milling tool body, so its size is unknown");
    return std::nullopt;
  }
  out.body = subject(*body);
  const Instance* dimension = ref(*body, "dimension", "milling_tool_dimension");
  const auto diameter = dimension ? number(*dimension, "diameter") : std::nullopt;
  if (!diameter || !(*diameter > 0)) {
    report_.bad(out.body, name(*body) + " (tool " + name(tool) + ") has no positive diameter");
    return std::nullopt;
  }
  out.radius = *diameter / 2;
  out.edge_length = number(*dimension, "cutting_edge_length");
  out.tip_half_angle = number(*dimension, "tool_tip_half_angle");
  out.corner_radius = number(*dimension, "edge_radius").value_or(0);
  out.left_hand = enumeration(*body, "hand_of_cut") == "LEFT";
  return out;
}

// Diagnostics: STEPNC-103 a parameter that is not a number; the geometry reader's for a
// strategy of the wrong type.
Operation Reader::read_operation() {
  const Instance& op = operation();
  Operation out;
  out.subject = subject(op);
  out.retract_plane = number(op, "retract_plane");
  out.axial = number(op, "axial_cutting_depth");
  out.radial = number(op, "radial_cutting_depth");
  out.allowance_side = number(op, "allowance_side").value_or(0);
  out.allowance_bottom = number(op, "allowance_bottom").value_or(0);
  out.strategy = subject(ref(op, "its_machining_strategy", ""));
  out.approach = subject(ref(op, "approach", "approach_retract_strategy"));
  out.retract = subject(ref(op, "retract", "approach_retract_strategy"));
  return out;
}

}  // namespace ncpost::stepnc::features
