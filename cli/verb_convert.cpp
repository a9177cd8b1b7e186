// `ncpost convert`: P21 or P28 (either binding) in, recognised from its first bytes; P21 or P28
// (late or early binding) out.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/jobs.hpp"

namespace ncpost::cli {

int run_convert(Args args) {
  static const VerbSpec spec{
      "convert",
      "convert --to p21|p28 [--binding late|early] [--schemas DIR] FILE|-\n"
      "  P21 or P28 in, P21 or P28 (late or early binding) out.\n",
      {{"to", "p21|p28"}, {"binding", "late|early"}, kSchemasOption, kStrictOption}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  const auto to = options.value("to");
  if (!to) return usage_error(spec, "--to p21|p28 is required");
  if (*to != "p21" && *to != "p28") return usage_error(spec, "--to must be p21 or p28");
  const std::string binding = options.value("binding").value_or("late");
  if (binding != "late" && binding != "early")
    return usage_error(spec, "--binding must be late or early");
  if (options.value("binding") && *to != "p28")
    return usage_error(spec, "--binding applies to --to p28 only");

  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  const pipeline::ConvertTo target = *to == "p21"         ? pipeline::ConvertTo::P21
                                     : binding == "early" ? pipeline::ConvertTo::P28Early
                                                          : pipeline::ConvertTo::P28Late;
  const pipeline::JobResult result =
      pipeline::convert(std::move(job->input), job->context, target, write_stdout);
  std::cout.flush();
  print_diagnostics(result.diagnostics);
  return result.ok ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
