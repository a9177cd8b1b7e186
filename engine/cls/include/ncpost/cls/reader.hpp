#pragma once
// The cutter-location reader: APT CL and NX CLSF text → canonical calls.
//
// In:  the text of a CL file (whole, or piece by piece through Reader::feed), options, and
//      optionally the shop's pre-post checks (checks.hpp).
// Out: canonical calls on `sink` as each record is read (PROJECT_BEGIN and the set-up first, a
//      WORKINGSTEP per TOOL PATH/ operation or APT tool load, PROGRAM_END and PROJECT_END last),
//      and diagnostics with line:column and stable CLS-xxx codes. The reader keeps a few numbers
//      of state and one record: its memory does not grow with the file. docs/cls.md lists every
//      major word and what it becomes.

#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ncpost/canon/call.hpp"
#include "ncpost/canon/sink.hpp"
#include "ncpost/diag/diagnostic.hpp"

namespace ncpost::cls {

struct CheckConfig;  // checks.hpp

struct ReadOptions {
  // The program's name when the file has no PARTNO/ (PROJECT_BEGIN's name).
  std::string program_name = "program";
  // Reading stops after this many errors; warnings and notes are bounded by the same number.
  std::size_t max_errors = 1000;
  // The shop's pre-post checks; null, or a config with enabled == false: no checks.
  const CheckConfig* checks = nullptr;
  // Checked every few thousand records: a cancelled job stops there, without the end sequence.
  const std::atomic<bool>* cancel = nullptr;
  // Stop at the first error, without the end sequence (what is posted must not look complete
  // when it is not). A trace goes on to show everything it can.
  bool stop_at_first_error = false;
  // The length unit of a file without UNITS/ (a note says it was assumed).
  canon::Units default_units = canon::Units::Millimetres;
  // MSYS/ maps the CL coordinates (the machine coordinate system) into the part's absolute
  // system; off: the coordinates stay as written (MSYS/ is still checked).
  bool apply_msys = true;
  // A start or end point of a CIRCLE/ may be this far (program units) off the circle.
  double arc_tolerance = 0.002;
  // One record with its continuation lines; longer ones are reported and skipped.
  std::size_t max_record_bytes = std::size_t{64} << 10;
  // Distinct tool names given numbers (NX TOOL PATH/ without LOAD/TOOL); reading stops beyond.
  std::size_t max_tool_names = 10000;
};

struct ReadResult {
  std::vector<diag::Diagnostic> diagnostics;
  std::size_t calls = 0;
  bool cancelled = false;
  // What the checks' operation-name rules selected, for the renderer: each (option, value) once,
  // in the order first selected, over the whole program (may be empty).
  std::vector<std::pair<std::string, std::string>> selected_options;
  [[nodiscard]] bool ok() const;
};

// Reads a CL file piece by piece: feed() any number of times with consecutive pieces of the text
// (cut anywhere), then finish() once. Calls reach `sink` as soon as their record is complete.
class Reader {
 public:
  Reader(canon::Sink& sink, const ReadOptions& options = {});
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;
  ~Reader();

  void feed(std::string_view piece);
  // Reads what is left, closes the program (unless stopped) and returns the result.
  [[nodiscard]] ReadResult finish();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

// The whole text at once.
[[nodiscard]] ReadResult read(std::string_view text, canon::Sink& sink,
                              const ReadOptions& options = {});

// For format detection from the first few KB: true when the first records are APT CL / CLSF
// (a known major word with its slash, RAPID, a $$ comment, ...), false for P21, P28, G-code and
// anything else.
[[nodiscard]] bool looks_like_cl(std::string_view head) noexcept;

}  // namespace ncpost::cls
