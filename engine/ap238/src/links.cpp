#include "links.hpp"

#include <string_view>
#include <utility>

namespace ncpost::ap238::detail {
namespace {

// The attributes the ARM-to-AIM mapping follows backwards: an instance of `entity` (or of a
// subtype) is a referrer of what its `attribute` points at.
struct Rule {
  std::string_view entity;
  std::string_view attribute;
};
constexpr Rule kRules[] = {
    {"action_property", "definition"},  // a method's properties
    {"action_property_representation", "property"},
    {"resource_property", "resource"},  // a tool's properties
    {"resource_property_representation", "property"},
    {"action_method_relationship", "relating_method"},  // elements, operation, toolpaths, ...
    {"action_resource", "usage"},                       // the tool of an operation
    {"product_definition_formation", "of_product"},     // project → its definitions
    {"product_definition", "formation"},
    {"process_product_association", "defined_product"},  // project → main workplan
    {"process_product_association", "process"},          // set-up workplan → set-up
    {"action", "chosen_method"},                         // workplan → its processes
    {"process_property_association", "process"},         // feature process → feature
    {"property_definition", "definition"},               // set-up, feature → their shapes
    {"property_definition_representation", "definition"},
    {"product_definition_relationship", "relating_product_definition"},  // set-up → workpieces
    {"representation_relationship", "rep_1"},                            // tool body → dimensions
    {"context_dependent_shape_representation", "represented_product_relation"},
};

}  // namespace

Links::Links(const p21::Model& model, const stepnc::AttributeReader& attributes) : model_(model) {
  const express::SchemaSet& schema = attributes.schema();
  const auto instances = model.instances();

  // Per keyword, the parameter positions to follow (resolved once, not per instance).
  std::vector<const express::Entity*> rule_entities;
  for (const Rule& r : kRules) rule_entities.push_back(schema.find_entity(r.entity));
  std::vector<std::vector<std::uint32_t>> positions(model.keyword_count());
  for (p21::KeywordId k = 0; k < model.keyword_count(); ++k) {
    if (k == p21::Model::kComplexKeyword || k == p21::Model::kExternalKeyword) continue;
    const express::Entity* e = schema.find_entity(model.keyword(k));
    if (e == nullptr) continue;
    for (std::size_t r = 0; r < std::size(kRules); ++r) {
      if (rule_entities[r] == nullptr || !schema.is_subtype_of(*e, *rule_entities[r])) continue;
      if (const auto index = e->attribute_index(kRules[r].attribute))
        positions[k].push_back(static_cast<std::uint32_t>(*index));
    }
  }

  // (target, source) in file order of the sources, then a stable counting sort by target.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  const auto follow = [&](p21::Value v, std::uint32_t source) {
    const auto add = [&](p21::Value ref) {
      if (!ref.is_reference()) return;
      if (const p21::Instance* target = model.find(ref.id()))
        pairs.emplace_back(index_of(*target), source);
    };
    if (v.is_list()) {
      for (p21::Value item : model.items(v)) add(item);
    } else {
      add(v);
    }
  };
  for (std::uint32_t i = 0; i < instances.size(); ++i) {
    const p21::Instance& instance = instances[i];
    if (model.is_complex(instance)) {
      // Rare in AIM programs (units, contexts): read through the schema, record by record.
      for (std::size_t r = 0; r < std::size(kRules); ++r)
        if (rule_entities[r] != nullptr && attributes.is_a(instance, rule_entities[r]))
          if (const auto v = attributes.get(instance, kRules[r].attribute)) follow(*v, i);
      continue;
    }
    if (instance.keyword >= positions.size()) continue;
    const auto params = model.params(instance);
    for (const std::uint32_t p : positions[instance.keyword])
      if (p < params.size()) follow(params[p], i);
  }

  start_.assign(instances.size() + 1, 0);
  for (const auto& [target, source] : pairs) ++start_[target + 1];
  for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
  from_.resize(pairs.size());
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  for (const auto& [target, source] : pairs) from_[next[target]++] = source;
}

std::span<const std::uint32_t> Links::referrers(const p21::Instance& target) const {
  const std::uint32_t i = index_of(target);
  if (i + 1 >= start_.size()) return {};
  return {from_.data() + start_[i], start_[i + 1] - start_[i]};
}

}  // namespace ncpost::ap238::detail
