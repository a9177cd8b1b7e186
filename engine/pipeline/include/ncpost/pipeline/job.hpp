#pragma once
// The front half of every job, shared by every verb and route: an Input is read into a Program
// (detect the format, read it with the reader registered for that format, choose and check the
// schema), and a Program is interpreted into canonical calls. What a job does with the calls
// (render, trace, verify) is in jobs.hpp and post.hpp.
//
// The readers are registered in one place (job.cpp, `reader_for`): a new input format is one
// entry there, and every verb of `ncpost` and every route of ncpostd reads it from then on.

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ncpost/canon/sink.hpp"
#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/express/registry.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "ncpost/p21/stream_reader.hpp"
#include "ncpost/parallel/pieces.hpp"
#include "ncpost/pipeline/detect.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"

namespace ncpost::profile {
struct LoadedProfile;
}

namespace ncpost::pipeline {

// A P21 upload that is read while it arrives (ncpostd's large raw uploads): the text is handed
// over piece by piece and the rest is read when the last byte came. Same result as a whole read
// (p21/stream_reader.hpp says how); an upload that turns out not to be P21 is read whole.
using ArrivingText = p21::StreamReader;
// One for an upload of `size` bytes; `cancel` stops it, `helpers` read its rest in pieces.
[[nodiscard]] std::unique_ptr<ArrivingText> arriving_text(std::size_t size,
                                                          const std::atomic<bool>* cancel,
                                                          const parallel::Helpers* helpers);

// What a job reads: the bytes of one file, or an upload read as it arrived.
struct Input {
  std::string name = "program";      // names the input in diagnostics
  std::string bytes;                 // empty when `arriving` holds the text
  ArrivingText* arriving = nullptr;  // every byte appended by the time the job reads it
};

// The schemas a job reads models with: the built-in ISO 14649 schema and, with a directory
// (`--schemas DIR`), every .exp file in it. A file with errors is left out and the others are
// used; its diagnostics are in `reports`, under the file's own name, and every job reports them
// first, so that a broken schema file never goes unnoticed.
struct Schemas {
  express::SchemaRegistry registry;
  std::vector<diag::FileDiagnostic> reports;
};
[[nodiscard]] Schemas load_schemas(const std::optional<std::filesystem::path>& directory = {});

// A tool table in NIST's format (`--tools TABLE`): which pocket holds each tool, its length.
struct ToolTableResult {
  std::optional<stepnc::ToolTable> table;  // none when the text has errors
  std::vector<diag::FileDiagnostic> diagnostics;
};
[[nodiscard]] ToolTableResult read_tool_table(std::string_view text, std::string_view name);

// Threads a process lends to its jobs for reading and checking large files in pieces (the CLI
// lends its spare cores; the server lends its worker pool through its own Helpers).
using parallel::Helpers;
using parallel::spare_cores;
using parallel::Task;
using parallel::ThreadGroup;

// A file that came with a G-code program, by its name (a subprogram file: docs/gcode.md).
using SourceFile = gcode::SourceFile;

// What one job may use. Cheap to copy: the schemas are shared by every job of a process.
struct JobContext {
  const Schemas* schemas = nullptr;  // never null when a job runs
  // Set by another thread to stop the job (client gone, time limit); polled by every stage.
  const std::atomic<bool>* cancel = nullptr;
  // Threads lent to read and check a large file in pieces (null: the job's own thread only).
  const Helpers* helpers = nullptr;
  // Deviations from the schema are errors (`--strict`, `strict=true`); otherwise a deviation
  // that nothing downstream reads is a warning (docs/interoperability.md).
  bool strict = false;
  // Tools by pocket and length offset; without one, a tool's pocket is its instance id.
  std::optional<stepnc::ToolTable> tools;
  // The profile whose dialect.json reads G-code input (`--from`/`--dialect`, `from=`/
  // `dialect=`): one profile id names how a machine's programs are read and written. Null: a
  // G-code input is refused with IO-003, which names the way to read it.
  std::shared_ptr<const profile::LoadedProfile> gcode_dialect;
  // Files that came with a G-code program (the upload's other `file` parts, `--subprograms
  // DIR`): where M98 P, G65 P, CALL PGM, o<name> call and .SPF calls find a subprogram that is
  // not in the program itself (docs/gcode.md, "Subprograms"). Null: none.
  std::shared_ptr<const std::vector<SourceFile>> gcode_subprograms;
};

// Receives output text, piece by piece, in order.
using TextSink = std::function<void(std::string_view)>;

// What every job reports besides its output.
struct JobResult {
  // In order: schema files, reading and checking, then the job's own stages.
  std::vector<diag::FileDiagnostic> diagnostics;
  bool ok = false;
  // The input was read and checked without error (a job may still fail after that).
  bool input_ok = false;
  bool cancelled = false;
  // Output reached the sink (a job may fail after that: trace goes on past errors).
  bool started = false;
  std::chrono::nanoseconds read_time{0};   // the input into a model (what was left of it)
  std::chrono::nanoseconds check_time{0};  // schema choice and the check against it
  std::chrono::nanoseconds work_time{0};   // the job's own stage (interpret, convert, ...)
};

// An input after the read stage: the model of a STEP-NC file, checked against its schema.
struct Program {
  std::string name;
  InputFormat format = InputFormat::Unknown;
  LoadedModel loaded;
  // The text of a format that is read as it is interpreted (CL): no model, one pass.
  std::string text;
  // The schema files' reports, then reading, schema choice and check, in that order.
  std::vector<diag::FileDiagnostic> diagnostics;
  bool cancelled = false;
  [[nodiscard]] bool ok() const;  // not cancelled, and no error above
};

// The read stage as a job reports it: diagnostics, ok, cancelled, times.
[[nodiscard]] JobResult read_result(const Program& program);

struct ReadOptions {
  // Check the model against its schema (a conversion does not need it: it is lossless
  // whatever the schema says).
  bool validate = true;
  // When a checked model has errors and no PROJECT, add why it is not an ISO 14649 program
  // (STEPNC-001 or -006). Inspect leaves it to its own structure report.
  bool name_what_is_not_a_program = true;
};

// detect → read → choose the schema → check. Never throws for bad input: what is wrong is in
// the diagnostics. A file that is not a program at all (an AP238 excerpt, say) is named so.
[[nodiscard]] Program read(Input input, const JobContext& context, const ReadOptions& options = {});

// Inspect, convert and a raw post work on the STEP-NC model itself, which a program of another
// kind (CL) does not have. Adds IO-003, naming `instead`, and returns false for such a program.
[[nodiscard]] bool require_model(Program& program, std::string_view job, std::string_view instead);

struct Interpretation {
  std::vector<diag::FileDiagnostic> diagnostics;
  std::size_t calls = 0;
  bool ok = false;
};

struct InterpretSettings {
  // Stop at the first executable after an error, without the program's end sequence: what is
  // posted to a machine must not look complete when it is not. A trace goes on to show all.
  bool stop_at_first_error = false;
  // The post's profile: its `checks` section (the shop's pre-post checks) applies to CL input.
  // Null: no checks (a trace, or `--no-checks`).
  const profile::LoadedProfile* checks_of = nullptr;
  // The post's (target) profile: its limits apply to G-code input as the reader's semantic
  // checks, with the line and column of the block (GCODE-036). Null: no limits (a trace).
  const profile::LoadedProfile* limits_of = nullptr;
};

// Program → canonical calls on `sink`, by the interpreter for the program's kind.
[[nodiscard]] Interpretation interpret(const Program& program, canon::Sink& sink,
                                       const JobContext& context,
                                       const InterpretSettings& settings = {});

}  // namespace ncpost::pipeline
