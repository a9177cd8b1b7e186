#pragma once
// G-code in: a controller's program text → the canonical machining program (engine/canon).
//
// In: the program text, the dialect it is written in (stylesheets/<profile-id>/dialect.json,
// loaded with load_dialect), and options (subprogram files of the upload, the tool table's
// tool numbers, limits). Out: canonical calls streamed into a canon::Sink block by block (or
// the XML intermediate form streamed to a callback), and diagnostics with line:column and a
// stable GCODE-xxx code. Processing goes on after an error, up to ReadOptions::max_errors.
//
// Four steps per block, as in LinuxCNC's rs274ngc and the papers in ../shared/papers: lex
// (words, numbers, comments), evaluate (parameters, expressions, control statements), check
// (required and conflicting words, modal groups, arcs, feed, spindle, tools, limits) and
// convert (the modal state machine that makes canonical calls). docs/gcode.md describes it.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/canon/sink.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/gcode/dialect.hpp"

namespace ncpost::gcode {

struct DialectResult {
  std::shared_ptr<const Dialect> dialect;  // null when the text is not a valid dialect
  std::vector<diag::Diagnostic> diagnostics;
};

// Parses and checks a dialect.json text (GCODE-001 not JSON, GCODE-002 against the schema).
[[nodiscard]] DialectResult load_dialect(std::string_view json_text);

// A subprogram file that came with the upload (M98 P, G65 P, CALL PGM, o<name> call, a
// Sinumerik .SPF call). Found by its name without folder and extension, case-insensitive;
// a numbered program also as O1234 / 1234 (docs/gcode.md, "Subprograms").
struct SourceFile {
  std::string name;
  std::string text;
};

// Machine limits to check motions against (the target profile's, in its length unit).
struct MachineLimits {
  struct Range {
    double min = 0;
    double max = 0;
  };
  std::optional<Range> x, y, z;  // in mm when `metric`, otherwise inches
  bool metric = true;
  std::optional<double> max_feed;     // length units per minute
  std::optional<double> max_spindle;  // rpm
  std::optional<std::int64_t> min_tool, max_tool;
  bool errors = false;  // a limit crossed is an error (otherwise a warning)
};

struct ReadOptions {
  std::string program_name = "program";       // names the input in diagnostics and markers
  std::size_t max_errors = 1000;              // go on after an error up to this many
  std::uint64_t max_steps = 10'000'000;       // bound on evaluated blocks and loop iterations
  std::vector<SourceFile> subprograms;        // M98 P, CALL PGM, o<name> call, .SPF lookups
  std::optional<std::vector<int>> tools;      // tool numbers of a tool table, when one is given
  const std::atomic<bool>* cancel = nullptr;  // polled; stop early when set
  std::optional<MachineLimits> limits;        // the target profile's limits, when checked
  std::size_t max_call_depth = 64;            // nested subprogram calls and loops
  std::size_t max_expression_depth = 64;      // nested brackets and function calls
  std::size_t max_line_length = 65536;        // bytes in one line (block)
  // The operator's block delete switch: on, blocks starting with '/' are skipped; off (as
  // LinuxCNC's rs274 starts), they run like any other.
  bool block_delete = false;
  // rs274's tool table lengths by tool number (G43 H), when known; see docs/gcode.md.
  std::vector<std::pair<int, double>> tool_lengths;
};

struct ReadResult {
  std::vector<diag::FileDiagnostic> diagnostics;  // file = program_name or the subprogram's name
  std::size_t calls = 0;                          // canonical calls made
  bool cancelled = false;
  [[nodiscard]] bool ok() const { return !cancelled && !diag::has_errors(diagnostics); }
};

// Text → canonical calls, streamed into `sink` as blocks are converted (memory does not grow
// with the program's length). The program always comes out whole: PROJECT_BEGIN, the set-up
// calls, the blocks read (up to the point where it stopped), PROJECT_END.
[[nodiscard]] ReadResult read(std::string_view text, const Dialect& dialect, canon::Sink& sink,
                              const ReadOptions& options = {});

// The whole step as the pipeline takes it: `dialect_json` (a profile's dialect.json:
// profile::LoadedProfile::dialect_json of a built-in or uploaded profile) checked with
// load_dialect, then `text` read into `sink` as read() does. A dialect that does not load gives
// its diagnostics (GCODE-001/002, file "<dialect_name>") and nothing is read: the sink gets no
// call and the result is not ok().
[[nodiscard]] ReadResult read_with_dialect(std::string_view text, std::string_view dialect_json,
                                           std::string_view dialect_name, canon::Sink& sink,
                                           const ReadOptions& options = {});

// The XML intermediate form (engine/gcode/gcode.rng): the blocks as evaluated, each with its
// words, evaluated values and canonical calls, and <error row= column= code=> elements where
// the program is wrong; written piece by piece to `out`.
[[nodiscard]] ReadResult write_xml(std::string_view text, const Dialect& dialect,
                                   const std::function<void(std::string_view)>& out,
                                   const ReadOptions& options = {});

// For format detection: does this start (first few KB) of an upload look like G-code rather
// than P21, P28 or APT CL? (`%`, `O1234`, N-numbered blocks, G/M words, `;`/`(` comments,
// Heidenhain `BEGIN PGM`.)
[[nodiscard]] bool looks_like_gcode(std::string_view head) noexcept;

}  // namespace ncpost::gcode
