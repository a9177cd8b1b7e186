// `ncpost`: the command line. It parses the verb and hands the rest to that verb's function.

#include <array>
#include <iostream>
#include <string_view>
#include <vector>

#include "ncpost/pipeline/process.hpp"
#include "verbs.hpp"

namespace {

using ncpost::cli::Args;

constexpr std::string_view kUsage = R"(usage: ncpost <verb> [options] FILE|-

verbs:
  inspect [--format json|text] FILE       program information of a STEP-NC file (JSON by default)
  convert --to p21|p28 [--binding late|early] FILE
                                          P21 or P28 in, P21 or P28 (late or early binding) out
  schema --to xml FILE.exp                EXPRESS schema as EXPRESS-X XML
  trace [--format text|xml] FILE          canonical machining program
  post --profile ID [--profiles DIR] FILE controller code for one machine profile
  profiles [--profiles DIR]               list machine profiles
  verify [--format text|json] [--tolerance MM] [--grid MM] FILE
                                          check the motions against the features they machine
  nc parse --dialect D FILE               read G-code (not implemented yet)
  nc translate --from D --to PROFILE FILE translate G-code (not implemented yet)

Every verb that reads a program also takes --schemas DIR, --strict and, where it interprets,
--tools TABLE; `ncpost VERB --help` shows a verb's own usage. FILE may be '-' for standard
input. Exit status: 0 ok, 1 input rejected, 2 usage error.
)";

struct Verb {
  std::string_view name;
  int (*run)(Args);
};

int not_implemented(std::string_view what, std::string_view issue) {
  std::cerr << "ncpost: error: NCPOST-001: '" << what << "' is not implemented yet (" << issue
            << ")\n";
  return ncpost::cli::kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  // Process-wide libxml2 / libxslt set-up, once, before anything parses XML.
  ncpost::pipeline::initialise_process();
  std::vector<std::string_view> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    (args.empty() ? std::cerr : std::cout) << kUsage;
    return args.empty() ? ncpost::cli::kExitUsage : ncpost::cli::kExitOk;
  }
  if (args[0] == "--version") {
    std::cout << "ncpost " << NCPOST_VERSION << '\n';
    return ncpost::cli::kExitOk;
  }

  static constexpr std::array kVerbs = {
      Verb{"inspect", ncpost::cli::run_inspect}, Verb{"convert", ncpost::cli::run_convert},
      Verb{"schema", ncpost::cli::run_schema},   Verb{"trace", ncpost::cli::run_trace},
      Verb{"post", ncpost::cli::run_post},       Verb{"profiles", ncpost::cli::run_profiles},
      Verb{"verify", ncpost::cli::run_verify},
  };
  const std::string_view verb = args[0];
  const Args rest = Args(args).subspan(1);
  for (const auto& v : kVerbs)
    if (v.name == verb) return v.run(rest);

  if (verb == "nc") return not_implemented("ncpost nc", "G-code reader");
  std::cerr << "ncpost: unknown verb '" << verb << "'\n" << kUsage;
  return ncpost::cli::kExitUsage;
}
