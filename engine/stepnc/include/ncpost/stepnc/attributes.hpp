#pragma once
// Reading ISO 14649 attributes by name, through the EXPRESS schema.
//
// The position of an attribute comes from the schema's flattened attribute list of the
// instance's own entity (supertype attributes first, as ISO 10303-21 orders them), so callers ask
// `reader.get(op, "its_tool")` whatever the operation's entity is. Nothing here knows a position.

#include <optional>
#include <string_view>
#include <vector>

#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/stepnc/variants.hpp"

namespace ncpost::stepnc {

// Attribute access for one model and one schema. Built once per model (it resolves every
// keyword of the model to its entity); read-only afterwards, so it may be shared by threads.
// The model and the schema must outlive it.
//
// Mode::Tolerant (the default, as every job's unless `--strict`) applies the variants table
// (variants.hpp): an instance of an entity alias (TOOL_DIMENSION) or of an ABSTRACT supertype
// the table names (CUTTING_TOOL) is read as the entity the table gives, and variant() tells the
// readers so, which note it. Mode::Strict reads the entities as written.
class AttributeReader {
 public:
  AttributeReader(const p21::Model& model, const express::SchemaSet& schema,
                  Mode mode = Mode::Tolerant);

  [[nodiscard]] Mode mode() const noexcept { return mode_; }
  // The variants-table row the instance is read through (a simple instance only); null when it
  // is read as written.
  [[nodiscard]] const Variant* variant(const p21::Instance& instance) const;

  // The value of attribute `name` (any case) of `instance`, or nullopt when the schema does not
  // know the instance's entity, the entity has no such attribute, or the instance has fewer
  // parameters than the schema gives it. For a complex instance, the partial record of the
  // entity that declares the attribute.
  [[nodiscard]] std::optional<p21::Value> get(const p21::Instance& instance,
                                              std::string_view name) const;

  // The schema entity of a simple instance; null for complex instances and unknown entities.
  [[nodiscard]] const express::Entity* entity(const p21::Instance& instance) const;

  // True when the instance's entity (for a complex instance: one of its partial records) is
  // `entity` or a subtype of it.
  [[nodiscard]] bool is_a(const p21::Instance& instance, std::string_view entity) const;
  [[nodiscard]] bool is_a(const p21::Instance& instance, const express::Entity* entity) const;

  // ISO 14649-10 EXECUTABLE and its subtypes: what a workplan's element list may hold.
  [[nodiscard]] bool is_executable(const p21::Instance& instance) const {
    return is_a(instance, executable_);
  }

  [[nodiscard]] const express::SchemaSet& schema() const noexcept { return schema_; }

 private:
  const p21::Model& model_;
  const express::SchemaSet& schema_;
  Mode mode_;
  std::vector<const express::Entity*> by_keyword_;  // keyword id → entity, null when unknown
  std::vector<const Variant*> variant_by_keyword_;  // keyword id → its row, null: as written
  const express::Entity* executable_ = nullptr;
};

// One look-up without keeping a reader (resolves the entity by name each time).
[[nodiscard]] std::optional<p21::Value> attribute(const p21::Model& model,
                                                  const express::SchemaSet& schema,
                                                  const p21::Instance& instance,
                                                  std::string_view name);

}  // namespace ncpost::stepnc
