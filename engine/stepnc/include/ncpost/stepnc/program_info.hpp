#pragma once
// Program-information extraction: what a STEP-NC controller shows before it runs a program.
//
// In:  a Model (read from P21 or P28) and the EXPRESS schema that describes it: every attribute
//      is read by name through the schema (attributes.hpp), and "executable" means a subtype of
//      ISO 14649-10 EXECUTABLE in that schema.
// Out: JSON with the header, the PROJECT → main WORKPLAN → executables tree (recursively), the
//      workpieces and tools, instance counts by entity type, and diagnostics about the program
//      structure. The JSON shape is a contract shared by `ncpost inspect` and the HTTP service;
//      docs/inspect.md describes it.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/express/schema.hpp"
#include "ncpost/p21/model.hpp"

namespace ncpost::stepnc {

struct ProgramInfo {
  nlohmann::ordered_json json;                // without the "diagnostics" member
  std::vector<diag::Diagnostic> diagnostics;  // about the program structure
};

struct InspectOptions {
  // Workplans nested deeper than this are reported instead of followed.
  unsigned max_nesting = 64;
};

// With the schema given: no check that it is the model's.
[[nodiscard]] ProgramInfo inspect(const p21::Model& model, const express::SchemaSet& schema,
                                  const InspectOptions& options = {});
// With the schema the registry selects for the model's FILE_SCHEMA; when it has none, the
// built-in ISO 14649 schema, and the diagnostics say so (EXP-050 warning, EXP-052 note).
[[nodiscard]] ProgramInfo inspect(const p21::Model& model, const express::SchemaRegistry& schemas,
                                  const InspectOptions& options = {});

// Why a model without a PROJECT is not an ISO 14649 program: an AP238 AIM file (STEPNC-006:
// engine/ap238 reads those), or no program at all (STEPNC-001). Shared by inspect and the
// interpreter.
[[nodiscard]] diag::Diagnostic no_program_diagnostic(const p21::Model& model);

// The "header" member: FILE_DESCRIPTION, FILE_NAME and FILE_SCHEMA by field name.
[[nodiscard]] nlohmann::ordered_json header_json(const p21::Model& model);
// The "statistics" member: bytes, instances, workingsteps, entity types and counts by type.
[[nodiscard]] nlohmann::ordered_json statistics_json(const p21::Model& model,
                                                     std::size_t workingsteps);

// Diagnostics as JSON objects {file, line, column, severity, code, message}.
[[nodiscard]] nlohmann::ordered_json diagnostics_json(const std::vector<diag::Diagnostic>& list,
                                                      std::string_view file);

// A human-readable tree of the same information (`ncpost inspect --format text`).
[[nodiscard]] std::string format_text(const nlohmann::ordered_json& info);

}  // namespace ncpost::stepnc
