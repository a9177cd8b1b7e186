#pragma once
// The diagnostics of a job in their one JSON form (diag/json.hpp), for the front ends: the CLI's
// --json output and the server's problem details include only pipeline headers.

#include <cstddef>
#include <span>

#include "ncpost/diag/json.hpp"

namespace ncpost::pipeline {

// A hostile upload can make a million diagnostics; an answer lists this many, then one HTTP-013
// note that counts the rest.
inline constexpr std::size_t kMaxListedDiagnostics = 1000;

[[nodiscard]] inline nlohmann::ordered_json diagnostic_json(const diag::FileDiagnostic& d) {
  return diag::to_json(d);
}
[[nodiscard]] nlohmann::ordered_json diagnostics_json(
    std::span<const diag::FileDiagnostic> diagnostics,
    std::size_t max_listed = kMaxListedDiagnostics);

}  // namespace ncpost::pipeline
