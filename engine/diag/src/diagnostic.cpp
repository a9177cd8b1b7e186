#include "ncpost/diag/diagnostic.hpp"

#include <algorithm>
#include <array>

namespace ncpost::diag {
namespace {

constexpr std::array kCodes = {
#define NCPOST_DIAG(name, code, severity, meaning) \
  CodeInfo{Code::name, code, Severity::severity, meaning},
#include "ncpost/diag/codes.def"
#undef NCPOST_DIAG
};

}  // namespace

const CodeInfo& info(Code code) noexcept {
  return kCodes[static_cast<std::size_t>(code)];
}

std::vector<CodeInfo> all_codes() {
  return {kCodes.begin(), kCodes.end()};
}

std::string_view to_string(Severity severity) noexcept {
  switch (severity) {
    case Severity::Note:
      return "note";
    case Severity::Warning:
      return "warning";
    case Severity::Error:
      return "error";
  }
  return "error";
}

Diagnostic make(Code code, std::uint32_t line, std::uint32_t column, std::string message) {
  return Diagnostic{code, info(code).default_severity, line, column, std::move(message)};
}

std::string format(const Diagnostic& d, std::string_view file) {
  std::string out;
  out.reserve(file.size() + d.message.size() + 32);
  out += file;
  out += ':';
  out += std::to_string(d.line);
  out += ':';
  out += std::to_string(d.column);
  out += ": ";
  out += to_string(d.severity);
  out += ": ";
  out += d.code_id();
  out += ": ";
  out += d.message;
  return out;
}

std::string format(const FileDiagnostic& d) {
  return format(d.diagnostic, d.file);
}

bool has_errors(std::span<const Diagnostic> diagnostics) noexcept {
  return std::any_of(diagnostics.begin(), diagnostics.end(),
                     [](const Diagnostic& d) { return d.severity == Severity::Error; });
}

bool has_errors(std::span<const FileDiagnostic> diagnostics) noexcept {
  return std::any_of(diagnostics.begin(), diagnostics.end(), [](const FileDiagnostic& d) {
    return d.diagnostic.severity == Severity::Error;
  });
}

std::vector<FileDiagnostic> with_file(std::span<const Diagnostic> diagnostics,
                                      std::string_view file) {
  std::vector<FileDiagnostic> out;
  out.reserve(diagnostics.size());
  for (const auto& d : diagnostics) out.push_back({std::string(file), d});
  return out;
}

void DiagnosticList::add(Diagnostic d) {
  if (d.severity == Severity::Error) ++errors_;
  items_.push_back(std::move(d));
}

}  // namespace ncpost::diag
