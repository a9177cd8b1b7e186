#include "report.hpp"

namespace ncpost::gcode::detail {

void Report::keep(diag::FileDiagnostic d) {
  items_.push_back(std::move(d));
  if (listener_) listener_(items_.back());
}

bool Report::add(std::string_view file, diag::Code code, std::uint32_t line, std::uint32_t column,
                 std::string message) {
  return add(file, code, diag::info(code).default_severity, line, column, std::move(message));
}

bool Report::add(std::string_view file, diag::Code code, diag::Severity severity,
                 std::uint32_t line, std::uint32_t column, std::string message) {
  if (full()) return false;
  bool last_other = false;
  if (severity != diag::Severity::Error) {
    // Warnings and notes once per place (a loop that passes a line a million times reports it
    // once), and no more of them than errors are allowed: a hostile file cannot grow the list.
    if (others_ >= max_errors_) return true;
    if (!once_.emplace(std::string(file), line, code).second) return true;
    last_other = ++others_ == max_errors_;
  }
  diag::Diagnostic d = diag::make(code, line, column, std::move(message));
  d.severity = severity;
  keep({std::string(file), std::move(d)});
  if (last_other)
    keep({std::string(file), diag::make(diag::Code::GcodeTooManyErrors, line, column,
                                        "further warnings and notes dropped "
                                        "(ReadOptions::max_errors)")});
  if (severity == diag::Severity::Error) ++errors_;
  if (full() && !dropped_) {
    dropped_ = true;
    keep({std::string(file), diag::make(diag::Code::GcodeTooManyErrors, line, column,
                                        "stopped after " + std::to_string(errors_) +
                                            " errors (ReadOptions::max_errors)")});
  }
  return !full();
}

}  // namespace ncpost::gcode::detail
