#pragma once
// ISO 10303-21 (editions 2 and 3) → Model.
//
// In:  the whole file as one string (the Model keeps it; values are slices of it).
// Out: a Model with everything that could be read, and the diagnostics. Errors never stop the
//      reader early except at `max_errors`: a broken instance is reported once and skipped, and
//      reading resumes at the next instance. References are resolved after the scan, and a
//      dangling one is named ("#12 used by #7 attribute 3 is not defined").

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/p21/model.hpp"
#include "ncpost/parallel/pieces.hpp"

namespace ncpost::p21 {

struct ReadOptions {
  // Lists nested deeper than this are rejected; it bounds every walk over values.
  std::uint32_t max_list_depth = 64;
  // Reading stops after this many errors, so hostile input cannot grow the list without bound.
  std::size_t max_errors = 1000;
  // Resolve references and report dangling ones (turn off only for partial or streamed files).
  bool check_references = true;
  // Set by another thread to stop reading (a client that went away, a job out of time): looked
  // at every few thousand tokens and instances. Null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
  // Threads lent to read a large file in pieces (null: one thread). The result is the same
  // either way, diagnostics included: a piece with anything to report is read again in order.
  const parallel::Helpers* helpers = nullptr;
  // No piece is smaller than this: below it, starting threads costs more than it saves.
  std::size_t min_piece_bytes = std::size_t{4} << 20;
  // A longer text is cut into more pieces than threads, none longer than this: a piece read on
  // another thread is held twice while it is joined to the rest.
  std::size_t max_piece_bytes = std::size_t{8} << 20;
};

struct ReadResult {
  Model model;
  std::vector<diag::Diagnostic> diagnostics;
  // Stopped by ReadOptions::cancel: the model and diagnostics are empty, not a verdict.
  bool cancelled = false;
  // 1 + how many pieces other threads read apart and were joined (ReadOptions::helpers); 1: the
  // text was read in order by one parser.
  std::size_t pieces = 1;

  [[nodiscard]] bool ok() const;
};

[[nodiscard]] ReadResult read(std::string text, const ReadOptions& options = {});

// Maps byte offsets of a text to 1-based line and column. Built on demand (one memchr pass),
// for diagnostics found after the scan.
class LineIndex {
 public:
  explicit LineIndex(std::string_view text);
  struct Position {
    std::uint32_t line;
    std::uint32_t column;
  };
  [[nodiscard]] Position at(std::uint32_t offset) const;

 private:
  std::vector<std::uint32_t> line_starts_;
};

}  // namespace ncpost::p21
