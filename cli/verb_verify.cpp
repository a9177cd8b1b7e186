// `ncpost verify`: interprets the program as `trace` does and checks each workingstep's motions
// against the feature it claims to machine (docs/verify.md). Text: the report on stdout,
// diagnostics on stderr. JSON: one document on stdout with the diagnostics in it. Exit 0 when
// every check passes, 1 on a failure (or a program that cannot be read or interpreted).

#include <charconv>
#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/jobs.hpp"

namespace ncpost::cli {
namespace {

std::optional<double> positive(const std::string& text) {
  double v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !(v > 0) || v > 1000)
    return std::nullopt;
  return v;
}

}  // namespace

int run_verify(Args args) {
  static const VerbSpec spec{
      "verify",
      "verify [--format text|json] [--tolerance MM] [--grid MM] [--tools TABLE] [--schemas DIR]\n"
      "              [--strict] FILE|-\n"
      "  Checks the motions against the features they machine.\n",
      {{"format", "text|json"},
       {"tolerance", "MM"},
       {"grid", "MM"},
       kToolsOption,
       kSchemasOption,
       kStrictOption}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  const std::string format = options.value("format").value_or("text");
  if (format != "text" && format != "json")
    return usage_error(spec, "--format must be text or json");
  pipeline::VerifySettings settings;
  if (const auto t = options.value("tolerance")) {
    const auto v = positive(*t);
    if (!v) return usage_error(spec, "--tolerance must be a length in mm, > 0 and <= 1000");
    settings.tolerance = *v;
  }
  if (const auto g = options.value("grid")) {
    const auto v = positive(*g);
    if (!v) return usage_error(spec, "--grid must be a length in mm, > 0 and <= 1000");
    settings.grid = *v;
  }

  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  const std::string name = job->input.name;
  const pipeline::VerifyOutcome outcome =
      pipeline::verify(std::move(job->input), job->context, settings);
  print_diagnostics(outcome.job.diagnostics);
  if (!outcome.result) return kExitRejected;
  if (format == "json") {
    std::cout << pipeline::verify_report_json(outcome, name);
  } else {
    std::cout << pipeline::verify_report_text(outcome, name);
    print_diagnostics(pipeline::verify_diagnostics(outcome, name));
  }
  std::cout.flush();
  return outcome.result->ok() ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
