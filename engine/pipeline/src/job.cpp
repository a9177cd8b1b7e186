#include "ncpost/pipeline/job.hpp"

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
      loaded.model.instances_of("PROJECT").empty())
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
  const stepnc::InterpretResult result = stepnc::interpret(model, attributes, sink, options);
  Interpretation out;
  out.diagnostics = diag::with_file(result.diagnostics, program.name);
  out.calls = result.calls;
  out.ok = result.ok();
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

}  // namespace ncpost::pipeline
