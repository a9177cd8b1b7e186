// `ncpost post`: controller code for one machine profile: read → interpret → render, chunk by
// chunk, so the program streams to stdout while later workingsteps are still being interpreted.
// Diagnostics go to stderr. An error known before any output means no output; an error after
// output started ends the output with the profile's error marker; both exit 1.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/post.hpp"
#include "ncpost/pipeline/profiles.hpp"

namespace ncpost::cli {

int run_post(Args args) {
  static const VerbSpec spec{
      "post",
      "post --profile ID [--profiles DIR] [--tools TABLE] [--schemas DIR] [--strict] "
      "[--no-checks]\n"
      "     FILE|-\n"
      "  Controller code for one machine profile (see `ncpost profiles`). --no-checks: skip the\n"
      "  profile's pre-post checks of CL input (docs/cls.md). --from PROFILE: G-code input is "
      "read\n"
      "  with that profile's dialect.json (as `ncpost nc translate`), its subprogram files\n"
      "  from --subprograms DIR.\n",
      {{"profile", "ID"},
       {"profiles", "DIR"},
       kToolsOption,
       kSchemasOption,
       kStrictOption,
       kFromOption,
       kSubprogramsOption,
       {"no-checks", ""}}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec)) return *exit;
  const auto id = options.value("profile");
  if (!id) return usage_error(spec, "--profile ID is required (see `ncpost profiles`)");

  const auto directory = options.value("profiles");
  const auto profiles = directory ? pipeline::Profiles::read_only(*directory)
                                  : std::make_unique<pipeline::Profiles>();
  const pipeline::ProfileLookup lookup = profiles->find(*id);
  print_diagnostics(lookup.diagnostics);
  if (!lookup.profile) return kExitRejected;

  auto job = prepare_job(options);
  if (!job) return kExitRejected;
  pipeline::PostOptions post_options;
  post_options.shop_checks = !options.flag("no-checks");
  const pipeline::PostJobResult result = pipeline::post(
      std::move(job->input), job->context, *lookup.profile,
      [](std::string_view piece) {
        write_stdout(piece);
        std::cout.flush();
      },
      post_options);
  std::cout.flush();
  print_diagnostics(result.diagnostics());
  return result.ok() ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
