#pragma once
// What the schema says about each entity and attribute of one model, resolved once before
// writing or reading so the per-value work is a pointer walk, not a name look-up.

#include <deque>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"

namespace ncpost::p28::detail {

// A declared type, resolved.
struct TypePlan {
  enum class Kind : std::uint8_t {
    Unknown,  // no schema information: literals follow the P21 value
    Integer,
    Real,  // REAL and NUMBER
    String,
    Binary,
    Boolean,
    Logical,
    Enumeration,  // `name` is the enumeration type
    Entity,       // a reference; `name` is the entity
    Select,       // `name` is the select type
    Defined,      // a defined type over `underlying`; `name` is the type
    Aggregate,    // `element`, `aggregate` says which kind
  };
  Kind kind = Kind::Unknown;
  std::string name;
  express::AggregateKind aggregate = express::AggregateKind::List;
  const TypePlan* element = nullptr;
  const TypePlan* underlying = nullptr;
};

struct AttributePlan {
  std::string name;  // schema name, or "attr_N" when the entity is not in the schema
  bool inherited = false;
  bool derived = false;  // a subtype redeclares it as DERIVE: the value is `*`
  const TypePlan* type = nullptr;
};

struct EntityPlan {
  std::string name;    // lower case
  bool known = false;  // in the schema: attributes are named
  std::vector<AttributePlan> attributes;
  std::unordered_map<std::string, std::size_t> index_of;  // attribute name → position
};

class Binding {
 public:
  Binding(const express::SchemaSet* schemas);

  // The plan for an entity name (any case); built on first use. Unknown entities get a plan
  // with positional attribute names, sized to `min_attributes`.
  const EntityPlan& entity(std::string_view name, std::size_t min_attributes = 0);
  // The plan of a type named in a typed parameter (select members), or Unknown.
  const TypePlan* named_type(std::string_view name);
  const TypePlan* unknown() const { return &unknown_; }
  [[nodiscard]] bool has_schema() const { return schemas_ != nullptr; }
  // Only before the first entity or type is planned (the reader learns the schema from the
  // header, which comes first).
  void set_schemas(const express::SchemaSet* schemas) { schemas_ = schemas; }

 private:
  const TypePlan* plan(const express::TypeSpec& spec, int depth);
  const TypePlan* plan_named(std::string_view name, int depth);

  const express::SchemaSet* schemas_;
  TypePlan unknown_;
  std::deque<TypePlan> types_;  // stable addresses
  std::unordered_map<const express::TypeSpec*, const TypePlan*> by_spec_;
  std::unordered_map<std::string, const TypePlan*> by_name_;
  std::unordered_map<std::string, EntityPlan> entities_;
};

std::string lower(std::string_view s);
std::string upper(std::string_view s);
std::string positional_name(std::size_t index);  // "attr_1" for index 0

}  // namespace ncpost::p28::detail
