#include "ncpost/pipeline/diagnostics.hpp"

#include <string>

namespace ncpost::pipeline {

nlohmann::ordered_json diagnostics_json(std::span<const diag::FileDiagnostic> diagnostics,
                                        std::size_t max_listed) {
  if (diagnostics.size() <= max_listed) return diag::to_json(diagnostics);
  nlohmann::ordered_json listed = diag::to_json(diagnostics.first(max_listed));
  const std::size_t left_out = diagnostics.size() - max_listed;
  listed.push_back(diag::to_json(diag::FileDiagnostic{
      diagnostics[max_listed].file,
      diag::make(diag::Code::HttpMoreDiagnostics, 0, 0,
                 std::to_string(left_out) + " more diagnostics are not listed")}));
  return listed;
}

}  // namespace ncpost::pipeline
