#include <iostream>

#include "cli_support.hpp"
#include "ncpost/express/validate.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::cli {

// ncpost inspect [--format json|text] [--schemas DIR] FILE|-
//
// The file is read, its schema chosen from FILE_SCHEMA (the built-in ISO 14649 schema, or one
// of DIR's .exp files), the model checked against that schema, and the program information
// extracted through it. When no schema matches, the program is read with the built-in schema
// (EXP-052 says so) and not checked: against a schema it was not written for, every instance
// would be reported. Diagnostics: the schema files' first (under their own names), then the
// input's: reading, schema choice, schema check, program structure. Any error, in the input or
// in a schema file, makes the exit status 1.
int run_inspect(Args args) {
  const Options options(args, {"format", "schemas"});
  if (!options.error().empty()) return usage_error("inspect", options.error());
  if (options.positionals().size() != 1) return usage_error("inspect", "expects one FILE or -");
  const std::string format = options.value("format").value_or("json");
  if (format != "json" && format != "text")
    return usage_error("inspect", "--format must be json or text");

  LoadedSchemas schemas = load_schemas(options.value("schemas"));
  auto input = read_input(options.positionals()[0]);
  if (!input) {
    print_schema_reports(schemas.reports);
    return kExitRejected;  // read_input printed IO-001
  }
  const std::string name = input->name;

  pipeline::LoadedModel loaded = load_on_all_cores(std::move(input->bytes), schemas.registry);
  add_builtin_report(schemas, loaded);
  std::vector<diag::Diagnostic> diagnostics = std::move(loaded.diagnostics);
  const auto append = [&](std::vector<diag::Diagnostic> more) {
    diagnostics.insert(diagnostics.end(), std::make_move_iterator(more.begin()),
                       std::make_move_iterator(more.end()));
  };
  stepnc::ProgramInfo info = stepnc::inspect(loaded.model, *loaded.schema);
  append(std::move(info.diagnostics));

  if (format == "json") {
    nlohmann::ordered_json all = nlohmann::ordered_json::array();
    for (const auto& report : schemas.reports)
      for (auto& d : stepnc::diagnostics_json(report.diagnostics, report.file.string()))
        all.push_back(std::move(d));
    for (auto& d : stepnc::diagnostics_json(diagnostics, name)) all.push_back(std::move(d));
    info.json["diagnostics"] = std::move(all);
    std::cout << info.json.dump(2) << '\n';
  } else {
    std::cout << stepnc::format_text(info.json);
  }
  print_schema_reports(schemas.reports);
  print_diagnostics(diagnostics, name);
  return has_errors(diagnostics) || has_errors(schemas.reports) ? kExitRejected : kExitOk;
}

}  // namespace ncpost::cli
