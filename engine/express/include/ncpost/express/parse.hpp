#pragma once
// EXPRESS source text in, SchemaSet and diagnostics out. The parser never throws for bad input,
// never prints and never aborts: every problem is a Diagnostic (codes EXP-0xx) with line:column,
// and parsing resynchronises at the next `;` or END_x so that one mistake gives one message.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/schema.hpp"

namespace ncpost::express {

// Named limits against hostile input; see docs/express.md.
struct ParseLimits {
  // Sources larger than this are rejected (EXP-040); the real long forms are below 1 MiB.
  std::size_t max_input_bytes = std::size_t{64} << 20;
  // Deepest nesting of parentheses/brackets in an expression, of aggregate types
  // (LIST OF LIST OF ...), of SUPERTYPE expressions and of FUNCTION/PROCEDURE/RULE blocks
  // (EXP-012). Type and supertype nesting are parsed recursively, so this also bounds the stack.
  std::uint32_t max_nesting_depth = 128;
  // Longest chain of SUBTYPE OF links (EXP-041). Flattened attribute lists grow with it; real
  // schemas stay below 20.
  std::uint32_t max_inheritance_depth = 64;
  // Parsing stops after this many errors (EXP-013).
  std::size_t max_errors = 200;
};

struct ParseResult {
  SchemaSet schemas;
  std::vector<diag::Diagnostic> diagnostics;

  [[nodiscard]] bool ok() const noexcept {
    for (const auto& d : diagnostics)
      if (d.severity == diag::Severity::Error) return false;
    return true;
  }
};

// Parses every SCHEMA in `source`, resolves USE FROM / REFERENCE FROM between them, checks the
// references and computes the flattened attributes. The SchemaSet is usable even when there are
// errors (declarations that failed to parse are left out).
[[nodiscard]] ParseResult parse_express(std::string_view source, const ParseLimits& limits = {});

// True when `name` can name an entity or a type (any case): an ISO 10303-11 simple_id (a letter,
// then letters, digits and underscores) that is no reserved word. Readers of other forms use it
// before a name becomes a P21 keyword.
[[nodiscard]] bool can_name_a_declaration(std::string_view name) noexcept;

}  // namespace ncpost::express
