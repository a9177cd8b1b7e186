// `ncpost inspect`: the program information a STEP-NC controller shows before it runs a
// program (docs/inspect.md), as JSON with every diagnostic in it, or as a text tree. Any error
// (in the input or in a schema file of --schemas DIR) makes the exit status 1; the information
// is printed anyway.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/jobs.hpp"

namespace ncpost::cli {

int run_inspect(Args args) {
  static const VerbSpec spec{"inspect",
                             "inspect [--format json|text] [--schemas DIR] [--strict] FILE|-\n"
                             "  Program information of a STEP-NC file (JSON by default).\n",
                             {{"format", "json|text"}, kSchemasOption, kStrictOption}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  const std::string format = options.value("format").value_or("json");
  if (format != "json" && format != "text")
    return usage_error(spec, "--format must be json or text");

  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  const auto print = [](std::string_view piece) {
    std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
  };
  pipeline::Inspection inspection;
  if (format == "json") {
    inspection = pipeline::inspect_to_json(std::move(job->input), job->context, print);
    std::cout << '\n';
  } else {
    inspection = pipeline::inspect_to_text(std::move(job->input), job->context, print);
  }
  std::cout.flush();
  print_diagnostics(inspection.job.diagnostics);
  return inspection.job.ok ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
