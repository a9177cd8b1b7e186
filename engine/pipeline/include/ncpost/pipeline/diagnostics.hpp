#pragma once
// The diagnostics of a job in their one JSON form (diag/json.hpp), for the front ends: the CLI's
// --json output and the server's problem details include only pipeline headers.

#include "ncpost/diag/json.hpp"

namespace ncpost::pipeline {

[[nodiscard]] inline nlohmann::ordered_json diagnostic_json(const diag::FileDiagnostic& d) {
  return diag::to_json(d);
}
[[nodiscard]] inline nlohmann::ordered_json diagnostics_json(
    std::span<const diag::FileDiagnostic> diagnostics) {
  return diag::to_json(diagnostics);
}

}  // namespace ncpost::pipeline
