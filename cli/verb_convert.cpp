// `ncpost convert --to p21|p28 [--binding late|early] [--schemas DIR] FILE|-`
// The input may be P21 or P28 (either binding); it is recognised from its first bytes.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"
#include "ncpost/p28/p28.hpp"
#include "ncpost/pipeline/detect.hpp"

namespace ncpost::cli {
namespace {

void write_stdout(std::string_view piece) {
  std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
}

}  // namespace

int run_convert(Args args) {
  const Options options(args, {"to", "binding", "schemas"});
  if (!options.error().empty()) return usage_error("convert", options.error());
  if (options.positionals().size() != 1) return usage_error("convert", "expects one FILE or -");
  const auto to = options.value("to");
  if (!to) return usage_error("convert", "--to p21|p28 is required");
  if (*to != "p21" && *to != "p28") return usage_error("convert", "--to must be p21 or p28");
  const std::string binding_name = options.value("binding").value_or("late");
  if (binding_name != "late" && binding_name != "early")
    return usage_error("convert", "--binding must be late or early");
  if (options.value("binding") && *to != "p28")
    return usage_error("convert", "--binding applies to --to p28 only");

  auto input = read_input(options.positionals()[0]);
  if (!input) return kExitRejected;
  const std::string name = input->name;
  LoadedSchemas schemas = load_schemas(options.value("schemas"));
  print_schema_reports(schemas.reports);

  p21::ReadResult read;
  std::vector<diag::Diagnostic> diagnostics;
  const pipeline::InputFormat format = pipeline::detect_format(input->bytes);
  if (format == pipeline::InputFormat::P28) {
    // Which schema: the one the document's own header names, else the built-in.
    p28::initialise_xml();
    p28::ReadOptions read_options;
    read_options.schema_for_header = [&](const p21::Model& header) {
      return schemas.registry.select_or_builtin(header).set();
    };
    read = p28::read(input->bytes, nullptr, read_options);
  } else {
    read = p21::read(std::move(input->bytes));
  }
  diagnostics = std::move(read.diagnostics);
  const express::SchemaSelection selection = schemas.registry.select_or_builtin(read.model);
  // A rejected input produces no output: a partial program must never look like a whole one.
  if (has_errors(diagnostics)) {
    print_diagnostics(diagnostics, name);
    return kExitRejected;
  }
  std::ios::sync_with_stdio(false);
  if (*to == "p21") {
    p21::write(read.model, write_stdout);
  } else {
    diagnostics.insert(diagnostics.end(), selection.diagnostics.begin(), selection.diagnostics.end());
    const auto notes = p28::write(read.model, selection.set(),
                                  binding_name == "early" ? p28::Binding::Early : p28::Binding::Late,
                                  write_stdout);
    diagnostics.insert(diagnostics.end(), notes.begin(), notes.end());
  }
  std::cout.flush();
  print_diagnostics(diagnostics, name);
  return kExitOk;
}

}  // namespace ncpost::cli
