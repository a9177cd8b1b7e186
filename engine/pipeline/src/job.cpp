#include "ncpost/pipeline/job.hpp"

#include "ncpost/ap238/ap238.hpp"
#include "ncpost/cls/checks.hpp"
#include "ncpost/cls/reader.hpp"
#include "ncpost/gcode/gcode.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/stepnc/attributes.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::pipeline {
namespace {

void append(std::vector<diag::FileDiagnostic>& to, std::vector<diag::FileDiagnostic> more) {
  to.insert(to.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
}

// The built-in schema's own problems (EXP-054: it did not build cleanly) matter to every job
// that reads a model with it.
void add_builtin_report(Program& program, const express::SchemaRegistry& registry) {
  const express::SchemaSource& builtin = registry.builtin();
  if (program.loaded.schema != &builtin.set()) return;
  append(program.diagnostics, diag::with_file(registry.builtin_diagnostics(), builtin.origin));
}

}  // namespace

std::unique_ptr<ArrivingText> arriving_text(std::size_t size, const std::atomic<bool>* cancel,
                                            const parallel::Helpers* helpers) {
  p21::ReadOptions options;
  options.cancel = cancel;
  options.helpers = helpers;
  return std::make_unique<ArrivingText>(size, options);
}

Schemas load_schemas(const std::optional<std::filesystem::path>& directory) {
  Schemas schemas;
  if (!directory) return schemas;
  for (auto& report : schemas.registry.add_directory(*directory))
    append(schemas.reports, diag::with_file(report.diagnostics, report.file.string()));
  return schemas;
}

ToolTableResult read_tool_table(std::string_view text, std::string_view name) {
  std::vector<diag::Diagnostic> diagnostics;
  ToolTableResult result;
  stepnc::ToolTable table = stepnc::read_tool_table(text, diagnostics);
  result.diagnostics = diag::with_file(diagnostics, name);
  if (!diag::has_errors(diagnostics)) result.table = std::move(table);
  return result;
}

JobResult read_result(const Program& program) {
  JobResult result;
  result.diagnostics = program.diagnostics;
  result.ok = program.ok();
  result.input_ok = result.ok;
  result.cancelled = program.cancelled;
  result.read_time = program.loaded.read_time;
  result.check_time = program.loaded.check_time;
  return result;
}

bool require_model(Program& program, std::string_view job, std::string_view instead) {
  if (program.format == InputFormat::P21 || program.format == InputFormat::P28) return true;
  if (program.format == InputFormat::Unknown) return false;  // IO-002 already says why
  program.diagnostics.push_back(
      {program.name,
       diag::make(diag::Code::IoFormatNotAccepted, 1, 1,
                  std::string(job) +
                      " reads STEP-NC programs (ISO 10303-21 or -28); "
                      "this input is " +
                      std::string(to_string(program.format)) + ": " + std::string(instead))});
  return false;
}

bool Program::ok() const {
  return !cancelled && !diag::has_errors(diagnostics);
}

namespace {

// ---- STEP-NC models (P21 and P28) ------------------------------------------------------------

Program read_model(Input input, const JobContext& context, const ReadOptions& options) {
  Program program;
  program.name = std::move(input.name);
  program.diagnostics = context.schemas->reports;
  LoadOptions load_options;
  load_options.validate = options.validate;
  load_options.cancel = context.cancel;
  load_options.helpers = context.helpers;
  load_options.tolerant = !context.strict;
  const express::SchemaRegistry& registry = context.schemas->registry;
  program.loaded = input.arriving != nullptr ? load(*input.arriving, registry, load_options)
                                             : load(std::move(input.bytes), registry, load_options);
  program.format = program.loaded.format;
  program.cancelled = program.loaded.cancelled;
  if (program.cancelled) return program;
  add_builtin_report(program, registry);
  LoadedModel& loaded = program.loaded;
  // Say what the file is, too, when it is not a program at all (an AP238 AIM excerpt, say).
  if (options.name_what_is_not_a_program && options.validate && !loaded.ok() &&
      loaded.model.instances_of("PROJECT").empty() && !ap238::is_aim(loaded.model))
    loaded.diagnostics.push_back(stepnc::no_program_diagnostic(loaded.model));
  append(program.diagnostics, diag::with_file(loaded.diagnostics, program.name));
  return program;
}

Interpretation interpret_model(const Program& program, canon::Sink& sink, const JobContext& context,
                               const InterpretSettings& settings) {
  stepnc::InterpretOptions options;
  options.tools = context.tools;
  options.cancel = context.cancel;
  options.stop_at_first_error = settings.stop_at_first_error;
  const p21::Model& model = program.loaded.model;
  const stepnc::AttributeReader attributes(model, *program.loaded.schema);
  // An AP238 AIM program (FILE_SCHEMA integrated_cnc_schema) says the same things with other
  // entities; its interpreter drives the same machine.
  const stepnc::InterpretResult result = ap238::is_aim(model)
                                             ? ap238::interpret(model, attributes, sink, options)
                                             : stepnc::interpret(model, attributes, sink, options);
  Interpretation out;
  out.diagnostics = diag::with_file(result.diagnostics, program.name);
  out.calls = result.calls;
  out.ok = result.ok();
  return out;
}

// ---- cutter-location files (APT CL, NX CLSF) -------------------------------------------------

// A format read as it is interpreted (CL, G-code): the read stage only keeps the whole text.
Program text_program(Input input, const JobContext& context, InputFormat format) {
  Program program;
  program.name = std::move(input.name);
  program.format = format;
  program.diagnostics = context.schemas->reports;
  program.text = input.arriving != nullptr ? input.arriving->take_text() : std::move(input.bytes);
  return program;
}

// CL records become canonical calls as they are read (engine/cls, docs/cls.md).
Program read_cl(Input input, const JobContext& context, const ReadOptions&) {
  return text_program(std::move(input), context, InputFormat::Cl);
}

// The profile's checks section, or why it cannot be used (an error: a shop that wrote checks
// does not want a post that skipped them).
std::optional<cls::CheckConfig> shop_checks(const profile::LoadedProfile* profile,
                                            std::vector<diag::FileDiagnostic>& diagnostics) {
  if (profile == nullptr || !profile->profile.checks_json) return std::nullopt;
  std::vector<diag::Diagnostic> found;
  auto config = cls::parse_checks(*profile->profile.checks_json, found);
  append(diagnostics, diag::with_file(found, profile->profile.id + "/profile.json"));
  return config;
}

Interpretation interpret_cl(const Program& program, canon::Sink& sink, const JobContext& context,
                            const InterpretSettings& settings) {
  Interpretation out;
  const std::optional<cls::CheckConfig> checks = shop_checks(settings.checks_of, out.diagnostics);
  if (diag::has_errors(out.diagnostics)) return out;
  cls::ReadOptions options;
  options.cancel = context.cancel;
  options.stop_at_first_error = settings.stop_at_first_error;
  options.checks = checks ? &*checks : nullptr;
  const cls::ReadResult result = cls::read(program.text, sink, options);
  append(out.diagnostics, diag::with_file(result.diagnostics, program.name));
  out.calls = result.calls;
  out.ok = result.ok();
  return out;
}

// ---- G-code ------------------------------------------------------------------------------------

// A controller's program is read with a dialect (engine/gcode, docs/gcode.md): the read stage
// keeps the text and says how to give the dialect when none was; the interpret stage reads it.
Program read_gcode(Input input, const JobContext& context, const ReadOptions&) {
  Program program = text_program(std::move(input), context, InputFormat::Gcode);
  const profile::LoadedProfile* dialect = context.gcode_dialect.get();
  if (dialect == nullptr || !dialect->dialect_json) {
    const std::string why =
        dialect == nullptr
            ? "the input is G-code, which is read with the dialect of the machine it was written "
              "for: `ncpost nc translate --from PROFILE --to PROFILE`, `ncpost nc parse --dialect "
              "PROFILE`, or POST /v1/nc/translate?from=PROFILE&to=PROFILE (from= also on "
              "/v1/posts)"
            : "the input is G-code and profile '" + dialect->profile.id +
                  "' has no dialect.json to read it with";
    program.diagnostics.push_back(
        {program.name, diag::make(diag::Code::IoFormatNotAccepted, 1, 1, why)});
  }
  return program;
}

gcode::ReadOptions gcode_options(const Program& program, const JobContext& context) {
  gcode::ReadOptions options;
  options.program_name = program.name;
  options.cancel = context.cancel;
  return options;
}

Interpretation interpret_gcode(const Program& program, canon::Sink& sink, const JobContext& context,
                               const InterpretSettings& settings) {
  Interpretation out;
  const profile::LoadedProfile& dialect = *context.gcode_dialect;  // read_gcode checked it
  gcode::ReadOptions options = gcode_options(program, context);
  // A post stops at the first error; the reader goes on to list them all otherwise.
  if (settings.stop_at_first_error) options.max_errors = 1;
  gcode::ReadResult result = gcode::read_with_dialect(
      program.text, *dialect.dialect_json, dialect.profile.id + "/dialect.json", sink, options);
  out.ok = result.ok();  // before the diagnostics it looks at are moved out
  out.diagnostics = std::move(result.diagnostics);
  out.calls = result.calls;
  return out;
}

// ---- the registry ----------------------------------------------------------------------------

// How one input format is read into a Program and interpreted into canonical calls. A new
// format is one more entry in kReaders (and its detection in detect.cpp).
struct Reader {
  InputFormat format;
  Program (*read)(Input input, const JobContext& context, const ReadOptions& options);
  Interpretation (*interpret)(const Program& program, canon::Sink& sink, const JobContext& context,
                              const InterpretSettings& settings);
};

constexpr Reader kReaders[] = {
    {InputFormat::P21, read_model, interpret_model},
    {InputFormat::P28, read_model, interpret_model},
    {InputFormat::Cl, read_cl, interpret_cl},
    {InputFormat::Gcode, read_gcode, interpret_gcode},
};

const Reader* reader_for(InputFormat format) {
  for (const Reader& reader : kReaders)
    if (reader.format == format) return &reader;
  return nullptr;
}

std::string_view head_of(const Input& input) {
  if (input.arriving != nullptr) return input.arriving->arrived(input.arriving->appended());
  return input.bytes;
}

// An input no reader recognises gets one error, not whatever a reader would make of it.
Program unreadable(Input input, const JobContext& context) {
  Program program;
  program.name = std::move(input.name);
  program.diagnostics = context.schemas->reports;
  program.diagnostics.push_back(
      {program.name, diag::make(diag::Code::IoUnknownFormat, 1, 1,
                                "the input is not ISO 10303-21 (it does not start with "
                                "ISO-10303-21;), not ISO 10303-28 XML, not an APT/CLSF "
                                "cutter-location file and not G-code")});
  return program;
}

}  // namespace

Program read(Input input, const JobContext& context, const ReadOptions& options) {
  const Reader* reader = reader_for(detect_format(head_of(input)));
  if (reader == nullptr) return unreadable(std::move(input), context);
  return reader->read(std::move(input), context, options);
}

Interpretation interpret(const Program& program, canon::Sink& sink, const JobContext& context,
                         const InterpretSettings& settings) {
  const Reader* reader = reader_for(program.format);
  if (reader == nullptr) return {};
  return reader->interpret(program, sink, context, settings);
}

JobResult gcode_xml(Input input, const JobContext& context, const TextSink& out) {
  Program program = read(std::move(input), context);
  if (program.ok() && program.format != InputFormat::Gcode)
    program.diagnostics.push_back(
        {program.name, diag::make(diag::Code::IoFormatNotAccepted, 1, 1,
                                  "nc parse reads G-code; this input is " +
                                      std::string(to_string(program.format)) +
                                      ": trace it instead (ncpost trace, POST /v1/traces)")});
  JobResult result = read_result(program);
  if (!result.ok) return result;
  const auto started = std::chrono::steady_clock::now();
  const profile::LoadedProfile& profile = *context.gcode_dialect;
  const gcode::DialectResult dialect = gcode::load_dialect(*profile.dialect_json);
  const std::string dialect_file = profile.profile.id + "/dialect.json";
  append(result.diagnostics, diag::with_file(dialect.diagnostics, dialect_file));
  if (dialect.dialect) {
    gcode::ReadResult read =
        gcode::write_xml(program.text, *dialect.dialect, out, gcode_options(program, context));
    append(result.diagnostics, std::move(read.diagnostics));
    result.cancelled = read.cancelled;
  }
  result.ok = !result.cancelled && !diag::has_errors(result.diagnostics);
  result.work_time = std::chrono::steady_clock::now() - started;
  return result;
}

}  // namespace ncpost::pipeline
