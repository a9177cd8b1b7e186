#pragma once
// The building blocks of the EXPRESS schema model: source positions, expressions kept as text,
// and the type specifications (simple, named, aggregate, generic) that attributes, constants and
// TYPE declarations use. All identifiers are stored in lower case (EXPRESS is case-insensitive).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace ncpost::express {

// 1-based line and column of a declaration in the schema source; 0 means unknown.
struct SourcePos {
  std::uint32_t line = 0;
  std::uint32_t column = 0;
};

// A name written in the schema together with where it was written, so that an unresolved
// reference can be reported at its own position.
struct NamedRef {
  std::string name;  // lower case
  SourcePos pos;
};

// An EXPRESS expression (a DERIVE formula, a WHERE rule, a bound, a constant value). The parser
// checks that it is balanced and keeps it as normalised text: reserved words in upper case,
// identifiers in lower case, literals as written, one space between words. Nothing evaluates it.
struct Expression {
  std::string text;
  SourcePos pos;
};

// One bound of an aggregate: a plain integer, the indeterminate `?`, or another expression
// (e.g. `SELF\mesh.index_count`).
struct Bound {
  std::string text;                   // normalised expression text, "?" when indeterminate
  std::optional<std::int64_t> value;  // set when the bound is an integer literal
  [[nodiscard]] bool indeterminate() const noexcept { return text == "?"; }
};

enum class TypeKind : std::uint8_t {
  Integer,
  Real,
  Number,
  String,
  Binary,
  Boolean,
  Logical,
  Named,          // a reference to a defined type or an entity, see TypeSpec::name
  Aggregate,      // LIST / SET / BAG / ARRAY / AGGREGATE OF TypeSpec::element
  Select,         // only as the underlying type of a TYPE declaration
  Enumeration,    // only as the underlying type of a TYPE declaration
  Generic,        // GENERIC [: label], in function signatures
  GenericEntity,  // GENERIC_ENTITY [: label], in function signatures
};

enum class AggregateKind : std::uint8_t { List, Set, Bag, Array, Aggregate };

// A type as written: simple, a reference by name, or an aggregate of another TypeSpec. Element
// types are shared and immutable, so copying a TypeSpec is cheap.
struct TypeSpec {
  TypeKind kind = TypeKind::Integer;
  SourcePos pos;
  std::string name;  // Named: the referenced name; Generic/GenericEntity/AGGREGATE: the label

  // REAL (precision), STRING (width) [FIXED], BINARY (width) [FIXED]
  std::optional<Expression> width;
  bool fixed = false;

  // Aggregates. Bounds come in pairs; both are absent for an unbounded `SET OF x`.
  AggregateKind aggregate = AggregateKind::List;
  std::optional<Bound> lower;
  std::optional<Bound> upper;
  bool optional_elements = false;  // ARRAY [..] OF OPTIONAL x
  bool unique_elements = false;    // LIST/ARRAY [..] OF UNIQUE x
  std::shared_ptr<const TypeSpec> element;

  [[nodiscard]] bool is_simple() const noexcept { return kind <= TypeKind::Logical; }
};

// Keyword spelling of a simple type or aggregate ("INTEGER", "LIST", ...); empty for others.
[[nodiscard]] std::string_view simple_type_keyword(TypeKind kind) noexcept;
[[nodiscard]] std::string_view aggregate_keyword(AggregateKind kind) noexcept;

// The type written back as EXPRESS text, e.g. "LIST [1:3] OF length_measure"; for messages,
// docs and tests.
[[nodiscard]] std::string to_express(const TypeSpec& type);

}  // namespace ncpost::express
