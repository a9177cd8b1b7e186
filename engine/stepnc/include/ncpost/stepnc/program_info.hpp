#pragma once
// Program-information extraction: what a STEP-NC controller shows before it runs a program.
//
// In:  a Model (read from P21 or P28).
// Out: JSON with the header, the PROJECT → main WORKPLAN → executables tree (recursively), the
//      workpieces and tools, instance counts by entity type, and diagnostics about the program
//      structure. The JSON shape is a contract shared by `ncpost inspect` and the HTTP service;
//      docs/inspect.md describes it.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"

namespace ncpost::stepnc {

struct ProgramInfo {
  nlohmann::ordered_json json;               // without the "diagnostics" member
  std::vector<diag::Diagnostic> diagnostics;  // about the program structure
};

struct InspectOptions {
  // Workplans nested deeper than this are reported instead of followed.
  unsigned max_nesting = 64;
};

[[nodiscard]] ProgramInfo inspect(const p21::Model& model, const InspectOptions& options = {});

// Diagnostics as JSON objects {file, line, column, severity, code, message}.
[[nodiscard]] nlohmann::ordered_json diagnostics_json(const std::vector<diag::Diagnostic>& list,
                                                      std::string_view file);

// A human-readable tree of the same information (`ncpost inspect --format text`).
[[nodiscard]] std::string format_text(const nlohmann::ordered_json& info);

}  // namespace ncpost::stepnc
