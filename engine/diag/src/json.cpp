#include "ncpost/diag/json.hpp"

#include <algorithm>

namespace ncpost::diag {

nlohmann::ordered_json to_json(const Diagnostic& d) {
  nlohmann::ordered_json j;
  j["line"] = d.line;
  j["column"] = d.column;
  j["severity"] = std::string(to_string(d.severity));
  j["code"] = std::string(d.code_id());
  j["message"] = d.message;
  return j;
}

nlohmann::ordered_json to_json(const FileDiagnostic& d) {
  nlohmann::ordered_json j;
  j["file"] = d.file;
  nlohmann::ordered_json rest = to_json(d.diagnostic);
  for (auto& [key, value] : rest.items()) j[key] = std::move(value);
  return j;
}

nlohmann::ordered_json to_json(std::span<const FileDiagnostic> diagnostics) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const auto& d : diagnostics) all.push_back(to_json(d));
  return all;
}

Diagnostic json_syntax_error(Code code, std::string_view text,
                             const nlohmann::json::parse_error& error,
                             std::string_view message_prefix) {
  // `byte` counts from 1 and is one past the character that stopped the parser.
  const std::size_t stop = std::min<std::size_t>(error.byte == 0 ? 0 : error.byte - 1, text.size());
  std::uint32_t line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < stop; ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  const auto column = static_cast<std::uint32_t>(stop - line_start + 1);
  std::string_view what = error.what();
  if (const auto colon = what.find(": ");
      what.rfind("[json.exception.", 0) == 0 && colon != std::string_view::npos)
    what.remove_prefix(colon + 2);
  return make(code, line, column, std::string(message_prefix) + std::string(what));
}

}  // namespace ncpost::diag
