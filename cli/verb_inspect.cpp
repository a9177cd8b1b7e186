#include <iostream>

#include "cli_support.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::cli {

// ncpost inspect [--format json|text] FILE|-
int run_inspect(Args args) {
  const Options options(args, {"format"});
  if (!options.error().empty()) return usage_error("inspect", options.error());
  if (options.positionals().size() != 1) return usage_error("inspect", "expects one FILE or -");
  const std::string format = options.value("format").value_or("json");
  if (format != "json" && format != "text")
    return usage_error("inspect", "--format must be json or text");

  auto input = read_input(options.positionals()[0]);
  if (!input) return kExitRejected;
  const std::string name = input->name;

  p21::ReadResult read = p21::read(std::move(input->bytes));
  stepnc::ProgramInfo info = stepnc::inspect(read.model);
  std::vector<diag::Diagnostic> diagnostics = std::move(read.diagnostics);
  diagnostics.insert(diagnostics.end(), info.diagnostics.begin(), info.diagnostics.end());

  if (format == "json") {
    info.json["diagnostics"] = stepnc::diagnostics_json(diagnostics, name);
    std::cout << info.json.dump(2) << '\n';
  } else {
    std::cout << stepnc::format_text(info.json);
  }
  print_diagnostics(diagnostics, name);
  return has_errors(diagnostics) ? kExitRejected : kExitOk;
}

}  // namespace ncpost::cli
