// `ncpost trace`: the canonical machining program of an input, one call per line (rs274 style),
// the XML form that profiles' stylesheets read, or JSON lines (one object per call), written as the
// interpreter finishes each chunk so that a long program streams.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/jobs.hpp"

namespace ncpost::cli {

int run_trace(Args args) {
  static const VerbSpec spec{
      "trace",
      "trace [--format text|xml|json] [--tools TABLE] [--schemas DIR] [--strict] [--dialect "
      "PROFILE]\n"
      "      [--subprograms DIR] FILE|-\n"
      "  The canonical machining program: one call per line (text), the XML form that\n"
      "  stylesheets read (xml), or JSON lines: a header with the stock, then one object\n"
      "  per call (json). G-code is read with PROFILE's dialect.json.\n",
      {{"format", "text|xml|json"},
       kToolsOption,
       kSchemasOption,
       kStrictOption,
       kDialectOption,
       kSubprogramsOption}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  const std::string format = options.value("format").value_or("text");
  if (format != "text" && format != "xml" && format != "json")
    return usage_error(spec, "--format must be text, xml or json");

  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  const pipeline::JobResult result =
      pipeline::trace(std::move(job->input), job->context,
                      format == "text"  ? pipeline::TraceFormat::Text
                      : format == "xml" ? pipeline::TraceFormat::Xml
                                        : pipeline::TraceFormat::Json,
                      write_stdout);
  std::cout.flush();
  print_diagnostics(result.diagnostics);
  return result.ok ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
