// `ncpost schema --to xml FILE.exp`: an EXPRESS schema as EXPRESS-X XML on stdout. Diagnostics
// go to stderr; a schema with errors is rejected (exit 1) and no XML is written, because a
// partial schema would silently lose declarations.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/jobs.hpp"

namespace ncpost::cli {

int run_schema(Args args) {
  static const VerbSpec spec{"schema",
                             "schema --to xml FILE.exp|-\n"
                             "  An EXPRESS schema as EXPRESS-X XML.\n",
                             {{"to", "xml"}}};
  const Options options(args, spec);
  if (options.help()) return print_help(spec);
  if (!options.error().empty()) return usage_error(spec, options.error());
  const std::string to = options.value("to").value_or("xml");
  if (to != "xml") return usage_error(spec, "--to must be 'xml' (got '" + to + "')");
  if (options.positionals().size() != 1)
    return usage_error(spec, "expected exactly one FILE.exp, or - for standard input");

  const auto input = read_input(options.positionals().front());
  if (!input) return kExitRejected;
  const pipeline::JobResult result =
      pipeline::schema_to_xml(input->bytes, input->name, write_stdout);
  std::cout.flush();
  print_diagnostics(result.diagnostics);
  return result.ok && std::cout ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
