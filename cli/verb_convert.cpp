#include <iostream>

#include "cli_support.hpp"
#include "ncpost/p21/reader.hpp"
#include "ncpost/p21/writer.hpp"

namespace ncpost::cli {

// ncpost convert --to p21|p28 [--binding late|early] FILE|-
int run_convert(Args args) {
  const Options options(args, {"to", "binding"});
  if (!options.error().empty()) return usage_error("convert", options.error());
  if (options.positionals().size() != 1) return usage_error("convert", "expects one FILE or -");
  const auto to = options.value("to");
  if (!to) return usage_error("convert", "--to p21|p28 is required");
  if (*to == "p28") {
    std::cerr << "ncpost: error: NCPOST-001: 'convert --to p28' is not implemented yet (issue 3)\n";
    return kExitUsage;
  }
  if (*to != "p21") return usage_error("convert", "--to must be p21 or p28");
  if (options.value("binding")) return usage_error("convert", "--binding applies to --to p28 only");

  auto input = read_input(options.positionals()[0]);
  if (!input) return kExitRejected;
  const std::string name = input->name;
  p21::ReadResult read = p21::read(std::move(input->bytes));
  print_diagnostics(read.diagnostics, name);
  // A rejected input produces no output: a partial program must never look like a whole one.
  if (!read.ok()) return kExitRejected;
  std::ios::sync_with_stdio(false);
  p21::write(read.model, [](std::string_view piece) {
    std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
  });
  std::cout.flush();
  return kExitOk;
}

}  // namespace ncpost::cli
