// `ncpost post --profile ID [--profiles DIR] [--tools TABLE] [--schemas DIR] FILE|-`
// Controller code for one machine profile: load → interpret → render, chunk by chunk, so the
// program streams to stdout while later workingsteps are still being interpreted. Diagnostics
// go to stderr. An error known before any output means no output; an error after output
// started ends the output with an "(ERROR: ...)" line; both exit 1.

#include <iostream>

#include "cli_support.hpp"
#include "ncpost/pipeline/load.hpp"
#include "ncpost/profile/profile.hpp"
#include "ncpost/render/render.hpp"
#include "ncpost/stepnc/interpreter.hpp"
#include "ncpost/stepnc/program_info.hpp"

namespace ncpost::cli {
namespace {

void print_file_diagnostics(const std::vector<xslt::FileDiagnostic>& diagnostics) {
  for (const auto& d : diagnostics) std::cerr << xslt::format(d) << '\n';
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
  std::vector<xslt::FileDiagnostic> profile_diagnostics;
  const auto loaded_profile = store.load(*id, profile_diagnostics);
  print_file_diagnostics(profile_diagnostics);
  if (!loaded_profile) return kExitRejected;

  auto job = load_program_job(options);
  if (!job) return kExitRejected;
  const pipeline::LoadedModel& loaded = job->loaded;
  stepnc::InterpretOptions& interpret_options = job->interpret;
  interpret_options.stop_at_first_error = true;
  const std::string& name = job->name;
  std::ios::sync_with_stdio(false);
  const stepnc::AttributeReader attributes(loaded.model, *loaded.schema);
  render::Renderer renderer(
      *loaded_profile,
      [](std::string_view piece) {
        std::cout.write(piece.data(), static_cast<std::streamsize>(piece.size()));
        std::cout.flush();
      },
      {}, name);
  const stepnc::InterpretResult result =
      stepnc::interpret(loaded.model, attributes, renderer, interpret_options);
  renderer.finish();
  const bool ok = result.ok() && !renderer.failed();
  if (!ok && renderer.started()) {
    std::string first;
    for (const auto& d : result.diagnostics)
      if (d.severity == diag::Severity::Error && first.empty())
        first = std::string(d.code_id()) + " " + d.message;
    for (const auto& d : renderer.diagnostics())
      if (d.diagnostic.severity == diag::Severity::Error && first.empty())
        first = std::string(d.diagnostic.code_id()) + " " + d.diagnostic.message;
    for (char& ch : first)
      if (ch == '(' || ch == ')' || ch == '\n' || ch == '\r') ch = ' ';
    std::cout << "(ERROR: " << first << " - the program is incomplete)"
              << loaded_profile->profile.line_ending;
  }
  std::cout.flush();
  print_diagnostics(loaded.diagnostics, name);
  print_diagnostics(result.diagnostics, name);
  print_file_diagnostics(renderer.diagnostics());
  return ok ? kExitOk : kExitRejected;
}

}  // namespace ncpost::cli
