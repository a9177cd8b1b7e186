// `ncpost trace [--format text|xml] [--schemas DIR] [--tools TABLE] FILE|-`
// The canonical machining program of a STEP-NC file: one call per line (RS274 style), or the
// XML form that profiles' stylesheets read. Chunks are written as the interpreter finishes
// them, so a long program streams.

#include <fstream>
#include <iostream>
#include <sstream>

#include "cli_support.hpp"
#include "ncpost/canon/trace.hpp"
#include "ncpost/canon/xml.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::cli {
namespace {

void write_stdout(std::string_view piece) {
  std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
}

}  // namespace

int run_trace(Args args) {
  const Options options(args, {"format", "schemas", "tools"});
  if (!options.error().empty()) return usage_error("trace", options.error());
  if (options.positionals().size() != 1) return usage_error("trace", "expects one FILE or -");
  const std::string format = options.value("format").value_or("text");
  if (format != "text" && format != "xml")
    return usage_error("trace", "--format must be text or xml");

  LoadedSchemas schemas = load_schemas(options.value("schemas"));
  print_schema_reports(schemas.reports);
  stepnc::InterpretOptions interpret_options;
  std::vector<diag::Diagnostic> table_diagnostics;
  if (const auto table = options.value("tools")) {
    auto text = read_input(*table);
    if (!text) return kExitRejected;
    interpret_options.tools = stepnc::read_tool_table(text->bytes, table_diagnostics);
    print_diagnostics(table_diagnostics, *table);
    if (has_errors(table_diagnostics)) return kExitRejected;
  }
  auto input = read_input(options.positionals()[0]);
  if (!input) return kExitRejected;
  const std::string name = input->name;
  pipeline::LoadedModel loaded = pipeline::load(std::move(input->bytes), schemas.registry);
  add_builtin_report(schemas, loaded);
  print_schema_reports(schemas.reports);
  if (!loaded.ok()) {
    // Say what the file is, too, when it is not a program at all (an AP238 AIM excerpt, say).
    if (loaded.model.instances_of("PROJECT").empty())
      loaded.diagnostics.push_back(stepnc::no_program_diagnostic(loaded.model));
    print_diagnostics(loaded.diagnostics, name);
    return kExitRejected;
  }
  std::ios::sync_with_stdio(false);
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  stepnc::InterpretResult result;
  if (format == "text") {
    canon::TraceWriter trace(write_stdout);
    result = stepnc::interpret(loaded.model, attributes, trace, interpret_options);
  } else {
    canon::XmlDocumentWriter xml(write_stdout);
    canon::Chunker chunker(xml);
    result = stepnc::interpret(loaded.model, attributes, chunker, interpret_options);
    chunker.finish();
    xml.finish();
  }
  std::cout.flush();
  print_diagnostics(loaded.diagnostics, name);
  print_diagnostics(result.diagnostics, name);
  return result.ok() ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
