#pragma once
// Edition and vendor variants of ISO 14649 that ncpost accepts, as one table of data
// (docs/interoperability.md, "Variants"): entity names of other editions read as their ISO 14649
// counterpart, ABSTRACT supertypes instantiated where ISO 14649 wants one of their subtypes, and
// FILE_SCHEMA names that mean the ISO 14649 schema under another name. Every row says where the
// variant comes from and what ncpost assumes when it reads it; nothing else in the engine knows
// a variant by name.
//
// The table applies in Mode::Tolerant (the default) only. Mode::Strict reads a file as it is
// written against the schema: no row of this table, no implicit value (features/implicit.hpp),
// no second reading of a unit (units.hpp).

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "ncpost/express/validate.hpp"

namespace ncpost::stepnc {

// How a program is read: `--strict` / `strict=true` is Strict.
enum class Mode : std::uint8_t { Tolerant, Strict };

struct Variant {
  enum class Kind : std::uint8_t {
    // An entity name ISO 14649 does not declare, read as the declared entity `read_as`, with
    // `read_as`'s attributes in `read_as`'s order (the schema check checks it as `read_as`).
    EntityAlias,
    // An ABSTRACT entity of ISO 14649 instantiated on its own; read as its subtype `read_as`,
    // whose extra attributes are all OPTIONAL, so they read as unset.
    Supertype,
    // A FILE_SCHEMA name read as the ISO 14649 schema `read_as` (the file is then checked).
    SchemaName,
  };
  Kind kind;
  std::string_view written;     // lower case, as other systems write it
  std::string_view read_as;     // lower case, the ISO 14649 name ncpost reads it as
  std::string_view source;      // where the variant comes from
  std::string_view assumption;  // what ncpost assumes in reading it (note and comment text)
};

// Every row, in the order docs/interoperability.md lists them.
[[nodiscard]] std::span<const Variant> variants() noexcept;

// The row of `kind` for `written` (any case; a FILE_SCHEMA entry's ASN.1 identifier ignored);
// null when there is none.
[[nodiscard]] const Variant* find_variant(Variant::Kind kind, std::string_view written) noexcept;

// The table's entity and schema rows as the schema check and the schema choice take them
// (express::NameAlias): empty in Mode::Strict.
[[nodiscard]] std::span<const express::NameAlias> entity_aliases(Mode mode) noexcept;
[[nodiscard]] std::span<const express::NameAlias> schema_aliases(Mode mode) noexcept;

}  // namespace ncpost::stepnc
