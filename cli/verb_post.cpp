// `ncpost post --profile ID [--profiles DIR] [--tools TABLE] [--schemas DIR] FILE|-`
// Controller code for one machine profile: load → interpret → render, chunk by chunk, so the
// program streams to stdout while later workingsteps are still being interpreted. Diagnostics
// go to stderr. An error known before any output means no output; an error after output
// started ends the output with an "(ERROR: ...)" line; both exit 1.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/post.hpp"
#include "ncpost/profile/profile.hpp"

namespace ncpost::cli {
namespace {

void print_file_diagnostics(const std::vector<diag::FileDiagnostic>& diagnostics) {
  for (const auto& d : diagnostics) std::cerr << diag::format(d) << '\n';
}

}  // namespace

int run_post(Args args) {
  const Options options(args, {"profile", "profiles", "schemas", "tools"});
  if (!options.error().empty()) return usage_error("post", options.error());
  if (options.positionals().size() != 1) return usage_error("post", "expects one FILE or -");
  const auto id = options.value("profile");
  if (!id) return usage_error("post", "--profile ID is required (see `ncpost profiles`)");

  profile::ProfileStore store(
      options.value("profiles").value_or(profile::builtin_directory().string()));
  std::vector<diag::FileDiagnostic> profile_diagnostics;
  const auto loaded_profile = store.load(*id, profile_diagnostics);
  print_file_diagnostics(profile_diagnostics);
  if (!loaded_profile) return kExitRejected;

  auto job = load_program_job(options);
  if (!job) return kExitRejected;
  std::ios::sync_with_stdio(false);
  pipeline::PostOptions post_options;
  post_options.input_name = job->name;
  post_options.tools = std::move(job->interpret.tools);
  const pipeline::PostResult result = pipeline::post(
      job->loaded, *loaded_profile,
      [](std::string_view piece) {
        std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
        std::cout.flush();
      },
      post_options);
  std::cout.flush();
  print_diagnostics(job->loaded.diagnostics, job->name);
  print_file_diagnostics(result.diagnostics);
  return result.ok ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
