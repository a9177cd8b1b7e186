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

  auto job = load_program_job(options);
  if (!job) return kExitRejected;
  const pipeline::LoadedModel& loaded = job->loaded;
  const stepnc::InterpretOptions& interpret_options = job->interpret;
  const std::string& name = job->name;
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
