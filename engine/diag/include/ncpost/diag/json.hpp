#pragma once
// The one JSON form of a diagnostic, as problem details, inspections and reports carry it:
// {"file", "line", "column", "severity", "code", "message"} ("file" only for a FileDiagnostic).
// Apart from diagnostic.hpp so that only the files that write JSON include the JSON library.

#include <nlohmann/json.hpp>
#include <span>

#include "ncpost/diag/diagnostic.hpp"

namespace ncpost::diag {

[[nodiscard]] nlohmann::ordered_json to_json(const Diagnostic& d);
[[nodiscard]] nlohmann::ordered_json to_json(const FileDiagnostic& d);
[[nodiscard]] nlohmann::ordered_json to_json(std::span<const FileDiagnostic> diagnostics);

}  // namespace ncpost::diag
