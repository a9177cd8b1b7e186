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
  Link link;
};
constexpr Rule kRules[] = {
    {"action_property", "definition", Link::PropertyDefinition},
    {"action_property_representation", "property", Link::PropertyRepresentation},
    {"resource_property", "resource", Link::ResourceProperty},
    {"resource_property_representation", "property", Link::ResourceRepresentation},
    {"action_method_relationship", "relating_method", Link::RelatingMethod},
    {"action_resource", "usage", Link::Usage},
    {"product_definition_formation", "of_product", Link::OfProduct},
    {"product_definition", "formation", Link::Formation},
    {"process_product_association", "defined_product", Link::DefinedProduct},
    {"process_product_association", "process", Link::Process},
    {"action", "chosen_method", Link::ChosenMethod},
    {"process_property_association", "process", Link::PropertyProcess},
    {"property_definition", "definition", Link::Definition},
    {"property_definition_representation", "definition", Link::RepresentedDefinition},
    {"product_definition_relationship", "relating_product_definition", Link::RelatingDefinition},
    {"representation_relationship", "rep_1", Link::Rep1},
    {"context_dependent_shape_representation", "represented_product_relation",
     Link::ProductRelation},
};

}  // namespace

std::string_view attribute_of(Link link) {
  for (const Rule& r : kRules)
    if (r.link == link) return r.attribute;
  return {};
}

Links::Links(const p21::Model& model, const stepnc::AttributeReader& attributes) : model_(model) {
  const express::SchemaSet& schema = attributes.schema();
  const auto instances = model.instances();

  // Per keyword, the parameter positions to follow (resolved once, not per instance).
  std::vector<const express::Entity*> rule_entities;
  for (const Rule& r : kRules) rule_entities.push_back(schema.find_entity(r.entity));
  // (position, rule) pairs per keyword.
  std::vector<std::vector<std::pair<std::uint32_t, Link>>> positions(model.keyword_count());
  for (p21::KeywordId k = 0; k < model.keyword_count(); ++k) {
    if (k == p21::Model::kComplexKeyword || k == p21::Model::kExternalKeyword) continue;
    const express::Entity* e = schema.find_entity(model.keyword(k));
    if (e == nullptr) continue;
    for (std::size_t r = 0; r < std::size(kRules); ++r) {
      if (rule_entities[r] == nullptr || !schema.is_subtype_of(*e, *rule_entities[r])) continue;
      if (const auto index = e->attribute_index(kRules[r].attribute))
        positions[k].emplace_back(static_cast<std::uint32_t>(*index), kRules[r].link);
    }
  }

  // Two passes over the links, counting then filling (a counting sort by target, stable, so
  // each target's referrers stay in file order), rather than one pass into a list of pairs:
  // the pairs of a 100 MB program would be another 36 MB to fault in and zero.
  std::uint32_t filling_source = 0;
  bool filling = false;
  start_.assign(instances.size() + 1, 0);
  const auto follow = [&](p21::Value v, Link link) {
    const auto add = [&](p21::Value ref) {
      if (!ref.is_reference()) return;
      const p21::Instance* target = model.find(ref.id());
      if (target == nullptr) return;
      const std::uint32_t t = index_of(*target);
      if (!filling) {
        ++start_[t + 1];
        return;
      }
      const std::uint32_t at = start_[t]++;
      from_[at] = filling_source;
      link_[at] = link;
    };
    if (v.is_list()) {
      for (p21::Value item : model.items(v)) add(item);
    } else {
      add(v);
    }
  };
  const auto pass = [&] {
    for (std::uint32_t i = 0; i < instances.size(); ++i) {
      const p21::Instance& instance = instances[i];
      filling_source = i;
      if (model.is_complex(instance)) {
        // Rare in AIM programs (units, contexts): read through the schema, record by record.
        for (std::size_t r = 0; r < std::size(kRules); ++r)
          if (rule_entities[r] != nullptr && attributes.is_a(instance, rule_entities[r]))
            if (const auto v = attributes.get(instance, kRules[r].attribute))
              follow(*v, kRules[r].link);
        continue;
      }
      if (instance.keyword >= positions.size()) continue;
      const auto params = model.params(instance);
      for (const auto& [p, link] : positions[instance.keyword])
        if (p < params.size()) follow(params[p], link);
    }
  };
  pass();
  for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
  from_.resize(start_.back());
  link_.resize(start_.back());
  filling = true;
  pass();  // start_[t] moves from t's first slot to the next target's first
  for (std::size_t i = start_.size() - 1; i > 0; --i) start_[i] = start_[i - 1];
  start_[0] = 0;
}

std::span<const std::uint32_t> Links::referrers(const p21::Instance& target) const {
  const std::uint32_t i = index_of(target);
  if (i + 1 >= start_.size()) return {};
  return {from_.data() + start_[i], start_[i + 1] - start_[i]};
}

std::span<const Link> Links::links(const p21::Instance& target) const {
  const std::uint32_t i = index_of(target);
  if (i + 1 >= start_.size()) return {};
  return {link_.data() + start_[i], start_[i + 1] - start_[i]};
}

}  // namespace ncpost::ap238::detail
