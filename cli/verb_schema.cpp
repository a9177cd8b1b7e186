// `ncpost schema --to xml FILE.exp`: an EXPRESS schema as EXPRESS-X XML on stdout.
// Diagnostics go to stderr; a schema with errors is rejected (exit 1) and no XML is written,
// because a partial schema would silently lose declarations.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/express/express_x.hpp"
#include "ncpost/express/parse.hpp"

namespace ncpost::cli {

int run_schema(Args args) {
  const Options options(args, {"to"});
  if (!options.error().empty()) return usage_error("schema", options.error());
  const std::string to = options.value("to").value_or("xml");
  if (to != "xml") return usage_error("schema", "--to must be 'xml' (got '" + to + "')");
  if (options.positionals().size() != 1)
    return usage_error("schema", "expected exactly one FILE.exp, or - for standard input");

  const auto input = read_input(options.positionals().front());
  if (!input) return kExitRejected;
  const express::ParseResult result = express::parse_express(input->bytes);
  print_diagnostics(result.diagnostics, input->name);
  if (!result.ok()) return kExitRejected;

  express::write_express_x(result.schemas, std::cout);
  std::cout.flush();
  return std::cout ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
