#pragma once
// The diagnostics of one read: bounded (max_errors errors; warnings and notes reported once per
// file, line and code, so a loop does not repeat them), each with the file it points at.

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"

namespace ncpost::gcode::detail {

class Report {
 public:
  explicit Report(std::size_t max_errors) : max_errors_(max_errors == 0 ? 1 : max_errors) {}

  // Adds a diagnostic with the code's default severity. Returns false once the error limit is
  // reached (the caller stops).
  bool add(std::string_view file, diag::Code code, std::uint32_t line, std::uint32_t column,
           std::string message);
  bool add(std::string_view file, diag::Code code, diag::Severity severity, std::uint32_t line,
           std::uint32_t column, std::string message);

  // Called with each diagnostic kept, as it is kept.
  void set_listener(std::function<void(const diag::FileDiagnostic&)> listener) {
    listener_ = std::move(listener);
  }
  [[nodiscard]] bool full() const noexcept { return errors_ >= max_errors_; }
  [[nodiscard]] std::size_t errors() const noexcept { return errors_; }
  [[nodiscard]] std::vector<diag::FileDiagnostic> take() && { return std::move(items_); }
  [[nodiscard]] const std::vector<diag::FileDiagnostic>& items() const noexcept { return items_; }

 private:
  void keep(diag::FileDiagnostic d);
  std::vector<diag::FileDiagnostic> items_;
  std::set<std::tuple<std::string, std::uint32_t, diag::Code>> once_;
  std::size_t errors_ = 0;
  std::size_t others_ = 0;  // warnings and notes
  std::size_t max_errors_;
  bool dropped_ = false;
  std::function<void(const diag::FileDiagnostic&)> listener_;
};

}  // namespace ncpost::gcode::detail
