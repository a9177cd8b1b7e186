// `ncpost nc parse` and `ncpost nc translate`: G-code in (engine/gcode, docs/gcode.md). A
// profile id names both how a machine's programs are read (its dialect.json) and how they are
// written (its stylesheet), so translating is reading with one profile and posting with another.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/jobs.hpp"
#include "ncpost/pipeline/post.hpp"

namespace ncpost::cli {
namespace {

int run_parse(Args args) {
  static const VerbSpec spec{
      "nc parse",
      "nc parse --dialect PROFILE [--format text|xml] [--profiles DIR] [--tools TABLE]\n"
      "         [--subprograms DIR] FILE|-\n"
      "  G-code read with PROFILE's dialect.json: the canonical program (text, as `ncpost\n"
      "  trace`) or the XML intermediate form with <error> elements where it is wrong (xml).\n"
      "  Subprograms the program calls but does not hold are looked for among DIR's files; a\n"
      "  T word that is not a pocket of TABLE is an error.\n",
      {kDialectOption, {"format", "text|xml"}, kProfilesOption, kToolsOption, kSubprogramsOption}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  if (!options.value("dialect")) return usage_error(spec, "--dialect PROFILE is required");
  const std::string format = options.value("format").value_or("text");
  if (format != "text" && format != "xml") return usage_error(spec, "--format must be text or xml");

  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  const pipeline::JobResult result =
      format == "xml" ? pipeline::gcode_xml(std::move(job->input), job->context, write_stdout)
                      : pipeline::trace(std::move(job->input), job->context,
                                        pipeline::TraceFormat::Text, write_stdout);
  std::cout.flush();
  print_diagnostics(result.diagnostics);
  return result.ok ? kExitOk : kExitRejected;
}

int run_translate(Args args) {
  static const VerbSpec spec{
      "nc translate",
      "nc translate --from PROFILE --to PROFILE [--profiles DIR] [--tools TABLE]\n"
      "             [--subprograms DIR] FILE|-\n"
      "  G-code written for one machine (read with --from's dialect.json) as the program of\n"
      "  another (posted with --to's stylesheet), streamed like `ncpost post`; --to's limits\n"
      "  are checked on the G-code blocks. Subprogram files are looked for in DIR.\n",
      {kFromOption, {"to", "PROFILE"}, kProfilesOption, kToolsOption, kSubprogramsOption}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  if (!options.value("from")) return usage_error(spec, "--from PROFILE is required");
  const auto to = options.value("to");
  if (!to) return usage_error(spec, "--to PROFILE is required");

  const pipeline::ProfileLookup target = open_profiles(options)->find(*to);
  print_diagnostics(target.diagnostics);
  if (!target.profile) return kExitRejected;
  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  const pipeline::PostJobResult result = pipeline::post(
      std::move(job->input), job->context, *target.profile, [](std::string_view piece) {
        write_stdout(piece);
        std::cout.flush();
      });
  std::cout.flush();
  print_diagnostics(result.diagnostics());
  return result.ok() ? kExitOk : kExitRejected;
}

}  // namespace

int run_nc(Args args) {
  if (!args.empty() && args[0] == "parse") return run_parse(args.subspan(1));
  if (!args.empty() && args[0] == "translate") return run_translate(args.subspan(1));
  std::cerr << "usage: ncpost nc parse --dialect PROFILE [--format text|xml] FILE|-\n"
               "       ncpost nc translate --from PROFILE --to PROFILE FILE|-\n";
  return kExitUsage;
}

}  // namespace ncpost::cli
