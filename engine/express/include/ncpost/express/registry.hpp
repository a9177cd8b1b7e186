#pragma once
// Which EXPRESS schema describes a model.
//
// In:  the built-in schemas (schemas/iso14649.exp for ISO 14649 programs, and schemas/ap238_aim.exp
//      for AP238 AIM programs, FILE_SCHEMA 'INTEGRATED_CNC_SCHEMA'; both embedded into the
//      library at build time) and, optionally, every `.exp` file of a directory
//      (`ncpost ... --schemas DIR`).
// Out: for a model, the SchemaSet that its FILE_SCHEMA header names.
//
// Names are compared case-insensitively, and a FILE_SCHEMA entry's ASN.1 object identifier is
// ignored ('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }' names AUTOMOTIVE_DESIGN). Schemas of a
// directory take precedence over the built-ins, so a newer schema can replace either.
//
// Thread safety: build the registry first (constructor, add_directory, add); after that every
// const member may be called from any number of threads at once. The registry holds each
// parse through a shared_ptr, so a SchemaSet it hands out lives as long as the registry.

#include <filesystem>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/parse.hpp"
#include "ncpost/express/schema_cache.hpp"
#include "ncpost/express/validate.hpp"

namespace ncpost::p21 {
class Model;
}

namespace ncpost::express {

// The text of schemas/iso14649.exp as it was when the library was built; empty when the file did
// not exist when the build was configured.
[[nodiscard]] std::string_view builtin_schema_text() noexcept;
// The parse of builtin_schema_text(), run once per process. Never null.
[[nodiscard]] std::shared_ptr<const ParseResult> builtin_schema();
// The same for schemas/ap238_aim.exp, the AP238 AIM subset (SCHEMA integrated_cnc_schema).
[[nodiscard]] std::string_view builtin_aim_schema_text() noexcept;
[[nodiscard]] std::shared_ptr<const ParseResult> builtin_aim_schema();

// One source of schemas: a parsed file, or the built-in.
struct SchemaSource {
  std::string origin;  // the file's path, or "<built-in>"
  std::shared_ptr<const ParseResult> parsed;
  bool builtin = false;
  [[nodiscard]] const SchemaSet& set() const noexcept { return parsed->schemas; }
  // What checks against set() learn about its types (validate.hpp), learnt once: made by the
  // first call, from whichever thread; later calls wait for it or share it.
  [[nodiscard]] const CheckPlan& check_plan() const;

 private:
  mutable std::once_flag plan_made_;
  mutable std::unique_ptr<const CheckPlan> plan_;
};

// The diagnostics of one schema file, with positions in that file.
struct SchemaFileReport {
  std::filesystem::path file;
  std::vector<diag::Diagnostic> diagnostics;
};

// What select_for found. `source` is null when no registered schema matches the model.
// `diagnostics`: EXP-050 at the FILE_SCHEMA header entity, EXP-052 without a position.
struct SchemaSelection {
  const SchemaSource* source = nullptr;
  // select_or_builtin found no schema of the model's and chose the built-in: good enough to
  // read an ISO 14649 program by, but checking the model against it (validate.hpp) would only
  // report that the file is written for another schema.
  bool fallback = false;
  std::vector<diag::Diagnostic> diagnostics;
  [[nodiscard]] const SchemaSet* set() const noexcept {
    return source != nullptr ? &source->set() : nullptr;
  }
};

class SchemaRegistry {
 public:
  // A registry with the built-in schemas only. The ISO 14649 one's declared schemas
  // (MACHINING_SCHEMA, MILLING_SCHEMA) and the AP238 AIM one's (INTEGRATED_CNC_SCHEMA) map to
  // them, even if a built-in is empty.
  SchemaRegistry();

  // Adds each `*.exp` file of `directory` (not its subdirectories), in file-name order, each
  // parsed once through `cache`. A file with errors is reported (its own diagnostics, then
  // EXP-053) and left out; the others are still added. An unreadable directory gives IO-001.
  // A schema name that an earlier file already declared gives EXP-051 and keeps the earlier one.
  std::vector<SchemaFileReport> add_directory(const std::filesystem::path& directory,
                                              SchemaCache& cache = SchemaCache::process_wide());
  // Adds one parsed source (tests and uploads). Returns EXP-051 for names already registered by
  // another added source; `parsed` must have no errors (else nothing is added, EXP-053).
  std::vector<diag::Diagnostic> add(std::string origin, std::shared_ptr<const ParseResult> parsed);

  // The built-in ISO 14649 schema: the default and the fallback.
  [[nodiscard]] const SchemaSource& builtin() const noexcept { return *builtin_; }
  // The built-in AP238 AIM schema (origin "<built-in AP238 AIM>").
  [[nodiscard]] const SchemaSource& builtin_aim() const noexcept { return *builtin_aim_; }
  // Problems of the built-ins themselves: EXP-054 for each that is empty or does not parse
  // cleanly.
  [[nodiscard]] std::vector<diag::Diagnostic> builtin_diagnostics() const;

  // The source that declares `schema_name` (case-insensitive, ASN.1 id ignored); null if none.
  [[nodiscard]] const SchemaSource* find(std::string_view schema_name) const;
  // Every registered schema name, lower case, sorted.
  [[nodiscard]] std::vector<std::string> known_names() const;

  // The source for the model's FILE_SCHEMA names: the source of the first name that is known.
  // Each name that source does not declare gives EXP-050, and so does a model without names.
  [[nodiscard]] SchemaSelection select_for(const p21::Model& model) const;
  // The same, where a FILE_SCHEMA name that no source declares may be an alias's `written`: it
  // selects the source of the alias's `read_as`, with an INTEROP-001 note instead of EXP-050.
  [[nodiscard]] SchemaSelection select_for(const p21::Model& model,
                                           std::span<const NameAlias> aliases) const;
  // select_for, or the built-in (with an EXP-052 note after the EXP-050s) when no name is known.
  [[nodiscard]] SchemaSelection select_or_builtin(const p21::Model& model) const;
  [[nodiscard]] SchemaSelection select_or_builtin(const p21::Model& model,
                                                  std::span<const NameAlias> aliases) const;

  // 'AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }' → "automotive_design": the text before the
  // first space or '{', trimmed, in lower case.
  [[nodiscard]] static std::string normalise_name(std::string_view file_schema_entry);
  // The FILE_SCHEMA entries of a model as written (strings of its first parameter).
  [[nodiscard]] static std::vector<std::string> file_schema_names(const p21::Model& model);

 private:
  struct Name {
    std::string name;  // lower case
    const SchemaSource* source;
  };
  // find(), else the source of the first alias of `schema_name` whose read_as is known
  // (`used`: that alias).
  const SchemaSource* find(std::string_view schema_name, std::span<const NameAlias> aliases,
                           const NameAlias** used) const;
  void register_names(const SchemaSource& source, std::vector<diag::Diagnostic>* clashes);

  // unique_ptr: SchemaSelection and Name point at sources, which must not move when more are added.
  std::vector<std::unique_ptr<SchemaSource>> sources_;
  const SchemaSource* builtin_ = nullptr;
  const SchemaSource* builtin_aim_ = nullptr;
  std::vector<Name> names_;  // directory sources first, then the built-in's names
};

}  // namespace ncpost::express
