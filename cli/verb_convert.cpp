// `ncpost convert --to p21|p28 [--binding late|early] [--schemas DIR] FILE|-`
// The input may be P21 or P28 (either binding); it is recognised from its first bytes.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"
#include "ncpost/p28/p28.hpp"
#include "ncpost/pipeline/load.hpp"

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

  // Conversion is lossless whatever the schema says of the data, so the model is not checked
  // against it here (`ncpost inspect` does that).
  pipeline::LoadedModel loaded =
      load_on_all_cores(std::move(input->bytes), schemas.registry, false);
  std::vector<diag::Diagnostic> diagnostics = std::move(loaded.diagnostics);
  // A rejected input produces no output: a partial program must never look like a whole one.
  if (has_errors(diagnostics)) {
    print_diagnostics(diagnostics, name);
    return kExitRejected;
  }
  std::ios::sync_with_stdio(false);
  if (*to == "p21") {
    p21::write(loaded.model, write_stdout);
  } else {
    const auto notes = p28::write(
        loaded.model, loaded.schema,
        binding_name == "early" ? p28::Binding::Early : p28::Binding::Late, write_stdout);
    diagnostics.insert(diagnostics.end(), notes.begin(), notes.end());
  }
  std::cout.flush();
  print_diagnostics(diagnostics, name);
  return kExitOk;
}

}  // namespace ncpost::cli
