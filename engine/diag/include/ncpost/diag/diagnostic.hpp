#pragma once
// Diagnostics are values: every stage returns them, none prints them. The CLI and the server
// format them as `file:line:column: severity: CODE: message` or as JSON problem details.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ncpost::diag {

enum class Severity : std::uint8_t { Note, Warning, Error };

enum class Code : std::uint16_t {
#define NCPOST_DIAG(name, code, severity, meaning) name,
#include "ncpost/diag/codes.def"
#undef NCPOST_DIAG
};

struct CodeInfo {
  Code code;
  std::string_view id;  // stable, e.g. "P21-003"
  Severity default_severity;
  std::string_view meaning;
};

[[nodiscard]] const CodeInfo& info(Code code) noexcept;
[[nodiscard]] std::vector<CodeInfo> all_codes();
[[nodiscard]] std::string_view to_string(Severity severity) noexcept;

// line and column are 1-based; 0 means "no position" (for example a whole-file problem).
struct Diagnostic {
  Code code{};
  Severity severity{};
  std::uint32_t line = 0;
  std::uint32_t column = 0;
  std::string message;

  [[nodiscard]] std::string_view code_id() const noexcept { return info(code).id; }
};

[[nodiscard]] Diagnostic make(Code code, std::uint32_t line, std::uint32_t column,
                              std::string message);

// `file:line:column: severity: CODE: message`, the one textual form.
[[nodiscard]] std::string format(const Diagnostic& d, std::string_view file);

// A diagnostic with the file it points at: the input's name, a schema file, a stylesheet (or
// one it imports), a subprogram file. Jobs that read several files report these.
struct FileDiagnostic {
  std::string file;
  Diagnostic diagnostic;
};

// `file:line:column: severity: CODE: message`.
[[nodiscard]] std::string format(const FileDiagnostic& d);
[[nodiscard]] bool has_errors(std::span<const Diagnostic> diagnostics) noexcept;
[[nodiscard]] bool has_errors(std::span<const FileDiagnostic> diagnostics) noexcept;
// Each of `diagnostics` with `file`.
[[nodiscard]] std::vector<FileDiagnostic> with_file(std::span<const Diagnostic> diagnostics,
                                                    std::string_view file);

// A bounded list: hostile input cannot make diagnostics grow without bound. Once the error limit
// is reached, `full()` tells the producer to stop.
class DiagnosticList {
 public:
  explicit DiagnosticList(std::size_t max_errors = 1000) : max_errors_(max_errors) {}

  void add(Diagnostic d);
  void add(Code code, std::uint32_t line, std::uint32_t column, std::string message) {
    add(make(code, line, column, std::move(message)));
  }
  [[nodiscard]] bool full() const noexcept { return errors_ >= max_errors_; }
  [[nodiscard]] std::size_t error_count() const noexcept { return errors_; }
  [[nodiscard]] bool has_errors() const noexcept { return errors_ > 0; }
  [[nodiscard]] const std::vector<Diagnostic>& items() const noexcept { return items_; }
  [[nodiscard]] std::vector<Diagnostic> take() && { return std::move(items_); }

 private:
  std::vector<Diagnostic> items_;
  std::size_t errors_ = 0;
  std::size_t max_errors_;
};

}  // namespace ncpost::diag
