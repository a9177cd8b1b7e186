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

// A JSON document that does not parse, as a diagnostic at the line and column where the parser
// stopped, with the parser's own words but not its exception prefix
// ("[json.exception.parse_error.101] parse error at line 1, column 9: ").
[[nodiscard]] Diagnostic json_syntax_error(Code code, std::string_view text,
                                           const nlohmann::json::parse_error& error,
                                           std::string_view message_prefix = {});

}  // namespace ncpost::diag
