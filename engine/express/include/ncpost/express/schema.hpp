#pragma once
// The EXPRESS (ISO 10303-11) schema model: what the parser (parse.hpp) gives back.
//
// A SchemaSet holds every SCHEMA of one source, with USE FROM / REFERENCE FROM resolved between
// them. Each Entity carries, besides its declaration as written, its FLATTENED explicit
// attributes in ISO 10303-21 order, so a reader can map the n-th parameter of an instance to a
// name and a type: `set.find_entity("machining_workingstep")->attribute_index("its_operation")`.
// Identifiers are stored in lower case; every lookup by name is case-insensitive.
//
// Declarations refer to each other by DeclRef (schema index + declaration index), never by
// pointer, so a SchemaSet can be copied and moved freely.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "ncpost/express/types.hpp"

namespace ncpost::express {

namespace detail {
class Linker;
}

enum class DeclKind : std::uint8_t {
  Entity,
  Type,
  Constant,
  Function,
  Procedure,
  Rule,
  SubtypeConstraint,
};

// A declaration in a SchemaSet: `index` counts within the schema's vector for that kind
// (entities, types, constants or algorithms).
struct DeclRef {
  DeclKind kind = DeclKind::Entity;
  std::uint32_t schema = 0;
  std::uint32_t index = 0;
  friend bool operator==(const DeclRef&, const DeclRef&) = default;
};

// `SELF\entity.attribute`, or a plain `attribute` (entity empty) in a UNIQUE rule.
struct QualifiedAttribute {
  std::string entity;
  std::string attribute;
  SourcePos pos;
};

struct ExplicitAttribute {
  // The attribute's name: for `SELF\e.a RENAMED b` it is `b`, for `SELF\e.a` it is `a`.
  std::string name;
  SourcePos pos;
  TypeSpec type;
  bool optional = false;
  std::optional<QualifiedAttribute> redeclares;  // set for `SELF\e.a : narrower_type`
};

struct DerivedAttribute {
  std::string name;
  SourcePos pos;
  TypeSpec type;
  Expression expression;
  std::optional<QualifiedAttribute> redeclares;  // `SELF\e.a : T := expr` in DERIVE
};

struct InverseAttribute {
  std::string name;
  SourcePos pos;
  std::optional<AggregateKind> aggregate;  // Set or Bag; absent for a single reference
  std::optional<Bound> lower;
  std::optional<Bound> upper;
  NamedRef entity;            // the entity whose attribute points here
  std::string for_attribute;  // that attribute
  std::optional<QualifiedAttribute> redeclares;
};

struct UniqueRule {
  std::string label;  // may be empty
  SourcePos pos;
  std::vector<QualifiedAttribute> attributes;
};

struct DomainRule {
  std::string label;  // may be empty
  Expression expression;
};

// SUPERTYPE OF (...): ONEOF / AND / ANDOR over entity references.
struct SupertypeExpression {
  enum class Op : std::uint8_t { Entity, OneOf, And, AndOr };
  Op op = Op::Entity;
  NamedRef entity;                            // Op::Entity
  std::vector<SupertypeExpression> operands;  // the others
};

// One explicit attribute of an entity after flattening, at its ISO 10303-21 position.
struct FlatAttribute {
  std::string name;
  std::string owner;          // the entity that declares the attribute
  std::string declared_name;  // the name in the owner's declaration (differs after RENAMED)
  TypeSpec type;              // as narrowed by the most specific explicit redeclaration
  bool optional = false;
  // A subtype re-declares this attribute in DERIVE: an instance of the subtype holds `*` here.
  bool derived_redeclared = false;
  std::string redeclared_by;  // entity of the last redeclaration that applies; empty if none
  // The schema (number in the set) in which `type` is resolved: that of the entity whose
  // declaration `type` comes from (the owner, or the last redeclaring entity).
  std::uint32_t schema = 0;
};

struct Entity {
  std::string name;
  SourcePos pos;
  std::uint32_t schema = 0;

  bool is_abstract = false;         // ABSTRACT or ABSTRACT SUPERTYPE
  bool declares_supertype = false;  // SUPERTYPE written, with or without OF (...)
  std::optional<SupertypeExpression> subtype_constraint;  // the OF (...) part
  std::vector<NamedRef> supertypes;                       // SUBTYPE OF (...), in order

  std::vector<ExplicitAttribute> explicit_attributes;
  std::vector<DerivedAttribute> derived_attributes;
  std::vector<InverseAttribute> inverse_attributes;
  std::vector<UniqueRule> unique_rules;
  std::vector<DomainRule> where_rules;

  // Computed once the whole set is known:
  std::vector<DeclRef> supertype_refs;  // `supertypes` resolved, in order
  // Every supertype, transitively, each once, in attribute order: the roots first, then
  // depth-first left-to-right over SUBTYPE OF.
  std::vector<DeclRef> ancestors;
  std::vector<DeclRef> subtypes;          // direct subtypes
  std::vector<FlatAttribute> attributes;  // flattened explicit attributes, in P21 order

  // Case-insensitive lookups in `attributes`. When two supertypes both declare an attribute of
  // that name (the instance then has both), the first position is returned.
  [[nodiscard]] const FlatAttribute* attribute(std::string_view name) const;
  [[nodiscard]] std::optional<std::size_t> attribute_index(std::string_view name) const;
};

struct SelectSpec {
  bool extensible = false;
  bool generic_entity = false;  // EXTENSIBLE GENERIC_ENTITY SELECT: only entities may extend it
  std::optional<NamedRef> based_on;
  std::vector<NamedRef> items;  // as written; see SchemaSet::select_leaves for the closure
};

struct EnumerationSpec {
  bool extensible = false;
  std::optional<NamedRef> based_on;
  std::vector<std::string> items;  // as written; see SchemaSet::enumeration_items
};

struct TypeDecl {
  std::string name;
  SourcePos pos;
  std::uint32_t schema = 0;
  TypeSpec underlying;  // kind Select or Enumeration for the constructed types
  SelectSpec select;
  EnumerationSpec enumeration;
  std::vector<DomainRule> where_rules;
};

struct Constant {
  std::string name;
  SourcePos pos;
  TypeSpec type;
  Expression value;
};

enum class AlgorithmKind : std::uint8_t { Function, Procedure, Rule, SubtypeConstraint };

// FUNCTION, PROCEDURE, RULE and SUBTYPE_CONSTRAINT bodies are checked for balance and skipped;
// the declaration is kept by name (and, for RULE and SUBTYPE_CONSTRAINT, the entities it is for).
struct Algorithm {
  AlgorithmKind kind = AlgorithmKind::Function;
  std::string name;
  SourcePos pos;
  std::vector<NamedRef> applies_to;
};

enum class InterfaceKind : std::uint8_t { Use, Reference };

struct InterfaceItem {
  NamedRef item;
  std::string alias;  // `AS alias`; empty if none
};

struct Interface {
  InterfaceKind kind = InterfaceKind::Use;
  NamedRef schema;
  std::vector<InterfaceItem> items;  // empty: everything the schema declares or imports
};

// Declarations by lower-case name; looked up with a string_view, so that a look-up builds no
// string (the schema check looks names up for every kind of instance of every model).
struct NameHash {
  using is_transparent = void;
  [[nodiscard]] std::size_t operator()(std::string_view name) const noexcept {
    return std::hash<std::string_view>{}(name);
  }
};
using DeclMap = std::unordered_map<std::string, DeclRef, NameHash, std::equal_to<>>;

struct Schema {
  std::string name;
  std::string version;  // the optional schema_version_id string, as written (without quotes)
  SourcePos pos;
  std::vector<Interface> interfaces;
  std::vector<Constant> constants;
  std::vector<TypeDecl> types;
  std::vector<Entity> entities;
  std::vector<Algorithm> algorithms;
  // Declarations made in this schema (imports excluded), by lower-case name.
  DeclMap declarations;

  // Declarations of this schema only, case-insensitive.
  [[nodiscard]] const Entity* find_entity(std::string_view name) const;
  [[nodiscard]] const TypeDecl* find_type(std::string_view name) const;
};

class SchemaSet {
 public:
  [[nodiscard]] const std::vector<Schema>& schemas() const noexcept { return schemas_; }
  [[nodiscard]] const Schema* find_schema(std::string_view name) const;

  // The first declaration of that name in any schema of the set, case-insensitive.
  [[nodiscard]] const Entity* find_entity(std::string_view name) const;
  [[nodiscard]] const TypeDecl* find_type(std::string_view name) const;

  // A name as seen from inside schema number `schema`: its own declarations first, then what
  // its USE FROM / REFERENCE FROM clauses bring in (under their aliases).
  [[nodiscard]] std::optional<DeclRef> resolve(std::uint32_t schema, std::string_view name) const;

  // Preconditions: ref.kind is Entity (resp. Type) and ref comes from this set.
  [[nodiscard]] const Entity& entity(DeclRef ref) const;
  [[nodiscard]] const TypeDecl& type(DeclRef ref) const;
  [[nodiscard]] std::string_view name_of(DeclRef ref) const;

  // True when `entity` is `ancestor` or inherits from it (reflexive, like EXPRESS TYPEOF).
  [[nodiscard]] bool is_subtype_of(const Entity& entity, const Entity& ancestor) const;
  // Same by names; false when either name is not an entity of the set.
  [[nodiscard]] bool is_subtype_of(std::string_view entity, std::string_view ancestor) const;

  // Follows defined types to what they stand for: with `TYPE length_measure = REAL;`,
  // `underlying_type(length_measure)` is REAL. Stops at a simple type, an aggregate, a SELECT,
  // an ENUMERATION or an entity reference. `type` is resolved in schema number `schema`; the
  // result refers into this set or is `type` itself.
  [[nodiscard]] const TypeSpec& underlying_type(const TypeDecl& decl) const;
  [[nodiscard]] const TypeSpec& underlying_type(std::uint32_t schema, const TypeSpec& type) const;

  // The closure of a SELECT: nested SELECTs replaced by their items, extensions (SELECT
  // BASED_ON ... WITH) merged in both directions, duplicates removed. The leaves are entities
  // and non-SELECT defined types, in first-seen order. Empty for a non-SELECT.
  [[nodiscard]] std::vector<DeclRef> select_leaves(const TypeDecl& select) const;

  // The items of an ENUMERATION including those of the type it is based on and of the types
  // based on it (extensible enumerations), in declaration order, duplicates removed.
  [[nodiscard]] std::vector<std::string> enumeration_items(const TypeDecl& enumeration) const;

 private:
  friend class detail::Linker;
  std::vector<Schema> schemas_;
  std::vector<DeclMap> visible_;  // per schema, see resolve
};

}  // namespace ncpost::express
