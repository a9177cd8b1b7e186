// `ncpost profiles`: the machine profiles, one a line: id, name, controller (tab-separated).

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/profiles.hpp"

namespace ncpost::cli {

int run_profiles(Args args) {
  static const VerbSpec spec{"profiles",
                             "profiles [--profiles DIR]\n"
                             "  The machine profiles: id, name, controller.\n",
                             {{"profiles", "DIR"}}};
  const Options options(args, spec);
  if (const auto exit = parse_or_exit(options, spec, 0)) return *exit;
  const auto directory = options.value("profiles");
  const auto profiles = directory ? pipeline::Profiles::read_only(*directory)
                                  : std::make_unique<pipeline::Profiles>();
  const pipeline::ProfileList list = profiles->list();
  for (const auto& p : list.profiles)
    std::cout << p.id << '\t' << p.name << '\t' << p.controller << '\n';
  print_diagnostics(list.diagnostics);
  return diag::has_errors(list.diagnostics) ? kExitRejected : kExitOk;
}

}  // namespace ncpost::cli
