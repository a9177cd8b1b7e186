#include "ncpost/diag/json.hpp"

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

}  // namespace ncpost::diag
