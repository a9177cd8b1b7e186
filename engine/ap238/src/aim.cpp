#include "aim.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace ncpost::ap238::detail {
namespace {

bool same_text(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; };
           return lower(x) == lower(y);
         });
}

// ISO 10303-41 si_prefix → factor.
std::optional<double> prefix_factor(std::string_view prefix) {
  static constexpr std::pair<std::string_view, double> kPrefixes[] = {
      {"EXA", 1e18},  {"PETA", 1e15},  {"TERA", 1e12},   {"GIGA", 1e9},
      {"MEGA", 1e6},  {"KILO", 1e3},   {"HECTO", 1e2},   {"DECA", 1e1},
      {"DECI", 1e-1}, {"CENTI", 1e-2}, {"MILLI", 1e-3},  {"MICRO", 1e-6},
      {"NANO", 1e-9}, {"PICO", 1e-12}, {"FEMTO", 1e-15}, {"ATTO", 1e-18}};
  for (const auto& [name, factor] : kPrefixes)
    if (same_text(prefix, name)) return factor;
  return std::nullopt;
}

// Exponents saturate: a hostile file nests units raised to large powers (16^9 overflows an int),
// and a unit whose exponent is that large is no speed or length anyway.
int saturated(std::int64_t exponent) {
  constexpr std::int64_t kLimit = 1 << 10;
  return static_cast<int>(std::clamp(exponent, -kLimit, kLimit));
}

Dimensions scaled(Dimensions d, int by) {
  const std::int64_t b = by;
  return {saturated(d.length * b), saturated(d.time * b), saturated(d.angle * b),
          saturated(d.revolution * b), saturated(d.other * std::abs(b))};
}

Dimensions sum(Dimensions a, Dimensions b) {
  return {saturated(std::int64_t{a.length} + b.length), saturated(std::int64_t{a.time} + b.time),
          saturated(std::int64_t{a.angle} + b.angle),
          saturated(std::int64_t{a.revolution} + b.revolution),
          saturated(std::int64_t{a.other} + b.other)};
}

}  // namespace

Aim::Aim(const p21::Model& model, const stepnc::AttributeReader& attributes,
         std::vector<diag::Diagnostic>& diagnostics)
    : model_(model),
      attributes_(attributes),
      diagnostics_(diagnostics),
      geometry_(model, attributes, diagnostics),
      links_(model, attributes) {}

std::string Aim::describe(const Instance& i) const {
  return stepnc::detail::describe(model_, i);
}

std::string Aim::text(const Instance& i, std::string_view attribute) {
  const auto v = get(i, attribute);
  return v && v->kind() == p21::ValueKind::String ? model_.as_string(*v) : std::string();
}

bool Aim::text_is(const Instance& i, std::string_view attribute, std::string_view wanted) {
  const auto v = get(i, attribute);
  if (!v || v->kind() != p21::ValueKind::String) return false;
  if (!v->needs_decoding()) return model_.slice(*v) == wanted;
  return model_.as_string(*v) == wanted;
}

const Instance* Aim::ref(const Instance& i, std::string_view attribute) {
  const auto v = get(i, attribute);
  return v && v->is_reference() ? model_.find(v->id()) : nullptr;
}

std::vector<const Instance*> Aim::instances_of(std::string_view entity) const {
  const express::SchemaSet& schema = attributes_.schema();
  const express::Entity* wanted = schema.find_entity(entity);
  std::vector<std::uint32_t> indices;
  if (wanted == nullptr) return {};
  for (p21::KeywordId k = 0; k < model_.keyword_count(); ++k) {
    const auto of_keyword = model_.instance_indices_of(k);
    if (k == p21::Model::kExternalKeyword || of_keyword.empty()) continue;
    if (k == p21::Model::kComplexKeyword) {
      for (const std::uint32_t i : of_keyword)
        if (attributes_.is_a(model_.instances()[i], wanted)) indices.push_back(i);
      continue;
    }
    const express::Entity* e = schema.find_entity(model_.keyword(k));
    if (e != nullptr && schema.is_subtype_of(*e, *wanted))
      indices.insert(indices.end(), of_keyword.begin(), of_keyword.end());
  }
  std::sort(indices.begin(), indices.end());
  std::vector<const Instance*> out;
  out.reserve(indices.size());
  for (const std::uint32_t i : indices)
    if (model_.instances()[i].id != 0) out.push_back(&model_.instances()[i]);
  return out;
}

std::vector<const Instance*> Aim::referring(const Instance& target, std::string_view entity,
                                            std::string_view attribute) {
  std::vector<const Instance*> out;
  const auto from = links_.referrers(target);
  const auto through = links_.links(target);
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (attribute_of(through[i]) != attribute) continue;
    const Instance& source = links_.instance(from[i]);
    if (is_a(source, entity)) out.push_back(&source);
  }
  return out;
}

std::vector<const Instance*> Aim::related(const Instance& method, std::string_view relationship) {
  const auto relationships = referring(method, relationship, "relating_method");
  struct Element {
    double position;
    const Instance* method;
  };
  std::vector<Element> elements;
  bool sequential = false;
  for (const Instance* r : relationships) {
    const Instance* target = ref(*r, "related_method");
    if (target == nullptr) continue;
    double position = 0;
    if (is_a(*r, "sequential_method")) {
      sequential = true;
      if (const auto p = get(*r, "sequence_position"); p && p->is_number())
        position = model_.as_real(*p);
    }
    elements.push_back({position, target});
  }
  if (sequential) {
    std::stable_sort(elements.begin(), elements.end(),
                     [](const Element& a, const Element& b) { return a.position < b.position; });
    const auto repeated =
        std::adjacent_find(elements.begin(), elements.end(),
                           [](const auto& a, const auto& b) { return a.position == b.position; });
    if (repeated != elements.end() && std::find(sequence_warned_.begin(), sequence_warned_.end(),
                                                method.id) == sequence_warned_.end()) {
      sequence_warned_.push_back(method.id);
      report(diag::Code::Ap238Sequence, method,
             describe(method) + ": several of its " + std::string(relationship) +
                 "s have sequence position " + std::to_string(repeated->position) +
                 "; those elements run in file order");
    }
  }
  std::vector<const Instance*> out;
  out.reserve(elements.size());
  for (const Element& e : elements) out.push_back(e.method);
  return out;
}

std::vector<Property> Aim::properties(const Instance& owner) {
  std::vector<Property> out;
  properties(owner, out);
  return out;
}

void Aim::properties(const Instance& owner, std::vector<Property>& out) {
  out.clear();
  const auto from = links_.referrers(owner);
  const auto through = links_.links(owner);
  for (std::size_t i = 0; i < from.size(); ++i) {
    const bool action = through[i] == Link::PropertyDefinition;
    if (!action && through[i] != Link::ResourceProperty) continue;
    const Instance& p = links_.instance(from[i]);
    Property& property = out.emplace_back();
    property.instance = &p;
    property.name = text(p, "name");
    const Link representation =
        action ? Link::PropertyRepresentation : Link::ResourceRepresentation;
    const auto pr_from = links_.referrers(p);
    const auto pr_through = links_.links(p);
    for (std::size_t k = 0; k < pr_from.size(); ++k)
      if (pr_through[k] == representation)
        if (const Instance* rep = ref(links_.instance(pr_from[k]), "representation"))
          property.representations.push_back(rep);
  }
}

const Instance* Aim::first_related(const Instance& method, std::string_view relationship,
                                   std::size_t& count) {
  const Instance* first = nullptr;
  count = 0;
  const auto from = links_.referrers(method);
  const auto through = links_.links(method);
  for (std::size_t i = 0; i < from.size(); ++i) {
    if (through[i] != Link::RelatingMethod) continue;
    const Instance& r = links_.instance(from[i]);
    if (!is_a(r, relationship)) continue;
    const Instance* target = ref(r, "related_method");
    if (target == nullptr) continue;
    if (first == nullptr) first = target;
    ++count;
  }
  return first;
}

const Instance* Aim::first_item(const Instance& representation, std::string_view entity,
                                std::string_view name) {
  const auto list = get(representation, "items");
  if (!list || !list->is_list()) return nullptr;
  for (const p21::Value v : model_.items(*list)) {
    const Instance* i = v.is_reference() ? model_.find(v.id()) : nullptr;
    if (i != nullptr && is_a(*i, entity) && (name.empty() || text_is(*i, "name", name))) return i;
  }
  return nullptr;
}

std::vector<const Instance*> Aim::items(const Instance& representation) {
  std::vector<const Instance*> out;
  const auto list = get(representation, "items");
  if (!list || !list->is_list()) return out;
  for (const p21::Value v : model_.items(*list))
    if (const Instance* i = v.is_reference() ? model_.find(v.id()) : nullptr) out.push_back(i);
  return out;
}

const Instance* Aim::item(const Property& p, std::string_view entity, std::string_view name) {
  const Instance* found = nullptr;
  p.representations.for_each([&](const Instance& rep) {
    if (found == nullptr) found = first_item(rep, entity, name);
  });
  return found;
}

std::optional<std::string> Aim::description_of(const Instance* item) {
  if (item == nullptr || !is_a(*item, "descriptive_representation_item")) return std::nullopt;
  return text(*item, "description");
}

const std::string& Aim::described(const Property& p) {
  static const std::string kNoText;
  if (p.representations.empty()) return kNoText;
  const std::uint64_t rep = p.representations.front()->id;
  if (const auto known = descriptions_.find(rep); known != descriptions_.end())
    return known->second;
  std::string text = description_of(item(p, "descriptive_representation_item")).value_or("");
  return descriptions_.emplace(rep, std::move(text)).first->second;
}

std::optional<Quantity> Aim::measure(const Instance& item) {
  auto v = get(item, "value_component");
  if (!v) return std::nullopt;
  if (v->kind() == p21::ValueKind::Typed) v = model_.typed_child(*v);
  if (!v->is_number()) return std::nullopt;
  const double value = model_.as_real(*v);
  const auto u = unit(get(item, "unit_component").value_or(p21::Value{}));
  if (!u || !std::isfinite(value)) return std::nullopt;
  return Quantity{value * u->factor, u->dimensions};
}

std::optional<Unit> Aim::unit(p21::Value reference, int depth) {
  if (depth > kMaxUnitDepth || !reference.is_reference()) return std::nullopt;
  if (const auto known = units_.find(reference.id()); known != units_.end()) return known->second;
  const Instance* u = model_.find(reference.id());
  if (u == nullptr) return std::nullopt;
  std::optional<Unit> result;
  if (is_a(*u, "derived_unit")) {
    Unit product;
    const auto elements = get(*u, "elements");
    bool readable = elements && elements->is_list();
    if (readable) {
      for (const p21::Value e : model_.items(*elements)) {
        const Instance* element = e.is_reference() ? model_.find(e.id()) : nullptr;
        const auto exponent = element ? get(*element, "exponent") : std::nullopt;
        const auto part =
            element ? unit(get(*element, "unit").value_or(p21::Value{}), depth + 1) : std::nullopt;
        if (!exponent || !exponent->is_number() || !part) {
          readable = false;
          break;
        }
        const double x = model_.as_real(*exponent);
        const double whole = std::round(x);
        if (!(std::abs(x - whole) <= 1e-9 && std::abs(whole) <= kMaxUnitExponent)) {
          // A fractional, huge or NaN power: nothing ncpost converts.
          product.dimensions.other = saturated(std::int64_t{product.dimensions.other} + 1);
          continue;
        }
        product.factor *= std::pow(part->factor, whole);
        product.dimensions = sum(product.dimensions, scaled(part->dimensions, int(whole)));
      }
    }
    if (readable) result = product;
  } else if (is_a(*u, "si_unit")) {
    const auto name = get(*u, "name");
    const auto prefix = get(*u, "prefix");
    double factor = 1;
    bool readable = name && name->kind() == p21::ValueKind::Enumeration;
    if (prefix && prefix->kind() == p21::ValueKind::Enumeration) {
      const auto f = prefix_factor(model_.enumeration(*prefix));
      readable = readable && f.has_value();
      factor = f.value_or(1);
    }
    if (readable) {
      const std::string_view n = model_.enumeration(*name);
      if (same_text(n, "METRE"))
        result = Unit{1000 * factor, kLength};
      else if (same_text(n, "SECOND"))
        result = Unit{factor, kTime};
      else if (same_text(n, "RADIAN"))
        result = Unit{factor, kAngle};
      else
        result = Unit{factor, Dimensions{0, 0, 0, 0, 1}};
    }
  } else if (is_a(*u, "conversion_based_unit")) {
    if (const Instance* m = ref(*u, "conversion_factor")) {
      auto v = get(*m, "value_component");
      if (v && v->kind() == p21::ValueKind::Typed) v = model_.typed_child(*v);
      const auto base = unit(get(*m, "unit_component").value_or(p21::Value{}), depth + 1);
      if (v && v->is_number() && base && std::isfinite(model_.as_real(*v)))
        result = Unit{model_.as_real(*v) * base->factor, base->dimensions};
    }
  } else if (is_a(*u, "context_dependent_unit")) {
    result = same_text(text(*u, "name"), "revolution") ? Unit{1, Dimensions{0, 0, 0, 1, 0}}
                                                       : Unit{1, Dimensions{0, 0, 0, 0, 1}};
  }
  if (result && (!std::isfinite(result->factor) || result->factor <= 0)) result.reset();
  units_.emplace(reference.id(), result);
  return result;
}

ContextUnits Aim::context_units(const Instance& representation) {
  const Instance* context = ref(representation, "context_of_items");
  if (context == nullptr) return {};
  if (const auto known = contexts_.find(context->id); known != contexts_.end())
    return known->second;
  ContextUnits units;
  if (is_a(*context, "global_unit_assigned_context")) {
    if (const auto list = get(*context, "units"); list && list->is_list()) {
      for (const p21::Value v : model_.items(*list)) {
        const auto u = unit(v);
        if (!u) continue;
        if (u->dimensions == kLength) units.mm_per_length = u->factor;
        if (u->dimensions == kAngle) units.radians_per_angle = u->factor;
      }
    }
  }
  contexts_.emplace(context->id, units);
  return units;
}

}  // namespace ncpost::ap238::detail
