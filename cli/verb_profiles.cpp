// `ncpost profiles [--profiles DIR]`: the machine profiles, one a line: id, name, controller
// (tab-separated).

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::cli {

int run_profiles(Args args) {
  const Options options(args, {"profiles"});
  if (!options.error().empty()) return usage_error("profiles", options.error());
  if (!options.positionals().empty()) return usage_error("profiles", "takes no FILE");
  const profile::ProfileStore store(
      options.value("profiles").value_or(profile::builtin_directory().string()));
  std::vector<diag::FileDiagnostic> diagnostics;
  const auto profiles = store.list(diagnostics);
  for (const auto& p : profiles)
    std::cout << p.id << '\t' << p.name << '\t' << p.controller << '\n';
  for (const auto& d : diagnostics) std::cerr << diag::format(d) << '\n';
  return diag::has_errors(diagnostics) ? kExitRejected : kExitOk;
}

}  // namespace ncpost::cli
