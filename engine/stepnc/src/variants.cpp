// The variants table (variants.hpp; docs/interoperability.md, "Variants").

#include "ncpost/stepnc/variants.hpp"

#include <array>
#include <cctype>

namespace ncpost::stepnc {
namespace {

using Kind = Variant::Kind;

// Adding a row: name where it comes from and what is assumed, add a case to
// tests/golden/tolerant/cases that uses it, and a row to docs/interoperability.md.
constexpr std::array kVariants{
    Variant{Kind::EntityAlias, "tool_dimension", "milling_tool_dimension",
            "programs of academic CAPP systems and Java STEP-NC toolkits, written before "
            "ISO 14649-111 named the entity MILLING_TOOL_DIMENSION",
            "a generic TOOL_DIMENSION read as a MILLING_TOOL_DIMENSION (diameter, tip half "
            "angle, circumference angle, cutting edge length, edge radius, edge centre)"},
    Variant{Kind::Supertype, "cutting_tool", "milling_cutting_tool",
            "toolkits that instantiate the ABSTRACT CUTTING_TOOL of ISO 14649-111 for every "
            "tool, drills and boring tools included",
            "the ABSTRACT CUTTING_TOOL read as a MILLING_CUTTING_TOOL (no spindle orientation); "
            "its tool body says what kind of tool it is"},
    Variant{Kind::SchemaName, "combined_schema", "machining_schema",
            "NIST's STEPNCpp toolkit: ISO 14649-10/-11/-12/-111/-121 combined in one schema "
            "named COMBINED_SCHEMA",
            "FILE_SCHEMA 'COMBINED_SCHEMA' read as ISO 14649 (MACHINING_SCHEMA): the file is "
            "checked against ncpost's ISO 14649 schema"},
};

template <Kind K>
constexpr auto aliases_of() {
  constexpr std::size_t n = [] {
    std::size_t count = 0;
    for (const Variant& v : kVariants) count += v.kind == K ? 1 : 0;
    return count;
  }();
  std::array<express::NameAlias, n> out{};
  std::size_t i = 0;
  for (const Variant& v : kVariants)
    if (v.kind == K) out[i++] = express::NameAlias{v.written, v.read_as};
  return out;
}

constexpr auto kEntityAliases = aliases_of<Kind::EntityAlias>();
constexpr auto kSchemaAliases = aliases_of<Kind::SchemaName>();

// Lower case, up to the first space or '{' (a FILE_SCHEMA entry's ASN.1 identifier).
bool same_name(std::string_view lower, std::string_view written) {
  std::size_t end = written.find_first_of(" {");
  if (end == std::string_view::npos) end = written.size();
  written = written.substr(0, end);
  if (written.size() != lower.size()) return false;
  for (std::size_t i = 0; i < lower.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(written[i])) != lower[i]) return false;
  return true;
}

}  // namespace

std::span<const Variant> variants() noexcept {
  return kVariants;
}

const Variant* find_variant(Variant::Kind kind, std::string_view written) noexcept {
  for (const Variant& v : kVariants)
    if (v.kind == kind && same_name(v.written, written)) return &v;
  return nullptr;
}

std::span<const express::NameAlias> entity_aliases(Mode mode) noexcept {
  if (mode == Mode::Strict) return {};
  return kEntityAliases;
}

std::span<const express::NameAlias> schema_aliases(Mode mode) noexcept {
  if (mode == Mode::Strict) return {};
  return kSchemaAliases;
}

}  // namespace ncpost::stepnc
