#pragma once
// One function per job that `ncpost` and ncpostd offer besides posting (post.hpp): trace,
// verify, inspect, convert, and an EXPRESS schema as EXPRESS-X. Each reads its Input through
// read() (job.hpp) and returns its result as a value; text that can be long goes to a TextSink
// piece by piece. The CLI prints what comes back, the server turns it into HTTP: neither
// assembles a job of its own.

#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ncpost/diag/diagnostic.hpp"
#include "ncpost/pipeline/job.hpp"
#include "ncpost/stepnc/program_info.hpp"
#include "ncpost/verify/verify.hpp"

namespace ncpost::pipeline {

// ---- trace --------------------------------------------------------------------------------

// Text: one call per line (rs274 style). Xml: the form that stylesheets read (canon.rng).
// Json: NDJSON, a header line then one JSON object per call (canon/json_trace.hpp);
// JsonDocument: the same records as one JSON document. Both JSON forms carry the program's
// stock boxes in their header ("stock", see stock_json).
enum class TraceFormat : std::uint8_t { Text, Xml, Json, JsonDocument };

// The canonical program of the input, streamed chunk by chunk. A trace goes on after an
// error, to show everything it can; `ok` is false then.
[[nodiscard]] JobResult trace(Input input, const JobContext& context, TraceFormat format,
                              const TextSink& out);

// The stock of a STEP-NC program, as the JSON trace's header member "stock": an array of
// {"workpiece", "name", "setup", "corners": [[x, y, z] x 8]} (verify::stock_boxes), empty for
// a program without a model (CL, G-code) or without a BLOCK.
[[nodiscard]] nlohmann::ordered_json stock_json(const Program& program);

// ---- verify -------------------------------------------------------------------------------

struct VerifySettings {
  double tolerance = 0.01;     // mm
  std::optional<double> grid;  // mm; unset: chosen per feature (docs/verify.md)
};

struct VerifyOutcome {
  JobResult job;  // reading and checking; ok when the program was read
  // Set when the program could be read: the checks' result (ok() when every check passed).
  std::optional<verify::VerifyResult> result;
};

[[nodiscard]] VerifyOutcome verify(Input input, const JobContext& context,
                                   const VerifySettings& settings);
// The report as text (one line per feature) or as one JSON document with the diagnostics.
[[nodiscard]] std::string verify_report_text(const VerifyOutcome& outcome, std::string_view name);
[[nodiscard]] std::string verify_report_json(const VerifyOutcome& outcome, std::string_view name);
// The interpreter's diagnostics and the findings, with the input's name.
[[nodiscard]] std::vector<diag::FileDiagnostic> verify_diagnostics(const VerifyOutcome& outcome,
                                                                   std::string_view name);

// ---- inspect ------------------------------------------------------------------------------

struct Inspection {
  JobResult job;  // ok: no error in reading, checking, or the program's structure
  stepnc::ProgramInfo info;
};

[[nodiscard]] Inspection inspect(Input input, const JobContext& context);
// docs/inspect.md: the program information without diagnostics, ...
[[nodiscard]] nlohmann::ordered_json program_info_json(const stepnc::ProgramInfo& info);
// ... and with every diagnostic of the inspection in "diagnostics".
[[nodiscard]] nlohmann::ordered_json inspection_json(const Inspection& inspection);
// inspection_json(inspection).dump(2), written to `out` as it goes, without building the
// document: its memory stays that of the program information (`ncpost inspect`).
void write_inspection_json(const Inspection& inspection, const TextSink& out);
// inspect(), written to `out` as write_inspection_json writes it, but while the model is
// walked: an ISO 14649 program's workplan tree is never held (`ncpost inspect`), and the
// returned main workplan is its root alone.
[[nodiscard]] Inspection inspect_to_json(Input input, const JobContext& context,
                                         const TextSink& out);
// The same as a human-readable tree (`ncpost inspect --format text`) ...
[[nodiscard]] std::string inspection_text(const Inspection& inspection);
// ... written to `out` as inspect_to_json writes JSON: while the model is walked.
[[nodiscard]] Inspection inspect_to_text(Input input, const JobContext& context,
                                         const TextSink& out);

// ---- convert ------------------------------------------------------------------------------

enum class ConvertTo : std::uint8_t { P21, P28Late, P28Early };

// P21 or P28 in, P21 or P28 out. Lossless whatever the schema says, so the model is not
// checked against it. An input with errors produces no output at all: a partial model must
// never look like a whole one.
[[nodiscard]] JobResult convert(Input input, const JobContext& context, ConvertTo to,
                                const TextSink& out);

// ---- G-code as XML -----------------------------------------------------------------------

// `ncpost nc parse --format xml`, POST /v1/nc/parse?format=xml: a G-code program read with
// `context.gcode_dialect` as the XML intermediate form (engine/gcode/gcode.rng): blocks, words,
// evaluated values and canonical calls, with <error> elements where the program is wrong. The
// text form is `trace` with the same context. Any other input is refused (IO-003).
[[nodiscard]] JobResult gcode_xml(Input input, const JobContext& context, const TextSink& out);

// ---- schema -------------------------------------------------------------------------------

// An EXPRESS schema as EXPRESS-X XML. A schema with errors gives no XML: a partial schema would
// silently lose declarations.
[[nodiscard]] JobResult schema_to_xml(std::string_view express_text, std::string_view name,
                                      const TextSink& out);

}  // namespace ncpost::pipeline
