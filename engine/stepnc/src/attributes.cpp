#include "ncpost/stepnc/attributes.hpp"

#include <algorithm>
#include <span>

namespace ncpost::stepnc {
namespace {

// A simple instance's parameter at the schema position of `name` in `entity`.
std::optional<p21::Value> at_position(const express::Entity& entity,
                                      std::span<const p21::Value> params, std::string_view name) {
  // Schema names are lower case, and so is every name the engine asks for: an exact compare
  // finds them without the case-folding look-up, which stays as the fallback.
  for (std::size_t i = 0; i < entity.attributes.size(); ++i) {
    if (entity.attributes[i].name == name) {
      if (i >= params.size()) return std::nullopt;
      return params[i];
    }
  }
  const auto index = entity.attribute_index(name);
  if (!index || *index >= params.size()) return std::nullopt;
  return params[*index];
}

// A partial record holds the explicit attributes its own entity declares (not redeclarations),
// in declaration order (ISO 10303-21 external mapping).
std::optional<p21::Value> in_record(const express::Entity& entity,
                                    std::span<const p21::Value> params, std::string_view name) {
  std::size_t position = 0;
  for (const auto& a : entity.explicit_attributes) {
    if (a.redeclares) continue;
    if (a.name.size() == name.size() &&
        std::equal(a.name.begin(), a.name.end(), name.begin(), [](char stored, char wanted) {
          return stored == (wanted >= 'A' && wanted <= 'Z' ? wanted - 'A' + 'a' : wanted);
        }))
      return position < params.size() ? std::optional(params[position]) : std::nullopt;
    ++position;
  }
  return std::nullopt;
}

std::optional<p21::Value> complex_attribute(const p21::Model& model,
                                            const express::SchemaSet& schema,
                                            const p21::Instance& instance, std::string_view name) {
  for (const p21::Value record : model.params(instance)) {
    if (record.kind() != p21::ValueKind::Typed) continue;
    const express::Entity* e = schema.find_entity(model.keyword(record.keyword_id()));
    const p21::Value list = model.typed_child(record);
    if (e == nullptr || !list.is_list()) continue;
    if (auto v = in_record(*e, model.items(list), name)) return v;
  }
  return std::nullopt;
}

}  // namespace

AttributeReader::AttributeReader(const p21::Model& model, const express::SchemaSet& schema,
                                 Mode mode)
    : model_(model), schema_(schema), mode_(mode), executable_(schema.find_entity("executable")) {
  by_keyword_.reserve(model.keyword_count());
  variant_by_keyword_.assign(model.keyword_count(), nullptr);
  for (p21::KeywordId k = 0; k < model.keyword_count(); ++k) {
    if (k == p21::Model::kComplexKeyword || k == p21::Model::kExternalKeyword) {
      by_keyword_.push_back(nullptr);
      continue;
    }
    const std::string_view written = model.keyword(k);
    const express::Entity* e = schema.find_entity(written);
    if (mode == Mode::Tolerant) {
      // The table's rows, the only place that knows a variant (variants.hpp).
      const Variant* row = e == nullptr     ? find_variant(Variant::Kind::EntityAlias, written)
                           : e->is_abstract ? find_variant(Variant::Kind::Supertype, written)
                                            : nullptr;
      if (const express::Entity* read_as = row ? schema.find_entity(row->read_as) : nullptr) {
        e = read_as;
        variant_by_keyword_[k] = row;
      }
    }
    by_keyword_.push_back(e);
  }
}

const Variant* AttributeReader::variant(const p21::Instance& instance) const {
  return instance.keyword < variant_by_keyword_.size() ? variant_by_keyword_[instance.keyword]
                                                       : nullptr;
}

const express::Entity* AttributeReader::entity(const p21::Instance& instance) const {
  return instance.keyword < by_keyword_.size() ? by_keyword_[instance.keyword] : nullptr;
}

std::optional<p21::Value> AttributeReader::get(const p21::Instance& instance,
                                               std::string_view name) const {
  if (model_.is_complex(instance)) return complex_attribute(model_, schema_, instance, name);
  const express::Entity* e = entity(instance);
  if (e == nullptr) return std::nullopt;
  return at_position(*e, model_.params(instance), name);
}

bool AttributeReader::is_a(const p21::Instance& instance, std::string_view name) const {
  return is_a(instance, schema_.find_entity(name));
}

bool AttributeReader::is_a(const p21::Instance& instance, const express::Entity* ancestor) const {
  if (ancestor == nullptr) return false;
  if (!model_.is_complex(instance)) {
    const express::Entity* e = entity(instance);
    return e != nullptr && schema_.is_subtype_of(*e, *ancestor);
  }
  for (const p21::Value record : model_.params(instance)) {
    if (record.kind() != p21::ValueKind::Typed || record.keyword_id() >= by_keyword_.size())
      continue;
    const express::Entity* e = by_keyword_[record.keyword_id()];
    if (e != nullptr && schema_.is_subtype_of(*e, *ancestor)) return true;
  }
  return false;
}

std::optional<p21::Value> attribute(const p21::Model& model, const express::SchemaSet& schema,
                                    const p21::Instance& instance, std::string_view name) {
  if (model.is_complex(instance)) return complex_attribute(model, schema, instance, name);
  const express::Entity* e = schema.find_entity(model.type_name(instance));
  if (e == nullptr) return std::nullopt;
  return at_position(*e, model.params(instance), name);
}

}  // namespace ncpost::stepnc
